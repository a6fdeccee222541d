// Hermite splines: positions and tangents are met, C¹ joints (not C²), local control.
#include <gtest/gtest.h>

#include "curve_test_util.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class Hermite : public ::testing::Test {};
TYPED_TEST_SUITE(Hermite, test::CurvePointTypes);

TYPED_TEST(Hermite, MeetsPositionsAndTangentsAndIsC1) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(361));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<P>(rng, 6), tans = test::random_points<P>(rng, 6);
  const auto c = build_hermite_spline(pts, tans).value();
  const T tol = T(256) * test::eps<T>;  // power form of O(1) inputs, ≤ 4 terms of ≤ 5 units
  for (int i = 0; i < 6; ++i) {
    EXPECT_LT(test::max_abs_diff(c.point(T(i)), pts[i]), tol);
    EXPECT_LT(test::max_abs_diff(c.derivative(T(i), 1), tans[i]), tol);
  }
  for (const auto& j : measure_continuity(c)) EXPECT_EQ(j.c_order(), 1) << j.u;
}

TEST(HermiteDouble, LocalControlAndErrors) {
  test::Random rng(test::seed_for(362));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<Vec2d>(rng, 7), tans = test::random_points<Vec2d>(rng, 7);
  test::expect_local_control([&](const std::vector<Vec2d>& p) { return build_hermite_spline(p, tans).value(); }, pts,
                             Vec2d{0.2, 0.3});
  EXPECT_EQ(build_hermite_spline(pts, tans).value().influence(3), (Interval<double>{2, 4}));
  test::expect_derivatives_match_differences(build_hermite_spline(pts, tans).value(), rng);
  const auto bad = build_hermite_spline(pts, std::vector<Vec2d>(3));
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().code, ErrorCode::wrong_arity);
}

}  // namespace
}  // namespace inbetween
