// Natural and clamped C² splines: interpolation, C² (not C³) joints, natural ends, clamped end
// tangents, global control, derivatives vs differences.
#include <gtest/gtest.h>

#include "curve_test_util.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class CubicSplineTest : public ::testing::Test {};
TYPED_TEST_SUITE(CubicSplineTest, test::CurvePointTypes);

TYPED_TEST(CubicSplineTest, InterpolatesIsC2AndNaturalAtTheEnds) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(351));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<P>(rng, 8);
  const auto c = build_natural_spline(pts).value();
  // Tridiagonal solve of a diagonally dominant system: error ≲ 10 ulp of O(10) tangents.
  const T tol = T(1024) * test::eps<T>;
  for (int i = 0; i < 8; ++i) EXPECT_LT(test::max_abs_diff(c.point(T(i)), pts[i]), tol);
  EXPECT_LT(test::max_abs_diff(c.derivative(T(0), 2), P{}), tol * T(10));
  EXPECT_LT(test::max_abs_diff(c.derivative(T(7), 2), P{}), tol * T(10));
  for (const auto& j : measure_continuity(c)) EXPECT_EQ(j.c_order(), 2) << j.u;
}

TEST(CubicSplineDouble, ClampedEndTangentsAndGlobalControl) {
  test::Random rng(test::seed_for(352));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<Vec3d>(rng, 7);
  const Vec3d t0{1, 0, 0}, t1{0, 2, 0};
  const auto c = build_clamped_spline(pts, t0, t1).value();
  EXPECT_LT(test::max_abs_diff(c.derivative(0.0, 1), t0), 1e-14);
  EXPECT_LT(test::max_abs_diff(c.derivative(6.0, 1), t1), 1e-14);
  for (const auto& j : measure_continuity(c)) EXPECT_EQ(j.c_order(), 2);
  test::expect_global_control([](const std::vector<Vec3d>& p) { return build_natural_spline(p).value(); }, pts,
                              Vec3d{0.1, 0.1, 0.1});
  test::expect_derivatives_match_differences(c, rng);
}

TEST(CubicSplineDouble, TwoPointsGiveTheStraightSegment) {
  const auto c = build_natural_spline(std::vector<Vec2d>{{0, 0}, {2, 4}}).value();
  EXPECT_LT(test::max_abs_diff(c.point(0.25), Vec2d{0.5, 1}), 1e-15);
  EXPECT_EQ(c.derivative(0.5, 2), Vec2d{});
}

}  // namespace
}  // namespace inbetween
