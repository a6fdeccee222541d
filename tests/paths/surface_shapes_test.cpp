// Named surfaces (texts 004 §3.4.4) against closed forms: the sphere's and torus's
// parametrisations lie on their implicit forms with the closed-form normals, a u-line on the sphere
// is a circle of latitude, the bicubic height field reproduces a quadratic exactly, downhill on the
// paraboloid is radial and ends at its bottom, downhill on a tilted plane is a straight line down
// the gradient, and the Bézier patch has linear precision.
#include "inbetween/paths/surface_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "inbetween/paths/surface_path.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// Closed forms evaluated in double: a few ulp of the values involved (|p| ≤ 10).
constexpr double kClosedForm = 1e-13;
// The walk's projection stops at |F|/|∇F| ≤ 1e-13 (ProjectionOptions); ten times that.
constexpr double kOnSurface = 1e-12;

SurfaceShape built(const RawSurface& raw) {
  auto s = SurfaceShape::build(raw);
  EXPECT_TRUE(s) << (s ? "" : s.error().describe());
  return *s;
}

// y = q(x, z) = x² + z² − 0.5·x·z + 0.25·x: a quadratic the bicubic Catmull-Rom grid reproduces.
double quadratic(double x, double z) { return x * x + z * z - 0.5 * x * z + 0.25 * x; }
Vec2d quadratic_gradient(double x, double z) { return {2 * x - 0.5 * z + 0.25, 2 * z - 0.5 * x}; }

SurfaceShape grid_of(double (*h)(double, double), double lo, double spacing, int n) {
  HeightGridShape g{{lo, lo}, {spacing, spacing}, n, n, {}};
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) g.heights.push_back(h(lo + k * spacing, lo + j * spacing));
  return built(g);
}

TEST(SurfaceShapes, SphereAndTorusPointsLieOnTheirImplicitFormsWithClosedFormNormals) {
  test::Random rng(test::seed_for(26));
  SCOPED_TRACE(rng.trace());
  const Vec3d c{1, -2, 0.5};
  const SurfaceShape sphere = built(SphereShape{c, 3});
  const SurfaceShape torus = built(TorusShape{c, 3, 1});
  for (int i = 0; i < 200; ++i) {
    const double u = rng.uniform(-7.0, 7.0), v = rng.uniform(-3.0, 3.0);
    // Normals: sphere (cos v cos u, sin v, cos v sin u); the torus has the same normal at (u, v).
    const Vec3d n{std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)};
    for (const SurfaceShape* s : {&sphere, &torus}) {
      const Vec3d p = s->point(u, v);
      EXPECT_NEAR(s->value(p), 0.0, kClosedForm) << s->kind() << " u=" << u << " v=" << v;
      EXPECT_NEAR(norm(Vec3d(normalized(s->gradient(p), Vec3d{}) - n)), 0.0, kClosedForm) << s->kind();
    }
  }
}

TEST(SurfaceShapes, AULineOnTheSphereIsACircleOfLatitudeAndAVLineAGreatCircle) {
  // S(u, v0) for u from 0.2 to 2.9: distance R·cos v0 from the axis, height R·sin v0, and the
  // angle about +y grows linearly with u.  S(u0, v) lies in the plane through the axis at angle u0,
  // at distance R from the centre.
  const double R = 2, v0 = 0.6, u0 = 1.1;
  const SurfaceShape s = built(SphereShape{{}, R});
  const auto line = parametric_surface_path<double>([&](double u, double v) { return s.point(u, v); }, Vec2d{0.2, v0},
                                                   Vec2d{2.9, v0}, 28);
  ASSERT_EQ(line.size(), 28u);
  for (std::size_t i = 0; i < line.size(); ++i) {
    const Vec3d p = line[i];
    EXPECT_NEAR(std::hypot(p.x, p.z), R * std::cos(v0), kClosedForm);
    EXPECT_NEAR(p.y, R * std::sin(v0), kClosedForm);
    EXPECT_NEAR(std::atan2(p.z, p.x), 0.2 + 2.7 * double(i) / 27, kClosedForm);
  }
  const auto meridian = parametric_surface_path<double>([&](double u, double v) { return s.point(u, v); }, Vec2d{u0, -1.2},
                                                       Vec2d{u0, 1.4}, 9);
  const Vec3d plane_normal{-std::sin(u0), 0, std::cos(u0)};  // ⟂ (cos u0, 0, sin u0) and +y
  for (const Vec3d& p : meridian) {
    EXPECT_NEAR(norm(p), R, kClosedForm);
    EXPECT_NEAR(dot(p, plane_normal), 0.0, kClosedForm);
  }
}

TEST(SurfaceShapes, BicubicGridReproducesAQuadraticAndItsGradientEverywhere) {
  // Keys' cubic convolution reproduces quadratics; with the quadratic extrapolation at the border
  // the first and last cells do too.  Points over the whole grid, border cells included.
  const SurfaceShape s = grid_of(quadratic, -2, 0.5, 9);
  test::Random rng(test::seed_for(2626));
  SCOPED_TRACE(rng.trace());
  for (int i = 0; i < 300; ++i) {
    const double x = rng.uniform(-2.0, 2.0), z = rng.uniform(-2.0, 2.0);
    Vec2d g{};
    EXPECT_NEAR(s.height(x, z, &g), quadratic(x, z), kClosedForm) << x << ", " << z;
    EXPECT_NEAR(g.x, quadratic_gradient(x, z).x, kClosedForm);
    EXPECT_NEAR(g.y, quadratic_gradient(x, z).y, kClosedForm);
  }
  // Outside the grid the point is clamped: flat beyond the edge.
  Vec2d g{};
  EXPECT_NEAR(s.height(5, 1, &g), quadratic(2, 1), kClosedForm);
  EXPECT_EQ(g.x, 0.0);
  EXPECT_NEAR(g.y, quadratic_gradient(2, 1).y, kClosedForm);
}

TEST(SurfaceShapes, DownhillOnTheParaboloidIsRadialAndEndsAtTheBottom) {
  // y = x² + z²: the steepest descent from (x0, z0) runs along the radius to the origin (the
  // gradient (2x, 2z) is radial), so every point has (x, z) ∥ (x0, z0); it ends within a step.
  const SurfaceShape s = grid_of([](double x, double z) { return x * x + z * z; }, -2, 0.25, 17);
  const double step = 0.01;
  auto path = walk_on_surface(s, s.point(1.5, 1), {.step = step, .max_steps = 10000});
  ASSERT_TRUE(path) << path.error().describe();
  ASSERT_GT(path->size(), 100u);
  for (const Vec3d& p : *path) {
    EXPECT_NEAR(p.x * 1 - p.z * 1.5, 0.0, kOnSurface) << p.x << ", " << p.z;  // (x, z) × (1.5, 1) = 0
    EXPECT_NEAR(s.value(p), 0.0, kOnSurface);
  }
  const Vec3d end = path->back();
  EXPECT_LE(std::hypot(end.x, end.z), step);
  EXPECT_LT(int(path->size()), 10000);  // stopped at the bottom, not by max_steps
}

TEST(SurfaceShapes, DownhillOnATiltedPlaneGoesStraightDownTheGradient) {
  // The height field y = 0.5x + 0.25z (a 2 × 2 grid: linear interpolation) and the same plane
  // given as a plane: downhill is −(0.5, 0.25) in (x, z), a straight line, each step of length `step`.
  HeightGridShape g{{-1, -1}, {2, 2}, 2, 2, {}};
  for (double z : {-1.0, 1.0})
    for (double x : {-1.0, 1.0}) g.heights.push_back(0.5 * x + 0.25 * z);
  const SurfaceShape field = built(g);
  const SurfaceShape plane = built(PlaneShape{{0, 0, 0}, {1, 0.5, 0}, {0, 0.25, 1}});
  const double step = 0.05;
  for (const SurfaceShape* s : {&field, &plane}) {
    SCOPED_TRACE(s->kind());
    auto path = walk_on_surface(*s, Vec3d{0.6, 0, 0.4}, {.step = step, .max_steps = 20});
    ASSERT_TRUE(path) << path.error().describe();
    ASSERT_EQ(path->size(), 21u);
    const Vec3d start = path->front();
    EXPECT_NEAR(start.y, 0.5 * start.x + 0.25 * start.z, kOnSurface);
    const double c = std::hypot(0.5, 0.25);
    for (std::size_t i = 1; i < path->size(); ++i) {
      const Vec3d d = (*path)[i] - start;
      // across the gradient: zero; along it: i steps of the 3-D length `step`.
      EXPECT_NEAR(d.x * 0.25 - d.z * 0.5, 0.0, kOnSurface);
      EXPECT_NEAR(distance((*path)[i], (*path)[i - 1]), step, kOnSurface);
      EXPECT_LT(d.x * 0.5 + d.z * 0.25, 0.0);
      EXPECT_NEAR(-(d.x * 0.5 + d.z * 0.25) / c, double(i) * step * std::cos(std::atan(c)), 1e-12);
    }
  }
}

TEST(SurfaceShapes, BezierPatchHasLinearPrecision) {
  // Control points on a regular grid of an affine map A(u, v) reproduce it: S(u, v) = A(u, v).
  BezierPatchShape b;
  auto affine = [](double u, double v) { return Vec3d{1 + 2 * u, 0.5 * u - v, 3 * v}; };
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 4; ++i) b.points[std::size_t(k * 4 + i)] = affine(i / 3.0, k / 3.0);
  const SurfaceShape s = built(b);
  EXPECT_FALSE(s.has_implicit());
  for (double u : {0.0, 0.3, 0.75, 1.0})
    for (double v : {0.0, 0.4, 1.0}) EXPECT_NEAR(distance(s.point(u, v), affine(u, v)), 0.0, kClosedForm);
  EXPECT_EQ(s.point(2, -1), affine(1, 0));  // clamped to [0, 1]²
}

TEST(SurfaceShapes, BuildErrorsNameThePlace) {
  struct Case {
    RawSurface raw;
    std::string pointer, text;
  };
  const std::vector<Case> cases{
      {SphereShape{{}, 0}, "/sphere/radius", "radius must be > 0 and at most 1e150"},
      {SphereShape{{0, 1e151, 0}, 1}, "/sphere/center", "beyond 1e150"},
      {TorusShape{{}, 1, 1}, "/torus/major_radius", "> minor_radius"},
      {TorusShape{{}, 2, -1}, "/torus/minor_radius", "minor_radius must be"},
      {PlaneShape{{}, {1, 0, 0}, {2, 0, 0}}, "/plane/v_axis", "parallel"},
      {HeightGridShape{{}, {1, 0}, 2, 2, {0, 0, 0, 0}}, "/height_field/spacing", "spacing"},
      {HeightGridShape{{}, {1, 1}, 1, 2, {0, 0}}, "/height_field/heights", "at least 2 rows"},
      {HeightGridShape{{}, {1, 1}, 2, 2, {0, 0, NAN, 0}}, "/height_field/heights/1/0", "not finite"},
      {HeightGridShape{{}, {1, 1}, 2, 2, {0, 0, 0, -1e200}}, "/height_field/heights/1/1", "beyond 1e150"},
  };
  for (const Case& c : cases) {
    auto s = SurfaceShape::build(c.raw);
    ASSERT_FALSE(s) << c.pointer;
    EXPECT_EQ(json_pointer(s.error().location), c.pointer);
    EXPECT_NE(s.error().message.find(c.text), std::string::npos) << s.error().message;
  }
}

}  // namespace
}  // namespace inbetween
