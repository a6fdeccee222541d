// The scene file's paths (src/io/scene_file.hpp lists the parts), version 2: the document's
// "paths" (a curve inline, from a curve file or on a mesh surface) and the legs of an object's
// "path" — curve, speed (ease, distance–time, velocity, constraints) and orientation — each read
// and written side by side.
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <variant>

#include "curve_value.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/obj.hpp"
#include "inbetween/io/read_file.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/paths/mesh_path.hpp"
#include "scene_file.hpp"

namespace inbetween::io_detail {

namespace {

// A curve file named in a scene, relative to the scene's folder.  Its own errors keep their place
// in the included file after its name: "climb.json:/points/3: expected 3 numbers".
Expected<AnyCurve> read_curve_file(const std::string& file, const Loc& loc, const Context& cx) {
  const std::filesystem::path resolved = cx.base_dir / std::filesystem::path(file);
  auto text = read_file_bytes(resolved);
  if (!text) return error_at(ErrorCode::io, "curve file \"" + resolved.string() + "\" " + text.error().message, loc);
  auto curve = parse_curve_json(*text, file);
  if (!curve) return error_at(curve.error().code, curve.error().describe(), loc);
  return curve;
}

// Points of a mesh path closer than this to the previous kept point, relative to the mesh's scale,
// are dropped before the spline is fitted (a walk passing a vertex within rounding gives such
// pairs; a centripetal Catmull-Rom through them would be ill-conditioned).
constexpr double kSurfacePointMerge = 1e-9;

// A path on a triangle mesh (texts 004 §3.4.4) as a curve: {"mesh": OBJ file relative to the scene,
// "from": I, "to": J, "method": "plane" | "greedy" | "edges"}.  The mesh path's points are fitted
// with a centripetal Catmull-Rom spline (α = ½: no cusps or self-intersections within a segment)
// through every point; it is then arc-length parameterised by the scene like any path.
Expected<AnyCurve> read_surface_curve(const json& sj, const Loc& loc, const Context& cx) {
  if (!sj.is_object()) return error_at(ErrorCode::invalid_argument, "expected an object with mesh, from, to", loc);
  if (auto ok = only_members(sj, loc, {"mesh", "from", "to", "method"}); !ok) return ok.error();
  const auto m = sj.find("mesh");
  const Loc mesh_at = at(loc, "mesh");
  if (m == sj.end()) return error_at(ErrorCode::invalid_argument, "missing required member \"mesh\" (an OBJ file)", mesh_at);
  if (!m->is_string()) return error_at(ErrorCode::invalid_argument, "expected an OBJ file name", mesh_at);
  const std::string file = m->get<std::string>();
  const std::filesystem::path resolved = cx.base_dir / std::filesystem::path(file);
  auto text = read_file_bytes(resolved);
  if (!text) return error_at(ErrorCode::io, "mesh \"" + resolved.string() + "\" " + text.error().message, mesh_at);
  auto mesh = parse_obj(*text, file);
  if (!mesh) return error_at(mesh.error().code, mesh.error().describe(), mesh_at);
  int ends[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const char* name = k == 0 ? "from" : "to";
    auto v = number_member(sj, loc, name, std::nullopt);
    if (!v) return v.error();
    if (!(*v >= 0) || *v != std::floor(*v) || *v >= double(mesh->vertex_count()))
      return error_at(ErrorCode::invalid_argument,
                      std::string(name) + " = " + shortest_text<double>(*v) + " is not a vertex of " + file + " (0 to " +
                          std::to_string(mesh->vertex_count() - 1) + ", in the order of its v lines)",
                      at(loc, name));
    ends[k] = int(*v);
  }
  if (ends[0] == ends[1])
    return error_at(ErrorCode::invalid_argument, "from and to are the same vertex: a path needs two ends", at(loc, "to"));
  std::string method = "plane";
  if (const auto me = sj.find("method"); me != sj.end()) {
    if (!me->is_string() || (*me != "plane" && *me != "greedy" && *me != "edges"))
      return error_at(ErrorCode::invalid_argument, "expected one of: plane, greedy, edges", at(loc, "method"));
    method = me->get<std::string>();
  }
  auto points = method == "plane"    ? plane_mesh_path(*mesh, ends[0], ends[1])
                : method == "greedy" ? greedy_mesh_path(*mesh, ends[0], ends[1])
                                     : edge_mesh_path(*mesh, ends[0], ends[1]);
  if (!points) {
    // A bad end names its argument (Parameter{"from"} or {"to"}), which is the member of the same
    // name here; any other failure belongs to the method.
    const std::vector<LocationStep>& where = points.error().location;
    const auto* arg = where.size() == 1 ? std::get_if<Parameter>(&where.front()) : nullptr;
    const Loc place = arg != nullptr && (arg->name == "from" || arg->name == "to") ? at(loc, arg->name) : at(loc, "method");
    return error_at(points.error().code,
                    "the " + method + " path from vertex " + std::to_string(ends[0]) + " to " + std::to_string(ends[1]) +
                        " cannot be found: " + points.error().describe(),
                    place);
  }
  std::vector<Vec3d> kept;
  const double merge = kSurfacePointMerge * std::max(1.0, double(mesh->scale()));
  for (const Vec3d& p : *points)
    if (kept.empty() || distance(kept.back(), p) > merge) kept.push_back(p);
  if (kept.size() > 1 && distance(kept.back(), points->back()) <= merge) kept.back() = points->back();
  else if (kept.back() != points->back()) kept.push_back(points->back());
  auto spline = build_catmull_rom(kept, CatmullRomOptions<double>{.alpha = 0.5});
  if (!spline) return error_at(spline.error().code, spline.error().describe(), loc);
  return AnyCurve{CurveKind::catmull_rom, 3, AnyCurveVariant{std::move(*spline)}};
}

// A curve given as "curve" (a path name or an inline curve object), "file" (a curve file) or
// "surface" (a path on a mesh), exactly one.
// `allow_name`: false for the entries of "paths" themselves.
Expected<std::variant<std::string, AnyCurve>> read_curve_ref(const json& obj, const Loc& loc, const Context& cx,
                                                             bool allow_name) {
  const auto c = obj.find("curve");
  const auto f = obj.find("file");
  const auto sf = obj.find("surface");
  const int given = (c != obj.end()) + (f != obj.end()) + (sf != obj.end());
  if (given > 1) {
    return error_at(ErrorCode::invalid_argument, "give one of \"curve\", \"file\" and \"surface\", not several",
                    at(loc, sf != obj.end() ? "surface" : "file"));
  }
  if (given == 0) {
    return error_at(ErrorCode::invalid_argument,
                    allow_name ? "missing \"curve\" (a path name or a curve object), \"file\" (a curve file) or \"surface\" (a path on a mesh)"
                               : "missing \"curve\" (a curve object), \"file\" (a curve file) or \"surface\" (a path on a mesh)",
                    loc);
  }
  if (sf != obj.end()) {
    auto curve = read_surface_curve(*sf, at(loc, "surface"), cx);
    if (!curve) return curve.error();
    return std::variant<std::string, AnyCurve>{std::move(*curve)};
  }
  if (f != obj.end()) {
    if (!f->is_string()) return error_at(ErrorCode::invalid_argument, "expected a file name", at(loc, "file"));
    auto curve = read_curve_file(f->get<std::string>(), at(loc, "file"), cx);
    if (!curve) return curve.error();
    return std::variant<std::string, AnyCurve>{std::move(*curve)};
  }
  const Loc cp = at(loc, "curve");
  if (c->is_string() && allow_name) return std::variant<std::string, AnyCurve>{c->get<std::string>()};
  if (!c->is_object()) {
    return error_at(ErrorCode::invalid_argument,
                    std::string(allow_name ? "expected a path name or a curve object" : "expected a curve object") +
                        ", found " + type_name(*c),
                    cp);
  }
  auto curve = io_detail::read_curve_value(*c);
  if (!curve) {
    Error e = curve.error();
    e.location.insert(e.location.begin(), cp.begin(), cp.end());
    return e;
  }
  return std::variant<std::string, AnyCurve>{std::move(*curve)};
}

Expected<RawEase> read_ease(const json& e, const Loc& loc) {
  RawEase ease;
  auto kind = name_member(e, loc, "kind", EaseKind::linear, enum_names<EaseKind>());
  if (!kind) return kind.error();
  ease.kind = *kind;
  for (auto [name, target] : {std::pair<std::string_view, std::optional<double>*>{"k1", &ease.k1},
                              {"k2", &ease.k2}, {"t1", &ease.t1}, {"t2", &ease.t2}, {"v0", &ease.v0},
                              {"accel_frames", &ease.accel_frames}, {"decel_frames", &ease.decel_frames},
                              {"acceleration", &ease.acceleration}, {"deceleration", &ease.deceleration}}) {
    auto v = optional_number(e, loc, name);
    if (!v) return v.error();
    *target = *v;
  }
  for (auto [name, target] :
       {std::pair<std::string_view, double*>{"x1", &ease.x1}, {"y1", &ease.y1}, {"x2", &ease.x2}, {"y2", &ease.y2}}) {
    auto v = number_member(e, loc, name, *target);
    if (!v) return v.error();
    *target = *v;
  }
  auto curve = name_member(e, loc, "curve", EasingCurve::sine, enum_names<EasingCurve>());
  if (!curve) return curve.error();
  ease.curve = *curve;
  auto direction = name_member(e, loc, "direction", EasingDirection::in_out, enum_names<EasingDirection>());
  if (!direction) return direction.error();
  ease.direction = *direction;
  auto params = object_member(e, loc, "params", {"back", "amplitude", "period"});
  if (!params) return params.error();
  if (*params) {
    const Loc pp = at(loc, "params");
    for (auto [name, target] : {std::pair<std::string_view, double*>{"back", &ease.params.back},
                                {"amplitude", &ease.params.amplitude}, {"period", &ease.params.period}}) {
      auto v = number_member(**params, pp, name, *target);
      if (!v) return v.error();
      *target = *v;
    }
  }
  return ease;
}

Expected<void> read_speed(const json& sj, const Loc& loc, RawPathLeg& leg) {
  RawSpeed& sp = leg.speed;
  auto kind = name_member(sj, loc, "kind", SpeedKind::ease, enum_names<SpeedKind>());
  if (!kind) return kind.error();
  sp.kind = *kind;
  if (sp.kind == SpeedKind::ease) {
    auto start = number_member(sj, loc, "start_frame", std::nullopt);
    if (!start) return start.error();
    auto end = number_member(sj, loc, "end_frame", std::nullopt);
    if (!end) return end.error();
    sp.start_frame = *start;
    sp.end_frame = *end;
  }
  auto from = optional_number(sj, loc, "from");
  if (!from) return from.error();
  sp.from = *from;
  auto to = optional_number(sj, loc, "to");
  if (!to) return to.error();
  sp.to = *to;
  auto fraction = bool_member(sj, loc, "fraction", false);
  if (!fraction) return fraction.error();
  sp.fraction = *fraction;
  auto repair = bool_member(sj, loc, "repair", false);
  if (!repair) return repair.error();
  sp.repair = *repair;
  auto ease = object_member(sj, loc, "ease",
                            {"kind", "k1", "k2", "t1", "t2", "v0", "accel_frames", "decel_frames", "acceleration", "deceleration", "x1", "y1", "x2", "y2",
                             "curve", "direction", "params"});
  if (!ease) return ease.error();
  if (*ease) {
    auto e = read_ease(**ease, at(loc, "ease"));
    if (!e) return e.error();
    sp.ease = *e;
  }
  if (sp.kind == SpeedKind::distance_keys || sp.kind == SpeedKind::constraints) {
    auto keys = object_array(sj, loc, "keys", {"frame", "distance", "speed", "acceleration"});
    if (!keys) return keys.error();
    for (std::size_t i = 0; i < (*keys)->size(); ++i) {
      const json& kj = (**keys)[i];
      const Loc p = at(at(loc, "keys"), i);
      RawDistanceKey k;
      auto frame = number_member(kj, p, "frame", std::nullopt);
      if (!frame) return frame.error();
      auto distance = number_member(kj, p, "distance", std::nullopt);
      if (!distance) return distance.error();
      auto speed = optional_number(kj, p, "speed");
      if (!speed) return speed.error();
      k.frame = *frame;
      k.distance = *distance;
      k.speed = *speed;
      auto acceleration = optional_number(kj, p, "acceleration");
      if (!acceleration) return acceleration.error();
      k.acceleration = *acceleration;
      sp.keys.push_back(k);
    }
  }
  auto interpolation =
      name_member(sj, loc, "interpolation", PositionInterpolation::monotone_cubic, enum_names<PositionInterpolation>());
  if (!interpolation) return interpolation.error();
  sp.interpolation = *interpolation;
  if (sp.kind == SpeedKind::velocity_keys) {
    auto keys = object_array(sj, loc, "velocities", {"frame", "speed"});
    if (!keys) return keys.error();
    for (std::size_t i = 0; i < (*keys)->size(); ++i) {
      const json& kj = (**keys)[i];
      const Loc p = at(at(loc, "velocities"), i);
      auto frame = number_member(kj, p, "frame", std::nullopt);
      if (!frame) return frame.error();
      auto speed = number_member(kj, p, "speed", std::nullopt);
      if (!speed) return speed.error();
      sp.velocities.push_back(RawVelocityKey{*frame, *speed});
    }
  }
  auto fit = name_member(sj, loc, "fit", VelocityFit::fix_keys_adjust_interior, enum_names<VelocityFit>());
  if (!fit) return fit.error();
  sp.fit = *fit;
  if (sp.kind == SpeedKind::acceleration_keys) {
    auto keys = object_array(sj, loc, "accelerations", {"frame", "acceleration"});
    if (!keys) return keys.error();
    for (std::size_t i = 0; i < (*keys)->size(); ++i) {
      const json& kj = (**keys)[i];
      const Loc p = at(at(loc, "accelerations"), i);
      auto frame = number_member(kj, p, "frame", std::nullopt);
      if (!frame) return frame.error();
      auto acceleration = number_member(kj, p, "acceleration", std::nullopt);
      if (!acceleration) return acceleration.error();
      sp.accelerations.push_back(RawAccelerationKey{*frame, *acceleration});
    }
    auto shape = name_member(sj, loc, "shape", AccelerationShape::constant, enum_names<AccelerationShape>());
    if (!shape) return shape.error();
    sp.shape = *shape;
    auto start_speed = number_member(sj, loc, "start_speed", 0.0);
    if (!start_speed) return start_speed.error();
    sp.start_speed = *start_speed;
  }
  if (sp.kind == SpeedKind::track) {
    if (!sj.contains("track")) {
      return error_at(ErrorCode::invalid_argument, "a track speed needs \"track\": the name of a scalar track", at(loc, "track"));
    }
    auto track = string_member(sj, loc, "track");
    if (!track) return track.error();
    leg.speed_track = *track;
  }
  return {};
}

Expected<void> read_orientation(const json& oj, const Loc& loc, RawPathLeg& leg) {
  RawOrientation& o = leg.orientation;
  auto mode = name_member(oj, loc, "mode", OrientationMode::rotation_minimizing, enum_names<OrientationMode>());
  if (!mode) return mode.error();
  o.mode = *mode;
  auto up = vec3_member(oj, loc, "up", o.up);
  if (!up) return up.error();
  o.up = *up;
  if (oj.contains("look_at")) {
    auto target = read_target(oj, loc, "look_at");
    if (!target) return target.error();
    if (const auto* name = std::get_if<std::string>(&*target)) leg.look_at_object = *name;
    else o.look_at = std::get<Vec3d>(*target);
  }
  auto closing = name_member(oj, loc, "closing", RmfClosing::automatic, enum_names<RmfClosing>());
  if (!closing) return closing.error();
  o.closing = *closing;
  auto banking = object_member(oj, loc, "banking", {"gain", "max_bank_rad", "lean_out"});
  if (!banking) return banking.error();
  if (*banking) {
    const Loc bp = at(loc, "banking");
    RawBanking b;
    auto gain = number_member(**banking, bp, "gain", b.gain);
    if (!gain) return gain.error();
    auto max_bank = number_member(**banking, bp, "max_bank_rad", b.max_bank_rad);
    if (!max_bank) return max_bank.error();
    auto lean_out = bool_member(**banking, bp, "lean_out", false);
    if (!lean_out) return lean_out.error();
    o.banking = RawBanking{*gain, *max_bank, *lean_out};
  }
  if (auto rj = oj.find("local_rotation"); rj != oj.end()) {
    const Loc rp = at(loc, "local_rotation");
    if (rj->is_array()) {
      auto v = vector_member(oj, loc, "local_rotation", 4, true);
      if (!v) return v.error();
      o.local_rotation = quat_from(*v);
    } else if (rj->is_object()) {
      if (auto ok = only_members(*rj, rp, {"keys", "distance_factor", "time_aware"}); !ok) return ok.error();
      auto q = read_quat_keys(*rj, rp);
      if (!q) return q.error();
      leg.local_rotation_keys = std::move(*q);
    } else {
      return error_at(ErrorCode::invalid_argument, "expected [w, x, y, z] or a track object", rp);
    }
  }
  return {};
}

}  // namespace

Expected<RawPathLeg> read_leg(const json& lj, const Loc& loc, const Context& cx) {
  if (!lj.is_object()) return error_at(ErrorCode::invalid_argument, "a path leg must be an object, found " + type_name(lj), loc);
  if (auto ok = only_members(lj, loc, {"curve", "file", "surface", "speed", "orientation"}); !ok) return ok.error();
  RawPathLeg leg;
  auto curve = read_curve_ref(lj, loc, cx, true);
  if (!curve) return curve.error();
  leg.curve = std::move(*curve);
  auto speed = object_member(lj, loc, "speed",
                             {"kind", "start_frame", "end_frame", "from", "to", "fraction", "ease", "keys", "interpolation",
                              "velocities", "fit", "track", "repair", "accelerations", "shape", "start_speed"});
  if (!speed) return speed.error();
  if (!*speed) return error_at(ErrorCode::invalid_argument, "missing required member \"speed\"", at(loc, "speed"));
  if (auto ok = read_speed(**speed, at(loc, "speed"), leg); !ok) return ok.error();
  auto orientation = object_member(lj, loc, "orientation", {"mode", "up", "look_at", "banking", "local_rotation", "closing"});
  if (!orientation) return orientation.error();
  if (*orientation) {
    if (auto ok = read_orientation(**orientation, at(loc, "orientation"), leg); !ok) return ok.error();
  }
  return leg;
}

Expected<void> needs_version_2(const json& obj, const Loc& loc, const Context& cx, std::string_view member) {
  if (cx.version >= 2 || !obj.contains(std::string(member))) return {};
  return error_at(ErrorCode::unsupported,
                  "\"" + std::string(member) + "\" is a version-2 member: the file needs \"inbetween\": 2",
                  at(loc, std::string(member)));
}

Expected<void> read_paths(const json& root, const Context& cx, RawScene& scene) {
  if (auto ps = root.find("paths"); ps != root.end()) {
    if (!ps->is_array()) return error_at(ErrorCode::invalid_argument, "\"paths\" must be an array", {"paths"});
    for (std::size_t i = 0; i < ps->size(); ++i) {
      const json& pj = (*ps)[i];
      const Loc p{"paths", i};
      if (!pj.is_object()) return error_at(ErrorCode::invalid_argument, "a path must be an object, found " + type_name(pj), p);
      if (auto ok = only_members(pj, p, {"name", "curve", "file", "surface"}); !ok) return ok.error();
      RawScenePath path;
      auto name = pj.find("name");
      if (name == pj.end() || !name->is_string()) {
        return error_at(ErrorCode::invalid_argument, "a path needs a non-empty string \"name\"", at(p, "name"));
      }
      path.name = name->get<std::string>();
      auto curve = read_curve_ref(pj, p, cx, false);
      if (!curve) return curve.error();
      path.curve = std::get<AnyCurve>(std::move(*curve));
      scene.paths.push_back(std::move(path));
    }
  }
  return {};
}

// ------------------------------------------------------------------ writing
// A curve as its curve-file object (io/curve_file.hpp's writer, the one curve writer).
ojson SceneWriter::curve(const AnyCurve& c) { return ojson::parse(write_curve_json(c)); }

ojson SceneWriter::target(const RawTarget<double>& t, const Loc& loc) {
  if (const auto* name = std::get_if<std::string>(&t)) return *name;
  return vec3(std::get<Vec3d>(t), loc);
}

ojson SceneWriter::ease(const RawEase& e, const Loc& loc) {
  const RawEase d;
  ojson j = ojson::object();
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
    ojson pj = ojson::object();
    pj["back"] = number(e.params.back, at(pl, "back"));
    pj["amplitude"] = number(e.params.amplitude, at(pl, "amplitude"));
    pj["period"] = number(e.params.period, at(pl, "period"));
    j["params"] = std::move(pj);
  }
  return j;
}

ojson SceneWriter::speed(const RawPathLeg& leg, const Loc& loc) {
  const RawSpeed& s = leg.speed;
  const RawSpeed d;
  ojson j = ojson::object();
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
    ojson keys = ojson::array();
    for (std::size_t i = 0; i < s.keys.size(); ++i) {
      const auto kl = at(at(loc, "keys"), i);
      ojson kj = ojson::object();
      kj["frame"] = number(s.keys[i].frame, at(kl, "frame"));
      kj["distance"] = number(s.keys[i].distance, at(kl, "distance"));
      if (s.keys[i].speed) kj["speed"] = number(*s.keys[i].speed, at(kl, "speed"));
      // Read for both kinds; the builder refuses it on distance_keys.
      if (s.keys[i].acceleration) kj["acceleration"] = number(*s.keys[i].acceleration, at(kl, "acceleration"));
      keys.push_back(std::move(kj));
    }
    j["keys"] = std::move(keys);
  }
  if (s.interpolation != d.interpolation) j["interpolation"] = std::string(to_string(s.interpolation));
  if (s.kind == SpeedKind::velocity_keys) {
    ojson keys = ojson::array();
    for (std::size_t i = 0; i < s.velocities.size(); ++i) {
      const auto kl = at(at(loc, "velocities"), i);
      ojson kj = ojson::object();
      kj["frame"] = number(s.velocities[i].frame, at(kl, "frame"));
      kj["speed"] = number(s.velocities[i].speed, at(kl, "speed"));
      keys.push_back(std::move(kj));
    }
    j["velocities"] = std::move(keys);
  }
  if (s.fit != d.fit) j["fit"] = std::string(to_string(s.fit));
  if (s.kind == SpeedKind::acceleration_keys) {
    ojson keys = ojson::array();
    for (std::size_t i = 0; i < s.accelerations.size(); ++i) {
      const auto kl = at(at(loc, "accelerations"), i);
      ojson kj = ojson::object();
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
ojson SceneWriter::orientation(const RawPathLeg& leg, const Loc& loc) {
  const RawOrientation& o = leg.orientation;
  ojson j = ojson::object();
  if (o.mode != OrientationMode::rotation_minimizing) j["mode"] = std::string(to_string(o.mode));
  if (o.up != Vec3d{0, 1, 0}) j["up"] = vec3(o.up, at(loc, "up"));
  if (!leg.look_at_object.empty()) {
    j["look_at"] = leg.look_at_object;
  } else if (o.look_at != Vec3d{}) {
    j["look_at"] = vec3(o.look_at, at(loc, "look_at"));
  }
  if (o.banking) {
    const auto bl = at(loc, "banking");
    ojson bj = ojson::object();
    bj["gain"] = number(o.banking->gain, at(bl, "gain"));
    bj["max_bank_rad"] = number(o.banking->max_bank_rad, at(bl, "max_bank_rad"));
    if (o.banking->lean_out) bj["lean_out"] = true;
    j["banking"] = std::move(bj);
  }
  if (o.closing != RmfClosing::automatic) j["closing"] = std::string(to_string(o.closing));
  if (leg.local_rotation_keys) {
    ojson rj = ojson::object();
    const RawQuatKeys& keys = *leg.local_rotation_keys;
    quat_keys(rj, keys, at(loc, "local_rotation"));
    j["local_rotation"] = std::move(rj);
  } else if (!(o.local_rotation == Quatd{})) {
    j["local_rotation"] = quat(o.local_rotation, at(loc, "local_rotation"));
  }
  return j;
}

ojson SceneWriter::leg(const RawPathLeg& leg, const Loc& loc) {
  ojson j = ojson::object();
  if (const auto* name = std::get_if<std::string>(&leg.curve)) j["curve"] = *name;
  else j["curve"] = curve(std::get<AnyCurve>(leg.curve));
  j["speed"] = speed(leg, at(loc, "speed"));
  ojson o = orientation(leg, at(loc, "orientation"));
  if (!o.empty()) j["orientation"] = std::move(o);
  return j;
}

ojson SceneWriter::path(const RawScenePath& p) {
  ojson j = ojson::object();
  j["name"] = p.name;
  j["curve"] = curve(p.curve);
  return j;
}

}  // namespace inbetween::io_detail
