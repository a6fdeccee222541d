// Obstacle environments (paths/environment.hpp): exact distances against closed forms and dense
// sampling, the hierarchy against a plain loop, and the builder's errors.
#include "inbetween/paths/environment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/random.hpp"

namespace {

// Named tolerances.  Coordinates are of order 10, so a distance computed in double is off by
// about 1e-14; kExact allows for that.  kRounding also covers the arc-length inverse (16ε·L,
// arclength/arc_length.hpp) and s(t) interpolation; neither hides a real overlap, which the
// guarantees under test make non-negative.
constexpr double kExact = 1e-12;
constexpr double kRounding = 1e-9;


using namespace inbetween;

// Minimum of the point distance over 20001 points of the segment: an independent upper bound on
// the segment distance that is within |b − a|/40000 of it (the distance is 1-Lipschitz in the
// point, and the nearest sample is within half a step of the minimiser).
template <class O>
double sampled_segment_distance(const O& o, const Vec3d& a, const Vec3d& b) {
  constexpr int kSamples = 20000;
  double best = 1e300;
  for (int i = 0; i <= kSamples; ++i) best = std::min(best, distance_to_obstacle(o, a + (b - a) * (double(i) / kSamples)));
  return best;
}

TEST(EnvironmentDistance, ClosedForms) {
  // Sphere: |p − c| − R.  Box: the clamped point.  Both worked by hand.
  EXPECT_DOUBLE_EQ(distance_to_obstacle(SphereObstacle{{1, 2, 3}, 2}, Vec3d{1, 2, 8}), 3.0);
  EXPECT_DOUBLE_EQ(distance_to_obstacle(SphereObstacle{{1, 2, 3}, 2}, Vec3d{1, 2, 4}), 0.0);
  const BoxObstacle box{{0, 0, 0}, {1, 2, 3}};
  EXPECT_DOUBLE_EQ(distance_to_obstacle(box, Vec3d{4, 6, 3}), 5.0);  // (3, 4, 0) past the corner
  EXPECT_DOUBLE_EQ(distance_to_obstacle(box, Vec3d{0.5, 1, 1}), 0.0);
  // An oriented box turned 90° about z is the axis-aligned box with x and y extents swapped.
  const OrientedBoxObstacle obb{{0, 0, 0}, {1, 2, 3}, Quatd::from_axis_angle(Vec3d{0, 0, 1}, pi_v<double> / 2)};
  EXPECT_NEAR(distance_to_obstacle(obb, Vec3d{5, 0, 0}), 3.0, kExact);  // x half extent is now 2
  EXPECT_NEAR(distance_to_obstacle(obb, Vec3d{0, 4, 0}), 3.0, kExact);  // y half extent is now 1
  // Segment past a sphere: the closest point is the foot of the perpendicular.
  EXPECT_DOUBLE_EQ(segment_distance_to_obstacle(SphereObstacle{{0, 0, 0}, 1}, Vec3d{-5, 3, 0}, Vec3d{5, 3, 0}), 2.0);
  // Segment parallel to a box edge at distance (1, 1): √2.
  EXPECT_NEAR(segment_distance_to_obstacle(box, Vec3d{2, 3, -5}, Vec3d{2, 3, 9}), std::sqrt(2.0), 1e-15);
  // Segment through the box: 0.
  EXPECT_EQ(segment_distance_to_obstacle(box, Vec3d{-1, 1, 1}, Vec3d{5, 1, 1}), 0.0);
}

TEST(EnvironmentDistance, SegmentToBoxMatchesDenseSamplingSeededLoop) {
  test::Random rng(test::seed_for(1301));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3d c = rng.vec3(-1.0, 1.0), h{rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0)};
    const Vec3d a = rng.vec3(-3.0, 3.0), b = rng.vec3(-3.0, 3.0);
    const BoxObstacle box{c - h, c + h};
    const OrientedBoxObstacle obb{c, h, rng.rotation()};
    const double tol = distance(a, b) / 40000 + kExact;  // the sampling bound of the reference
    const double exact_box = segment_distance_to_obstacle(box, a, b);
    const double sampled_box = sampled_segment_distance(box, a, b);
    EXPECT_LE(exact_box, sampled_box + kExact) << trial;
    EXPECT_GE(exact_box, sampled_box - tol) << trial;
    const double exact_obb = segment_distance_to_obstacle(obb, a, b);
    const double sampled_obb = sampled_segment_distance(obb, a, b);
    EXPECT_LE(exact_obb, sampled_obb + kExact) << trial;
    EXPECT_GE(exact_obb, sampled_obb - tol) << trial;
  }
}

RawEnvironment random_environment(test::Random& rng, int count) {
  RawEnvironment raw;
  raw.radius = 0.2;
  raw.bounds_min = {-10, -10, -10};
  raw.bounds_max = {10, 10, 10};
  for (int i = 0; i < count; ++i) {
    const Vec3d c = rng.vec3(-10.0, 10.0);
    const Vec3d h{rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0), rng.uniform(0.1, 1.0)};
    switch (i % 4) {
      case 0: raw.obstacles.push_back(SphereObstacle{c, h.x}); break;
      case 1: raw.obstacles.push_back(BoxObstacle{c - h, c + h}); break;
      case 2: raw.obstacles.push_back(OrientedBoxObstacle{c, h, rng.rotation()}); break;
      default: raw.obstacles.push_back(MovingSphereObstacle{c, rng.vec3(), h.x, 0}); break;
    }
  }
  return raw;
}

// The hierarchy's answers equal a plain loop over every obstacle.
TEST(Environment, HierarchyAgreesWithPlainLoopSeededLoop) {
  test::Random rng(test::seed_for(1302));
  SCOPED_TRACE(rng.trace());
  const auto env = Environment::build(random_environment(rng, 200));
  ASSERT_TRUE(env) << env.error().describe();
  EXPECT_EQ(env->static_count(), 150);
  EXPECT_EQ(env->moving_indices().size(), 50u);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3d p = rng.vec3(-10.0, 10.0), q = rng.vec3(-10.0, 10.0);
    const double margin = rng.uniform(0.0, 0.5);
    EXPECT_EQ(env->blocking_static(p, margin) >= 0, env->static_clearance(p) < margin) << trial;
    // Segment: lowest obstacle index closer than r + margin, by brute force.
    const Vec3d b = p + (q - p) * 0.2;
    int want = -1;
    for (std::size_t k = 0; k < env->obstacles().size() && want < 0; ++k) {
      const double d = std::visit(
          [&](const auto& o) -> double {
            if constexpr (std::is_same_v<std::decay_t<decltype(o)>, MovingSphereObstacle>) return 1e300;
            else return segment_distance_to_obstacle(o, p, b);
          },
          env->obstacles()[k]);
      if (d < env->radius() + margin) want = int(k);
    }
    EXPECT_EQ(env->blocking_static(p, b, margin), want) << trial;
  }
}

TEST(Environment, MovingSphereFollowsItsLine) {
  RawEnvironment raw{0.5, {-10, -10, -10}, {10, 10, 10}, {MovingSphereObstacle{{0, 0, 0}, {1, 0, 0}, 1, 2}}};
  const auto env = Environment::build(raw);
  ASSERT_TRUE(env);
  // centre(5) = (3, 0, 0); the point (3, 4, 0) is 4 away: clearance 4 − 1 − 0.5.
  EXPECT_DOUBLE_EQ(env->moving_clearance(0, Vec3d{3, 4, 0}, 5), 2.5);
  EXPECT_EQ(env->blocking_static(Vec3d{0, 0, 0}), -1);  // moving spheres are not static
}

TEST(Environment, BuilderErrorsNameTheObstacle) {
  auto with = [](RawObstacle o) {
    RawEnvironment raw{0.5, {0, 0, 0}, {1, 1, 1}, {SphereObstacle{{0, 0, 0}, 1}, o}};
    return Environment::build(raw);
  };
  auto e = with(SphereObstacle{{0, 0, 0}, 0});
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/obstacles/1/sphere/radius");
  EXPECT_NE(e.error().message.find("obstacle 1"), std::string::npos);
  e = with(BoxObstacle{{0, 0, 0}, {1, 0, 1}});
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/obstacles/1/box/max");
  e = with(OrientedBoxObstacle{{0, 0, 0}, {1, 1, 1}, Quatd::from_wxyz(0, 0, 0, 0)});
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/obstacles/1/obb/rotation");
  e = with(OrientedBoxObstacle{{0, 0, 0}, {1, -1, 1}, Quatd{}});
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/obstacles/1/obb/half_size");
  e = with(MovingSphereObstacle{{0, 0, 0}, {std::nan(""), 0, 0}, 1, 0});
  ASSERT_FALSE(e);
  EXPECT_EQ(json_pointer(e.error().location), "/obstacles/1/moving_sphere/velocity");
  EXPECT_EQ(e.error().code, ErrorCode::not_finite);
  RawEnvironment raw{-1, {0, 0, 0}, {1, 1, 1}, {}};
  EXPECT_EQ(json_pointer(Environment::build(raw).error().location), "/radius");
  raw = RawEnvironment{1, {0, 0, 0}, {1, 0, 1}, {}};
  EXPECT_EQ(json_pointer(Environment::build(raw).error().location), "/bounds/max");
  raw = RawEnvironment{1, {-1e308, 0, 0}, {1e308, 1, 1}, {}};  // max − min overflows
  EXPECT_EQ(json_pointer(Environment::build(raw).error().location), "/bounds/max");
  // A rotation of norm 2 is normalised.
  e = with(OrientedBoxObstacle{{0, 0, 0}, {1, 1, 1}, Quatd::from_wxyz(2, 0, 0, 0)});
  ASSERT_TRUE(e);
  EXPECT_DOUBLE_EQ(std::get<OrientedBoxObstacle>(e->obstacles()[1]).rotation.w, 1.0);
}

}  // namespace
