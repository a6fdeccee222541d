// Composite cubic Bézier paths: anchors interpolated, C⁰ in general, C¹ with mirrored handles and
// G¹-only with collinear unequal handles; local control of anchors and handles.
#include <gtest/gtest.h>

#include "curve_test_util.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/continuity.hpp"

namespace inbetween {
namespace {

TEST(BezierPathTest, ContinuityDependsOnHandlesAsTheoryPredicts) {
  // Anchor (3,0) with handles (2,1)/(4,-1): mirrored → C¹; (2,1)/(5,-2): collinear, unequal → G¹ not C¹;
  // (2,1)/(4,1): a corner → C⁰ only.
  auto joint = [](Vec2d h) {
    const auto c = build_bezier_path(std::vector<Vec2d>{{0, 0}, {1, 1}, {2, 1}, {3, 0}, h, {5, 1}, {6, 0}}).value();
    return measure_continuity(c).at(0);
  };
  EXPECT_GE(joint({4, -1}).c_order(), 1);
  EXPECT_EQ(joint({5, -2}).c_order(), 0);
  EXPECT_TRUE(joint({5, -2}).g1);
  EXPECT_EQ(joint({4, 1}).c_order(), 0);
  EXPECT_FALSE(joint({4, 1}).g1);
}

TEST(BezierPathTest, LocalControlAnchorsTwoSegmentsHandlesOne) {
  test::Random rng(test::seed_for(371));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<Vec3d>(rng, 10);
  test::expect_local_control([](const std::vector<Vec3d>& p) { return build_bezier_path(p).value(); }, pts,
                             Vec3d{0.1, 0.2, 0.3});
  const auto c = build_bezier_path(pts).value();
  EXPECT_EQ(c.influence(3), (Interval<double>{0, 2}));
  EXPECT_EQ(c.influence(4), (Interval<double>{1, 2}));
  EXPECT_EQ(c.point(1.0), pts[3]);  // segment 1 starts exactly at its anchor (power form d = P3)
  EXPECT_FALSE(c.interpolates_control_points());
  test::expect_derivatives_match_differences(c, rng);
  EXPECT_FALSE(build_bezier_path(std::vector<Vec3d>(5)).has_value());  // not 3k + 1
}

}  // namespace
}  // namespace inbetween
