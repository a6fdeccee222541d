// Reads the inbetween scene JSON format (docs/scene-format.md) into built tracks.  nlohmann_json
// stays inside this file; every error carries the JSON pointer of the offending value.
#include "inbetween/math/format.hpp"
#include "inbetween/io/scene.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace inbetween {

namespace {


using nlohmann::json;

// A JSON pointer built while descending.
std::string child(const std::string& ptr, std::string_view key) {
  std::string escaped;
  for (char ch : key) {
    if (ch == '~') escaped += "~0";
    else if (ch == '/') escaped += "~1";
    else escaped += ch;
  }
  return ptr + "/" + escaped;
}
std::string child(const std::string& ptr, std::size_t index) { return ptr + "/" + std::to_string(index); }

std::string type_name(const json& j) { return j.type_name(); }

Error error_at(ErrorCode code, std::string message, std::string where) {
  return Error{code, std::move(message), where.empty() ? std::string("/") : std::move(where)};
}

// Rejects members not in `allowed` (catches misspelt field names).
Expected<void> only_members(const json& obj, const std::string& ptr, std::initializer_list<std::string_view> allowed) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool known = false;
    for (std::string_view a : allowed) known = known || (it.key() == a);
    if (!known) {
      std::string list;
      for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      return error_at(ErrorCode::InvalidArgument, "unknown member \"" + it.key() + "\" (expected one of: " + list + ")",
                      child(ptr, it.key()));
    }
  }
  return {};
}

Expected<double> get_number(const json& j, const std::string& ptr) {
  if (!j.is_number()) {
    return error_at(ErrorCode::InvalidArgument, "expected a number, found " + type_name(j), ptr);
  }
  const double v = j.get<double>();
  if (!std::isfinite(v)) return error_at(ErrorCode::NotFinite, "number is not finite", ptr);
  return v;
}

// Reads a number; JSON has no NaN, but the strings "nan"/"inf" are reported as non-finite numbers
// so that a scene written by a careless exporter gets a clear message.
// An optional true/false member; `fallback` when absent.
Expected<bool> bool_member(const json& obj, const std::string& ptr, std::string_view name, bool fallback) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return fallback;
  if (!it->is_boolean()) return error_at(ErrorCode::InvalidArgument, "expected true or false", child(ptr, name));
  return it->get<bool>();
}

Expected<double> number_member(const json& obj, const std::string& ptr, std::string_view name,
                               std::optional<double> fallback) {
  const std::string p = child(ptr, name);
  auto it = obj.find(std::string(name));
  if (it == obj.end()) {
    if (fallback) return *fallback;
    return error_at(ErrorCode::InvalidArgument, "missing required member \"" + std::string(name) + "\"", p);
  }
  if (it->is_string()) {
    const std::string s = it->get<std::string>();
    if (s == "nan" || s == "NaN" || s == "inf" || s == "-inf" || s == "Infinity" || s == "-Infinity") {
      return error_at(ErrorCode::NotFinite, "number is not finite (\"" + s + "\")", p);
    }
  }
  return get_number(*it, p);
}

template <class Enum>
Expected<Enum> enum_member(const json& obj, const std::string& ptr, std::string_view name, Enum fallback,
                           const std::vector<std::string_view>& names) {
  const std::string p = child(ptr, name);
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return fallback;
  if (!it->is_string()) return error_at(ErrorCode::InvalidArgument, "expected a string, found " + type_name(*it), p);
  const std::string s = it->get<std::string>();
  if (auto v = enum_from_string<Enum>(s)) return *v;
  std::string list;
  for (std::string_view a : names) list += (list.empty() ? "" : ", ") + std::string(a);
  return error_at(ErrorCode::InvalidArgument, "unknown " + std::string(name) + " \"" + s + "\" (expected one of: " + list + ")",
                  p);
}

Expected<Vec2d> point_member(const json& obj, const std::string& ptr, std::string_view name, bool required) {
  const std::string p = child(ptr, name);
  auto it = obj.find(std::string(name));
  if (it == obj.end()) {
    if (!required) return Vec2d{};
    return error_at(ErrorCode::InvalidArgument, "missing \"" + std::string(name) + "\" (required for free and aligned handles)", p);
  }
  if (!it->is_array()) return error_at(ErrorCode::WrongArity, "expected [frame, value], found " + type_name(*it), p);
  if (it->size() != 2) {
    return error_at(ErrorCode::WrongArity, "expected 2 numbers [frame, value], found " + std::to_string(it->size()), p);
  }
  auto x = get_number((*it)[0], child(p, std::size_t{0}));
  if (!x) return x.error();
  auto y = get_number((*it)[1], child(p, std::size_t{1}));
  if (!y) return y.error();
  return Vec2d{*x, *y};
}

const std::vector<std::string_view> kInterp = {"constant", "linear", "bezier", "back",  "bounce",
                                                               "circ",     "cubic",  "elastic", "expo", "quad",
                                                               "quart",    "quint",  "sine"};
const std::vector<std::string_view> kEasing = {"auto", "ease_in", "ease_out", "ease_in_out"};
const std::vector<std::string_view> kHandles = {"free", "aligned", "vector", "auto", "auto_clamped"};
const std::vector<std::string_view> kExtrap = {"constant", "linear"};
const std::vector<std::string_view> kSmooth = {"none", "cont_accel"};
const std::vector<std::string_view> kCycle = {"none", "repeat", "repeat_offset", "mirror"};

Expected<FCurveKey> parse_key(const json& j, const std::string& ptr) {
  if (!j.is_object()) return error_at(ErrorCode::InvalidArgument, "a key must be an object, found " + type_name(j), ptr);
  if (auto ok = only_members(j, ptr, {"frame", "value", "interpolation", "easing", "handle_left_type",
                                      "handle_right_type", "handle_left", "handle_right", "back", "amplitude",
                                      "period"});
      !ok) {
    return ok.error();
  }
  FCurveKey k;
  auto frame = number_member(j, ptr, "frame", std::nullopt);
  if (!frame) return frame.error();
  auto value = number_member(j, ptr, "value", std::nullopt);
  if (!value) return value.error();
  k.frame = *frame;
  k.value = *value;
  auto interp = enum_member(j, ptr, "interpolation", Interpolation::bezier, kInterp);
  if (!interp) return interp.error();
  auto easing = enum_member(j, ptr, "easing", KeyEasing::automatic, kEasing);
  if (!easing) return easing.error();
  auto hl = enum_member(j, ptr, "handle_left_type", HandleType::auto_clamped, kHandles);
  if (!hl) return hl.error();
  auto hr = enum_member(j, ptr, "handle_right_type", HandleType::auto_clamped, kHandles);
  if (!hr) return hr.error();
  k.interpolation = *interp;
  k.easing = *easing;
  k.handle_left_type = *hl;
  k.handle_right_type = *hr;
  auto needs = [](HandleType h) { return h == HandleType::free || h == HandleType::aligned; };
  auto pl = point_member(j, ptr, "handle_left", needs(k.handle_left_type));
  if (!pl) return pl.error();
  auto pr = point_member(j, ptr, "handle_right", needs(k.handle_right_type));
  if (!pr) return pr.error();
  // Handles not given (automatic types) start flat at one frame from the key, as Blender's insert() does.
  if (j.contains("handle_left")) k.handle_left = *pl;
  if (j.contains("handle_right")) k.handle_right = *pr;
  auto back = number_member(j, ptr, "back", 1.70158);
  if (!back) return back.error();
  auto amp = number_member(j, ptr, "amplitude", 0.8);
  if (!amp) return amp.error();
  auto period = number_member(j, ptr, "period", 4.1);
  if (!period) return period.error();
  k.back = *back;
  k.amplitude = *amp;
  k.period = *period;
  return k;
}

Expected<int> count_member(const json& obj, const std::string& ptr, std::string_view name) {
  auto v = number_member(obj, ptr, name, 0.0);
  if (!v) return v.error();
  if (*v < 0 || *v > 32767 || std::floor(*v) != *v) {
    return error_at(ErrorCode::InvalidArgument, "expected a whole number in 0..32767 (0 = forever)", child(ptr, name));
  }
  return int(*v);
}

Expected<SceneScalarTrack> parse_scalar_track(const json& j, const std::string& ptr) {
  if (auto ok = only_members(j, ptr, {"name", "kind", "keys", "extrapolation", "auto_smoothing", "cycles"}); !ok) {
    return ok.error();
  }
  SceneScalarTrack track;
  auto name_it = j.find("name");
  if (name_it == j.end() || !name_it->is_string() || name_it->get<std::string>().empty()) {
    return error_at(ErrorCode::InvalidArgument, "a track needs a non-empty string \"name\"", child(ptr, "name"));
  }
  track.name = name_it->get<std::string>();
  RawFCurve raw;
  auto extrap = enum_member(j, ptr, "extrapolation", Extrapolation::constant, kExtrap);
  if (!extrap) return extrap.error();
  auto smooth = enum_member(j, ptr, "auto_smoothing", AutoSmoothing::none, kSmooth);
  if (!smooth) return smooth.error();
  raw.extrapolation = *extrap;
  raw.auto_smoothing = *smooth;
  if (auto c = j.find("cycles"); c != j.end()) {
    const std::string cp = child(ptr, "cycles");
    if (!c->is_object()) return error_at(ErrorCode::InvalidArgument, "\"cycles\" must be an object", cp);
    if (auto ok = only_members(*c, cp, {"before", "after", "count_before", "count_after"}); !ok) return ok.error();
    FCurveCycles cyc;
    auto before = enum_member(*c, cp, "before", CycleMode::repeat, kCycle);
    if (!before) return before.error();
    auto after = enum_member(*c, cp, "after", CycleMode::repeat, kCycle);
    if (!after) return after.error();
    auto nb = count_member(*c, cp, "count_before");
    if (!nb) return nb.error();
    auto na = count_member(*c, cp, "count_after");
    if (!na) return na.error();
    cyc.before = *before;
    cyc.after = *after;
    cyc.count_before = *nb;
    cyc.count_after = *na;
    raw.cycles = cyc;
  }
  const std::string kp = child(ptr, "keys");
  auto keys = j.find("keys");
  if (keys == j.end()) return error_at(ErrorCode::InvalidArgument, "missing required member \"keys\"", kp);
  if (!keys->is_array()) return error_at(ErrorCode::InvalidArgument, "\"keys\" must be an array", kp);
  if (keys->empty()) return error_at(ErrorCode::TooFewPoints, "a track needs at least one key", kp);
  for (std::size_t i = 0; i < keys->size(); ++i) {
    auto key = parse_key((*keys)[i], child(kp, i));
    if (!key) return key.error();
    if (i > 0 && !(key->frame > raw.keys.back().frame)) {
      return error_at(ErrorCode::KeysNotIncreasing,
                      "frame " + shortest_text<double>(key->frame) + " is not after the previous key's frame " +
                          shortest_text<double>(raw.keys.back().frame) + " (keys must be sorted by strictly increasing frame)",
                      child(child(kp, i), "frame"));
    }
    raw.keys.push_back(*key);
  }
  auto built = build_fcurve(raw);
  if (!built) {
    Error e = built.error();
    // "key 3" from the builder → the pointer of that key.
    if (e.where.rfind("key ", 0) == 0) e.where = child(kp, std::size_t(std::stoul(e.where.substr(4))));
    else if (e.where == "cycles") e.where = child(ptr, "cycles");
    else e.where = ptr;
    return e;
  }
  track.curve = std::move(*built);
  return track;
}

const std::vector<std::string_view> kTangents = {"hermite", "catmull_rom", "kochanek_bartels", "flat",
                                                 "linear",  "clamped",     "plateau",          "stepped"};
const std::vector<std::string_view> kExtend = {"constant", "linear", "cycle", "cycle_offset", "oscillate"};

template <class Enum>
Expected<Enum> name_member(const json& obj, const std::string& ptr, std::string_view name, Enum fallback,
                           const std::vector<std::string_view>& names) {
  const std::string p = child(ptr, name);
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return fallback;
  if (!it->is_string()) return error_at(ErrorCode::InvalidArgument, "expected a string, found " + type_name(*it), p);
  const std::string s = it->get<std::string>();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == s) return static_cast<Enum>(i);
  std::string list;
  for (std::string_view a : names) list += (list.empty() ? "" : ", ") + std::string(a);
  return error_at(ErrorCode::InvalidArgument, "unknown " + std::string(name) + " \"" + s + "\" (expected one of: " + list + ")",
                  p);
}

Expected<Vec4d> vector_member(const json& obj, const std::string& ptr, std::string_view name, int dim, bool required) {
  const std::string p = child(ptr, name);
  auto it = obj.find(std::string(name));
  if (it == obj.end()) {
    if (!required) return Vec4d{};
    return error_at(ErrorCode::InvalidArgument, "missing required member \"" + std::string(name) + "\"", p);
  }
  if (!it->is_array() || int(it->size()) != dim) {
    return error_at(ErrorCode::WrongArity,
                    "expected an array of " + std::to_string(dim) + " numbers, found " +
                        (it->is_array() ? std::to_string(it->size()) + " elements" : type_name(*it)),
                    p);
  }
  Vec4d v{};
  for (int i = 0; i < dim; ++i) {
    auto x = get_number((*it)[std::size_t(i)], child(p, std::size_t(i)));
    if (!x) return x.error();
    v[i] = *x;
  }
  return v;
}

Expected<std::string> track_name(const json& j, const std::string& ptr) {
  auto name_it = j.find("name");
  if (name_it == j.end() || !name_it->is_string() || name_it->get<std::string>().empty()) {
    return error_at(ErrorCode::InvalidArgument, "a track needs a non-empty string \"name\"", child(ptr, "name"));
  }
  return name_it->get<std::string>();
}

// Maps a builder error "key 3" to the pointer of that key.
Error relocate(Error e, const std::string& keys_ptr, const std::string& fallback) {
  if (e.where.rfind("key ", 0) == 0) e.where = child(keys_ptr, std::size_t(std::stoul(e.where.substr(4))));
  else e.where = fallback;
  return e;
}

Expected<const json*> keys_array(const json& j, const std::string& ptr) {
  const std::string kp = child(ptr, "keys");
  auto keys = j.find("keys");
  if (keys == j.end()) return error_at(ErrorCode::InvalidArgument, "missing required member \"keys\"", kp);
  if (!keys->is_array()) return error_at(ErrorCode::InvalidArgument, "\"keys\" must be an array", kp);
  if (keys->empty()) return error_at(ErrorCode::TooFewPoints, "a track needs at least one key", kp);
  return &*keys;
}

// One key of a track's "keys" array: the object and its JSON pointer (/tracks/3/keys/2).
struct KeyObject {
  const json* value;
  std::string pointer;
};

// The "keys" array of a track object, each key checked to be an object with only `allowed` members.
Expected<std::vector<KeyObject>> key_objects(const json& j, const std::string& ptr,
                                             std::initializer_list<std::string_view> allowed) {
  auto keys = keys_array(j, ptr);
  if (!keys) return keys.error();
  const std::string kp = child(ptr, "keys");
  std::vector<KeyObject> out;
  for (std::size_t i = 0; i < (*keys)->size(); ++i) {
    const json& kj = (**keys)[i];
    std::string p = child(kp, i);
    if (!kj.is_object()) return error_at(ErrorCode::InvalidArgument, "a key must be an object, found " + type_name(kj), p);
    if (auto ok = only_members(kj, p, allowed); !ok) return ok.error();
    out.push_back({&kj, std::move(p)});
  }
  return out;
}

// Keys, before and after of a vector-valued track object (shared by vector tracks and the
// translation/scale channels of objects).
template <class V>
V shrink(const Vec4d& v) {
  if constexpr (std::is_same_v<V, Vec4d>) return v;
  else return V{v.x, v.y, v.z};
}

template <class V>
Expected<Track<V>> parse_vector_keys(const json& j, const std::string& ptr, int dim) {
  auto before = name_member(j, ptr, "before", TrackExtend::constant, kExtend);
  if (!before) return before.error();
  auto after = name_member(j, ptr, "after", TrackExtend::constant, kExtend);
  if (!after) return after.error();
  auto key_list = key_objects(j, ptr, {"frame", "value", "tangent", "in_tangent", "out_tangent", "tension",
                                       "continuity", "bias"});
  if (!key_list) return key_list.error();
  const std::string kp = child(ptr, "keys");
  std::vector<TrackKey<V>> raw;
  for (std::size_t i = 0; i < key_list->size(); ++i) {
    const json& kj = *(*key_list)[i].value;
    const std::string& p = (*key_list)[i].pointer;
    TrackKey<V> k;
    auto frame = number_member(kj, p, "frame", std::nullopt);
    if (!frame) return frame.error();
    auto value = vector_member(kj, p, "value", dim, true);
    if (!value) return value.error();
    auto tangent = name_member(kj, p, "tangent", TangentKind::catmull_rom, kTangents);
    if (!tangent) return tangent.error();
    const bool hermite = *tangent == TangentKind::explicit_hermite;
    auto tin = vector_member(kj, p, "in_tangent", dim, hermite);
    if (!tin) return tin.error();
    auto tout = vector_member(kj, p, "out_tangent", dim, hermite);
    if (!tout) return tout.error();
    k.frame = *frame;
    k.value = shrink<V>(*value);
    k.tangent = *tangent;
    k.in_tangent = shrink<V>(*tin);
    k.out_tangent = shrink<V>(*tout);
    for (auto [field, target] : {std::pair<std::string_view, double*>{"tension", &k.tension},
                                 {"continuity", &k.continuity}, {"bias", &k.bias}}) {
      auto v = number_member(kj, p, field, 0.0);
      if (!v) return v.error();
      if (*v < -1 || *v > 1) return error_at(ErrorCode::InvalidArgument, "must be in [-1, 1]", child(p, field));
      *target = *v;
    }
    if (i > 0 && !(k.frame > raw.back().frame)) {
      return error_at(ErrorCode::KeysNotIncreasing,
                      "frame " + shortest_text<double>(k.frame) + " is not after the previous key's frame " + shortest_text<double>(raw.back().frame) +
                          " (keys must be sorted by strictly increasing frame)",
                      child(p, "frame"));
    }
    raw.push_back(k);
  }
  auto built = build_track(raw, *before, *after);
  if (!built) return relocate(built.error(), kp, ptr);
  return std::move(*built);
}

Expected<SceneVectorTrack> parse_vector_track(const json& j, const std::string& ptr, const std::string& kind) {
  if (auto ok = only_members(j, ptr, {"name", "kind", "keys", "before", "after"}); !ok) return ok.error();
  SceneVectorTrack track;
  auto name = track_name(j, ptr);
  if (!name) return name.error();
  track.name = *name;
  track.dim = kind == "vec2" ? 2 : (kind == "vec3" ? 3 : 4);
  track.components = kind == "color" ? "rgba" : std::string("xyzw").substr(0, std::size_t(track.dim));
  auto built = parse_vector_keys<Vec4d>(j, ptr, track.dim);
  if (!built) return built.error();
  track.track = std::move(*built);
  return track;
}

const std::vector<std::string_view> kQuatInterp = {"step", "slerp", "bezier", "squad", "gltf_cubic"};

Quatd quat_from(const Vec4d& v) { return Quatd::from_wxyz(v.x, v.y, v.z, v.w); }

// Keys and options of a quaternion track object (values and tangents as [w, x, y, z]).
Expected<QuatTrack<double>> parse_quat_keys(const json& j, const std::string& ptr) {
  QuatSplineOptions<double> options;
  auto k = number_member(j, ptr, "distance_factor", 1.0 / 3.0);
  if (!k) return k.error();
  if (!(*k > 0 && *k <= 1)) return error_at(ErrorCode::InvalidArgument, "must be in (0, 1]", child(ptr, "distance_factor"));
  options.distance_factor = *k;
  auto time_aware = bool_member(j, ptr, "time_aware", options.time_aware);
  if (!time_aware) return time_aware.error();
  options.time_aware = *time_aware;
  auto key_list = key_objects(j, ptr, {"frame", "value", "interpolation", "long_way", "in_tangent", "out_tangent"});
  if (!key_list) return key_list.error();
  const std::string kp = child(ptr, "keys");
  std::vector<QuatKey<double>> raw;
  for (std::size_t i = 0; i < key_list->size(); ++i) {
    const json& kj = *(*key_list)[i].value;
    const std::string& p = (*key_list)[i].pointer;
    QuatKey<double> q;
    auto frame = number_member(kj, p, "frame", std::nullopt);
    if (!frame) return frame.error();
    auto value = vector_member(kj, p, "value", 4, true);
    if (!value) return value.error();
    auto interp = name_member(kj, p, "interpolation", QuatInterpolation::slerp, kQuatInterp);
    if (!interp) return interp.error();
    const bool gltf = *interp == QuatInterpolation::gltf_cubic;
    auto tin = vector_member(kj, p, "in_tangent", 4, gltf);
    if (!tin) return tin.error();
    auto tout = vector_member(kj, p, "out_tangent", 4, gltf);
    if (!tout) return tout.error();
    auto long_way = bool_member(kj, p, "long_way", false);
    if (!long_way) return long_way.error();
    q.long_way = *long_way;
    q.frame = *frame;
    q.value = quat_from(*value);
    q.interpolation = *interp;
    q.in_tangent = quat_from(*tin);
    q.out_tangent = quat_from(*tout);
    if (i > 0 && !(q.frame > raw.back().frame)) {
      return error_at(ErrorCode::KeysNotIncreasing,
                      "frame " + shortest_text<double>(q.frame) + " is not after the previous key's frame " + shortest_text<double>(raw.back().frame) +
                          " (keys must be sorted by strictly increasing frame)",
                      child(p, "frame"));
    }
    raw.push_back(q);
  }
  auto built = build_quat_track(raw, options);
  if (!built) {
    Error e = built.error();
    if (e.where.rfind("key ", 0) == 0) e.where = child(child(kp, std::size_t(std::stoul(e.where.substr(4)))), "value");
    else e.where = ptr;
    return e;
  }
  return std::move(*built);
}

Expected<SceneQuatTrack> parse_quat_track(const json& j, const std::string& ptr) {
  if (auto ok = only_members(j, ptr, {"name", "kind", "keys", "distance_factor", "time_aware"}); !ok) return ok.error();
  SceneQuatTrack track;
  auto name = track_name(j, ptr);
  if (!name) return name.error();
  track.name = *name;
  auto built = parse_quat_keys(j, ptr);
  if (!built) return built.error();
  track.track = std::move(*built);
  return track;
}

const std::vector<std::string_view> kEulerModes = {"angles", "quaternion"};

Expected<SceneEulerTrack> parse_euler_track(const json& j, const std::string& ptr) {
  if (auto ok = only_members(j, ptr, {"name", "kind", "keys", "convention", "units", "mode", "filter"}); !ok) {
    return ok.error();
  }
  SceneEulerTrack track;
  auto name = track_name(j, ptr);
  if (!name) return name.error();
  track.name = *name;
  EulerTrackOptions<double> options;
  const std::string cp = child(ptr, "convention");
  auto conv = j.find("convention");
  if (conv == j.end() || !conv->is_string()) {
    return error_at(ErrorCode::InvalidArgument, "an Euler track needs a \"convention\" such as \"XYZ\" or \"zxz\"", cp);
  }
  auto seq = parse_euler_sequence(conv->get<std::string>());
  if (!seq) return error_at(ErrorCode::InvalidArgument, seq.error().message, cp);
  options.sequence = *seq;
  double unit = 1;
  if (auto u = j.find("units"); u != j.end()) {
    if (!u->is_string() || (u->get<std::string>() != "rad" && u->get<std::string>() != "deg")) {
      return error_at(ErrorCode::InvalidArgument, "\"units\" must be \"rad\" or \"deg\"", child(ptr, "units"));
    }
    if (u->get<std::string>() == "deg") unit = pi_v<double> / 180;
  }
  auto mode = name_member(j, ptr, "mode", EulerTrackMode::angles, kEulerModes);
  if (!mode) return mode.error();
  options.mode = *mode;
  auto filter = bool_member(j, ptr, "filter", options.filter);
  if (!filter) return filter.error();
  options.filter = *filter;
  auto key_list = key_objects(j, ptr, {"frame", "value", "tangent", "interpolation"});
  if (!key_list) return key_list.error();
  const std::string kp = child(ptr, "keys");
  std::vector<EulerKey<double>> raw;
  for (std::size_t i = 0; i < key_list->size(); ++i) {
    const json& kj = *(*key_list)[i].value;
    const std::string& p = (*key_list)[i].pointer;
    EulerKey<double> k;
    auto frame = number_member(kj, p, "frame", std::nullopt);
    if (!frame) return frame.error();
    auto value = vector_member(kj, p, "value", 3, true);
    if (!value) return value.error();
    auto tangent = name_member(kj, p, "tangent", TangentKind::catmull_rom, kTangents);
    if (!tangent) return tangent.error();
    if (*tangent == TangentKind::explicit_hermite) {
      return error_at(ErrorCode::Unsupported, "Euler keys take no explicit tangents", child(p, "tangent"));
    }
    auto interp = name_member(kj, p, "interpolation", QuatInterpolation::slerp, kQuatInterp);
    if (!interp) return interp.error();
    if (*interp == QuatInterpolation::gltf_cubic) {
      return error_at(ErrorCode::Unsupported, "Euler keys take no glTF tangents", child(p, "interpolation"));
    }
    if (i > 0 && !(*frame > raw.back().frame)) {
      return error_at(ErrorCode::KeysNotIncreasing,
                      "frame " + shortest_text<double>(*frame) + " is not after the previous key's frame " + shortest_text<double>(raw.back().frame) +
                          " (keys must be sorted by strictly increasing frame)",
                      child(p, "frame"));
    }
    k.frame = *frame;
    k.angles_rad = {value->x * unit, value->y * unit, value->z * unit};
    k.tangent = *tangent;
    k.interpolation = *interp;
    raw.push_back(k);
  }
  auto built = build_euler_track(raw, options);
  if (!built) return relocate(built.error(), kp, ptr);
  track.track = std::move(*built);
  return track;
}

Vec3d xyz(const Vec4d& v) { return {v.x, v.y, v.z}; }

// An object's channel: a constant array, or a track object without name and kind.
Expected<std::optional<Track<Vec3d>>> vec3_channel(const json& obj, const std::string& ptr, std::string_view name,
                                                   Vec3d& rest) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return std::optional<Track<Vec3d>>{};
  const std::string p = child(ptr, name);
  if (it->is_array()) {
    auto v = vector_member(obj, ptr, name, 3, true);
    if (!v) return v.error();
    rest = xyz(*v);
    return std::optional<Track<Vec3d>>{};
  }
  if (!it->is_object()) return error_at(ErrorCode::InvalidArgument, "expected [x, y, z] or a track object", p);
  if (auto ok = only_members(*it, p, {"keys", "before", "after"}); !ok) return ok.error();
  auto built = parse_vector_keys<Vec3d>(*it, p, 3);
  if (!built) return built.error();
  return std::optional<Track<Vec3d>>{std::move(*built)};
}

Expected<TransformHierarchy<double>> parse_objects(const json& arr) {
  if (!arr.is_array()) return error_at(ErrorCode::InvalidArgument, "\"objects\" must be an array", "/objects");
  std::vector<HierarchyNode<double>> nodes;
  std::vector<std::string> parents;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json& oj = arr[i];
    const std::string p = child(std::string("/objects"), i);
    if (!oj.is_object()) return error_at(ErrorCode::InvalidArgument, "an object must be a JSON object", p);
    if (auto ok = only_members(oj, p, {"name", "parent", "translation", "rotation", "scale"}); !ok) return ok.error();
    HierarchyNode<double> node;
    auto name = track_name(oj, p);
    if (!name) return name.error();
    node.name = *name;
    for (const auto& other : nodes) {
      if (other.name == node.name) {
        return error_at(ErrorCode::InvalidArgument, "duplicate object name \"" + node.name + "\"", child(p, "name"));
      }
    }
    std::string parent;
    if (auto pj = oj.find("parent"); pj != oj.end() && !pj->is_null()) {
      if (!pj->is_string()) return error_at(ErrorCode::InvalidArgument, "\"parent\" must be an object name", child(p, "parent"));
      parent = pj->get<std::string>();
    }
    parents.push_back(parent);
    auto tr = vec3_channel(oj, p, "translation", node.local.rest.translation);
    if (!tr) return tr.error();
    node.local.translation = std::move(*tr);
    auto sc = vec3_channel(oj, p, "scale", node.local.rest.scale);
    if (!sc) return sc.error();
    node.local.scale = std::move(*sc);
    if (auto rj = oj.find("rotation"); rj != oj.end()) {
      const std::string rp = child(p, "rotation");
      if (rj->is_array()) {
        auto v = vector_member(oj, p, "rotation", 4, true);
        if (!v) return v.error();
        const Quatd q = quat_from(*v);
        if (!(norm(q) > 0)) return error_at(ErrorCode::InvalidArgument, "zero quaternion is not a rotation", rp);
        node.local.rest.rotation = normalized(q);
      } else if (rj->is_object()) {
        if (auto ok = only_members(*rj, rp, {"keys", "distance_factor", "time_aware"}); !ok) return ok.error();
        auto q = parse_quat_keys(*rj, rp);
        if (!q) return q.error();
        node.local.rotation = std::move(*q);
      } else {
        return error_at(ErrorCode::InvalidArgument, "expected [w, x, y, z] or a track object", rp);
      }
    }
    nodes.push_back(std::move(node));
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (parents[i].empty()) continue;
    bool found = false;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      if (nodes[k].name == parents[i]) {
        nodes[i].parent = k;
        found = true;
      }
    }
    if (!found) {
      return error_at(ErrorCode::InvalidArgument, "no object named \"" + parents[i] + "\"",
                      child(child(std::string("/objects"), i), "parent"));
    }
  }
  auto h = build_hierarchy(std::move(nodes));
  if (!h) {
    Error e = h.error();
    e.where = e.where.rfind("node ", 0) == 0 ? child(child(std::string("/objects"), std::size_t(std::stoul(e.where.substr(5)))), "parent")
                                             : std::string("/objects");
    return e;
  }
  return std::move(*h);
}

Expected<Scene> parse_scene_json(const json& root) {
  if (!root.is_object()) return error_at(ErrorCode::InvalidArgument, "a scene must be a JSON object", "");
  if (auto ok = only_members(root, "", {"inbetween", "fps", "range", "tracks", "objects"}); !ok) return ok.error();
  Scene scene;
  auto version = root.find("inbetween");
  if (version == root.end()) {
    return error_at(ErrorCode::InvalidArgument, "missing \"inbetween\": 1 (the format version)", "/inbetween");
  }
  if (!version->is_number_integer() || version->get<long long>() != 1) {
    return error_at(ErrorCode::Unsupported, "unsupported format version " + version->dump() + " (this reader knows 1)",
                    "/inbetween");
  }
  auto fps = number_member(root, "", "fps", 24.0);
  if (!fps) return fps.error();
  if (!(*fps > 0)) return error_at(ErrorCode::InvalidArgument, "fps must be positive", "/fps");
  scene.fps = *fps;
  if (auto r = root.find("range"); r != root.end()) {
    if (!r->is_array() || r->size() != 2) {
      return error_at(ErrorCode::WrongArity, "\"range\" must be [first_frame, last_frame]", "/range");
    }
    auto a = get_number((*r)[0], "/range/0");
    if (!a) return a.error();
    auto b = get_number((*r)[1], "/range/1");
    if (!b) return b.error();
    if (*b < *a) return error_at(ErrorCode::InvalidArgument, "range end is before its start", "/range/1");
    scene.range_start = *a;
    scene.range_end = *b;
  }
  std::vector<std::string> names;
  // Every output column belongs to one track or object: "p" (vec2) and a scalar "p.x" would both
  // write a column p.x.  Column → pointer of the name that made it.
  std::map<std::string, std::string> column_owner;
  auto claim = [&](const std::string& column, const std::string& owner) -> Expected<void> {
    const auto [it, inserted] = column_owner.emplace(column, owner);
    if (!inserted) {
      return error_at(ErrorCode::InvalidArgument,
                      "output column \"" + column + "\" is also a column of " + it->second + " (names must give distinct columns)",
                      owner);
    }
    return {};
  };
  if (auto t = root.find("tracks"); t != root.end()) {
    if (!t->is_array()) return error_at(ErrorCode::InvalidArgument, "\"tracks\" must be an array", "/tracks");
    for (std::size_t i = 0; i < t->size(); ++i) {
      const json& tj = (*t)[i];
      const std::string tp = child(std::string("/tracks"), i);
      if (!tj.is_object()) return error_at(ErrorCode::InvalidArgument, "a track must be an object", tp);
      std::string kind = "scalar";
      if (auto k = tj.find("kind"); k != tj.end()) {
        if (!k->is_string()) return error_at(ErrorCode::InvalidArgument, "\"kind\" must be a string", child(tp, "kind"));
        kind = k->get<std::string>();
      }
      std::string name;
      if (kind == "scalar") {
        auto track = parse_scalar_track(tj, tp);
        if (!track) return track.error();
        name = track->name;
        scene.track_order.emplace_back(SceneTrackKind::scalar, scene.scalar_tracks.size());
        scene.scalar_tracks.push_back(std::move(*track));
      } else if (kind == "vec2" || kind == "vec3" || kind == "vec4" || kind == "color") {
        auto track = parse_vector_track(tj, tp, kind);
        if (!track) return track.error();
        name = track->name;
        scene.track_order.emplace_back(SceneTrackKind::vector, scene.vector_tracks.size());
        scene.vector_tracks.push_back(std::move(*track));
      } else if (kind == "quaternion") {
        auto track = parse_quat_track(tj, tp);
        if (!track) return track.error();
        name = track->name;
        scene.track_order.emplace_back(SceneTrackKind::quaternion, scene.quat_tracks.size());
        scene.quat_tracks.push_back(std::move(*track));
      } else if (kind == "euler") {
        auto track = parse_euler_track(tj, tp);
        if (!track) return track.error();
        name = track->name;
        scene.track_order.emplace_back(SceneTrackKind::euler, scene.euler_tracks.size());
        scene.euler_tracks.push_back(std::move(*track));
      } else {
        return error_at(ErrorCode::InvalidArgument,
                        "unknown track kind \"" + kind + "\" (expected one of: scalar, vec2, vec3, vec4, color, quaternion, euler)",
                        child(tp, "kind"));
      }
      for (const auto& other : names) {
        if (other == name) {
          return error_at(ErrorCode::InvalidArgument, "duplicate track name \"" + name + "\"", child(tp, "name"));
        }
      }
      names.push_back(name);
      std::string suffixes;  // one letter per component column; none for a scalar track
      if (kind == "vec2" || kind == "vec3" || kind == "vec4" || kind == "color") suffixes = scene.vector_tracks.back().components;
      if (kind == "quaternion" || kind == "euler") suffixes = "wxyz";
      if (suffixes.empty()) {
        if (auto ok = claim(name, child(tp, "name")); !ok) return ok.error();
      }
      for (char c : suffixes) {
        if (auto ok = claim(name + "." + c, child(tp, "name")); !ok) return ok.error();
      }
    }
  }
  if (auto o = root.find("objects"); o != root.end()) {
    auto h = parse_objects(*o);
    if (!h) return h.error();
    scene.objects = std::move(*h);
    for (std::size_t i = 0; i < scene.objects->nodes().size(); ++i) {
      const std::string owner = child(child(std::string("/objects"), i), "name");
      for (std::string_view channel : {"translation.x", "translation.y", "translation.z", "rotation.w", "rotation.x",
                                       "rotation.y", "rotation.z", "scale.x", "scale.y", "scale.z"}) {
        if (auto ok = claim(scene.objects->nodes()[i].name + "." + std::string(channel), owner); !ok) return ok.error();
      }
    }
  }
  return scene;
}

}  // namespace

Expected<Scene> parse_scene(std::string_view json_text) {
  json root;
  try {
    root = json::parse(json_text.begin(), json_text.end());
  } catch (const json::parse_error& e) {
    // Convert the byte offset into line and column for the message.
    std::size_t line = 1, col = 1;
    const std::size_t upto = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, json_text.size());
    for (std::size_t i = 0; i < upto; ++i) {
      if (json_text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    return Error{ErrorCode::Parse, "not valid JSON", "line " + std::to_string(line) + ", column " + std::to_string(col)};
  }
  return parse_scene_json(root);
}

std::vector<SceneColumn> scene_columns(const Scene& scene) {
  std::vector<SceneColumn> cols;
  for (const auto& [kind, idx] : scene.track_order) {
    switch (kind) {
      case SceneTrackKind::scalar:
        cols.push_back({scene.scalar_tracks[idx].name, true});
        break;
      case SceneTrackKind::vector:
        for (char c : scene.vector_tracks[idx].components) cols.push_back({scene.vector_tracks[idx].name + "." + c, false});
        break;
      case SceneTrackKind::quaternion:
        for (char c : std::string("wxyz")) cols.push_back({scene.quat_tracks[idx].name + "." + c, false});
        break;
      case SceneTrackKind::euler:
        for (char c : std::string("wxyz")) cols.push_back({scene.euler_tracks[idx].name + "." + c, false});
        break;
    }
  }
  if (scene.objects) {
    for (const auto& node : scene.objects->nodes()) {
      for (char c : std::string("xyz")) cols.push_back({node.name + ".translation." + c, false});
      for (char c : std::string("wxyz")) cols.push_back({node.name + ".rotation." + c, false});
      for (char c : std::string("xyz")) cols.push_back({node.name + ".scale." + c, false});
    }
  }
  return cols;
}

void evaluate_scene(const Scene& scene, double frame, std::span<double> out) noexcept {
  // Beyond float's range the conversion is undefined; the nearest float frame is the largest one.
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  const float single_precision_frame = std::isnan(frame) ? std::numeric_limits<float>::quiet_NaN()
                                                         : float(std::clamp(frame, -kFloatMax, kFloatMax));
  std::size_t col = 0;
  auto put = [&](double v) {
    if (col < out.size()) out[col] = v;
    ++col;
  };
  for (const auto& [kind, idx] : scene.track_order) {
    switch (kind) {
      case SceneTrackKind::scalar:
        put(scene.scalar_tracks[idx].curve.evaluate(single_precision_frame));
        break;
      case SceneTrackKind::vector: {
        const auto& t = scene.vector_tracks[idx];
        const Vec4d v = t.track.sample(frame);
        for (int c = 0; c < t.dim; ++c) put(v[c]);
        break;
      }
      case SceneTrackKind::quaternion:
      case SceneTrackKind::euler: {
        const Quatd q = kind == SceneTrackKind::quaternion ? scene.quat_tracks[idx].track.sample(frame)
                                                          : scene.euler_tracks[idx].track.sample(frame);
        put(q.w);
        put(q.x);
        put(q.y);
        put(q.z);
        break;
      }
    }
  }
  if (scene.objects) {
    const auto nodes = scene.objects->nodes();
    // Small scenes: a fixed buffer avoids allocating; larger ones fall back to a vector.
    std::array<Transform<double>, 64> small;
    std::vector<Transform<double>> large;
    std::span<Transform<double>> world;
    if (nodes.size() <= small.size()) {
      world = std::span<Transform<double>>(small.data(), nodes.size());
    } else {
      large.resize(nodes.size());
      world = large;
    }
    scene.objects->sample_world(frame, world);
    for (const auto& trs : world) {
      put(trs.translation.x);
      put(trs.translation.y);
      put(trs.translation.z);
      put(trs.rotation.w);
      put(trs.rotation.x);
      put(trs.rotation.y);
      put(trs.rotation.z);
      put(trs.scale.x);
      put(trs.scale.y);
      put(trs.scale.z);
    }
  }
}

}  // namespace inbetween
