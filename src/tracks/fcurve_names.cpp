// Names of the F-curve enumerations (their file-format spellings): to_string.
#include "inbetween/tracks/fcurve.hpp"

#include <array>
#include <optional>

namespace inbetween {

// ------------------------------------------------------------------ names
namespace {
constexpr std::array<std::string_view, 13> kInterpolationNames = {
    "constant", "linear", "bezier", "back", "bounce", "circ", "cubic",
    "elastic",  "expo",   "quad",   "quart", "quint", "sine"};
constexpr std::array<std::string_view, 4> kEasingNames = {"auto", "ease_in", "ease_out", "ease_in_out"};
constexpr std::array<std::string_view, 5> kHandleNames = {"free", "aligned", "vector", "auto", "auto_clamped"};
constexpr std::array<std::string_view, 2> kExtrapolationNames = {"constant", "linear"};
constexpr std::array<std::string_view, 2> kSmoothingNames = {"none", "cont_accel"};
constexpr std::array<std::string_view, 4> kCycleNames = {"none", "repeat", "repeat_offset", "mirror"};

template <class Enum, std::size_t N>
std::optional<Enum> find_name(const std::array<std::string_view, N>& names, std::string_view name) noexcept {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == name) return static_cast<Enum>(i);
  return std::nullopt;
}
}  // namespace

std::string_view to_string(Interpolation v) noexcept { return kInterpolationNames[std::size_t(v)]; }
std::string_view to_string(KeyEasing v) noexcept { return kEasingNames[std::size_t(v)]; }
std::string_view to_string(HandleType v) noexcept { return kHandleNames[std::size_t(v)]; }
std::string_view to_string(Extrapolation v) noexcept { return kExtrapolationNames[std::size_t(v)]; }
std::string_view to_string(AutoSmoothing v) noexcept { return kSmoothingNames[std::size_t(v)]; }
std::string_view to_string(CycleMode v) noexcept { return kCycleNames[std::size_t(v)]; }

template <>
std::optional<Interpolation> enum_from_string<Interpolation>(std::string_view n) noexcept {
  return find_name<Interpolation>(kInterpolationNames, n);
}
template <>
std::optional<KeyEasing> enum_from_string<KeyEasing>(std::string_view n) noexcept {
  return find_name<KeyEasing>(kEasingNames, n);
}
template <>
std::optional<HandleType> enum_from_string<HandleType>(std::string_view n) noexcept {
  return find_name<HandleType>(kHandleNames, n);
}
template <>
std::optional<Extrapolation> enum_from_string<Extrapolation>(std::string_view n) noexcept {
  return find_name<Extrapolation>(kExtrapolationNames, n);
}
template <>
std::optional<AutoSmoothing> enum_from_string<AutoSmoothing>(std::string_view n) noexcept {
  return find_name<AutoSmoothing>(kSmoothingNames, n);
}
template <>
std::optional<CycleMode> enum_from_string<CycleMode>(std::string_view n) noexcept {
  return find_name<CycleMode>(kCycleNames, n);
}

}  // namespace inbetween
