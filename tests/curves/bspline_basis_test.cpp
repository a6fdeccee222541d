// B-spline basis functions: partition of unity on the domain, non-negativity, local support,
// derivatives vs central differences, and the knot generators.
#include <gtest/gtest.h>

#include <numeric>

#include "curve_test_util.hpp"
#include "inbetween/curves/bspline_basis.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
class BSplineBasis : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(BSplineBasis, Scalars);

TYPED_TEST(BSplineBasis, PartitionOfUnityNonNegativeAndLocalSupport) {
  using T = TypeParam;
  test::Random rng(test::seed_for(331));
  SCOPED_TRACE(rng.trace());
  int valid_vectors = 0;  // random knot vectors that pass check_knots (the rest are skipped)
  for (int degree = 1; degree <= 5; ++degree) {
    for (int trial = 0; trial < 10; ++trial) {
      const int n = degree + 1 + rng.integer(0, 6);
      // Random non-decreasing knots with some repeats (rounded to quarters).
      std::vector<T> knots(n + degree + 1);
      T acc = T(0);
      for (auto& k : knots) k = acc, acc += T(rng.integer(0, 3)) / T(4);
      if (!check_knots<T>(knots, n, degree)) continue;
      ++valid_vectors;
      std::vector<T> basis(n);
      for (int s = 0; s <= 50; ++s) {
        const T u = knots[degree] + (knots[n] - knots[degree]) * T(s) / T(50);
        bspline_basis_all<T>(knots, degree, u, 0, basis);
        // Sum of p + 1 non-negative terms each a product of ≤ p ratios in [0, 1]: a few ulp each.
        EXPECT_NEAR(std::accumulate(basis.begin(), basis.end(), T(0)), T(1), T(16) * test::eps<T>) << "u=" << u;
        for (int i = 0; i < n; ++i) {
          EXPECT_GE(basis[i], T(0));
          if (u < knots[i] || u > knots[i + degree + 1]) EXPECT_EQ(basis[i], T(0)) << i;
        }
        // Derivatives of a partition of unity sum to zero.
        std::vector<T> d(n);
        bspline_basis_all<T>(knots, degree, u, 1, d);
        const T scale = std::accumulate(d.begin(), d.end(), T(0), [](T a, T b) { return a + std::abs(b); });
        EXPECT_NEAR(std::accumulate(d.begin(), d.end(), T(0)), T(0), T(64) * test::eps<T> * (T(1) + scale));
      }
    }
  }
  // The skip above must not empty the test: a quarter of the draws repeat a knot, and only runs
  // longer than degree + 1 or an empty domain are rejected (measured: 40 to 49 of 50 pass, 16 seeds).
  EXPECT_GE(valid_vectors, 25);
}

TEST(BSplineBasisDouble, DerivativesMatchCentralDifferences) {
  const std::vector<double> knots{0, 0, 0, 0, 0.5, 1, 1.5, 2, 2, 2, 2};
  const int degree = 3, n = 7;
  const double h = 1e-6;
  for (double u : {0.1, 0.3, 0.7, 1.2, 1.9}) {
    for (int k = 1; k <= 3; ++k) {
      for (int i = 0; i < n; ++i) {
        const double fd = (bspline_basis<double>(knots, degree, i, u + h, k - 1) -
                           bspline_basis<double>(knots, degree, i, u - h, k - 1)) / (2 * h);
        // h = 1e-6: truncation ~h²·|N^{(k+2)}| ≤ 1e-9 and rounding ~1e-16/1e-6·|N^{(k-1)}| ≤ 1e-8 here
        // (|N''| ≤ 24 on spans of length 0.5); 1e-7 leaves a factor 10 over that bound.
        EXPECT_NEAR(bspline_basis<double>(knots, degree, i, u, k), fd, 1e-7 * (1 + std::abs(fd))) << i << " " << k;
      }
    }
  }
}

TEST(BSplineBasisDouble, UniformCubicMatchesTheTextbookBlendingFunctions) {
  // Uniform cubic B-spline on knots 0..7, span [3, 4): N_{0..3,3}(3 + v) = (1−v)³/6,
  // (3v³ − 6v² + 4)/6, (−3v³ + 3v² + 3v + 1)/6, v³/6 (the rows of the uniform B-spline matrix).
  const auto knots = uniform_knots<double>(4, 3);
  for (double v : {0.0, 0.25, 0.6}) {
    std::vector<double> b(4);
    bspline_basis_all<double>(knots, 3, 3 + v, 0, b);
    EXPECT_NEAR(b[0], (1 - v) * (1 - v) * (1 - v) / 6, 1e-15);
    EXPECT_NEAR(b[1], (3 * v * v * v - 6 * v * v + 4) / 6, 1e-15);
    EXPECT_NEAR(b[2], (-3 * v * v * v + 3 * v * v + 3 * v + 1) / 6, 1e-15);
    EXPECT_NEAR(b[3], v * v * v / 6, 1e-15);
  }
}

TEST(BSplineBasisDouble, KnotChecksNameTheKnot) {
  const std::vector<double> bad{0, 0, 2, 1, 3};
  const auto r = check_knots<double>(bad, 3, 1);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::keys_not_increasing);
  EXPECT_EQ(json_pointer(r.error().location), "/knots/3");
  EXPECT_FALSE(check_knots<double>(std::vector<double>{0, 0, 0}, 3, 1).has_value());  // wrong count
  EXPECT_EQ(clamped_uniform_knots<double>(5, 2), (std::vector<double>{0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1}));
}

}  // namespace
}  // namespace inbetween
