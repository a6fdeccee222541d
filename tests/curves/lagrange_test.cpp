// Lagrange interpolation: passes through its points, global control, derivatives, and Runge's
// oscillation on equally spaced samples of 1/(1 + 25x²).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "curve_test_util.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

double runge(double x) { return 1 / (1 + 25 * x * x); }

// Max |p(x) − f(x)| over [−1, 1] of the interpolant on n equally spaced nodes.
double runge_error(int n) {
  std::vector<double> pts, params;
  for (int i = 0; i < n; ++i) {
    const double x = -1 + 2.0 * i / (n - 1);
    params.push_back(x);
    pts.push_back(runge(x));
  }
  const auto c = build_lagrange(pts, params).value();
  double worst = 0;
  for (int s = 0; s <= 2000; ++s) {
    const double x = -1 + 2.0 * s / 2000;
    worst = std::max(worst, std::abs(c.point(x) - runge(x)));
  }
  return worst;
}

// Issue 9, defect 4: the curve through 1.6e308, 0, 1 at u = 0, 1, 2 has finite coefficients
// (1.6e308, −1.6e308, 0.8e308) but its nested evaluation overflowed an intermediate (−2.4e308 at
// u = 0, then −inf·0 = NaN), so `curve sample` printed "0,-nan" and -inf.  Reference: the Lagrange
// form Σ y_i L_i(u) evaluated in long double (whose range holds every intermediate); the double
// evaluation must agree to a few ulp of the largest term, 1.6e308.  Derivatives: the first is
// 0.8e308·(2u − 3), whose true value exceeds double near u = 0 — ±inf there (documented
// saturation), finite elsewhere, never NaN.
TEST(LagrangeTest, HugeValuesEvaluateWithoutOverflowingIntermediates) {
  using L = long double;
  const std::vector<double> ys{1.6e308, 0, 1}, us{0, 1, 2};
  for (const bool explicit_params : {false, true}) {
    const auto c = explicit_params ? build_lagrange<double>(ys, us) : build_lagrange<double>(ys);
    ASSERT_TRUE(c.has_value()) << c.error().describe();
    int non_finite_values = 0, nan_derivatives = 0;
    for (int i = 0; i <= 200; ++i) {
      const double u = 2.0 * i / 200;
      L want = 0;
      for (int a = 0; a < 3; ++a) {
        L basis = 1;
        for (int b = 0; b < 3; ++b)
          if (b != a) basis *= (L(u) - L(us[std::size_t(b)])) / (L(us[std::size_t(a)]) - L(us[std::size_t(b)]));
        want += L(ys[std::size_t(a)]) * basis;
      }
      const double got = c->point(u);
      if (!std::isfinite(got)) ++non_finite_values;
      // Rounding of the coefficients and of three nested steps: a few ulp of the largest term.
      EXPECT_NEAR(L(got), want, L(16) * L(test::eps<double>) * L(1.6e308)) << "u = " << u;
      for (int k = 1; k <= 3; ++k)
        if (std::isnan(c->derivative(u, k))) ++nan_derivatives;
      const L slope = L(0.8e308) * (2 * L(u) - 3);  // closed form of P′ (up to the rounded 0.5)
      const double d1 = c->derivative(u, 1);
      const L top = L(std::numeric_limits<double>::max());
      if (std::fabs(slope) < L(0.99) * top) EXPECT_NEAR(L(d1), slope, L(64) * L(test::eps<double>) * 2.4e308L) << u;
      else if (std::fabs(slope) > L(1.01) * top) EXPECT_TRUE(std::isinf(d1) && (d1 < 0) == (slope < 0)) << u << " " << d1;
    }
    EXPECT_EQ(non_finite_values, 0);
    EXPECT_EQ(nan_derivatives, 0);
  }
}

TEST(LagrangeTest, RungeOscillationGrowsWithTheNumberOfEquallySpacedPoints) {
  // Known behaviour (Runge 1901): the max error on equally spaced nodes grows without bound;
  // independent evaluation with numpy.polyfit/polyval on the same nodes and 2001 sample points gives
  // 0.4327 (6 nodes), 1.91564 (11), 59.82 (21).
  const double e6 = runge_error(6), e11 = runge_error(11), e21 = runge_error(21);
  EXPECT_GT(e11, e6);
  EXPECT_GT(e21, 10 * e11);
  EXPECT_NEAR(e6, 0.43269, 1e-4);
  EXPECT_NEAR(e11, 1.91564, 1e-4);
  EXPECT_NEAR(e21, 59.822, 0.01);
}

TEST(LagrangeTest, InterpolatesGlobalControlAndDerivatives) {
  test::Random rng(test::seed_for(401));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<Vec2d>(rng, 6);
  const std::vector<double> params{0, 0.5, 1.5, 2, 3, 4.5};
  const auto c = build_lagrange(pts, params).value();
  for (int i = 0; i < 6; ++i) EXPECT_LT(test::max_abs_diff(c.point(params[i]), pts[i]), 1e-13);
  test::expect_global_control([&](const std::vector<Vec2d>& p) { return build_lagrange(p, params).value(); }, pts,
                              Vec2d{0.1, 0.1});
  test::expect_derivatives_match_differences(c, rng);
  const auto bad = build_lagrange(pts, std::vector<double>{0, 1, 1, 2, 3, 4});
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(json_pointer(bad.error().location), "/params/2");
  // The values are printed exactly (std::to_string's six decimals printed both as 0.000000).
  const auto close = build_lagrange(pts, std::vector<double>{0, 1e-9, 2e-9, 1.5e-9, 3, 4});
  ASSERT_FALSE(close.has_value());
  EXPECT_EQ(close.error().message, "param 3 (1.5e-09) is not greater than param 2 (2e-09)");
}

}  // namespace
}  // namespace inbetween
