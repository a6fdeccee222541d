// Reads the version-2 members of the scene format (docs/scene-format.md): "paths", and an object's
// "path" (legs with speed and orientation) and "camera".  Shape only, as the rest of the reader:
// names are resolved and values checked by build_scene().
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <string>
#include <utility>
#include <variant>

#include "curve_value.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/obj.hpp"
#include "inbetween/io/read_file.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/paths/mesh_path.hpp"
#include "scene_json.hpp"

namespace inbetween::io_detail {

namespace {



// The scene-file names of an enumeration, from its one name table (to_string).
template <class Enum, std::size_t N>
const std::array<std::string_view, N>& names_of() {
  static const std::array<std::string_view, N> names = [] {
    std::array<std::string_view, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = to_string(static_cast<Enum>(i));
    return out;
  }();
  return names;
}


// A member that must be a JSON object when present; nullptr when absent.
Expected<const json*> object_member(const json& obj, const Loc& loc, std::string_view name,
                                    std::initializer_list<std::string_view> allowed) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return static_cast<const json*>(nullptr);
  const Loc p = at(loc, std::string(name));
  if (!it->is_object()) return error_at(ErrorCode::InvalidArgument, "expected an object, found " + type_name(*it), p);
  if (auto ok = only_members(*it, p, allowed); !ok) return ok.error();
  return &*it;
}

// A string member ("" when absent).
Expected<std::string> string_member(const json& obj, const Loc& loc, std::string_view name) {
  auto it = obj.find(std::string(name));
  if (it == obj.end()) return std::string();
  if (!it->is_string()) {
    return error_at(ErrorCode::InvalidArgument, "expected a string, found " + type_name(*it), at(loc, std::string(name)));
  }
  return it->get<std::string>();
}

// An optional number member.
Expected<std::optional<double>> optional_number(const json& obj, const Loc& loc, std::string_view name) {
  if (!obj.contains(std::string(name))) return std::optional<double>{};
  auto v = number_member(obj, loc, name, std::nullopt);
  if (!v) return v.error();
  return std::optional<double>{*v};
}

// An array member whose elements are objects with only `allowed` members.
Expected<const json*> object_array(const json& obj, const Loc& loc, std::string_view name,
                                   std::initializer_list<std::string_view> allowed) {
  auto it = obj.find(std::string(name));
  const Loc p = at(loc, std::string(name));
  if (it == obj.end()) return error_at(ErrorCode::InvalidArgument, "missing required member \"" + std::string(name) + "\"", p);
  if (!it->is_array()) return error_at(ErrorCode::InvalidArgument, "\"" + std::string(name) + "\" must be an array", p);
  for (std::size_t i = 0; i < it->size(); ++i) {
    const json& e = (*it)[i];
    if (!e.is_object()) return error_at(ErrorCode::InvalidArgument, "expected an object, found " + type_name(e), at(p, i));
    if (auto ok = only_members(e, at(p, i), allowed); !ok) return ok.error();
  }
  return &*it;
}

// A curve file named in a scene, relative to the scene's folder.  Its own errors keep their place
// in the included file after its name: "climb.json:/points/3: expected 3 numbers".
Expected<AnyCurve> read_curve_file(const std::string& file, const Loc& loc, const Context& cx) {
  const std::filesystem::path resolved = cx.base_dir / std::filesystem::path(file);
  auto text = read_file_bytes(resolved);
  if (!text) return error_at(ErrorCode::Io, "curve file \"" + resolved.string() + "\" " + text.error().message, loc);
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
  if (!sj.is_object()) return error_at(ErrorCode::InvalidArgument, "expected an object with mesh, from, to", loc);
  if (auto ok = only_members(sj, loc, {"mesh", "from", "to", "method"}); !ok) return ok.error();
  const auto m = sj.find("mesh");
  const Loc mesh_at = at(loc, "mesh");
  if (m == sj.end()) return error_at(ErrorCode::InvalidArgument, "missing required member \"mesh\" (an OBJ file)", mesh_at);
  if (!m->is_string()) return error_at(ErrorCode::InvalidArgument, "expected an OBJ file name", mesh_at);
  const std::string file = m->get<std::string>();
  const std::filesystem::path resolved = cx.base_dir / std::filesystem::path(file);
  auto text = read_file_bytes(resolved);
  if (!text) return error_at(ErrorCode::Io, "mesh \"" + resolved.string() + "\" " + text.error().message, mesh_at);
  auto mesh = parse_obj(*text, file);
  if (!mesh) return error_at(mesh.error().code, mesh.error().describe(), mesh_at);
  int ends[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const char* name = k == 0 ? "from" : "to";
    auto v = number_member(sj, loc, name, std::nullopt);
    if (!v) return v.error();
    if (!(*v >= 0) || *v != std::floor(*v) || *v >= double(mesh->vertex_count()))
      return error_at(ErrorCode::InvalidArgument,
                      std::string(name) + " = " + shortest_text<double>(*v) + " is not a vertex of " + file + " (0 to " +
                          std::to_string(mesh->vertex_count() - 1) + ", in the order of its v lines)",
                      at(loc, name));
    ends[k] = int(*v);
  }
  if (ends[0] == ends[1])
    return error_at(ErrorCode::InvalidArgument, "from and to are the same vertex: a path needs two ends", at(loc, "to"));
  std::string method = "plane";
  if (const auto me = sj.find("method"); me != sj.end()) {
    if (!me->is_string() || (*me != "plane" && *me != "greedy" && *me != "edges"))
      return error_at(ErrorCode::InvalidArgument, "expected one of: plane, greedy, edges", at(loc, "method"));
    method = me->get<std::string>();
  }
  auto points = method == "plane"    ? plane_mesh_path(*mesh, ends[0], ends[1])
                : method == "greedy" ? greedy_mesh_path(*mesh, ends[0], ends[1])
                                     : edge_mesh_path(*mesh, ends[0], ends[1]);
  if (!points) {
    const std::string& w = points.error().where;
    const Loc place = w == "from" || w == "to" ? at(loc, w) : at(loc, "method");
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
    return error_at(ErrorCode::InvalidArgument, "give one of \"curve\", \"file\" and \"surface\", not several",
                    at(loc, sf != obj.end() ? "surface" : "file"));
  }
  if (given == 0) {
    return error_at(ErrorCode::InvalidArgument,
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
    if (!f->is_string()) return error_at(ErrorCode::InvalidArgument, "expected a file name", at(loc, "file"));
    auto curve = read_curve_file(f->get<std::string>(), at(loc, "file"), cx);
    if (!curve) return curve.error();
    return std::variant<std::string, AnyCurve>{std::move(*curve)};
  }
  const Loc cp = at(loc, "curve");
  if (c->is_string() && allow_name) return std::variant<std::string, AnyCurve>{c->get<std::string>()};
  if (!c->is_object()) {
    return error_at(ErrorCode::InvalidArgument,
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

// A [x, y, z] member.
Expected<Vec3d> vec3_member(const json& obj, const Loc& loc, std::string_view name, Vec3d fallback) {
  if (!obj.contains(std::string(name))) return fallback;
  auto v = vector_member(obj, loc, name, 3, true);
  if (!v) return v.error();
  return xyz(*v);
}

// A target: [x, y, z] or an object name.
Expected<RawTarget<double>> read_target(const json& obj, const Loc& loc, std::string_view name) {
  auto it = obj.find(std::string(name));
  const Loc p = at(loc, std::string(name));
  if (it == obj.end()) return error_at(ErrorCode::InvalidArgument, "missing required member \"" + std::string(name) + "\"", p);
  if (it->is_string()) return RawTarget<double>{it->get<std::string>()};
  if (!it->is_array()) return error_at(ErrorCode::InvalidArgument, "expected [x, y, z] or an object name", p);
  auto v = vector_member(obj, loc, name, 3, true);
  if (!v) return v.error();
  return RawTarget<double>{xyz(*v)};
}

Expected<RawEase> read_ease(const json& e, const Loc& loc) {
  RawEase ease;
  auto kind = name_member(e, loc, "kind", EaseKind::linear, names_of<EaseKind, 7>());
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
  auto curve = name_member(e, loc, "curve", EasingCurve::sine, names_of<EasingCurve, 10>());
  if (!curve) return curve.error();
  ease.curve = *curve;
  auto direction = name_member(e, loc, "direction", EasingDirection::in_out, names_of<EasingDirection, 3>());
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
  auto kind = name_member(sj, loc, "kind", SpeedKind::ease, names_of<SpeedKind, 6>());
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
      name_member(sj, loc, "interpolation", PositionInterpolation::monotone_cubic, names_of<PositionInterpolation, 3>());
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
  auto fit = name_member(sj, loc, "fit", VelocityFit::fix_keys_adjust_interior, names_of<VelocityFit, 2>());
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
    auto shape = name_member(sj, loc, "shape", AccelerationShape::constant, names_of<AccelerationShape, 2>());
    if (!shape) return shape.error();
    sp.shape = *shape;
    auto start_speed = number_member(sj, loc, "start_speed", 0.0);
    if (!start_speed) return start_speed.error();
    sp.start_speed = *start_speed;
  }
  if (sp.kind == SpeedKind::track) {
    if (!sj.contains("track")) {
      return error_at(ErrorCode::InvalidArgument, "a track speed needs \"track\": the name of a scalar track", at(loc, "track"));
    }
    auto track = string_member(sj, loc, "track");
    if (!track) return track.error();
    leg.speed_track = *track;
  }
  return {};
}

Expected<void> read_orientation(const json& oj, const Loc& loc, RawPathLeg& leg) {
  RawOrientation& o = leg.orientation;
  auto mode = name_member(oj, loc, "mode", OrientationMode::rotation_minimizing, names_of<OrientationMode, 4>());
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
  auto closing = name_member(oj, loc, "closing", RmfClosing::automatic, names_of<RmfClosing, 3>());
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
      return error_at(ErrorCode::InvalidArgument, "expected [w, x, y, z] or a track object", rp);
    }
  }
  return {};
}

Expected<RawPathLeg> read_leg(const json& lj, const Loc& loc, const Context& cx) {
  if (!lj.is_object()) return error_at(ErrorCode::InvalidArgument, "a path leg must be an object, found " + type_name(lj), loc);
  if (auto ok = only_members(lj, loc, {"curve", "file", "surface", "speed", "orientation"}); !ok) return ok.error();
  RawPathLeg leg;
  auto curve = read_curve_ref(lj, loc, cx, true);
  if (!curve) return curve.error();
  leg.curve = std::move(*curve);
  auto speed = object_member(lj, loc, "speed",
                             {"kind", "start_frame", "end_frame", "from", "to", "fraction", "ease", "keys", "interpolation",
                              "velocities", "fit", "track", "repair", "accelerations", "shape", "start_speed"});
  if (!speed) return speed.error();
  if (!*speed) return error_at(ErrorCode::InvalidArgument, "missing required member \"speed\"", at(loc, "speed"));
  if (auto ok = read_speed(**speed, at(loc, "speed"), leg); !ok) return ok.error();
  auto orientation = object_member(lj, loc, "orientation", {"mode", "up", "look_at", "banking", "local_rotation", "closing"});
  if (!orientation) return orientation.error();
  if (*orientation) {
    if (auto ok = read_orientation(**orientation, at(loc, "orientation"), leg); !ok) return ok.error();
  }
  return leg;
}

Expected<RawCameraViewd> read_camera(const json& cj, const Loc& loc) {
  RawCameraViewd cam;
  auto yfov = number_member(cj, loc, "yfov_deg", cam.yfov_deg);
  if (!yfov) return yfov.error();
  cam.yfov_deg = *yfov;
  int modes = 0;
  for (const char* m : {"look_at", "ahead", "coi_path", "hold", "own_rotation"}) modes += cj.contains(m) ? 1 : 0;
  if (modes != 1) {
    return error_at(ErrorCode::InvalidArgument,
                    "a camera needs exactly one of \"look_at\", \"ahead\", \"coi_path\", \"hold\", \"own_rotation\" (got " +
                        std::to_string(modes) + ")",
                    loc);
  }
  if (cj.contains("look_at")) {
    auto target = read_target(cj, loc, "look_at");
    if (!target) return target.error();
    cam.coi = RawLookAt<double>{*target};
  } else if (cj.contains("ahead")) {
    auto ahead = object_member(cj, loc, "ahead", {"distance", "count", "spread"});
    if (!ahead) return ahead.error();
    const Loc ap = at(loc, "ahead");
    RawLookAhead<double> a;
    auto distance = number_member(**ahead, ap, "distance", std::nullopt);
    if (!distance) return distance.error();
    auto count = number_member(**ahead, ap, "count", 1.0);
    if (!count) return count.error();
    if (std::floor(*count) != *count || std::abs(*count) > 1e6) {
      return error_at(ErrorCode::InvalidArgument, "expected a whole number of points (1 to 10^6)", at(ap, "count"));
    }
    auto spread = number_member(**ahead, ap, "spread", 0.0);
    if (!spread) return spread.error();
    a.distance = *distance;
    a.count = int(*count);
    a.spread = *spread;
    cam.coi = a;
  } else if (cj.contains("own_rotation")) {
    auto own = object_member(cj, loc, "own_rotation", {"distance"});
    if (!own) return own.error();
    RawOwnRotation<double> r;
    auto distance = number_member(**own, at(loc, "own_rotation"), "distance", r.distance);
    if (!distance) return distance.error();
    r.distance = *distance;
    cam.coi = r;
  } else if (cj.contains("coi_path")) {
    auto path = string_member(cj, loc, "coi_path");
    if (!path) return path.error();
    cam.coi = RawCoiPath{*path};
  } else {
    auto hold = object_array(cj, loc, "hold", {"target", "hold_until", "move_frames"});
    if (!hold) return hold.error();
    RawHoldThenMove<double> h;
    for (std::size_t i = 0; i < (*hold)->size(); ++i) {
      const json& sj = (**hold)[i];
      const Loc p = at(at(loc, "hold"), i);
      RawHoldSegment<double> seg;
      auto target = read_target(sj, p, "target");
      if (!target) return target.error();
      auto until = number_member(sj, p, "hold_until", std::nullopt);
      if (!until) return until.error();
      auto move = number_member(sj, p, "move_frames", 0.0);
      if (!move) return move.error();
      seg.target = *target;
      seg.hold_until = *until;
      seg.move_frames = *move;
      h.segments.push_back(seg);
    }
    cam.coi = std::move(h);
  }
  auto up = vec3_member(cj, loc, "up", cam.up);
  if (!up) return up.error();
  cam.up = *up;
  auto up_path = string_member(cj, loc, "up_path");
  if (!up_path) return up_path.error();
  cam.up_path = *up_path;
  auto tilt = number_member(cj, loc, "tilt_deg", 0.0);
  if (!tilt) return tilt.error();
  cam.tilt_deg = *tilt;
  auto tilt_track = string_member(cj, loc, "tilt_track");
  if (!tilt_track) return tilt_track.error();
  cam.tilt_track = *tilt_track;
  return cam;
}

}  // namespace

Expected<void> needs_version_2(const json& obj, const Loc& loc, const Context& cx, std::string_view member) {
  if (cx.version >= 2 || !obj.contains(std::string(member))) return {};
  return error_at(ErrorCode::Unsupported,
                  "\"" + std::string(member) + "\" is a version-2 member: the file needs \"inbetween\": 2",
                  at(loc, std::string(member)));
}

Expected<void> read_paths(const json& root, const Context& cx, RawScene& scene) {
  if (auto ps = root.find("paths"); ps != root.end()) {
    if (!ps->is_array()) return error_at(ErrorCode::InvalidArgument, "\"paths\" must be an array", {"paths"});
    for (std::size_t i = 0; i < ps->size(); ++i) {
      const json& pj = (*ps)[i];
      const Loc p{"paths", i};
      if (!pj.is_object()) return error_at(ErrorCode::InvalidArgument, "a path must be an object, found " + type_name(pj), p);
      if (auto ok = only_members(pj, p, {"name", "curve", "file", "surface"}); !ok) return ok.error();
      RawScenePath path;
      auto name = pj.find("name");
      if (name == pj.end() || !name->is_string()) {
        return error_at(ErrorCode::InvalidArgument, "a path needs a non-empty string \"name\"", at(p, "name"));
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

Expected<void> read_skins(const json& root, RawScene& scene) {
  auto ss = root.find("skins");
  if (ss == root.end()) return {};
  if (!ss->is_array()) return error_at(ErrorCode::InvalidArgument, "\"skins\" must be an array", {"skins"});
  for (std::size_t i = 0; i < ss->size(); ++i) {
    const json& sj = (*ss)[i];
    const Loc p{"skins", i};
    if (!sj.is_object()) return error_at(ErrorCode::InvalidArgument, "a skin must be an object, found " + type_name(sj), p);
    if (auto ok = only_members(sj, p, {"name", "joints"}); !ok) return ok.error();
    RawSkin skin;
    if (auto name = sj.find("name"); name != sj.end()) {
      if (!name->is_string()) return error_at(ErrorCode::InvalidArgument, "\"name\" must be a string", at(p, "name"));
      skin.name = name->get<std::string>();
    }
    auto joints = sj.find("joints");
    if (joints == sj.end() || !joints->is_array()) {
      return error_at(ErrorCode::InvalidArgument, "a skin needs \"joints\": an array of object names", at(p, "joints"));
    }
    for (std::size_t j = 0; j < joints->size(); ++j) {
      const json& name = (*joints)[j];
      if (!name.is_string()) {
        return error_at(ErrorCode::InvalidArgument, "a joint is an object name (a string), found " + type_name(name),
                        at(at(p, "joints"), j));
      }
      skin.joints.push_back(name.get<std::string>());
    }
    scene.skins.push_back(std::move(skin));
  }
  return {};
}

Expected<void> read_path_and_camera(const json& oj, const Loc& p, const Context& cx, RawObject& object) {
  for (std::string_view member : {"path", "camera"}) {
    if (auto ok = needs_version_2(oj, p, cx, member); !ok) return ok.error();
  }
  if (auto pj = oj.find("path"); pj != oj.end()) {
    const Loc pp = at(p, "path");
    if (pj->is_array()) {
      object.path_is_array = true;
      if (pj->empty()) return error_at(ErrorCode::TooFewPoints, "a path needs at least one leg", pp);
      for (std::size_t k = 0; k < pj->size(); ++k) {
        auto leg = read_leg((*pj)[k], at(pp, k), cx);
        if (!leg) return leg.error();
        object.path.push_back(std::move(*leg));
      }
    } else {
      auto leg = read_leg(*pj, pp, cx);
      if (!leg) return leg.error();
      object.path.push_back(std::move(*leg));
    }
  }
  if (auto cj = oj.find("camera"); cj != oj.end()) {
    const Loc cp = at(p, "camera");
    if (!cj->is_object()) return error_at(ErrorCode::InvalidArgument, "expected an object, found " + type_name(*cj), cp);
    if (auto ok = only_members(*cj, cp, {"yfov_deg", "look_at", "ahead", "coi_path", "hold", "own_rotation", "up", "up_path",
                                         "tilt_deg", "tilt_track"});
        !ok) {
      return ok.error();
    }
    auto camera = read_camera(*cj, cp);
    if (!camera) return camera.error();
    object.camera = std::move(*camera);
  }
  return {};
}

}  // namespace inbetween::io_detail
