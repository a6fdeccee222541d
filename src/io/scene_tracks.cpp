// The scene file's tracks and keyed channels (src/io/scene_file.hpp lists the parts): "tracks" of
// every kind — scalar F-curves, vectors, quaternions, Euler angles — and the keys of objects'
// translation, rotation and scale channels, each read and written side by side with one name table
// per enumeration.
#include <array>
#include <initializer_list>
#include <optional>
#include <variant>
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

// ------------------------------------------------------------------ F-curve modifiers
constexpr std::span<const std::string_view> kGenModes = enum_names<GeneratorMode>();
constexpr std::span<const std::string_view> kFunctions = enum_names<BuiltinFunction>();
constexpr std::span<const std::string_view> kNoiseBlend = enum_names<NoiseBlend>();

// An optional number member that may also be null (off): nullopt when absent or null.
Expected<std::optional<double>> optional_number(const json& obj, const Loc& loc, std::string_view name) {
  auto it = obj.find(std::string(name));
  if (it == obj.end() || it->is_null()) return std::optional<double>{};
  auto v = number_member(obj, loc, name, std::nullopt);
  if (!v) return v.error();
  return std::optional<double>{*v};
}

// Reads the numbers named in `fields` into their targets (defaults kept when absent).
Expected<void> numbers_into(const json& obj, const Loc& loc, std::initializer_list<std::pair<std::string_view, double*>> fields) {
  for (auto [name, target] : fields) {
    auto v = number_member(obj, loc, name, *target);
    if (!v) return v.error();
    *target = *v;
  }
  return {};
}

Expected<FCurveCycles> read_cycles(const json& c, const Loc& cp) {
  FCurveCycles cyc;
  auto before = enum_member(c, cp, "before", CycleMode::repeat, kCycle);
  if (!before) return before.error();
  auto after = enum_member(c, cp, "after", CycleMode::repeat, kCycle);
  if (!after) return after.error();
  auto nb = count_member(c, cp, "count_before");
  if (!nb) return nb.error();
  auto na = count_member(c, cp, "count_after");
  if (!na) return na.error();
  cyc.before = *before;
  cyc.after = *after;
  cyc.count_before = *nb;
  cyc.count_after = *na;
  return cyc;
}

#define INBETWEEN_TRY(var, expr) \
  auto var = (expr);             \
  if (!var) return var.error()

Expected<FCurveModifier> read_modifier(const json& j, const Loc& loc) {
  if (!j.is_object()) return error_at(ErrorCode::invalid_argument, "a modifier must be an object", loc);
  auto type_it = j.find("type");
  if (type_it == j.end() || !type_it->is_string()) {
    return error_at(ErrorCode::invalid_argument,
                    "a modifier needs a \"type\" (one of: " + name_list(fmodifier_type_names) + ")", at(loc, "type"));
  }
  const std::string type = type_it->get<std::string>();
  FCurveModifier m;
  INBETWEEN_TRY(mute, bool_member(j, loc, "mute", false));
  m.mute = *mute;
  INBETWEEN_TRY(influence, optional_number(j, loc, "influence"));
  m.influence = *influence;
  if (auto r = j.find("range"); r != j.end() && !r->is_null()) {
    const Loc rp = at(loc, "range");
    if (!r->is_object()) return error_at(ErrorCode::invalid_argument, "\"range\" must be an object", rp);
    if (auto ok = only_members(*r, rp, {"start", "end", "blend_in", "blend_out"}); !ok) return ok.error();
    FModifierRange range;
    INBETWEEN_TRY(start, number_member(*r, rp, "start", std::nullopt));
    INBETWEEN_TRY(end, number_member(*r, rp, "end", std::nullopt));
    range.start = *start;
    range.end = *end;
    if (auto ok = numbers_into(*r, rp, {{"blend_in", &range.blend_in}, {"blend_out", &range.blend_out}}); !ok) return ok.error();
    m.range = range;
  }
  auto members = [&](std::initializer_list<std::string_view> own) -> Expected<void> {
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool known = it.key() == "type" || it.key() == "mute" || it.key() == "influence" || it.key() == "range";
      for (std::string_view a : own) known = known || it.key() == a;
      if (!known) {
        return error_at(ErrorCode::invalid_argument,
                        "unknown member \"" + io_detail::truncated(it.key()) + "\" of a " + type +
                            " modifier (expected type, mute, influence, range or one of: " + name_list(own) + ")",
                        at(loc, it.key()));
      }
    }
    return {};
  };
  if (type == "generator") {
    if (auto ok = members({"mode", "additive", "coefficients"}); !ok) return ok.error();
    FCurveGenerator g;
    INBETWEEN_TRY(mode, enum_member(j, loc, "mode", GeneratorMode::expanded, kGenModes));
    INBETWEEN_TRY(additive, bool_member(j, loc, "additive", false));
    g.mode = *mode;
    g.additive = *additive;
    if (auto c = j.find("coefficients"); c != j.end()) {
      const Loc cp = at(loc, "coefficients");
      if (!c->is_array()) return error_at(ErrorCode::invalid_argument, "\"coefficients\" must be an array of numbers", cp);
      g.coefficients.clear();
      for (std::size_t i = 0; i < c->size(); ++i) {
        INBETWEEN_TRY(v, get_number((*c)[i], at(cp, i)));
        g.coefficients.push_back(*v);
      }
    }
    m.kind = std::move(g);
  } else if (type == "function") {
    if (auto ok = members({"function", "amplitude", "phase_multiplier", "phase_offset", "value_offset", "additive"}); !ok) {
      return ok.error();
    }
    FCurveFunction f;
    INBETWEEN_TRY(fn, enum_member(j, loc, "function", BuiltinFunction::sin, kFunctions));
    INBETWEEN_TRY(additive, bool_member(j, loc, "additive", false));
    f.function = *fn;
    f.additive = *additive;
    if (auto ok = numbers_into(j, loc, {{"amplitude", &f.amplitude}, {"phase_multiplier", &f.phase_multiplier},
                                        {"phase_offset", &f.phase_offset}, {"value_offset", &f.value_offset}});
        !ok) {
      return ok.error();
    }
    m.kind = f;
  } else if (type == "envelope") {
    if (auto ok = members({"reference", "default_min", "default_max", "points"}); !ok) return ok.error();
    FCurveEnvelope e;
    if (auto ok = numbers_into(j, loc, {{"reference", &e.reference}, {"default_min", &e.default_min},
                                        {"default_max", &e.default_max}});
        !ok) {
      return ok.error();
    }
    if (auto p = j.find("points"); p != j.end()) {
      const Loc pp = at(loc, "points");
      if (!p->is_array()) return error_at(ErrorCode::invalid_argument, "\"points\" must be an array", pp);
      for (std::size_t i = 0; i < p->size(); ++i) {
        const json& pj = (*p)[i];
        const Loc ip = at(pp, i);
        if (!pj.is_object()) return error_at(ErrorCode::invalid_argument, "a point must be an object", ip);
        if (auto ok = only_members(pj, ip, {"frame", "min", "max"}); !ok) return ok.error();
        FCurveEnvelopePoint point;
        INBETWEEN_TRY(frame, number_member(pj, ip, "frame", std::nullopt));
        INBETWEEN_TRY(mn, number_member(pj, ip, "min", std::nullopt));
        INBETWEEN_TRY(mx, number_member(pj, ip, "max", std::nullopt));
        point.frame = *frame, point.min = *mn, point.max = *mx;
        e.points.push_back(point);
      }
    }
    m.kind = std::move(e);
  } else if (type == "cycles") {
    if (auto ok = members({"before", "after", "count_before", "count_after"}); !ok) return ok.error();
    INBETWEEN_TRY(c, read_cycles(j, loc));
    m.kind = *c;
  } else if (type == "noise") {
    if (auto ok = members({"blend", "scale", "strength", "phase", "offset", "depth"}); !ok) return ok.error();
    FCurveNoise n;
    INBETWEEN_TRY(blend, enum_member(j, loc, "blend", NoiseBlend::replace, kNoiseBlend));
    n.blend = *blend;
    if (auto ok = numbers_into(j, loc, {{"scale", &n.scale}, {"strength", &n.strength}, {"phase", &n.phase},
                                        {"offset", &n.offset}});
        !ok) {
      return ok.error();
    }
    INBETWEEN_TRY(depth, count_member(j, loc, "depth"));
    n.depth = *depth;
    m.kind = n;
  } else if (type == "limits") {
    if (auto ok = members({"min_x", "max_x", "min_y", "max_y"}); !ok) return ok.error();
    FCurveLimits l;
    for (auto [name, target] : {std::pair<std::string_view, std::optional<double>*>{"min_x", &l.min_x},
                                {"max_x", &l.max_x}, {"min_y", &l.min_y}, {"max_y", &l.max_y}}) {
      INBETWEEN_TRY(v, optional_number(j, loc, name));
      *target = *v;
    }
    m.kind = l;
  } else if (type == "stepped") {
    if (auto ok = members({"step", "offset", "start", "end"}); !ok) return ok.error();
    FCurveStepped st;
    if (auto ok = numbers_into(j, loc, {{"step", &st.step}, {"offset", &st.offset}}); !ok) return ok.error();
    INBETWEEN_TRY(start, optional_number(j, loc, "start"));
    INBETWEEN_TRY(end, optional_number(j, loc, "end"));
    st.start = *start;
    st.end = *end;
    m.kind = st;
  } else {
    return error_at(ErrorCode::invalid_argument,
                    "unknown modifier type \"" + io_detail::truncated(type) + "\" (expected one of: " +
                        name_list(fmodifier_type_names) + ")",
                    at(loc, "type"));
  }
  return m;
}

#undef INBETWEEN_TRY

Expected<RawScalarTrack> read_scalar_track(const json& j, const Loc& loc) {
  RawScalarTrack track;
  auto name = name_of(j, loc);
  if (!name) return name.error();
  track.name = *name;
  auto curve = read_fcurve_members(j, loc, {"name", "kind"});
  if (!curve) return curve.error();
  track.curve = std::move(*curve);
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

Expected<RawFCurve> read_fcurve_members(const json& j, const Loc& loc, std::initializer_list<std::string_view> extra_members) {
  static constexpr std::string_view own[] = {"keys", "extrapolation", "auto_smoothing", "modifiers", "cycles"};
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    for (std::string_view a : own) known = known || it.key() == a;
    for (std::string_view a : extra_members) known = known || it.key() == a;
    if (!known) {
      std::string expected;
      for (std::string_view a : extra_members) expected += std::string(a) + ", ";
      return error_at(ErrorCode::invalid_argument,
                      "unknown member \"" + io_detail::truncated(it.key()) + "\" (expected one of: " + expected +
                          name_list(std::span<const std::string_view>(own)) + ")",
                      at(loc, it.key()));
    }
  }
  RawFCurve curve;
  auto extrap = enum_member(j, loc, "extrapolation", Extrapolation::constant, kExtrap);
  if (!extrap) return extrap.error();
  auto smooth = enum_member(j, loc, "auto_smoothing", AutoSmoothing::none, kSmooth);
  if (!smooth) return smooth.error();
  curve.extrapolation = *extrap;
  curve.auto_smoothing = *smooth;
  const auto c = j.find("cycles");
  const auto mods = j.find("modifiers");
  if (c != j.end() && mods != j.end()) {
    return error_at(ErrorCode::invalid_argument,
                    "\"cycles\" (the older spelling of a first Cycles modifier) and \"modifiers\" together; put the "
                    "Cycles modifier first in \"modifiers\"",
                    at(loc, "cycles"));
  }
  if (c != j.end()) {
    const Loc cp = at(loc, "cycles");
    if (!c->is_object()) return error_at(ErrorCode::invalid_argument, "\"cycles\" must be an object", cp);
    if (auto ok = only_members(*c, cp, {"before", "after", "count_before", "count_after"}); !ok) return ok.error();
    auto cyc = read_cycles(*c, cp);
    if (!cyc) return cyc.error();
    curve.modifiers.push_back(FCurveModifier{.kind = *cyc});
  }
  if (mods != j.end()) {
    const Loc mp = at(loc, "modifiers");
    if (!mods->is_array()) return error_at(ErrorCode::invalid_argument, "\"modifiers\" must be an array", mp);
    for (std::size_t i = 0; i < mods->size(); ++i) {
      auto m = read_modifier((*mods)[i], at(mp, i));
      if (!m) return m.error();
      curve.modifiers.push_back(std::move(*m));
    }
  }
  auto keys = key_array(j, loc, {"frame", "value", "interpolation", "easing", "handle_left_type", "handle_right_type",
                                 "handle_left", "handle_right", "back", "amplitude", "period"});
  if (!keys) return keys.error();
  for (std::size_t i = 0; i < (*keys)->size(); ++i) {
    auto key = read_fcurve_key((**keys)[i], at(at(loc, "keys"), i));
    if (!key) return key.error();
    curve.keys.push_back(*key);
  }
  return curve;
}


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
  track.curve = std::move(*keys);
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

void SceneWriter::quat_keys(ojson& out, const RawQuatKeys& curve, const Loc& loc) {
  const auto& keys = curve.keys;
  const auto& tangents = curve.tangents;
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
  if (curve.distance_factor != 1.0 / 3.0) {
    out["distance_factor"] = number(curve.distance_factor, at(loc, "distance_factor"));
  }
  if (!curve.time_aware) out["time_aware"] = false;
}

namespace {
// A modifier's own members (after "type" and the common ones), defaults left out.
void modifier_members(SceneWriter& w, ojson& mj, const FCurveModifier& m, const Loc& loc) {
  auto put = [&](const char* name, double v, double fallback) {
    if (v != fallback) mj[name] = w.number(v, at(loc, name));
  };
  auto put_optional = [&](const char* name, const std::optional<double>& v) {
    if (v) mj[name] = w.number(*v, at(loc, name));
  };
  std::visit(
      [&](const auto& k) {
        using T = std::decay_t<decltype(k)>;
        if constexpr (std::is_same_v<T, FCurveGenerator>) {
          if (k.mode != GeneratorMode::expanded) mj["mode"] = enum_text(k.mode, kGenModes);
          if (k.additive) mj["additive"] = true;
          ojson c = ojson::array();
          for (std::size_t i = 0; i < k.coefficients.size(); ++i) c.push_back(w.number(k.coefficients[i], at(at(loc, "coefficients"), i)));
          mj["coefficients"] = std::move(c);
        } else if constexpr (std::is_same_v<T, FCurveFunction>) {
          mj["function"] = enum_text(k.function, kFunctions);
          put("amplitude", k.amplitude, 1);
          put("phase_multiplier", k.phase_multiplier, 1);
          put("phase_offset", k.phase_offset, 0);
          put("value_offset", k.value_offset, 0);
          if (k.additive) mj["additive"] = true;
        } else if constexpr (std::is_same_v<T, FCurveEnvelope>) {
          put("reference", k.reference, 0);
          put("default_min", k.default_min, -1);
          put("default_max", k.default_max, 1);
          ojson pts = ojson::array();
          for (std::size_t i = 0; i < k.points.size(); ++i) {
            const Loc pl = at(at(loc, "points"), i);
            ojson pj = ojson::object();
            pj["frame"] = w.number(k.points[i].frame, at(pl, "frame"));
            pj["min"] = w.number(k.points[i].min, at(pl, "min"));
            pj["max"] = w.number(k.points[i].max, at(pl, "max"));
            pts.push_back(std::move(pj));
          }
          mj["points"] = std::move(pts);
        } else if constexpr (std::is_same_v<T, FCurveCycles>) {
          mj["before"] = std::string(to_string(k.before));
          mj["after"] = std::string(to_string(k.after));
          if (k.count_before != 0) mj["count_before"] = k.count_before;
          if (k.count_after != 0) mj["count_after"] = k.count_after;
        } else if constexpr (std::is_same_v<T, FCurveNoise>) {
          if (k.blend != NoiseBlend::replace) mj["blend"] = enum_text(k.blend, kNoiseBlend);
          put("scale", k.scale, 1);
          put("strength", k.strength, 1);
          put("phase", k.phase, 1);
          put("offset", k.offset, 0);
          if (k.depth != 0) mj["depth"] = k.depth;
        } else if constexpr (std::is_same_v<T, FCurveLimits>) {
          put_optional("min_x", k.min_x);
          put_optional("max_x", k.max_x);
          put_optional("min_y", k.min_y);
          put_optional("max_y", k.max_y);
        } else if constexpr (std::is_same_v<T, FCurveStepped>) {
          put("step", k.step, 2);
          put("offset", k.offset, 0);
          put_optional("start", k.start);
          put_optional("end", k.end);
        }
      },
      m.kind);
}
}  // namespace

void SceneWriter::fcurve_members(ojson& j, const RawFCurve& c, const Loc& loc) {
  if (c.extrapolation != Extrapolation::constant) j["extrapolation"] = std::string(to_string(c.extrapolation));
  if (c.auto_smoothing != AutoSmoothing::none) j["auto_smoothing"] = std::string(to_string(c.auto_smoothing));
  if (!c.modifiers.empty()) {
    ojson list = ojson::array();
    for (std::size_t i = 0; i < c.modifiers.size(); ++i) {
      const FCurveModifier& m = c.modifiers[i];
      const Loc ml = at(at(loc, "modifiers"), i);
      ojson mj = ojson::object();
      mj["type"] = std::string(type_name(m));
      if (m.mute) mj["mute"] = true;
      if (m.influence) mj["influence"] = number(*m.influence, at(ml, "influence"));
      if (m.range) {
        const Loc rl = at(ml, "range");
        ojson rj = ojson::object();
        rj["start"] = number(m.range->start, at(rl, "start"));
        rj["end"] = number(m.range->end, at(rl, "end"));
        if (m.range->blend_in != 0) rj["blend_in"] = number(m.range->blend_in, at(rl, "blend_in"));
        if (m.range->blend_out != 0) rj["blend_out"] = number(m.range->blend_out, at(rl, "blend_out"));
        mj["range"] = std::move(rj);
      }
      modifier_members(*this, mj, m, ml);
      list.push_back(std::move(mj));
    }
    j["modifiers"] = std::move(list);
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
}

ojson SceneWriter::track(const RawScalarTrack& t, const Loc& loc) {
  ojson j = ojson::object();
  j["name"] = t.name;
  j["kind"] = "scalar";
  fcurve_members(j, t.curve, loc);
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
  quat_keys(j, t.curve, loc);
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
