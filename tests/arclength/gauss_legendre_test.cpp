#include "inbetween/arclength/gauss_legendre.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace inbetween {
namespace {

// Rounding of a sum of up to 64 terms of size ~1: 64 ulp is ample and still catches any wrong node.
constexpr double kRuleTol = 64 * 2.220446049250313e-16;

TEST(GaussLegendre, WeightsSumToTwoAndNodesAreSymmetricAndAscending) {
  for (int n = 1; n <= kMaxGaussLegendreOrder; ++n) {
    SCOPED_TRACE(n);
    const GaussLegendreRule r = gauss_legendre_rule(n);
    ASSERT_EQ(r.order(), n);
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      sum += r.weights[i];
      EXPECT_GT(r.weights[i], 0.0);
      EXPECT_DOUBLE_EQ(r.nodes[i], -r.nodes[n - 1 - i]);
      if (i > 0) EXPECT_LT(r.nodes[i - 1], r.nodes[i]);
    }
    EXPECT_NEAR(sum, 2.0, kRuleTol);  // ∫_{-1}^{1} 1 dx = 2
  }
}

TEST(GaussLegendre, IntegratesPolynomialsOfDegree2nMinus1Exactly) {
  for (int n = 1; n <= 40; ++n) {
    SCOPED_TRACE(n);
    const GaussLegendreRule r = gauss_legendre_rule(n);
    // Closed form: ∫_{-1}^{1} x^m dx = 2/(m+1) for even m, 0 for odd m; exact up to m = 2n − 1.
    for (int m = 0; m <= 2 * n - 1; ++m) {
      const double got = integrate_gauss_legendre<double>([m](double x) { return std::pow(x, m); }, -1.0, 1.0, r);
      const double want = m % 2 == 0 ? 2.0 / (m + 1) : 0.0;
      EXPECT_NEAR(got, want, kRuleTol) << "m=" << m;
    }
  }
  // And not beyond: the 2-point rule misses ∫x⁴ = 2/5 (it gives 2·(1/3)² = 2/9).
  const double got = integrate_gauss_legendre<double>([](double x) { return x * x * x * x; }, -1.0, 1.0,
                                                      gauss_legendre_rule(2));
  EXPECT_NEAR(got, 2.0 / 9.0, kRuleTol);
}

TEST(GaussLegendre, MatchesTheTenPointTablePrintedInFigure38) {
  // Texts 004 Figure 3.8 prints the positive nodes and weights of the 10-point rule truncated (not
  // rounded) to 10 digits, so they agree to one unit in the 10th digit.
  const double x[5] = {.1488743389, .4333953941, .6794095682, .8650633666, .9739065285};
  const double w[5] = {.2955242247, .2692667193, .2190863625, .1494513491, .0666713443};
  const GaussLegendreRule r = gauss_legendre_rule(10);
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(r.nodes[5 + i], x[i], 1e-10);
    EXPECT_NEAR(r.weights[5 + i], w[i], 1e-10);
  }
}

TEST(GaussLegendre, MapsToAnyIntervalAndClampsTheOrder) {
  // ∫_1^3 x² dx = (27 − 1)/3 (closed form); reversed limits give the negative.
  const auto sq = [](double x) { return x * x; };
  EXPECT_NEAR(integrate_gauss_legendre<double>(sq, 1.0, 3.0, gauss_legendre_rule(2)), 26.0 / 3.0, 1e-14);
  EXPECT_NEAR(integrate_gauss_legendre<double>(sq, 3.0, 1.0, gauss_legendre_rule(2)), -26.0 / 3.0, 1e-14);
  EXPECT_EQ(integrate_gauss_legendre<double>(sq, 2.0, 2.0, gauss_legendre_rule(5)), 0.0);
  EXPECT_EQ(gauss_legendre_rule(0).order(), 1);
  EXPECT_EQ(gauss_legendre_rule(1000).order(), kMaxGaussLegendreOrder);
}

}  // namespace
}  // namespace inbetween
