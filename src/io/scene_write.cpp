// RawScene → scene JSON (inbetween/io/scene_write.hpp): the member names and enumeration names
// of the reader (src/io/scene.cpp), member for member, defaults left out.
#include "inbetween/io/scene_write.hpp"

#include "inbetween/io/curve_file.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

namespace inbetween {
namespace {

using json = nlohmann::ordered_json;  // members in the order written: "inbetween" first, then "fps" …

// The enumeration names of the format, by enumerator position (as the reader's tables).
constexpr std::string_view kTangents[] = {"hermite", "catmull_rom", "kochanek_bartels", "flat",
                                          "linear",  "clamped",     "plateau",          "stepped"};
constexpr std::string_view kExtend[] = {"constant", "linear", "cycle", "cycle_offset", "oscillate"};
constexpr std::string_view kQuatInterp[] = {"step", "slerp", "bezier", "squad", "gltf_cubic"};
constexpr std::string_view kUnits[] = {"rad", "deg"};
constexpr std::string_view kEulerModes[] = {"angles", "quaternion"};
constexpr std::string_view kVectorKinds[] = {"vec2", "vec3", "vec4", "color", "vec1"};  // VectorKind order
constexpr int kVectorDims[] = {2, 3, 4, 4, 1};

template <class Enum, std::size_t N>
std::string name_of(Enum v, const std::string_view (&names)[N]) {
  return std::string(names[std::size_t(v)]);
}

// Builds the document; the first non-finite number met is remembered with its location.
class Writer {
 public:
  std::optional<Error> failure;

  json number(double v, std::vector<LocationStep> loc) {
    if (!std::isfinite(v) && !failure) {
      Error e{ErrorCode::NotFinite, "number is not finite (JSON cannot hold NaN or infinity)", ""};
      e.location = std::move(loc);
      failure = std::move(e);
    }
    return std::isfinite(v) ? json(v) : json(nullptr);
  }

  json numbers(std::initializer_list<double> vs, const std::vector<LocationStep>& loc) {
    json a = json::array();
    std::size_t i = 0;
    for (double v : vs) {
      auto l = loc;
      l.emplace_back(i++);
      a.push_back(number(v, std::move(l)));
    }
    return a;
  }

  json quat(const Quatd& q, const std::vector<LocationStep>& loc) { return numbers({q.w, q.x, q.y, q.z}, loc); }
  json vec3(const Vec3d& v, const std::vector<LocationStep>& loc) { return numbers({v.x, v.y, v.z}, loc); }
  json vec(const Vec4d& v, int dim, const std::vector<LocationStep>& loc) {
    switch (dim) {
      case 1: return numbers({v.x}, loc);
      case 2: return numbers({v.x, v.y}, loc);
      case 3: return numbers({v.x, v.y, v.z}, loc);
      default: return numbers({v.x, v.y, v.z, v.w}, loc);
    }
  }

  static std::vector<LocationStep> at(std::vector<LocationStep> loc, LocationStep step) {
    loc.push_back(std::move(step));
    return loc;
  }

  // Keys of a vector-valued track or channel (dim components), with "before"/"after" into `out`.
  template <class V>
  void vector_keys(json& out, const std::vector<TrackKey<V>>& keys, TrackExtend before, TrackExtend after, int dim,
                   const std::vector<LocationStep>& loc) {
    auto widen = [](const V& v) {
      if constexpr (std::is_same_v<V, Vec4d>) return v;
      else return Vec4d{v.x, v.y, v.z, 0};
    };
    json list = json::array();
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const auto& k = keys[i];
      const auto kl = at(at(loc, "keys"), i);
      json kj = json::object();
      kj["frame"] = number(k.frame, at(kl, "frame"));
      kj["value"] = vec(widen(k.value), dim, at(kl, "value"));
      if (k.tangent != TangentKind::catmull_rom) kj["tangent"] = name_of(k.tangent, kTangents);
      const bool hermite = k.tangent == TangentKind::explicit_hermite;
      if (hermite || widen(k.in_tangent) != Vec4d{}) kj["in_tangent"] = vec(widen(k.in_tangent), dim, at(kl, "in_tangent"));
      if (hermite || widen(k.out_tangent) != Vec4d{}) kj["out_tangent"] = vec(widen(k.out_tangent), dim, at(kl, "out_tangent"));
      if (k.tension != 0) kj["tension"] = number(k.tension, at(kl, "tension"));
      if (k.continuity != 0) kj["continuity"] = number(k.continuity, at(kl, "continuity"));
      if (k.bias != 0) kj["bias"] = number(k.bias, at(kl, "bias"));
      list.push_back(std::move(kj));
    }
    out["keys"] = std::move(list);
    if (before != TrackExtend::constant) out["before"] = name_of(before, kExtend);
    if (after != TrackExtend::constant) out["after"] = name_of(after, kExtend);
  }

  void quat_keys(json& out, const std::vector<QuatKey<double>>& keys, const std::vector<QuatKeyTangents<double>>& tangents,
                 double distance_factor, bool time_aware, const std::vector<LocationStep>& loc) {
    json list = json::array();
    const Quatd zero = Quatd::from_wxyz(0, 0, 0, 0);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const auto& k = keys[i];
      const auto kl = at(at(loc, "keys"), i);
      json kj = json::object();
      kj["frame"] = number(k.frame, at(kl, "frame"));
      kj["value"] = quat(k.value, at(kl, "value"));
      if (k.interpolation != QuatInterpolation::slerp) kj["interpolation"] = name_of(k.interpolation, kQuatInterp);
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

  json track(const RawScalarTrack& t, const std::vector<LocationStep>& loc) {
    json j = json::object();
    j["name"] = t.name;
    j["kind"] = "scalar";
    const RawFCurve& c = t.curve;
    if (c.extrapolation != Extrapolation::constant) j["extrapolation"] = std::string(to_string(c.extrapolation));
    if (c.auto_smoothing != AutoSmoothing::none) j["auto_smoothing"] = std::string(to_string(c.auto_smoothing));
    if (c.cycles) {
      json cj = json::object();
      cj["before"] = std::string(to_string(c.cycles->before));
      cj["after"] = std::string(to_string(c.cycles->after));
      cj["count_before"] = c.cycles->count_before;
      cj["count_after"] = c.cycles->count_after;
      j["cycles"] = std::move(cj);
    }
    json list = json::array();
    const FCurveKey defaults;
    for (std::size_t i = 0; i < c.keys.size(); ++i) {
      const FCurveKey& k = c.keys[i];
      const auto kl = at(at(loc, "keys"), i);
      json kj = json::object();
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

  json track(const RawVectorTrack& t, const std::vector<LocationStep>& loc) {
    json j = json::object();
    j["name"] = t.name;
    j["kind"] = name_of(t.kind, kVectorKinds);
    vector_keys(j, t.keys, t.before, t.after, kVectorDims[std::size_t(t.kind)], loc);
    return j;
  }

  json track(const RawQuatTrack& t, const std::vector<LocationStep>& loc) {
    json j = json::object();
    j["name"] = t.name;
    j["kind"] = "quaternion";
    quat_keys(j, t.keys, t.tangents, t.distance_factor, t.time_aware, loc);
    return j;
  }

  json track(const RawEulerTrack& t, const std::vector<LocationStep>& loc) {
    json j = json::object();
    j["name"] = t.name;
    j["kind"] = "euler";
    j["convention"] = t.convention;
    if (t.units != AngleUnits::rad) j["units"] = name_of(t.units, kUnits);
    if (t.mode != EulerTrackMode::angles) j["mode"] = name_of(t.mode, kEulerModes);
    if (!t.filter) j["filter"] = false;
    json list = json::array();
    for (std::size_t i = 0; i < t.keys.size(); ++i) {
      const RawEulerKey& k = t.keys[i];
      const auto kl = at(at(loc, "keys"), i);
      json kj = json::object();
      kj["frame"] = number(k.frame, at(kl, "frame"));
      kj["value"] = vec3(k.value, at(kl, "value"));
      if (k.tangent != TangentKind::catmull_rom) kj["tangent"] = name_of(k.tangent, kTangents);
      if (k.interpolation != QuatInterpolation::slerp) kj["interpolation"] = name_of(k.interpolation, kQuatInterp);
      list.push_back(std::move(kj));
    }
    j["keys"] = std::move(list);
    return j;
  }

  json vec3_channel(const std::variant<Vec3d, RawVec3Channel>& c, const std::vector<LocationStep>& loc) {
    if (const auto* v = std::get_if<Vec3d>(&c)) return vec3(*v, loc);
    const auto& keyed = std::get<RawVec3Channel>(c);
    json j = json::object();
    vector_keys(j, keyed.keys, keyed.before, keyed.after, 3, loc);
    return j;
  }

  // ---------------------------------------------------------------- version 2 (src/io/scene_v2.cpp)

  // A curve as its curve-file object (io/curve_file.hpp's writer, the one curve writer).
  static json curve(const AnyCurve& c) { return json::parse(write_curve_json(c)); }

  json target(const RawTarget<double>& t, const std::vector<LocationStep>& loc) {
    if (const auto* name = std::get_if<std::string>(&t)) return *name;
    return vec3(std::get<Vec3d>(t), loc);
  }

  json ease(const RawEase& e, const std::vector<LocationStep>& loc) {
    const RawEase d;
    json j = json::object();
    j["kind"] = std::string(to_string(e.kind));
    for (auto [name, v] : {std::pair<const char*, const std::optional<double>*>{"k1", &e.k1}, {"k2", &e.k2}, {"t1", &e.t1},
                           {"t2", &e.t2}, {"v0", &e.v0}, {"accel_frames", &e.accel_frames}, {"decel_frames", &e.decel_frames},
                           {"acceleration", &e.acceleration}, {"deceleration", &e.deceleration}}) {
      if (*v) j[name] = number(**v, at(loc, name));
    }
    for (auto [name, v, dv] : {std::tuple<const char*, double, double>{"x1", e.x1, d.x1}, {"y1", e.y1, d.y1}, {"x2", e.x2, d.x2},
                               {"y2", e.y2, d.y2}}) {
      if (v != dv) j[name] = number(v, at(loc, name));
    }
    if (e.curve != d.curve) j["curve"] = std::string(to_string(e.curve));
    if (e.direction != d.direction) j["direction"] = std::string(to_string(e.direction));
    if (e.params.back != d.params.back || e.params.amplitude != d.params.amplitude || e.params.period != d.params.period) {
      const auto pl = at(loc, "params");
      json pj = json::object();
      pj["back"] = number(e.params.back, at(pl, "back"));
      pj["amplitude"] = number(e.params.amplitude, at(pl, "amplitude"));
      pj["period"] = number(e.params.period, at(pl, "period"));
      j["params"] = std::move(pj);
    }
    return j;
  }

  json speed(const RawPathLeg& leg, const std::vector<LocationStep>& loc) {
    const RawSpeed& s = leg.speed;
    const RawSpeed d;
    json j = json::object();
    j["kind"] = std::string(to_string(s.kind));
    if (s.kind == SpeedKind::ease) {
      j["start_frame"] = number(s.start_frame, at(loc, "start_frame"));
      j["end_frame"] = number(s.end_frame, at(loc, "end_frame"));
    }
    if (s.from) j["from"] = number(*s.from, at(loc, "from"));
    if (s.to) j["to"] = number(*s.to, at(loc, "to"));
    if (s.fraction) j["fraction"] = true;
    if (s.repair) j["repair"] = true;
    if (s.kind == SpeedKind::ease) j["ease"] = ease(s.ease, at(loc, "ease"));
    if (s.kind == SpeedKind::distance_keys || s.kind == SpeedKind::constraints) {
      json keys = json::array();
      for (std::size_t i = 0; i < s.keys.size(); ++i) {
        const auto kl = at(at(loc, "keys"), i);
        json kj = json::object();
        kj["frame"] = number(s.keys[i].frame, at(kl, "frame"));
        kj["distance"] = number(s.keys[i].distance, at(kl, "distance"));
        if (s.keys[i].speed) kj["speed"] = number(*s.keys[i].speed, at(kl, "speed"));
        // Read for both kinds (src/io/scene_v2.cpp); the builder refuses it on distance_keys.
        if (s.keys[i].acceleration) kj["acceleration"] = number(*s.keys[i].acceleration, at(kl, "acceleration"));
        keys.push_back(std::move(kj));
      }
      j["keys"] = std::move(keys);
    }
    if (s.interpolation != d.interpolation) j["interpolation"] = std::string(to_string(s.interpolation));
    if (s.kind == SpeedKind::velocity_keys) {
      json keys = json::array();
      for (std::size_t i = 0; i < s.velocities.size(); ++i) {
        const auto kl = at(at(loc, "velocities"), i);
        json kj = json::object();
        kj["frame"] = number(s.velocities[i].frame, at(kl, "frame"));
        kj["speed"] = number(s.velocities[i].speed, at(kl, "speed"));
        keys.push_back(std::move(kj));
      }
      j["velocities"] = std::move(keys);
    }
    if (s.fit != d.fit) j["fit"] = std::string(to_string(s.fit));
    if (s.kind == SpeedKind::acceleration_keys) {
      json keys = json::array();
      for (std::size_t i = 0; i < s.accelerations.size(); ++i) {
        const auto kl = at(at(loc, "accelerations"), i);
        json kj = json::object();
        kj["frame"] = number(s.accelerations[i].frame, at(kl, "frame"));
        kj["acceleration"] = number(s.accelerations[i].acceleration, at(kl, "acceleration"));
        keys.push_back(std::move(kj));
      }
      j["accelerations"] = std::move(keys);
      if (s.shape != d.shape) j["shape"] = std::string(to_string(s.shape));
      if (s.start_speed != d.start_speed) j["start_speed"] = number(s.start_speed, at(loc, "start_speed"));
    }
    if (s.kind == SpeedKind::track) j["track"] = leg.speed_track;
    return j;
  }

  // The leg's "orientation" object; empty when every member has its default.
  json orientation(const RawPathLeg& leg, const std::vector<LocationStep>& loc) {
    const RawOrientation& o = leg.orientation;
    json j = json::object();
    if (o.mode != OrientationMode::rotation_minimizing) j["mode"] = std::string(to_string(o.mode));
    if (o.up != Vec3d{0, 1, 0}) j["up"] = vec3(o.up, at(loc, "up"));
    if (!leg.look_at_object.empty()) {
      j["look_at"] = leg.look_at_object;
    } else if (o.look_at != Vec3d{}) {
      j["look_at"] = vec3(o.look_at, at(loc, "look_at"));
    }
    if (o.banking) {
      const auto bl = at(loc, "banking");
      json bj = json::object();
      bj["gain"] = number(o.banking->gain, at(bl, "gain"));
      bj["max_bank_rad"] = number(o.banking->max_bank_rad, at(bl, "max_bank_rad"));
      if (o.banking->lean_out) bj["lean_out"] = true;
      j["banking"] = std::move(bj);
    }
    if (o.closing != RmfClosing::automatic) j["closing"] = std::string(to_string(o.closing));
    if (leg.local_rotation_keys) {
      json rj = json::object();
      const RawQuatKeys& keys = *leg.local_rotation_keys;
      quat_keys(rj, keys.keys, keys.tangents, keys.distance_factor, keys.time_aware, at(loc, "local_rotation"));
      j["local_rotation"] = std::move(rj);
    } else if (!(o.local_rotation == Quatd{})) {
      j["local_rotation"] = quat(o.local_rotation, at(loc, "local_rotation"));
    }
    return j;
  }

  json leg(const RawPathLeg& leg, const std::vector<LocationStep>& loc) {
    json j = json::object();
    if (const auto* name = std::get_if<std::string>(&leg.curve)) j["curve"] = *name;
    else j["curve"] = curve(std::get<AnyCurve>(leg.curve));
    j["speed"] = speed(leg, at(loc, "speed"));
    json o = orientation(leg, at(loc, "orientation"));
    if (!o.empty()) j["orientation"] = std::move(o);
    return j;
  }

  json camera(const RawCameraViewd& c, const std::vector<LocationStep>& loc) {
    const RawCameraViewd d;
    json j = json::object();
    if (c.yfov_deg != d.yfov_deg) j["yfov_deg"] = number(c.yfov_deg, at(loc, "yfov_deg"));
    if (const auto* look = std::get_if<RawLookAt<double>>(&c.coi)) {
      j["look_at"] = target(look->target, at(loc, "look_at"));
    } else if (const auto* ahead = std::get_if<RawLookAhead<double>>(&c.coi)) {
      const auto al = at(loc, "ahead");
      json aj = json::object();
      aj["distance"] = number(ahead->distance, at(al, "distance"));
      if (ahead->count != 1) aj["count"] = ahead->count;
      if (ahead->spread != 0) aj["spread"] = number(ahead->spread, at(al, "spread"));
      j["ahead"] = std::move(aj);
    } else if (const auto* coi = std::get_if<RawCoiPath>(&c.coi)) {
      j["coi_path"] = coi->path;
    } else if (const auto* own = std::get_if<RawOwnRotation<double>>(&c.coi)) {
      json oj = json::object();
      if (own->distance != RawOwnRotation<double>{}.distance) {
        oj["distance"] = number(own->distance, at(at(loc, "own_rotation"), "distance"));
      }
      j["own_rotation"] = std::move(oj);
    } else {
      const auto& hold = std::get<RawHoldThenMove<double>>(c.coi);
      json hj = json::array();
      for (std::size_t i = 0; i < hold.segments.size(); ++i) {
        const auto sl = at(at(loc, "hold"), i);
        const auto& seg = hold.segments[i];
        json sj = json::object();
        sj["target"] = target(seg.target, at(sl, "target"));
        sj["hold_until"] = number(seg.hold_until, at(sl, "hold_until"));
        if (seg.move_frames != 0) sj["move_frames"] = number(seg.move_frames, at(sl, "move_frames"));
        hj.push_back(std::move(sj));
      }
      j["hold"] = std::move(hj);
    }
    if (c.up != d.up) j["up"] = vec3(c.up, at(loc, "up"));
    if (!c.up_path.empty()) j["up_path"] = c.up_path;
    if (c.tilt_deg != 0) j["tilt_deg"] = number(c.tilt_deg, at(loc, "tilt_deg"));
    if (!c.tilt_track.empty()) j["tilt_track"] = c.tilt_track;
    return j;
  }

  json object(const RawObject& o, const std::vector<LocationStep>& loc) {
    json j = json::object();
    j["name"] = o.name;
    if (o.parent) j["parent"] = *o.parent;
    if (o.translation) j["translation"] = vec3_channel(*o.translation, at(loc, "translation"));
    if (!o.rotation) {
    } else if (const auto* q = std::get_if<Quatd>(&*o.rotation)) {
      j["rotation"] = quat(*q, at(loc, "rotation"));
    } else {
      const auto& keyed = std::get<RawQuatKeys>(*o.rotation);
      json rj = json::object();
      quat_keys(rj, keyed.keys, keyed.tangents, keyed.distance_factor, keyed.time_aware, at(loc, "rotation"));
      j["rotation"] = std::move(rj);
    }
    j["scale"] = vec3_channel(o.scale, at(loc, "scale"));
    if (!o.path.empty()) {
      const auto pl = at(loc, "path");
      if (o.path_is_array || o.path.size() > 1) {
        json legs = json::array();
        for (std::size_t k = 0; k < o.path.size(); ++k) legs.push_back(leg(o.path[k], at(pl, k)));
        j["path"] = std::move(legs);
      } else {
        j["path"] = leg(o.path[0], pl);
      }
    }
    if (o.camera) j["camera"] = camera(*o.camera, at(loc, "camera"));
    return j;
  }
};

// Indented JSON in which every array or object that fits in kOneLine characters stays on one line
// (a key, a vector, a constant channel), so a scene with thousands of keys reads as one key a line.
constexpr std::size_t kOneLine = 100;

std::string scalar_text(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// One line with a space after each ':' and ',': {"frame": 0, "value": [1, 2, 3]}.
std::string one_line(const json& j) {
  if (!j.is_structured()) return scalar_text(j);
  std::string out = j.is_object() ? "{" : "[";
  bool first = true;
  for (auto it = j.begin(); it != j.end(); ++it) {
    out += first ? "" : ", ";
    first = false;
    if (j.is_object()) out += scalar_text(json(it.key())) + ": ";
    out += one_line(it.value());
  }
  return out + (j.is_object() ? "}" : "]");
}

void pretty(const json& j, int indent, int depth, std::string& out) {
  std::string flat = one_line(j);
  if (!j.is_structured() || j.empty() || flat.size() <= kOneLine) {
    out += flat;
    return;
  }
  const std::string pad(std::size_t(indent * (depth + 1)), ' '), end_pad(std::size_t(indent * depth), ' ');
  out += j.is_object() ? "{\n" : "[\n";
  bool first = true;
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      out += first ? "" : ",\n";
      first = false;
      out += pad + scalar_text(json(it.key())) + ": ";
      pretty(it.value(), indent, depth + 1, out);
    }
  } else {
    for (const json& item : j) {
      out += first ? "" : ",\n";
      first = false;
      out += pad;
      pretty(item, indent, depth + 1, out);
    }
  }
  out += "\n" + end_pad + (j.is_object() ? "}" : "]");
}

}  // namespace

Expected<std::string> write_scene_json(const RawScene& scene, const SceneWriteOptions& options) {
  Writer w;
  json root = json::object();
  root["inbetween"] = 2;
  root["fps"] = w.number(scene.fps, {"fps"});
  root["range"] = w.numbers({scene.range[0], scene.range[1]}, {"range"});
  if (!scene.paths.empty()) {
    json paths = json::array();
    for (const RawScenePath& p : scene.paths) {
      json pj = json::object();
      pj["name"] = p.name;
      pj["curve"] = Writer::curve(p.curve);
      paths.push_back(std::move(pj));
    }
    root["paths"] = std::move(paths);
  }
  if (!scene.tracks.empty()) {
    json tracks = json::array();
    for (std::size_t i = 0; i < scene.tracks.size(); ++i)
      tracks.push_back(std::visit([&](const auto& t) { return w.track(t, {"tracks", i}); }, scene.tracks[i]));
    root["tracks"] = std::move(tracks);
  }
  if (!scene.objects.empty()) {
    json objects = json::array();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) objects.push_back(w.object(scene.objects[i], {"objects", i}));
    root["objects"] = std::move(objects);
  }
  if (!scene.skins.empty()) {
    json skins = json::array();
    for (const RawSkin& skin : scene.skins) {
      json sj = json::object();
      if (!skin.name.empty()) sj["name"] = skin.name;
      sj["joints"] = skin.joints;
      skins.push_back(std::move(sj));
    }
    root["skins"] = std::move(skins);
  }
  if (w.failure) return *w.failure;
  // Names are arbitrary bytes in a RawScene: invalid UTF-8 is replaced rather than thrown on.
  if (options.indent < 0) return root.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
  std::string out;
  pretty(root, options.indent, 0, out);
  return out + "\n";
}

}  // namespace inbetween
