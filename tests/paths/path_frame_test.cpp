// Path frame helpers: perpendiculars, signed angles, rotations about an axis, unit tangents.
#include "inbetween/paths/path_frame.hpp"

#include <gtest/gtest.h>

#include "support/random.hpp"

namespace inbetween {
namespace {

TEST(PathFrame, AnyPerpendicularIsUnitAndPerpendicular) {
  test::Random rng(test::seed_for(5));
  SCOPED_TRACE(rng.trace());
  for (int k = 0; k < 200; ++k) {
    const Vec3d v = rng.vec3() * std::pow(10.0, rng.uniform(-100.0, 100.0));
    const Vec3d p = any_perpendicular(v);
    EXPECT_NEAR(norm(p), 1.0, 1e-15);
    EXPECT_NEAR(dot(p, v) / norm(v), 0.0, 1e-15);
  }
  EXPECT_EQ(any_perpendicular(Vec3d{}), (Vec3d{0, 1, 0}));  // documented fallback
  EXPECT_EQ(any_perpendicular(Vec3d{0, 0, 2}), (Vec3d{0, 1, 0}));  // (0,0,1) × (1,0,0) = (0,1,0)
}

TEST(PathFrame, SignedAngleAndRotationAreInverse) {
  test::Random rng(test::seed_for(6));
  SCOPED_TRACE(rng.trace());
  for (int k = 0; k < 200; ++k) {
    const Vec3d axis = rng.unit_vec3();
    const Vec3d a = any_perpendicular(axis);
    const double angle = rng.uniform(-3.1, 3.1);
    const Vec3d b = rotate_about(a, axis, angle);
    EXPECT_NEAR(signed_angle_about(a, b, axis), angle, 1e-14);
    EXPECT_NEAR(norm(b), 1.0, 1e-15);
  }
  // Quarter turn about z takes x to y (right-hand rule).
  const Vec3d y = rotate_about(Vec3d{1, 0, 0}, Vec3d{0, 0, 1}, pi_v<double> / 2);
  EXPECT_NEAR(y.x, 0.0, 1e-16);
  EXPECT_NEAR(y.y, 1.0, 1e-16);
}

TEST(PathFrame, MatrixAndQuaternionAgree) {
  const PathFramed f{{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}};  // quarter turn about z
  const Mat3d m = f.matrix();
  EXPECT_EQ(m.column(0), f.tangent);
  EXPECT_NEAR(distance(rotate(f.rotation(), Vec3d{1, 0, 0}), f.tangent), 0.0, 1e-15);
  EXPECT_NEAR(distance(rotate(f.rotation(), Vec3d{0, 1, 0}), f.normal), 0.0, 1e-15);
}

TEST(PathFrame, PerpendicularPartFallsBack) {
  EXPECT_EQ(perpendicular_part(Vec3d{0, 3, 0}, Vec3d{1, 0, 0}), (Vec3d{0, 1, 0}));
  // Parallel: any_perpendicular((1, 0, 0)) crosses with y (the first smallest component):
  // (1, 0, 0) × (0, 1, 0) = (0, 0, 1).
  EXPECT_EQ(perpendicular_part(Vec3d{2, 0, 0}, Vec3d{1, 0, 0}), (Vec3d{0, 0, 1}));
}

}  // namespace
}  // namespace inbetween
