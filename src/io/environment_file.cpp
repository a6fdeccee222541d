// Environment files: JSON → EnvironmentFile.  The JSON is read with bounded nesting
// (json_text.hpp); every error carries its place as a structured location (Error::location, the
// same mechanism as the scene reader and the library's Environment::build / plan_polyline /
// time_path), rendered once as "<source>:<JSON pointer>" in `where` at the API boundary.
#include "inbetween/io/environment_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "json_read.hpp"
#include "json_text.hpp"

namespace inbetween {
namespace {

using io_detail::json;
using io_detail::located;
using io_detail::fail;
using io_detail::join;
using io_detail::Loc;
using io_detail::only_fields;
using io_detail::read_number;

// The required member `name` of `obj`.
Expected<const json*> field(const json& obj, const Loc& at, std::string_view name) {
  const auto it = obj.find(std::string(name));
  if (it == obj.end()) return fail(join(at, name), "missing required field");
  return &*it;
}

Expected<Vec3d> read_vec3(const json& v, const Loc& at) {
  if (!v.is_array()) return fail(at, "expected an array of 3 numbers, got " + std::string(v.type_name()));
  if (v.size() != 3) return fail(at, "expected 3 numbers, got " + std::to_string(v.size()), ErrorCode::wrong_arity);
  Vec3d out{};
  for (std::size_t c = 0; c < 3; ++c) {
    auto d = read_number(v[c], join(at, c));
    if (!d) return d.error();
    out[int(c)] = *d;
  }
  return out;
}

Expected<Vec3d> read_vec3_field(const json& obj, const Loc& at, std::string_view name) {
  auto f = field(obj, at, name);
  if (!f) return f.error();
  return read_vec3(**f, join(at, name));
}

Expected<double> read_number_field(const json& obj, const Loc& at, std::string_view name) {
  auto f = field(obj, at, name);
  if (!f) return f.error();
  return read_number(**f, join(at, name));
}

Expected<RawObstacle> read_obstacle(const json& o, const Loc& pointer) {
  if (!o.is_object() || o.size() != 1)
    return fail(pointer, "expected an object with one key: sphere, box, obb or moving_sphere");
  const std::string kind = o.begin().key();
  const json& v = o.begin().value();
  const Loc at = join(pointer, kind);
  if (!v.is_object()) return fail(at, "expected an object");
  if (kind == "sphere") {
    if (auto ok = only_fields(v, at, {"center", "radius"}); !ok) return ok.error();
    auto c = read_vec3_field(v, at, "center");
    if (!c) return c.error();
    auto rad = read_number_field(v, at, "radius");
    if (!rad) return rad.error();
    return RawObstacle{SphereObstacle{*c, *rad}};
  }
  if (kind == "box") {
    if (auto ok = only_fields(v, at, {"min", "max"}); !ok) return ok.error();
    auto lo = read_vec3_field(v, at, "min");
    if (!lo) return lo.error();
    auto hi = read_vec3_field(v, at, "max");
    if (!hi) return hi.error();
    return RawObstacle{BoxObstacle{*lo, *hi}};
  }
  if (kind == "obb") {
    if (auto ok = only_fields(v, at, {"center", "half_size", "rotation"}); !ok) return ok.error();
    auto c = read_vec3_field(v, at, "center");
    if (!c) return c.error();
    auto h = read_vec3_field(v, at, "half_size");
    if (!h) return h.error();
    Quatd q{};
    if (v.contains("rotation")) {
      const json& qa = v["rotation"];
      const Loc qp = join(at, "rotation");
      if (!qa.is_array() || qa.size() != 4)
        return fail(qp, "expected 4 numbers [w, x, y, z]", qa.is_array() ? ErrorCode::wrong_arity : ErrorCode::parse);
      double wxyz[4];
      for (std::size_t k = 0; k < 4; ++k) {
        auto d = read_number(qa[k], join(qp, k));
        if (!d) return d.error();
        wxyz[k] = *d;
      }
      q = Quatd::from_wxyz(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    }
    return RawObstacle{OrientedBoxObstacle{*c, *h, q}};
  }
  if (kind == "moving_sphere") {
    if (auto ok = only_fields(v, at, {"center", "velocity", "radius", "t0"}); !ok) return ok.error();
    auto c = read_vec3_field(v, at, "center");
    if (!c) return c.error();
    auto vel = read_vec3_field(v, at, "velocity");
    if (!vel) return vel.error();
    auto rad = read_number_field(v, at, "radius");
    if (!rad) return rad.error();
    double t0 = 0;
    if (v.contains("t0")) {
      auto d = read_number(v["t0"], join(at, "t0"));
      if (!d) return d.error();
      t0 = *d;
    }
    return RawObstacle{MovingSphereObstacle{*c, *vel, *rad, t0}};
  }
  return fail(at, "unknown obstacle kind; expected sphere, box, obb or moving_sphere",
                ErrorCode::unsupported);
}

// The document → EnvironmentFile; errors with structured locations (not yet rendered).
Expected<EnvironmentFile> read_environment(const json& doc) {
  const Loc root{};
  if (!doc.is_object()) return fail(root, "expected a JSON object with \"inbetween_env\": 1");
  if (!doc.contains("inbetween_env"))
    return fail(join(root, "inbetween_env"), "missing required field (the format version, 1)");
  {
    const json& v = doc["inbetween_env"];
    if (!v.is_number_integer() || v.get<long long>() != environment_format_version)
      return fail(join(root, "inbetween_env"),
                  "unsupported version " + (v.is_number() ? io_detail::short_dump(v) : std::string(v.type_name())) +
                      "; this reader knows version " + std::to_string(environment_format_version),
                  ErrorCode::unsupported);
  }
  if (auto ok = only_fields(doc, root, {"inbetween_env", "radius", "start", "goal", "via", "bounds", "obstacles", "speed",
                                        "fps", "cell_size", "margin", "mover"});
      !ok)
    return ok.error();
  EnvironmentFile out;
  auto radius = read_number_field(doc, root, "radius");
  if (!radius) return radius.error();
  out.environment.radius = *radius;
  auto bounds = field(doc, root, "bounds");
  if (!bounds) return bounds.error();
  const Loc bounds_at = join(root, "bounds");
  if (!(*bounds)->is_object()) return fail(bounds_at, "expected an object with min and max");
  if (auto ok = only_fields(**bounds, bounds_at, {"min", "max"}); !ok) return ok.error();
  auto lo = read_vec3_field(**bounds, bounds_at, "min");
  if (!lo) return lo.error();
  auto hi = read_vec3_field(**bounds, bounds_at, "max");
  if (!hi) return hi.error();
  out.environment.bounds_min = *lo;
  out.environment.bounds_max = *hi;
  if (doc.contains("mover")) {
    const json& m = doc["mover"];
    const Loc mover_at = join(root, "mover");
    if (!m.is_object() || m.size() != 1) return fail(mover_at, "expected an object with one key: sphere or capsule");
    const std::string kind = m.begin().key();
    const json& v = m.begin().value();
    const Loc at = join(mover_at, kind);
    if (kind == "sphere") {
      if (!v.is_object() || !v.empty()) return fail(at, "expected {} (the sphere's radius is the top-level radius)");
    } else if (kind == "capsule") {
      if (!v.is_object()) return fail(at, "expected an object with half_length (and turn_rate_deg)");
      if (auto ok = only_fields(v, at, {"half_length", "turn_rate_deg"}); !ok) return ok.error();
      CapsuleMover c;
      auto half = read_number_field(v, at, "half_length");
      if (!half) return half.error();
      c.half_length = *half;
      if (v.contains("turn_rate_deg")) {
        auto rate = read_number(v["turn_rate_deg"], join(at, "turn_rate_deg"));
        if (!rate) return rate.error();
        c.turn_rate_deg = *rate;
      }
      out.environment.capsule = c;
    } else {
      return fail(at, "unknown mover; expected sphere or capsule", ErrorCode::unsupported);
    }
  }
  auto start = read_vec3_field(doc, root, "start");
  if (!start) return start.error();
  auto goal = read_vec3_field(doc, root, "goal");
  if (!goal) return goal.error();
  out.ends.start = *start;
  out.ends.goal = *goal;
  if (doc.contains("via")) {
    const json& via = doc["via"];
    const Loc via_at = join(root, "via");
    if (!via.is_array()) return fail(via_at, "expected an array of points [x, y, z]");
    for (std::size_t i = 0; i < via.size(); ++i) {
      auto p = read_vec3(via[i], join(via_at, i));
      if (!p) return p.error();
      out.ends.via.push_back(*p);
    }
  }
  auto obstacles = field(doc, root, "obstacles");
  if (!obstacles) return obstacles.error();
  const Loc obstacles_at = join(root, "obstacles");
  if (!(*obstacles)->is_array()) return fail(obstacles_at, "expected an array of obstacles");
  for (std::size_t i = 0; i < (*obstacles)->size(); ++i) {
    auto o = read_obstacle((**obstacles)[i], join(obstacles_at, i));
    if (!o) return o.error();
    out.environment.obstacles.push_back(*o);
  }
  for (const char* name : {"speed", "fps", "cell_size", "margin"}) {
    if (!doc.contains(name)) continue;
    auto d = read_number(doc[name], join(root, name));
    if (!d) return d.error();
    const std::string n = name;
    (n == "speed" ? out.timing.speed : n == "fps" ? out.timing.fps : n == "cell_size" ? out.planner.cell_size
                                                                                     : out.planner.margin) = *d;
  }
  return out;
}

}  // namespace

Expected<EnvironmentFile> parse_environment_json(std::string_view text, std::string_view source_name) {
  const std::string source(source_name);
  const io_detail::JsonText parsed = io_detail::parse_json_text(text);
  if (auto bad = io_detail::json_text_error(parsed, source)) return *bad;
  auto file = read_environment(parsed.value);
  if (file) return file;
  return locate_environment_error(file.error(), source_name);
}

Error locate_environment_error(const Error& error, std::string_view source_name) {
  // "env.json:/obstacles/2/box/min/1"; a library error without a place in the file (an option of
  // the call) is placed at the file.
  return located(error, std::string(source_name));
}

}  // namespace inbetween
