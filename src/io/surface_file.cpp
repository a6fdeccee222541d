// Surface files: JSON → SurfaceShape (include/inbetween/io/surface_file.hpp).  The JSON is read with
// bounded nesting (json_text.hpp); the shape errors and SurfaceShape::build's value errors carry a
// structured location, rendered once as "<source>:<JSON pointer>".
#include "inbetween/io/surface_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>

#include "json_read.hpp"
#include "json_text.hpp"

namespace inbetween {
namespace {

using io_detail::json;
using io_detail::fail;
using io_detail::join;
using io_detail::Loc;
using io_detail::only_fields;
using io_detail::read_number;

// An array of n numbers into out[0 … n − 1].
Expected<void> read_numbers(const json& v, const Loc& at, double* out, std::size_t n) {
  if (!v.is_array())
    return fail(at, "expected an array of " + std::to_string(n) + " numbers, got " + std::string(v.type_name()));
  if (v.size() != n)
    return fail(at, "expected " + std::to_string(n) + " numbers, got " + std::to_string(v.size()), ErrorCode::wrong_arity);
  for (std::size_t c = 0; c < n; ++c) {
    auto d = read_number(v[c], join(at, c));
    if (!d) return d.error();
    out[c] = *d;
  }
  return {};
}

// Optional member `name` of `obj` as a Vec3d into `out` (kept when absent).
Expected<void> opt_vec3(const json& obj, const Loc& at, std::string_view name, Vec3d& out) {
  const auto it = obj.find(std::string(name));
  if (it == obj.end()) return {};
  double xyz[3];
  if (auto ok = read_numbers(*it, join(at, name), xyz, 3); !ok) return ok;
  out = {xyz[0], xyz[1], xyz[2]};
  return {};
}
Expected<void> opt_vec2(const json& obj, const Loc& at, std::string_view name, Vec2d& out) {
  const auto it = obj.find(std::string(name));
  if (it == obj.end()) return {};
  double xy[2];
  if (auto ok = read_numbers(*it, join(at, name), xy, 2); !ok) return ok;
  out = {xy[0], xy[1]};
  return {};
}
Expected<double> need_number(const json& obj, const Loc& at, std::string_view name) {
  const auto it = obj.find(std::string(name));
  if (it == obj.end()) return fail(join(at, name), "missing required field");
  return read_number(*it, join(at, name));
}

Expected<RawSurface> read_kind(const std::string& kind, const json& v, const Loc& at) {
  if (!v.is_object()) return fail(at, "expected an object");
  if (kind == "plane") {
    if (auto ok = only_fields(v, at, {"origin", "u_axis", "v_axis"}); !ok) return ok.error();
    PlaneShape p;
    for (auto [name, dst] : {std::pair{"origin", &p.origin}, std::pair{"u_axis", &p.u_axis}, std::pair{"v_axis", &p.v_axis}})
      if (auto ok = opt_vec3(v, at, name, *dst); !ok) return ok.error();
    return RawSurface{p};
  }
  if (kind == "sphere") {
    if (auto ok = only_fields(v, at, {"center", "radius"}); !ok) return ok.error();
    SphereShape s;
    if (auto ok = opt_vec3(v, at, "center", s.center); !ok) return ok.error();
    auto r = need_number(v, at, "radius");
    if (!r) return r.error();
    s.radius = *r;
    return RawSurface{s};
  }
  if (kind == "torus") {
    if (auto ok = only_fields(v, at, {"center", "major_radius", "minor_radius"}); !ok) return ok.error();
    TorusShape t;
    if (auto ok = opt_vec3(v, at, "center", t.center); !ok) return ok.error();
    auto big = need_number(v, at, "major_radius");
    if (!big) return big.error();
    auto small = need_number(v, at, "minor_radius");
    if (!small) return small.error();
    t.major_radius = *big;
    t.minor_radius = *small;
    return RawSurface{t};
  }
  if (kind == "height_field") {
    if (auto ok = only_fields(v, at, {"origin", "spacing", "heights"}); !ok) return ok.error();
    HeightGridShape g;
    if (auto ok = opt_vec2(v, at, "origin", g.origin); !ok) return ok.error();
    if (auto ok = opt_vec2(v, at, "spacing", g.spacing); !ok) return ok.error();
    const auto it = v.find("heights");
    const Loc hat = join(at, "heights");
    if (it == v.end()) return fail(hat, "missing required field (rows of heights, one row per z)");
    if (!it->is_array()) return fail(hat, "expected an array of rows of heights");
    g.rows = int(std::min<std::size_t>(it->size(), 1u << 30));
    for (std::size_t j = 0; j < it->size(); ++j) {
      const json& row = (*it)[j];
      const Loc rat = join(hat, j);
      if (!row.is_array()) return fail(rat, "expected an array of heights, got " + std::string(row.type_name()));
      if (j == 0) g.columns = int(std::min<std::size_t>(row.size(), 1u << 30));
      if (row.size() != std::size_t(g.columns))
        return fail(rat, "row " + std::to_string(j) + " has " + std::to_string(row.size()) + " heights, row 0 has " +
                             std::to_string(g.columns), ErrorCode::wrong_arity);
      for (std::size_t k = 0; k < row.size(); ++k) {
        auto d = read_number(row[k], join(rat, k));
        if (!d) return d.error();
        g.heights.push_back(*d);
      }
    }
    return RawSurface{std::move(g)};
  }
  if (kind == "bezier_patch") {
    if (auto ok = only_fields(v, at, {"points"}); !ok) return ok.error();
    const auto it = v.find("points");
    const Loc pat = join(at, "points");
    if (it == v.end()) return fail(pat, "missing required field (4 rows of 4 control points)");
    if (!it->is_array() || it->size() != 4)
      return fail(pat, "expected 4 rows of 4 control points [x, y, z]", it->is_array() ? ErrorCode::wrong_arity : ErrorCode::parse);
    BezierPatchShape b;
    for (std::size_t k = 0; k < 4; ++k) {
      const json& row = (*it)[k];
      const Loc rat = join(pat, k);
      if (!row.is_array() || row.size() != 4)
        return fail(rat, "expected a row of 4 control points [x, y, z]", row.is_array() ? ErrorCode::wrong_arity : ErrorCode::parse);
      for (std::size_t i = 0; i < 4; ++i) {
        double xyz[3];
        if (auto ok = read_numbers(row[i], join(rat, i), xyz, 3); !ok) return ok.error();
        b.points[k * 4 + i] = {xyz[0], xyz[1], xyz[2]};
      }
    }
    return RawSurface{b};
  }
  return fail(at, "unknown surface kind; expected plane, sphere, torus, height_field or bezier_patch", ErrorCode::unsupported);
}

Expected<SurfaceShape> read_surface(const json& doc) {
  const Loc root{};
  if (!doc.is_object()) return fail(root, "expected a JSON object with \"inbetween_surface\": 1");
  if (!doc.contains("inbetween_surface"))
    return fail(join(root, "inbetween_surface"), "missing required field (the format version, 1)");
  const json& version = doc["inbetween_surface"];
  if (!version.is_number_integer() || version.get<long long>() != surface_format_version)
    return fail(join(root, "inbetween_surface"),
                "unsupported version " + (version.is_number() ? io_detail::short_dump(version) : std::string(version.type_name())) +
                    "; this reader knows version " + std::to_string(surface_format_version),
                ErrorCode::unsupported);
  if (doc.size() != 2)
    return fail(root, "expected exactly one surface beside \"inbetween_surface\": plane, sphere, torus, height_field or "
                      "bezier_patch, got " + std::to_string(doc.size() - 1) + " members");
  for (const auto& item : doc.items()) {
    if (item.key() == "inbetween_surface") continue;
    auto raw = read_kind(item.key(), item.value(), join(root, item.key()));
    if (!raw) return raw.error();
    return SurfaceShape::build(*raw);
  }
  return fail(root, "no surface");  // unreachable: doc.size() == 2
}

}  // namespace

Expected<SurfaceShape> parse_surface_json(std::string_view text, std::string_view source_name) {
  const std::string source(source_name);
  const io_detail::JsonText parsed = io_detail::parse_json_text(text);
  if (auto bad = io_detail::json_text_error(parsed, source)) return *bad;
  auto surface = read_surface(parsed.value);
  if (surface) return surface;
  return io_detail::located(surface.error(), source);
}

}  // namespace inbetween
