#pragma once
// Private to src/io: the JSON-shape helpers of the scene file's reader (src/io/scene_file.hpp lists
// its parts, one per concept), building errors with structured locations; nothing here checks
// values (build_scene() does).
#include <nlohmann/json.hpp>

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "json_text.hpp"

namespace inbetween::io_detail {

using nlohmann::json;
using Loc = std::vector<LocationStep>;

// Where included curve files are found: the scene file's folder (the current directory for text
// without a file, e.g. standard input).
struct Context {
  int version = 1;
  std::filesystem::path base_dir;
};


// The location one step further in.
inline Loc at(const Loc& loc, LocationStep step) {
  Loc out = loc;
  out.push_back(std::move(step));
  return out;
}

inline std::string type_name(const json& j) { return j.type_name(); }

inline Error error_at(ErrorCode code, std::string message, Loc loc) { return Error{code, std::move(message), std::move(loc)}; }

inline std::string name_list(std::span<const std::string_view> names) {
  std::string list;
  for (std::string_view a : names) list += (list.empty() ? "" : ", ") + std::string(a);
  return list;
}
inline std::string name_list(std::initializer_list<std::string_view> names) {
  return name_list(std::span<const std::string_view>(names.begin(), names.size()));
}

// Rejects members not in `allowed` (catches misspelt field names).
inline Expected<void> only_members(const json& obj, const Loc& loc, std::initializer_list<std::string_view> allowed) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool known = false;
    for (std::string_view a : allowed) known = known || (it.key() == a);
    if (!known) {
      return error_at(ErrorCode::invalid_argument,
                      "unknown member \"" + io_detail::truncated(it.key()) + "\" (expected one of: " + name_list(allowed) + ")",
                      at(loc, it.key()));
    }
  }
  return {};
}

// A number (finite: the bounded JSON reader refuses numbers beyond double's range; whether a value
// must be finite is build_scene()'s check).
inline Expected<double> get_number(const json& j, const Loc& loc) {
  if (!j.is_number()) return error_at(ErrorCode::invalid_argument, "expected a number, found " + type_name(j), loc);
  return j.get<double>();
}

// An optional true/false member; `fallback` when absent.
inline Expected<bool> bool_member(const json& obj, const Loc& loc, std::string_view name, bool fallback) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return fallback;
  if (!it->is_boolean()) return error_at(ErrorCode::invalid_argument, "expected true or false", at(loc, std::string(name)));
  return it->get<bool>();
}

// A number member; JSON has no NaN, but the strings "nan"/"inf" are reported as non-finite numbers
// so that a scene written by a careless exporter gets a clear message.
inline Expected<double> number_member(const json& obj, const Loc& loc, std::string_view name, std::optional<double> fallback) {
  const Loc p = at(loc, std::string(name));
  auto it = obj.find(std::string(name));
  if (it == obj.end()) {
    if (fallback) return *fallback;
    return error_at(ErrorCode::invalid_argument, "missing required member \"" + std::string(name) + "\"", p);
  }
  if (it->is_string()) {
    const std::string& s = it->get_ref<const std::string&>();
    if (s == "nan" || s == "NaN" || s == "inf" || s == "-inf" || s == "Infinity" || s == "-Infinity") {
      return error_at(ErrorCode::not_finite, "number is not finite (\"" + s + "\")", p);
    }
  }
  return get_number(*it, p);
}

// An enumeration named by a string: the F-curve vocabulary (enum_from_string) …
template <class Enum>
Expected<Enum> enum_member(const json& obj, const Loc& loc, std::string_view name, Enum fallback,
                           std::span<const std::string_view> names) {
  const Loc p = at(loc, std::string(name));
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return fallback;
  if (!it->is_string()) return error_at(ErrorCode::invalid_argument, "expected a string, found " + type_name(*it), p);
  const std::string& s = it->get_ref<const std::string&>();
  if (auto v = enum_from_string<Enum>(s)) return *v;
  return error_at(ErrorCode::invalid_argument,
                  "unknown " + std::string(name) + " \"" + io_detail::truncated(s) + "\" (expected one of: " + name_list(names) + ")", p);
}

// … or by position in `names` (the other enumerations of the format).
template <class Enum>
Expected<Enum> name_member(const json& obj, const Loc& loc, std::string_view name, Enum fallback,
                           std::span<const std::string_view> names) {
  const Loc p = at(loc, std::string(name));
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return fallback;
  if (!it->is_string()) return error_at(ErrorCode::invalid_argument, "expected a string, found " + type_name(*it), p);
  const std::string& s = it->get_ref<const std::string&>();
  std::size_t i = 0;
  for (std::string_view n : names) {
    if (n == s) return static_cast<Enum>(i);
    ++i;
  }
  return error_at(ErrorCode::invalid_argument,
                  "unknown " + std::string(name) + " \"" + io_detail::truncated(s) + "\" (expected one of: " + name_list(names) + ")", p);
}

// An F-curve handle [frame, value]: absent → nullopt (the error when `required`).
inline Expected<std::optional<Vec2d>> point_member(const json& obj, const Loc& loc, std::string_view name, bool required) {
  const Loc p = at(loc, std::string(name));
  auto it = obj.find(std::string(name));
  if (it == obj.end()) {
    if (!required) return std::optional<Vec2d>{};
    return error_at(ErrorCode::invalid_argument,
                    "missing \"" + std::string(name) + "\" (required for free and aligned handles)", p);
  }
  if (!it->is_array()) return error_at(ErrorCode::wrong_arity, "expected [frame, value], found " + type_name(*it), p);
  if (it->size() != 2) {
    return error_at(ErrorCode::wrong_arity, "expected 2 numbers [frame, value], found " + std::to_string(it->size()), p);
  }
  auto x = get_number((*it)[0], at(p, std::size_t{0}));
  if (!x) return x.error();
  auto y = get_number((*it)[1], at(p, std::size_t{1}));
  if (!y) return y.error();
  return std::optional<Vec2d>{Vec2d{*x, *y}};
}

// An array of `dim` numbers (2 to 4) as a Vec4d, unused components zero; zero when absent and not `required`.
inline Expected<Vec4d> vector_member(const json& obj, const Loc& loc, std::string_view name, int dim, bool required) {
  const Loc p = at(loc, std::string(name));
  auto it = obj.find(std::string(name));
  if (it == obj.end()) {
    if (!required) return Vec4d{};
    return error_at(ErrorCode::invalid_argument, "missing required member \"" + std::string(name) + "\"", p);
  }
  if (!it->is_array() || int(it->size()) != dim) {
    return error_at(ErrorCode::wrong_arity,
                    "expected an array of " + std::to_string(dim) + " numbers, found " +
                        (it->is_array() ? std::to_string(it->size()) + " elements" : type_name(*it)),
                    p);
  }
  Vec4d v{};
  for (int i = 0; i < dim; ++i) {
    auto x = get_number((*it)[std::size_t(i)], at(p, std::size_t(i)));
    if (!x) return x.error();
    v[i] = *x;
  }
  return v;
}

inline Vec3d xyz(const Vec4d& v) { return {v.x, v.y, v.z}; }
inline Quatd quat_from(const Vec4d& v) { return Quatd::from_wxyz(v.x, v.y, v.z, v.w); }

// A track's or object's "name": present and a string (non-empty is build_scene()'s check).
inline Expected<std::string> name_of(const json& j, const Loc& loc) {
  auto it = j.find("name");
  if (it == j.end() || !it->is_string()) {
    return error_at(ErrorCode::invalid_argument, "a track needs a non-empty string \"name\"", at(loc, "name"));
  }
  return it->get<std::string>();
}

// The "keys" array of a track object, each key checked to be an object with only `allowed` members.
inline Expected<const json*> key_array(const json& j, const Loc& loc, std::initializer_list<std::string_view> allowed) {
  const Loc kp = at(loc, "keys");
  auto keys = j.find("keys");
  if (keys == j.end()) return error_at(ErrorCode::invalid_argument, "missing required member \"keys\"", kp);
  if (!keys->is_array()) return error_at(ErrorCode::invalid_argument, "\"keys\" must be an array", kp);
  for (std::size_t i = 0; i < keys->size(); ++i) {
    const json& kj = (*keys)[i];
    const Loc p = at(kp, i);
    if (!kj.is_object()) return error_at(ErrorCode::invalid_argument, "a key must be an object, found " + type_name(kj), p);
    if (auto ok = only_members(kj, p, allowed); !ok) return ok.error();
  }
  return &*keys;
}

// A member that must be a JSON object when present; nullptr when absent.
inline Expected<const json*> object_member(const json& obj, const Loc& loc, std::string_view name,
                                           std::initializer_list<std::string_view> allowed) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return static_cast<const json*>(nullptr);
  const Loc p = at(loc, std::string(name));
  if (!it->is_object()) return error_at(ErrorCode::invalid_argument, "expected an object, found " + type_name(*it), p);
  if (auto ok = only_members(*it, p, allowed); !ok) return ok.error();
  return &*it;
}

// A string member ("" when absent).
inline Expected<std::string> string_member(const json& obj, const Loc& loc, std::string_view name) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return std::string();
  if (!it->is_string()) {
    return error_at(ErrorCode::invalid_argument, "expected a string, found " + type_name(*it), at(loc, std::string(name)));
  }
  return it->get<std::string>();
}

// An optional number member.
inline Expected<std::optional<double>> optional_number(const json& obj, const Loc& loc, std::string_view name) {
  if (!obj.contains(std::string(name))) return std::optional<double>{};
  auto v = number_member(obj, loc, name, std::nullopt);
  if (!v) return v.error();
  return std::optional<double>{*v};
}

// An array member whose elements are objects with only `allowed` members.
inline Expected<const json*> object_array(const json& obj, const Loc& loc, std::string_view name,
                                          std::initializer_list<std::string_view> allowed) {
  auto it = obj.find(std::string(name));
  const Loc p = at(loc, std::string(name));
  if (it == obj.end()) return error_at(ErrorCode::invalid_argument, "missing required member \"" + std::string(name) + "\"", p);
  if (!it->is_array()) return error_at(ErrorCode::invalid_argument, "\"" + std::string(name) + "\" must be an array", p);
  for (std::size_t i = 0; i < it->size(); ++i) {
    const json& e = (*it)[i];
    if (!e.is_object()) return error_at(ErrorCode::invalid_argument, "expected an object, found " + type_name(e), at(p, i));
    if (auto ok = only_members(e, at(p, i), allowed); !ok) return ok.error();
  }
  return &*it;
}

// A [x, y, z] member.
inline Expected<Vec3d> vec3_member(const json& obj, const Loc& loc, std::string_view name, Vec3d fallback) {
  if (!obj.contains(std::string(name))) return fallback;
  auto v = vector_member(obj, loc, name, 3, true);
  if (!v) return v.error();
  return xyz(*v);
}

// A target: [x, y, z] or an object name.
inline Expected<RawTarget<double>> read_target(const json& obj, const Loc& loc, std::string_view name) {
  auto it = obj.find(std::string(name));
  const Loc p = at(loc, std::string(name));
  if (it == obj.end()) return error_at(ErrorCode::invalid_argument, "missing required member \"" + std::string(name) + "\"", p);
  if (it->is_string()) return RawTarget<double>{it->get<std::string>()};
  if (!it->is_array()) return error_at(ErrorCode::invalid_argument, "expected [x, y, z] or an object name", p);
  auto v = vector_member(obj, loc, name, 3, true);
  if (!v) return v.error();
  return RawTarget<double>{xyz(*v)};
}

}  // namespace inbetween::io_detail
