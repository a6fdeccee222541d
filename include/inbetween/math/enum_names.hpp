#pragma once
/// One name table per enumeration: the spelling each enumerator has in files and on the command
/// line.  The tables sit next to their enums (penner.hpp, distance_time.hpp, any_curve.hpp,
/// track.hpp, fcurve.hpp, path_motion.hpp, scene.hpp, …) as specialisations of enum_names<Enum>();
/// to_string(), enum_from_string<Enum>() and the readers' "expected one of: …" lists all read
/// them, so a name is spelt in exactly one place.  It lives in math, the first module, so that an
/// enum of any module can have its table next to it.

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace inbetween {

/// The names of `Enum`'s enumerators, indexed by their underlying value (declaration order).
/// Specialised next to each enum that has a file spelling; unspecialised enums do not compile.
template <class Enum>
constexpr std::span<const std::string_view> enum_names() noexcept;

/// The name of `v` in enum_names<Enum>(); empty for a value outside the enumeration.
template <class Enum>
[[nodiscard]] constexpr std::string_view enum_name(Enum v) noexcept {
  const std::span<const std::string_view> names = enum_names<Enum>();
  const auto i = static_cast<std::size_t>(v);
  return i < names.size() ? names[i] : std::string_view{};
}

/// The enumerator of `Enum` whose name in `names` is `name`; nullopt for an unknown name.
template <class Enum>
[[nodiscard]] constexpr std::optional<Enum> find_enum_name(std::span<const std::string_view> names,
                                                           std::string_view name) noexcept {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<Enum>(i);
  }
  return std::nullopt;
}

/// Parses a name written by to_string() / enum_name(); nullopt for an unknown name.  Reads the
/// enum's enum_names<Enum>() table, so it works for every enum that has one.
template <class Enum>
[[nodiscard]] constexpr std::optional<Enum> enum_from_string(std::string_view name) noexcept {
  return find_enum_name<Enum>(enum_names<Enum>(), name);
}

}  // namespace inbetween
