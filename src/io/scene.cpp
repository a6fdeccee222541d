// Reads the inbetween scene JSON format (docs/scene-format.md) into a RawScene: the document,
// tracks and version-1 objects here, version-2 members in scene_v2.cpp, shared helpers in
// scene_json.hpp.  nlohmann_json stays inside src/io.  The reader checks shape only (syntax, member types, unknown members, names
// of enumerations, the version); build_scene() does every other check.  Errors carry the JSON
// pointer as structured location steps; parse_scene() renders it once.
#include "inbetween/io/scene.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "scene_json.hpp"

namespace inbetween {

namespace {

using namespace io_detail;

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
    return error_at(ErrorCode::InvalidArgument, "expected a whole number in 0..32767 (0 = forever)", at(loc, std::string(name)));
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
Expected<RawQuatKeys> read_quat_keys_impl(const json& j, const Loc& loc) {
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

Expected<RawQuatTrack> read_quat_track(const json& j, const Loc& loc) {
  if (auto ok = only_members(j, loc, {"name", "kind", "keys", "distance_factor", "time_aware"}); !ok) return ok.error();
  RawQuatTrack track;
  auto name = name_of(j, loc);
  if (!name) return name.error();
  track.name = *name;
  auto keys = read_quat_keys_impl(j, loc);
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
    return error_at(ErrorCode::InvalidArgument, "an Euler track needs a \"convention\" such as \"XYZ\" or \"zxz\"",
                    at(loc, "convention"));
  }
  track.convention = conv->get<std::string>();
  auto units = name_member(j, loc, "units", AngleUnits::rad, kUnits);
  if (!units) return error_at(ErrorCode::InvalidArgument, "\"units\" must be \"rad\" or \"deg\"", at(loc, "units"));
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

Expected<RawTrack> read_track(const json& tj, const Loc& loc) {
  if (!tj.is_object()) return error_at(ErrorCode::InvalidArgument, "a track must be an object", loc);
  std::string kind = "scalar";
  if (auto k = tj.find("kind"); k != tj.end()) {
    if (!k->is_string()) return error_at(ErrorCode::InvalidArgument, "\"kind\" must be a string", at(loc, "kind"));
    kind = k->get<std::string>();
  }
  auto wrap = [](auto&& t) -> Expected<RawTrack> {
    if (!t) return t.error();
    return RawTrack{std::move(*t)};
  };
  if (kind == "scalar") return wrap(read_scalar_track(tj, loc));
  if (kind == "vec1") return wrap(read_vector_track(tj, loc, VectorKind::vec1));
  if (kind == "vec2") return wrap(read_vector_track(tj, loc, VectorKind::vec2));
  if (kind == "vec3") return wrap(read_vector_track(tj, loc, VectorKind::vec3));
  if (kind == "vec4") return wrap(read_vector_track(tj, loc, VectorKind::vec4));
  if (kind == "color") return wrap(read_vector_track(tj, loc, VectorKind::color));
  if (kind == "quaternion") return wrap(read_quat_track(tj, loc));
  if (kind == "euler") return wrap(read_euler_track(tj, loc));
  return error_at(ErrorCode::InvalidArgument,
                  "unknown track kind \"" + io_detail::truncated(kind) +
                      "\" (expected one of: scalar, vec1, vec2, vec3, vec4, color, quaternion, euler)",
                  at(loc, "kind"));
}

// ------------------------------------------------------------------ objects
// A translation or scale channel: a constant array, or a track object without name and kind.
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
  if (!it->is_object()) return error_at(ErrorCode::InvalidArgument, "expected [x, y, z] or a track object", p);
  if (auto ok = only_members(*it, p, {"keys", "before", "after"}); !ok) return ok.error();
  RawVec3Channel keyed;
  if (auto ok = read_vector_keys<Vec3d>(*it, p, 3, keyed.keys, keyed.before, keyed.after); !ok) return ok.error();
  channel = std::move(keyed);
  return {};
}

Expected<RawObject> read_object(const json& oj, const Loc& p, const Context& cx) {
  if (!oj.is_object()) return error_at(ErrorCode::InvalidArgument, "an object must be a JSON object", p);
  if (auto ok = only_members(oj, p, {"name", "parent", "translation", "rotation", "scale", "path", "camera"}); !ok) {
    return ok.error();
  }
  RawObject object;
  auto name = name_of(oj, p);
  if (!name) return name.error();
  object.name = *name;
  if (auto pj = oj.find("parent"); pj != oj.end() && !pj->is_null()) {
    if (!pj->is_string()) return error_at(ErrorCode::InvalidArgument, "\"parent\" must be an object name", at(p, "parent"));
    object.parent = pj->get<std::string>();
  }
  if (oj.contains("translation")) {
    std::variant<Vec3d, RawVec3Channel> translation = Vec3d{};
    if (auto ok = read_vec3_channel(oj, p, "translation", translation); !ok) return ok.error();
    object.translation = std::move(translation);
  }
  if (auto ok = read_vec3_channel(oj, p, "scale", object.scale); !ok) return ok.error();
  if (auto rj = oj.find("rotation"); rj != oj.end()) {
    const Loc rp = at(p, "rotation");
    if (rj->is_array()) {
      auto v = vector_member(oj, p, "rotation", 4, true);
      if (!v) return v.error();
      object.rotation = quat_from(*v);
    } else if (rj->is_object()) {
      if (auto ok = only_members(*rj, rp, {"keys", "distance_factor", "time_aware"}); !ok) return ok.error();
      auto q = read_quat_keys_impl(*rj, rp);
      if (!q) return q.error();
      object.rotation = std::move(*q);
    } else {
      return error_at(ErrorCode::InvalidArgument, "expected [w, x, y, z] or a track object", rp);
    }
  }
  if (auto ok = read_path_and_camera(oj, p, cx, object); !ok) return ok.error();
  return object;
}

// ------------------------------------------------------------------ the document
Expected<RawScene> read_scene(const json& root, Context cx) {
  const Loc doc;
  if (!root.is_object()) return error_at(ErrorCode::InvalidArgument, "a scene must be a JSON object", doc);
  if (auto ok = only_members(root, doc, {"inbetween", "fps", "range", "tracks", "paths", "objects", "skins"}); !ok) return ok.error();
  RawScene scene;
  auto version = root.find("inbetween");
  if (version == root.end()) {
    return error_at(ErrorCode::InvalidArgument, "missing \"inbetween\": 1 (the format version)", {"inbetween"});
  }
  if (!version->is_number_integer() || version->get<long long>() < scene_format_version_min ||
      version->get<long long>() > scene_format_version_max) {
    return error_at(ErrorCode::Unsupported,
                    "unsupported format version " + io_detail::short_dump(*version) + " (this reader knows 1 and 2)",
                    {"inbetween"});
  }
  cx.version = int(version->get<long long>());
  for (std::string_view member : {"paths", "skins"}) {
    if (auto ok = needs_version_2(root, doc, cx, member); !ok) return ok.error();
  }
  auto fps = number_member(root, doc, "fps", 24.0);
  if (!fps) return fps.error();
  scene.fps = *fps;
  if (auto r = root.find("range"); r != root.end()) {
    if (!r->is_array() || r->size() != 2) {
      return error_at(ErrorCode::WrongArity, "\"range\" must be [first_frame, last_frame]", {"range"});
    }
    for (std::size_t i = 0; i < 2; ++i) {
      auto v = get_number((*r)[i], {"range", i});
      if (!v) return v.error();
      scene.range[i] = *v;
    }
  }
  if (auto t = root.find("tracks"); t != root.end()) {
    if (!t->is_array()) return error_at(ErrorCode::InvalidArgument, "\"tracks\" must be an array", {"tracks"});
    for (std::size_t i = 0; i < t->size(); ++i) {
      auto track = read_track((*t)[i], {"tracks", i});
      if (!track) return track.error();
      scene.tracks.push_back(std::move(*track));
    }
  }
  if (auto ok = read_paths(root, cx, scene); !ok) return ok.error();
  if (auto o = root.find("objects"); o != root.end()) {
    if (!o->is_array()) return error_at(ErrorCode::InvalidArgument, "\"objects\" must be an array", {"objects"});
    for (std::size_t i = 0; i < o->size(); ++i) {
      auto object = read_object((*o)[i], {"objects", i}, cx);
      if (!object) return object.error();
      scene.objects.push_back(std::move(*object));
    }
  }
  if (auto ok = read_skins(root, scene); !ok) return ok.error();
  return scene;
}

}  // namespace

Expected<RawQuatKeys> io_detail::read_quat_keys(const json& j, const Loc& loc) { return read_quat_keys_impl(j, loc); }

Expected<RawScene> read_scene_json(std::string_view json_text, std::string_view source_path) {
  io_detail::JsonText parsed = io_detail::parse_json_text(json_text);
  const std::string place = "line " + std::to_string(parsed.line) + ", column " + std::to_string(parsed.column);
  switch (parsed.failure) {
    case io_detail::JsonFailure::none:
      return read_scene(parsed.value, Context{1, source_path.empty() || source_path == "-"
                                                    ? std::filesystem::path()
                                                    : std::filesystem::path(source_path).parent_path()});
    case io_detail::JsonFailure::syntax:
      return Error{ErrorCode::Parse, "not valid JSON", place};
    case io_detail::JsonFailure::number_out_of_range:
      return Error{ErrorCode::Parse, "the number " + parsed.detail + " is beyond double precision's range", place};
    case io_detail::JsonFailure::too_deep:
      return Error{ErrorCode::Parse, "JSON " + parsed.detail + " (not accepted)", place};
  }
  return Error{ErrorCode::Parse, "not valid JSON", place};
}

Expected<Scene> parse_scene(std::string_view json_text, std::string_view source_path) {
  auto raw = read_scene_json(json_text, source_path);
  Expected<Scene> scene = raw ? build_scene(*raw) : Expected<Scene>(raw.error());
  if (scene) return scene;
  Error e = scene.error();
  if (e.where.empty()) e.where = e.location.empty() ? std::string("/") : json_pointer(e.location);
  return e;
}

}  // namespace inbetween
