// The scene file's tracks and keyed channels (src/io/scene_file.hpp lists the parts): "tracks" of
// every kind — scalar F-curves, vectors, quaternions, Euler angles — and the keys of objects'
// translation, rotation and scale channels, each read and written side by side with one name table
// per enumeration.
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene_file.hpp"

namespace inbetween::io_detail {

namespace {

// ------------------------------------------------------------------ scalar tracks (F-curves)
constexpr std::span<const std::string_view> kInterp = enum_names<Interpolation>();
constexpr std::span<const std::string_view> kEasing = enum_names<KeyEasing>();
constexpr std::span<const std::string_view> kHandles = enum_names<HandleType>();
constexpr std::span<const std::string_view> kExtrap = enum_names<Extrapolation>();
constexpr std::span<const std::string_view> kSmooth = enum_names<AutoSmoothing>();
constexpr std::span<const std::string_view> kCycle = enum_names<CycleMode>();

Expected<FCurveKey> read_fcurve_key(const json& j, const Loc& loc) {
  FCurveKey k;
  auto frame = number_member(j, loc, "frame", std::nullopt);
  if (!frame) return frame.error();
  auto value = number_member(j, loc, "value", std::nullopt);
  if (!value) return value.error();
  k.frame = *frame;
  k.value = *value;
  auto interp = enum_member(j, loc, "interpolation", Interpolation::bezier, kInterp);
  if (!interp) return interp.error();
  auto easing = enum_member(j, loc, "easing", KeyEasing::automatic, kEasing);
  if (!easing) return easing.error();
  auto hl = enum_member(j, loc, "handle_left_type", HandleType::auto_clamped, kHandles);
  if (!hl) return hl.error();
  auto hr = enum_member(j, loc, "handle_right_type", HandleType::auto_clamped, kHandles);
  if (!hr) return hr.error();
  k.interpolation = *interp;
  k.easing = *easing;
  k.handle_left_type = *hl;
  k.handle_right_type = *hr;
  auto needs = [](HandleType h) { return h == HandleType::free || h == HandleType::aligned; };
  auto pl = point_member(j, loc, "handle_left", needs(k.handle_left_type));
  if (!pl) return pl.error();
  auto pr = point_member(j, loc, "handle_right", needs(k.handle_right_type));
  if (!pr) return pr.error();
  // Handles not given (automatic types) start flat at one frame from the key, as Blender's insert() does.
  k.handle_left = *pl;
  k.handle_right = *pr;
  auto back = number_member(j, loc, "back", 1.70158);
  if (!back) return back.error();
  auto amp = number_member(j, loc, "amplitude", 0.8);
  if (!amp) return amp.error();
  auto period = number_member(j, loc, "period", 4.1);
  if (!period) return period.error();
  k.back = *back;
  k.amplitude = *amp;
  k.period = *period;
  return k;
}

// A cycle count: a whole number that fits an int (its range, 0..32767, is build_fcurve()'s check).
Expected<int> count_member(const json& obj, const Loc& loc, std::string_view name) {
  auto v = number_member(obj, loc, name, 0.0);
  if (!v) return v.error();
  if (std::floor(*v) != *v || std::abs(*v) > double(std::numeric_limits<int>::max())) {
    return error_at(ErrorCode::invalid_argument, "expected a whole number in 0..32767 (0 = forever)", at(loc, std::string(name)));
  }
  return int(*v);
}

Expected<RawScalarTrack> read_scalar_track(const json& j, const Loc& loc) {
  if (auto ok = only_members(j, loc, {"name", "kind", "keys", "extrapolation", "auto_smoothing", "cycles"}); !ok) {
    return ok.error();
  }
  RawScalarTrack track;
  auto name = name_of(j, loc);
  if (!name) return name.error();
  track.name = *name;
  auto extrap = enum_member(j, loc, "extrapolation", Extrapolation::constant, kExtrap);
  if (!extrap) return extrap.error();
  auto smooth = enum_member(j, loc, "auto_smoothing", AutoSmoothing::none, kSmooth);
  if (!smooth) return smooth.error();
  track.curve.extrapolation = *extrap;
  track.curve.auto_smoothing = *smooth;
  if (auto c = j.find("cycles"); c != j.end()) {
    const Loc cp = at(loc, "cycles");
    if (!c->is_object()) return error_at(ErrorCode::invalid_argument, "\"cycles\" must be an object", cp);
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
    track.curve.cycles = cyc;
  }
  auto keys = key_array(j, loc, {"frame", "value", "interpolation", "easing", "handle_left_type", "handle_right_type",
                                 "handle_left", "handle_right", "back", "amplitude", "period"});
  if (!keys) return keys.error();
  for (std::size_t i = 0; i < (*keys)->size(); ++i) {
    auto key = read_fcurve_key((**keys)[i], at(at(loc, "keys"), i));
    if (!key) return key.error();
    track.curve.keys.push_back(*key);
  }
  return track;
}

// ------------------------------------------------------------------ vector, quaternion, Euler tracks
constexpr std::span<const std::string_view> kTangents = enum_names<TangentKind>();
constexpr std::span<const std::string_view> kExtend = enum_names<TrackExtend>();
constexpr std::span<const std::string_view> kQuatInterp = enum_names<QuatInterpolation>();
constexpr std::string_view kUnits[] = {"rad", "deg"};
constexpr std::span<const std::string_view> kEulerModes = enum_names<EulerTrackMode>();
constexpr std::array<std::string_view, 5> kVectorKinds = {"vec2", "vec3", "vec4", "color", "vec1"};  // VectorKind order
constexpr int kVectorDims[] = {2, 3, 4, 4, 1};

template <class V>
V shrink(const Vec4d& v) {
  if constexpr (std::is_same_v<V, Vec4d>) return v;
  else return V{v.x, v.y, v.z};
}

// Keys, before and after of a vector-valued track object (vector tracks and the translation and
// scale channels of objects).
template <class V>
Expected<void> read_vector_keys(const json& j, const Loc& loc, int dim, std::vector<TrackKey<V>>& keys,
                                TrackExtend& before, TrackExtend& after) {
  auto b = name_member(j, loc, "before", TrackExtend::constant, kExtend);
  if (!b) return b.error();
  auto a = name_member(j, loc, "after", TrackExtend::constant, kExtend);
  if (!a) return a.error();
  before = *b;
  after = *a;
  auto list = key_array(j, loc, {"frame", "value", "tangent", "in_tangent", "out_tangent", "tension", "continuity", "bias"});
  if (!list) return list.error();
  for (std::size_t i = 0; i < (*list)->size(); ++i) {
    const json& kj = (**list)[i];
    const Loc p = at(at(loc, "keys"), i);
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
      *target = *v;
    }
    keys.push_back(k);
  }
  return {};
}

Expected<RawVectorTrack> read_vector_track(const json& j, const Loc& loc, VectorKind kind) {
  if (auto ok = only_members(j, loc, {"name", "kind", "keys", "before", "after"}); !ok) return ok.error();
  RawVectorTrack track;
  auto name = name_of(j, loc);
  if (!name) return name.error();
  track.name = *name;
  track.kind = kind;
  const int dim = kind == VectorKind::vec1 ? 1 : kind == VectorKind::vec2 ? 2 : (kind == VectorKind::vec3 ? 3 : 4);
  if (auto ok = read_vector_keys<Vec4d>(j, loc, dim, track.keys, track.before, track.after); !ok) return ok.error();
  return track;
}

// Keys and options of a quaternion track object (values and tangents as [w, x, y, z]).
}  // namespace

Expected<RawQuatKeys> read_quat_keys(const json& j, const Loc& loc) {
  RawQuatKeys out;
  auto k = number_member(j, loc, "distance_factor", 1.0 / 3.0);
  if (!k) return k.error();
  out.distance_factor = *k;
  auto time_aware = bool_member(j, loc, "time_aware", true);
  if (!time_aware) return time_aware.error();
  out.time_aware = *time_aware;
  auto list = key_array(j, loc, {"frame", "value", "interpolation", "long_way", "in_tangent", "out_tangent"});
  if (!list) return list.error();
  for (std::size_t i = 0; i < (*list)->size(); ++i) {
    const json& kj = (**list)[i];
    const Loc p = at(at(loc, "keys"), i);
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
    out.keys.push_back(q);
    // Tangents only once some key has them (given, or required by gltf_cubic); the keys before
    // it had none, i.e. zero.
    const QuatKeyTangents<double> t{quat_from(*tin), quat_from(*tout)};
    if (!out.tangents.empty() || gltf || t != QuatKeyTangents<double>{}) {
      out.tangents.resize(i + 1);
      out.tangents.back() = t;
    }
  }
  return out;
}

namespace {


Expected<RawQuatTrack> read_quat_track(const json& j, const Loc& loc) {
  if (auto ok = only_members(j, loc, {"name", "kind", "keys", "distance_factor", "time_aware"}); !ok) return ok.error();
  RawQuatTrack track;
  auto name = name_of(j, loc);
  if (!name) return name.error();
  track.name = *name;
  auto keys = read_quat_keys(j, loc);
  if (!keys) return keys.error();
  track.keys = std::move(keys->keys);
  track.tangents = std::move(keys->tangents);
  track.distance_factor = keys->distance_factor;
  track.time_aware = keys->time_aware;
  return track;
}

Expected<RawEulerTrack> read_euler_track(const json& j, const Loc& loc) {
  if (auto ok = only_members(j, loc, {"name", "kind", "keys", "convention", "units", "mode", "filter"}); !ok) {
    return ok.error();
  }
  RawEulerTrack track;
  auto name = name_of(j, loc);
  if (!name) return name.error();
  track.name = *name;
  auto conv = j.find("convention");
  if (conv == j.end() || !conv->is_string()) {
    return error_at(ErrorCode::invalid_argument, "an Euler track needs a \"convention\" such as \"XYZ\" or \"zxz\"",
                    at(loc, "convention"));
  }
  track.convention = conv->get<std::string>();
  auto units = name_member(j, loc, "units", AngleUnits::rad, kUnits);
  if (!units) return error_at(ErrorCode::invalid_argument, "\"units\" must be \"rad\" or \"deg\"", at(loc, "units"));
  track.units = *units;
  auto mode = name_member(j, loc, "mode", EulerTrackMode::angles, kEulerModes);
  if (!mode) return mode.error();
  track.mode = *mode;
  auto filter = bool_member(j, loc, "filter", true);
  if (!filter) return filter.error();
  track.filter = *filter;
  auto list = key_array(j, loc, {"frame", "value", "tangent", "interpolation"});
  if (!list) return list.error();
  for (std::size_t i = 0; i < (*list)->size(); ++i) {
    const json& kj = (**list)[i];
    const Loc p = at(at(loc, "keys"), i);
    RawEulerKey k;
    auto frame = number_member(kj, p, "frame", std::nullopt);
    if (!frame) return frame.error();
    auto value = vector_member(kj, p, "value", 3, true);
    if (!value) return value.error();
    auto tangent = name_member(kj, p, "tangent", TangentKind::catmull_rom, kTangents);
    if (!tangent) return tangent.error();
    auto interp = name_member(kj, p, "interpolation", QuatInterpolation::slerp, kQuatInterp);
    if (!interp) return interp.error();
    k.frame = *frame;
    k.value = xyz(*value);
    k.tangent = *tangent;
    k.interpolation = *interp;
    track.keys.push_back(k);
  }
  return track;
}

}  // namespace

Expected<RawTrack> read_track(const json& tj, const Loc& loc) {
  if (!tj.is_object()) return error_at(ErrorCode::invalid_argument, "a track must be an object", loc);
  std::string kind = "scalar";
  if (auto k = tj.find("kind"); k != tj.end()) {
    if (!k->is_string()) return error_at(ErrorCode::invalid_argument, "\"kind\" must be a string", at(loc, "kind"));
    kind = k->get<std::string>();
  }
  auto wrap = [](auto&& t) -> Expected<RawTrack> {
    if (!t) return t.error();
    return RawTrack{std::move(*t)};
  };
  if (kind == "scalar") return wrap(read_scalar_track(tj, loc));
  for (std::size_t v = 0; v < kVectorKinds.size(); ++v) {
    if (kind == kVectorKinds[v]) return wrap(read_vector_track(tj, loc, VectorKind(v)));
  }
  if (kind == "quaternion") return wrap(read_quat_track(tj, loc));
  if (kind == "euler") return wrap(read_euler_track(tj, loc));
  return error_at(ErrorCode::invalid_argument,
                  "unknown track kind \"" + io_detail::truncated(kind) +
                      "\" (expected one of: scalar, vec1, vec2, vec3, vec4, color, quaternion, euler)",
                  at(loc, "kind"));
}

Expected<void> read_vec3_channel(const json& obj, const Loc& loc, std::string_view name,
                                 std::variant<Vec3d, RawVec3Channel>& channel) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return {};
  const Loc p = at(loc, std::string(name));
  if (it->is_array()) {
    auto v = vector_member(obj, loc, name, 3, true);
    if (!v) return v.error();
    channel = xyz(*v);
    return {};
  }
  if (!it->is_object()) return error_at(ErrorCode::invalid_argument, "expected [x, y, z] or a track object", p);
  if (auto ok = only_members(*it, p, {"keys", "before", "after"}); !ok) return ok.error();
  RawVec3Channel keyed;
  if (auto ok = read_vector_keys<Vec3d>(*it, p, 3, keyed.keys, keyed.before, keyed.after); !ok) return ok.error();
  channel = std::move(keyed);
  return {};
}

// ------------------------------------------------------------------ writing
// Keys of a vector-valued track or channel (dim components), with "before"/"after" into `out`.
template <class V>
void SceneWriter::vector_keys(ojson& out, const std::vector<TrackKey<V>>& keys, TrackExtend before, TrackExtend after, int dim,
                 const Loc& loc) {
  auto widen = [](const V& v) {
    if constexpr (std::is_same_v<V, Vec4d>) return v;
    else return Vec4d{v.x, v.y, v.z, 0};
  };
  ojson list = ojson::array();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const auto& k = keys[i];
    const auto kl = at(at(loc, "keys"), i);
    ojson kj = ojson::object();
    kj["frame"] = number(k.frame, at(kl, "frame"));
    kj["value"] = vec(widen(k.value), dim, at(kl, "value"));
    if (k.tangent != TangentKind::catmull_rom) kj["tangent"] = enum_text(k.tangent, kTangents);
    const bool hermite = k.tangent == TangentKind::explicit_hermite;
    if (hermite || widen(k.in_tangent) != Vec4d{}) kj["in_tangent"] = vec(widen(k.in_tangent), dim, at(kl, "in_tangent"));
    if (hermite || widen(k.out_tangent) != Vec4d{}) kj["out_tangent"] = vec(widen(k.out_tangent), dim, at(kl, "out_tangent"));
    if (k.tension != 0) kj["tension"] = number(k.tension, at(kl, "tension"));
    if (k.continuity != 0) kj["continuity"] = number(k.continuity, at(kl, "continuity"));
    if (k.bias != 0) kj["bias"] = number(k.bias, at(kl, "bias"));
    list.push_back(std::move(kj));
  }
  out["keys"] = std::move(list);
  if (before != TrackExtend::constant) out["before"] = enum_text(before, kExtend);
  if (after != TrackExtend::constant) out["after"] = enum_text(after, kExtend);
}

void SceneWriter::quat_keys(ojson& out, const std::vector<QuatKey<double>>& keys, const std::vector<QuatKeyTangents<double>>& tangents,
               double distance_factor, bool time_aware, const Loc& loc) {
  ojson list = ojson::array();
  const Quatd zero = Quatd::from_wxyz(0, 0, 0, 0);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const auto& k = keys[i];
    const auto kl = at(at(loc, "keys"), i);
    ojson kj = ojson::object();
    kj["frame"] = number(k.frame, at(kl, "frame"));
    kj["value"] = quat(k.value, at(kl, "value"));
    if (k.interpolation != QuatInterpolation::slerp) kj["interpolation"] = enum_text(k.interpolation, kQuatInterp);
    if (k.long_way) kj["long_way"] = true;
    const bool gltf = k.interpolation == QuatInterpolation::gltf_cubic;
    const QuatKeyTangents<double> t = i < tangents.size() ? tangents[i] : QuatKeyTangents<double>{};
    if (gltf || !(t.in == zero)) kj["in_tangent"] = quat(t.in, at(kl, "in_tangent"));
    if (gltf || !(t.out == zero)) kj["out_tangent"] = quat(t.out, at(kl, "out_tangent"));
    list.push_back(std::move(kj));
  }
  out["keys"] = std::move(list);
  if (distance_factor != 1.0 / 3.0) out["distance_factor"] = number(distance_factor, at(loc, "distance_factor"));
  if (!time_aware) out["time_aware"] = false;
}

ojson SceneWriter::track(const RawScalarTrack& t, const Loc& loc) {
  ojson j = ojson::object();
  j["name"] = t.name;
  j["kind"] = "scalar";
  const RawFCurve& c = t.curve;
  if (c.extrapolation != Extrapolation::constant) j["extrapolation"] = std::string(to_string(c.extrapolation));
  if (c.auto_smoothing != AutoSmoothing::none) j["auto_smoothing"] = std::string(to_string(c.auto_smoothing));
  if (c.cycles) {
    ojson cj = ojson::object();
    cj["before"] = std::string(to_string(c.cycles->before));
    cj["after"] = std::string(to_string(c.cycles->after));
    cj["count_before"] = c.cycles->count_before;
    cj["count_after"] = c.cycles->count_after;
    j["cycles"] = std::move(cj);
  }
  ojson list = ojson::array();
  const FCurveKey defaults;
  for (std::size_t i = 0; i < c.keys.size(); ++i) {
    const FCurveKey& k = c.keys[i];
    const auto kl = at(at(loc, "keys"), i);
    ojson kj = ojson::object();
    kj["frame"] = number(k.frame, at(kl, "frame"));
    kj["value"] = number(k.value, at(kl, "value"));
    if (k.interpolation != defaults.interpolation) kj["interpolation"] = std::string(to_string(k.interpolation));
    if (k.easing != defaults.easing) kj["easing"] = std::string(to_string(k.easing));
    if (k.handle_left_type != defaults.handle_left_type) kj["handle_left_type"] = std::string(to_string(k.handle_left_type));
    if (k.handle_right_type != defaults.handle_right_type) kj["handle_right_type"] = std::string(to_string(k.handle_right_type));
    if (k.handle_left) kj["handle_left"] = numbers({k.handle_left->x, k.handle_left->y}, at(kl, "handle_left"));
    if (k.handle_right) kj["handle_right"] = numbers({k.handle_right->x, k.handle_right->y}, at(kl, "handle_right"));
    if (k.back != defaults.back) kj["back"] = number(k.back, at(kl, "back"));
    if (k.amplitude != defaults.amplitude) kj["amplitude"] = number(k.amplitude, at(kl, "amplitude"));
    if (k.period != defaults.period) kj["period"] = number(k.period, at(kl, "period"));
    list.push_back(std::move(kj));
  }
  j["keys"] = std::move(list);
  return j;
}

ojson SceneWriter::track(const RawVectorTrack& t, const Loc& loc) {
  ojson j = ojson::object();
  j["name"] = t.name;
  j["kind"] = enum_text(t.kind, kVectorKinds);
  vector_keys(j, t.keys, t.before, t.after, kVectorDims[std::size_t(t.kind)], loc);
  return j;
}

ojson SceneWriter::track(const RawQuatTrack& t, const Loc& loc) {
  ojson j = ojson::object();
  j["name"] = t.name;
  j["kind"] = "quaternion";
  quat_keys(j, t.keys, t.tangents, t.distance_factor, t.time_aware, loc);
  return j;
}

ojson SceneWriter::track(const RawEulerTrack& t, const Loc& loc) {
  ojson j = ojson::object();
  j["name"] = t.name;
  j["kind"] = "euler";
  j["convention"] = t.convention;
  if (t.units != AngleUnits::rad) j["units"] = enum_text(t.units, kUnits);
  if (t.mode != EulerTrackMode::angles) j["mode"] = enum_text(t.mode, kEulerModes);
  if (!t.filter) j["filter"] = false;
  ojson list = ojson::array();
  for (std::size_t i = 0; i < t.keys.size(); ++i) {
    const RawEulerKey& k = t.keys[i];
    const auto kl = at(at(loc, "keys"), i);
    ojson kj = ojson::object();
    kj["frame"] = number(k.frame, at(kl, "frame"));
    kj["value"] = vec3(k.value, at(kl, "value"));
    if (k.tangent != TangentKind::catmull_rom) kj["tangent"] = enum_text(k.tangent, kTangents);
    if (k.interpolation != QuatInterpolation::slerp) kj["interpolation"] = enum_text(k.interpolation, kQuatInterp);
    list.push_back(std::move(kj));
  }
  j["keys"] = std::move(list);
  return j;
}

ojson SceneWriter::vec3_channel(const std::variant<Vec3d, RawVec3Channel>& c, const Loc& loc) {
  if (const auto* v = std::get_if<Vec3d>(&c)) return vec3(*v, loc);
  const auto& keyed = std::get<RawVec3Channel>(c);
  ojson j = ojson::object();
  vector_keys(j, keyed.keys, keyed.before, keyed.after, 3, loc);
  return j;
}

}  // namespace inbetween::io_detail
