// Named surfaces (texts 004 §3.4.4); see include/inbetween/paths/surface_shapes.hpp.
#include "inbetween/paths/surface_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace inbetween {
namespace {

using Loc = std::vector<LocationStep>;

Error bad(Loc loc, std::string message, ErrorCode code = ErrorCode::invalid_argument) {
  return Error{code, std::move(message), std::move(loc)};
}

// Within kSurfaceMaxMagnitude: finite, and squares and sums of squares stay finite.
bool ok1(double v) { return std::abs(v) <= kSurfaceMaxMagnitude; }
bool finite3(const Vec3d& v) { return ok1(v.x) && ok1(v.y) && ok1(v.z); }

// Keys' cubic convolution (a = −½) on one interval: the Catmull-Rom cubic through f1 at t = 0 and f2
// at t = 1 with tangents (f2 − f0)/2 and (f3 − f1)/2; *d gets the derivative in t.
double catmull_rom(double f0, double f1, double f2, double f3, double t, double* d) {
  const double m1 = 0.5 * (f2 - f0), m2 = 0.5 * (f3 - f1);
  const double t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  if (d != nullptr) {
    const double d00 = 6 * t2 - 6 * t, d10 = 3 * t2 - 4 * t + 1, d01 = -6 * t2 + 6 * t, d11 = 3 * t2 - 2 * t;
    *d = d00 * f1 + d10 * m1 + d01 * f2 + d11 * m2;
  }
  return h00 * f1 + h10 * m1 + h01 * f2 + h11 * m2;
}

// Sample i of a line of n samples read by `at`, with the quadratic (n ≥ 3) or linear extrapolation
// beyond the ends (file comment of the header).
template <class At>
double extended(const At& at, int n, int i) {
  if (i >= 0 && i < n) return at(i);
  if (i < 0) return n >= 3 ? 3 * at(0) - 3 * at(1) + at(2) : 2 * at(0) - at(1);
  return n >= 3 ? 3 * at(n - 1) - 3 * at(n - 2) + at(n - 3) : 2 * at(n - 1) - at(n - 2);
}

// Grid coordinate of x in [0, n − 1] (clamped), split into cell i ∈ [0, n − 2] and t ∈ [0, 1];
// *inside is false where the clamp was active (the height is flat in that direction there).
void cell_of(double x, double origin, double spacing, int n, int& i, double& t, bool& inside) {
  double g = (x - origin) / spacing;
  inside = g >= 0 && g <= double(n - 1);
  g = std::clamp(std::isfinite(g) ? g : 0.0, 0.0, double(n - 1));
  i = std::min(int(std::floor(g)), n - 2);
  t = g - double(i);
}

double bernstein3(int i, double t) {
  const double s = 1 - t;
  switch (i) {
    case 0: return s * s * s;
    case 1: return 3 * t * s * s;
    case 2: return 3 * t * t * s;
    default: return t * t * t;
  }
}

}  // namespace

std::string_view surface_kind_name(const RawSurface& s) noexcept {
  switch (s.index()) {
    case 0: return "plane";
    case 1: return "sphere";
    case 2: return "torus";
    case 3: return "height_field";
    default: return "bezier_patch";
  }
}

Expected<SurfaceShape> SurfaceShape::build(const RawSurface& raw) {
  const std::string kind(surface_kind_name(raw));
  auto at = [&](std::string member) { return Loc{kind, std::move(member)}; };
  SurfaceShape out(raw);
  if (const auto* p = std::get_if<PlaneShape>(&raw)) {
    if (!finite3(p->origin)) return bad(at("origin"), "the plane's origin is not finite or beyond 1e150", ErrorCode::not_finite);
    if (!finite3(p->u_axis)) return bad(at("u_axis"), "the plane's u_axis is not finite or beyond 1e150", ErrorCode::not_finite);
    if (!finite3(p->v_axis)) return bad(at("v_axis"), "the plane's v_axis is not finite or beyond 1e150", ErrorCode::not_finite);
    const Vec3d n = cross(p->u_axis, p->v_axis);
    if (!(norm(n) > 1e-12 * norm(p->u_axis) * norm(p->v_axis)) || !std::isfinite(norm(n)))
      return bad(at("v_axis"), "the plane's u_axis and v_axis are zero or parallel");
    out.plane_normal_ = normalized(n, Vec3d{0, 1, 0});
  } else if (const auto* s = std::get_if<SphereShape>(&raw)) {
    if (!finite3(s->center)) return bad(at("center"), "the sphere's center is not finite or beyond 1e150", ErrorCode::not_finite);
    if (!(s->radius > 0) || !ok1(s->radius)) return bad(at("radius"), "the sphere's radius must be > 0 and at most 1e150");
  } else if (const auto* t = std::get_if<TorusShape>(&raw)) {
    if (!finite3(t->center)) return bad(at("center"), "the torus's center is not finite or beyond 1e150", ErrorCode::not_finite);
    if (!(t->minor_radius > 0) || !ok1(t->minor_radius))
      return bad(at("minor_radius"), "the torus's minor_radius must be > 0 and at most 1e150");
    if (!(t->major_radius > t->minor_radius) || !ok1(t->major_radius))
      return bad(at("major_radius"), "the torus's major_radius must be > minor_radius (a ring torus) and at most 1e150");
  } else if (const auto* g = std::get_if<HeightGridShape>(&raw)) {
    if (!(ok1(g->origin.x) && ok1(g->origin.y)))
      return bad(at("origin"), "the height field's origin is not finite or beyond 1e150", ErrorCode::not_finite);
    if (!(g->spacing.x > 0 && g->spacing.y > 0 && ok1(g->spacing.x) && ok1(g->spacing.y)))
      return bad(at("spacing"), "the height field's spacing must be two numbers > 0 and at most 1e150");
    if (g->rows < 2 || g->columns < 2)
      return bad(at("heights"), "the height field needs at least 2 rows of at least 2 heights, got " +
                                    std::to_string(g->rows) + " × " + std::to_string(g->columns));
    if (g->heights.size() != std::size_t(g->rows) * std::size_t(g->columns))
      return bad(at("heights"), "the height field has " + std::to_string(g->heights.size()) + " heights, not rows × columns = " +
                                    std::to_string(std::size_t(g->rows) * std::size_t(g->columns)));
    for (std::size_t i = 0; i < g->heights.size(); ++i)
      if (!ok1(g->heights[i]))
        return bad(Loc{kind, std::string("heights"), i / std::size_t(g->columns), i % std::size_t(g->columns)},
                   "height is not finite or beyond 1e150", ErrorCode::not_finite);
  } else {
    const auto& b = std::get<BezierPatchShape>(raw);
    for (std::size_t i = 0; i < 16; ++i)
      if (!finite3(b.points[i]))
        return bad(Loc{kind, std::string("points"), i / 4, i % 4}, "control point is not finite or beyond 1e150", ErrorCode::not_finite);
  }
  return out;
}

double SurfaceShape::height(double x, double z, Vec2d* gradient) const noexcept {
  const auto* g = std::get_if<HeightGridShape>(&raw_);
  if (g == nullptr) {
    if (gradient != nullptr) *gradient = {};
    return 0;
  }
  int k = 0, j = 0;
  double tx = 0, tz = 0;
  bool in_x = true, in_z = true;
  cell_of(x, g->origin.x, g->spacing.x, g->columns, k, tx, in_x);
  cell_of(z, g->origin.y, g->spacing.y, g->rows, j, tz, in_z);
  const int nc = g->columns, nr = g->rows;
  auto sample = [&](int row, int col) { return g->heights[std::size_t(row) * std::size_t(nc) + std::size_t(col)]; };
  // Along x in four rows j − 1 … j + 2 (rows beyond the grid extrapolated column by column).
  double row_value[4], row_dx[4];
  for (int a = 0; a < 4; ++a) {
    const int row = j - 1 + a;
    auto at = [&](int col) {
      return extended([&](int r) { return sample(r, col); }, nr, row);
    };
    const double f0 = extended(at, nc, k - 1), f1 = at(k), f2 = at(k + 1), f3 = extended(at, nc, k + 2);
    row_value[a] = catmull_rom(f0, f1, f2, f3, tx, &row_dx[a]);
  }
  double dz = 0, dx_dz_unused = 0;
  const double h = catmull_rom(row_value[0], row_value[1], row_value[2], row_value[3], tz, &dz);
  const double dx = catmull_rom(row_dx[0], row_dx[1], row_dx[2], row_dx[3], tz, &dx_dz_unused);
  if (gradient != nullptr)
    *gradient = {in_x ? dx / g->spacing.x : 0.0, in_z ? dz / g->spacing.y : 0.0};
  return h;
}

Vec3d SurfaceShape::point(double u, double v) const noexcept {
  switch (raw_.index()) {
    case 0: {
      const auto& p = std::get<PlaneShape>(raw_);
      return p.origin + p.u_axis * u + p.v_axis * v;
    }
    case 1: {
      const auto& s = std::get<SphereShape>(raw_);
      return s.center + Vec3d{std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)} * s.radius;
    }
    case 2: {
      const auto& t = std::get<TorusShape>(raw_);
      const double rho = t.major_radius + t.minor_radius * std::cos(v);
      return t.center + Vec3d{rho * std::cos(u), t.minor_radius * std::sin(v), rho * std::sin(u)};
    }
    case 3:
      return {u, height(u, v), v};
    default: {
      const auto& b = std::get<BezierPatchShape>(raw_);
      const double uu = std::clamp(std::isfinite(u) ? u : 0.0, 0.0, 1.0), vv = std::clamp(std::isfinite(v) ? v : 0.0, 0.0, 1.0);
      Vec3d out{};
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 4; ++i) out += b.points[std::size_t(k * 4 + i)] * (bernstein3(i, uu) * bernstein3(k, vv));
      return out;
    }
  }
}

double SurfaceShape::value(const Vec3d& p) const noexcept {
  switch (raw_.index()) {
    case 0: return dot(plane_normal_, p - std::get<PlaneShape>(raw_).origin);
    case 1: {
      const auto& s = std::get<SphereShape>(raw_);
      return distance(p, s.center) - s.radius;
    }
    case 2: {
      const auto& t = std::get<TorusShape>(raw_);
      const Vec3d q = p - t.center;
      const double rho = std::hypot(q.x, q.z) - t.major_radius;
      return rho * rho + q.y * q.y - t.minor_radius * t.minor_radius;
    }
    case 3: return p.y - height(p.x, p.z);
    default: return 0;
  }
}

Vec3d SurfaceShape::gradient(const Vec3d& p) const noexcept {
  switch (raw_.index()) {
    case 0: return plane_normal_;
    case 1: return normalized(Vec3d(p - std::get<SphereShape>(raw_).center), Vec3d{});
    case 2: {
      const auto& t = std::get<TorusShape>(raw_);
      const Vec3d q = p - t.center;
      const double rho = std::hypot(q.x, q.z);
      if (!(rho > 0)) return {};
      const double f = 2 * (rho - t.major_radius) / rho;
      return {f * q.x, 2 * q.y, f * q.z};
    }
    case 3: {
      Vec2d d{};
      height(p.x, p.z, &d);
      return {-d.x, 1, -d.y};
    }
    default: return {};
  }
}

double SurfaceShape::scale() const noexcept {
  switch (raw_.index()) {
    case 0: {
      const auto& p = std::get<PlaneShape>(raw_);
      return std::min(norm(p.u_axis), norm(p.v_axis));
    }
    case 1: return std::get<SphereShape>(raw_).radius;
    case 2: return std::get<TorusShape>(raw_).minor_radius;
    case 3: {
      const auto& g = std::get<HeightGridShape>(raw_);
      return std::min(g.spacing.x, g.spacing.y);
    }
    default: {
      const auto& b = std::get<BezierPatchShape>(raw_);
      double longest = 0;
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 4; ++i) {
          const Vec3d p = b.points[std::size_t(k * 4 + i)];
          if (i < 3) longest = std::max(longest, distance(p, b.points[std::size_t(k * 4 + i + 1)]));
          if (k < 3) longest = std::max(longest, distance(p, b.points[std::size_t(k * 4 + i + 4)]));
        }
      return longest;
    }
  }
}

}  // namespace inbetween
