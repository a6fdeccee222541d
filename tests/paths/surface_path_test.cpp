// Paths on surfaces (texts 004 §3.4.4) on a plane, a sphere and a paraboloid (closed forms).
#include "inbetween/paths/surface_path.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/random.hpp"

namespace inbetween {
namespace {

constexpr double kR = 2.0;
// The projection stops at |F|/|∇F| ≤ 1e-13 (ProjectionOptions default for double); the closed-form
// checks below allow ten times that for the rounding of the final Newton step.
constexpr double kOnSurface = 1e-12;

auto sphere() {
  return make_implicit_surface<double>([](const Vec3d& p) { return dot(p, p) - kR * kR; },
                                       [](const Vec3d& p) { return p * 2.0; });
}

TEST(SurfacePath, DownhillVectorOnATiltedPlane) {
  // Plane y = s·x: n = (−s, 1, 0)/√(1+s²); n × (n × up) ∝ (−1, −s, 0): down the slope (x and y fall).
  const double s = 0.75, c = std::sqrt(1 + s * s);
  const Vec3d d = downhill_direction(Vec3d{-s / c, 1 / c, 0});
  EXPECT_NEAR(d.x, -1 / c, 1e-15);
  EXPECT_NEAR(d.y, -s / c, 1e-15);
  EXPECT_NEAR(d.z, 0.0, 1e-15);
  EXPECT_EQ(downhill_direction(Vec3d{0, 1, 0}), (Vec3d{}));  // level: no downhill
}

TEST(SurfacePath, HeadingOnAPlaneIsAStraightLine) {
  // Plane n0·p = 1 with n0 = (1, 2, 2)/3: the heading (1, 0, 0) projected on the plane is
  // h = (1, 0, 0) − (1/3)n0 = (8, −2, −2)/9, normalised; the walk is p0 + k·step·ĥ exactly.
  const Vec3d n0 = Vec3d{1, 2, 2} / 3.0;
  auto plane = make_implicit_surface<double>([n0](const Vec3d& p) { return dot(n0, p) - 1.0; },
                                             [n0](const Vec3d&) { return n0; });
  auto path = walk_on_surface(plane, Vec3d{0, 0, 0},
                              {.mode = SurfaceWalk::heading, .heading = {1, 0, 0}, .step = 0.25, .max_steps = 20});
  ASSERT_TRUE(path) << path.error().describe();
  ASSERT_EQ(path->size(), 21u);
  const Vec3d p0 = n0;  // the origin projected onto the plane: n0·(n0) = 1
  const Vec3d h = normalized(Vec3d{8, -2, -2}, Vec3d{});
  for (std::size_t k = 0; k < path->size(); ++k)
    EXPECT_NEAR(distance((*path)[k], p0 + h * (0.25 * double(k))), 0.0, 1e-14) << k;
}

TEST(SurfacePath, HeadingOnASphereFollowsAGreatCircle) {
  test::Random rng(test::seed_for(11));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3d start = rng.unit_vec3() * (kR * rng.uniform(0.5, 1.5));
    const Vec3d heading = rng.unit_vec3();
    auto path = walk_on_surface(sphere(), start,
                                {.mode = SurfaceWalk::heading, .heading = heading, .step = 0.1, .max_steps = 200});
    if (!path) continue;  // heading parallel to the normal: tested below
    const Vec3d p0 = (*path)[0];
    // Great circle: every point stays in the plane through the centre spanned by p0 and the first
    // step, and consecutive points are atan(step/R) apart (tangent step, then radial projection).
    const Vec3d axis = normalized(cross(p0, (*path)[1]), Vec3d{});
    for (std::size_t k = 0; k < path->size(); ++k) {
      const Vec3d p = (*path)[k];
      EXPECT_NEAR(norm(p), kR, kOnSurface) << k;
      EXPECT_NEAR(dot(p, axis), 0.0, 1e-11) << k;
      if (k > 0) {
        const Vec3d q = (*path)[k - 1];
        EXPECT_NEAR(std::atan2(norm(cross(q, p)), dot(q, p)), std::atan(0.1 / kR), 1e-12) << k;
      }
    }
  }
}

TEST(SurfacePath, DownhillOnASphereRunsDownAMeridianToTheBottom) {
  const double step = 0.05;
  const Vec3d start = Vec3d{1, 1, 1} * (kR / std::sqrt(3.0));
  auto path = walk_on_surface(sphere(), start, {.step = step, .max_steps = 1000});
  ASSERT_TRUE(path);
  const Vec3d meridian = normalized(cross(start, Vec3d{0, 1, 0}), Vec3d{});
  for (std::size_t k = 0; k < path->size(); ++k) {
    EXPECT_NEAR(norm((*path)[k]), kR, kOnSurface) << k;
    EXPECT_NEAR(dot((*path)[k], meridian), 0.0, 1e-12) << k;
    if (k > 0) EXPECT_LT((*path)[k].y, (*path)[k - 1].y) << k;
  }
  // Each step turns by α = atan(step/R) about the centre; the walk stops once a step would not
  // descend, which leaves it within α/2 of the bottom (0, −R, 0).
  const Vec3d last = path->back();
  const double from_bottom = std::atan2(std::hypot(last.x, last.z), -last.y);
  EXPECT_LE(from_bottom, std::atan(step / kR) / 2 + 1e-12);
  EXPECT_LT(path->size(), 1000u);
}

TEST(SurfacePath, DownhillOnAParaboloidIsRadial) {
  // y = x² + z²: rotationally symmetric, so steepest descent follows the meridian z/x = const.
  auto bowl = make_height_field<double>([](double x, double z) { return x * x + z * z; },
                                        [](double x, double z) { return Vec2d{2 * x, 2 * z}; });
  auto path = walk_on_surface(bowl, Vec3d{1, 0, 0.5}, {.step = 0.02, .max_steps = 500});
  ASSERT_TRUE(path);
  for (std::size_t k = 0; k < path->size(); ++k) {
    const Vec3d p = (*path)[k];
    EXPECT_NEAR(p.y, p.x * p.x + p.z * p.z, kOnSurface) << k;
    EXPECT_NEAR(p.z, 0.5 * p.x, 1e-12) << k;
  }
  EXPECT_LT(norm(path->back()), 0.02);  // within a step of the bottom
}

TEST(SurfacePath, ParametricLineMapsOntoTheSurface) {
  auto sph = [](double u, double v) { return Vec3d{kR * std::cos(u) * std::cos(v), kR * std::sin(v), kR * std::sin(u) * std::cos(v)}; };
  const auto pts = parametric_surface_path<double>(sph, Vec2d{0, 0}, Vec2d{1, 0.5}, 11);
  ASSERT_EQ(pts.size(), 11u);
  EXPECT_EQ(pts.front(), sph(0, 0));
  EXPECT_NEAR(distance(pts.back(), sph(1, 0.5)), 0.0, 1e-15);
  for (const auto& p : pts) EXPECT_NEAR(norm(p), kR, 1e-14);
}

TEST(SurfacePath, BadInputIsNamed) {
  const double nan = std::nan("");
  auto a = walk_on_surface(sphere(), Vec3d{nan, 0, 0});
  ASSERT_FALSE(a);
  EXPECT_EQ(a.error().where, "start");
  auto b = walk_on_surface(sphere(), Vec3d{1, 0, 0}, {.step = 0.0});
  ASSERT_FALSE(b);
  EXPECT_EQ(b.error().where, "step");
  // Heading along the normal at (R, 0, 0): no tangent direction.
  auto c = walk_on_surface(sphere(), Vec3d{1, 0, 0}, {.mode = SurfaceWalk::heading, .heading = {1, 0, 0}});
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().where, "heading");
  // The centre of the sphere has ∇F = 0: projection cannot start there.
  auto d = walk_on_surface(sphere(), Vec3d{0, 0, 0});
  ASSERT_FALSE(d);
  EXPECT_EQ(d.error().where, "start");
  auto e = walk_on_surface(sphere(), Vec3d{1, 0, 0}, {.max_steps = -1});
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().where, "max_steps");
  auto f = walk_on_surface(sphere(), Vec3d{1, 0, 0}, {.up = {0, 0, 0}});
  ASSERT_FALSE(f);
  EXPECT_EQ(f.error().where, "up");
}

template <class T>
class SurfaceTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SurfaceTyped, Scalars);

// Both walks keep every point on the unit sphere to the projection tolerance (1e-6 in float,
// 1e-13 in double: ProjectionOptions defaults), with a few ulp of |p| on top.
TYPED_TEST(SurfaceTyped, WalksStayOnTheSphere) {
  using T = TypeParam;
  const T tol = sizeof(T) == 4 ? T(2e-6) : T(1e-12);
  auto s = make_implicit_surface<T>([](const Vec3<T>& p) { return dot(p, p) - T(1); },
                                    [](const Vec3<T>& p) { return p * T(2); });
  for (auto mode : {SurfaceWalk::downhill, SurfaceWalk::heading}) {
    auto path = walk_on_surface(s, Vec3<T>{T(0.3), T(0.9), T(-0.2)},
                                {.mode = mode, .heading = {0, 0, 1}, .step = T(0.05), .max_steps = 300});
    ASSERT_TRUE(path);
    EXPECT_GT(path->size(), 10u);
    for (const auto& p : *path) EXPECT_NEAR(norm(p), T(1), tol);
  }
}

TEST(SurfacePath, StartingAtTheBottomStopsAtOnce) {
  auto path = walk_on_surface(sphere(), Vec3d{0, -3, 0});
  ASSERT_TRUE(path);
  ASSERT_EQ(path->size(), 1u);  // level spot: no downhill direction
  EXPECT_NEAR(path->front().y, -kR, kOnSurface);
}

}  // namespace
}  // namespace inbetween
