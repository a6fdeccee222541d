// The continuity measurement itself: jump sizes and tangent angles on hand-built joints whose
// values are known in closed form.
#include <gtest/gtest.h>

#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

TEST(Continuity, RightAngleCornerHasKnownJumpsAndAngle) {
  // Two Bézier segments meeting at (3,0): left end tangent 3((3,0) − (2,0)) = (3,0), right start
  // tangent 3((3,1) − (3,0)) = (0,3): |jump| = 3√2 and a 90° angle; position continuous.
  const auto c = build_bezier_path(std::vector<Vec2d>{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {3, 2}, {3, 3}}).value();
  const auto joints = measure_continuity(c);
  ASSERT_EQ(joints.size(), 1u);
  const auto& j = joints[0];
  EXPECT_EQ(j.u, 1.0);
  EXPECT_EQ(j.left_segment, 0);
  EXPECT_EQ(j.right_segment, 1);
  EXPECT_EQ(j.jump[0], 0.0);
  EXPECT_NEAR(j.jump[1], 3 * std::sqrt(2.0), test::few_ulp<double> * 8);
  EXPECT_NEAR(j.tangent_angle_rad, pi_v<double> / 2, test::few_ulp<double>);
  EXPECT_TRUE(j.tangent_defined);
  EXPECT_FALSE(j.g1);
  EXPECT_EQ(j.c_order(), 0);
}

TEST(Continuity, ParallelTangentsOfDifferentLengthAreG1NotC1AndZeroTangentIsNotG1) {
  const std::vector<Vec2d> pts{{0, 0}, {1, 0}, {2, 1}};
  // Hermite tangents are the same at a point for both segments: C¹ by construction.
  const auto h = build_hermite_spline(pts, std::vector<Vec2d>{{1, 0}, {2, 0}, {0, 1}}).value();
  EXPECT_EQ(measure_continuity(h)[0].c_order(), 1);
  // Bézier path with handles (0.5,0) | (1,0) | (2,0): same direction, lengths 1.5 and 3.
  const auto b = build_bezier_path(std::vector<Vec2d>{{-1, 0}, {0, 0}, {0.5, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}}).value();
  const auto j = measure_continuity(b)[0];
  EXPECT_EQ(j.c_order(), 0);
  EXPECT_TRUE(j.g1);
  EXPECT_NEAR(j.jump[1], 1.5, 1e-15);
  EXPECT_EQ(j.tangent_angle_rad, 0.0);
  // A handle on its anchor: zero tangent on the left, G¹ undefined (reported false, not NaN).
  const auto z = build_bezier_path(std::vector<Vec2d>{{-1, 0}, {0, 0}, {1, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}}).value();
  const auto jz = measure_continuity(z)[0];
  EXPECT_FALSE(jz.tangent_defined);
  EXPECT_FALSE(jz.g1);
  EXPECT_EQ(jz.tangent_angle_rad, 0.0);
}

}  // namespace
}  // namespace inbetween
