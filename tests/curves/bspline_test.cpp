// B-spline curves: de Boor equals the basis-function sum, C^{p−1} at simple knots and C^{p−r} at
// knots of multiplicity r, clamped ends, local control over [u_i, u_{i+p+1}], periodic closure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "curve_test_util.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/continuity.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class BSplineCurve : public ::testing::Test {};
TYPED_TEST_SUITE(BSplineCurve, test::CurvePointTypes);

TYPED_TEST(BSplineCurve, DeBoorEqualsBasisSumAndClampedEndsInterpolate) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(341));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 5; ++degree) {
    const auto pts = test::random_points<P>(rng, degree + 4);
    const auto c = build_bspline(pts, degree).value();
    std::vector<T> basis(pts.size());
    for (int s = 0; s <= 20; ++s) {
      const T u = T(s) / T(20);
      bspline_basis_all<T>(c.knots(), degree, u, 0, basis);
      P sum{};
      for (std::size_t i = 0; i < pts.size(); ++i) sum = sum + pts[i] * basis[i];
      // Two convex-combination evaluations of points in [−1, 1]: 256 ulp.
      EXPECT_LT(test::max_abs_diff(c.point(u), sum), T(256) * test::eps<T>) << degree << " " << u;
    }
    EXPECT_LT(test::max_abs_diff(c.point(T(0)), pts.front()), T(4) * test::eps<T>);
    EXPECT_LT(test::max_abs_diff(c.point(T(1)), pts.back()), T(4) * test::eps<T>);
  }
}

// Issue 9, defect 7c: with control points near 1e307 the points stay finite but the first and second
// derivatives came out inf and NaN (differencing P_{i+1} − P_i and multiplying by p/Δu overflows,
// then inf − inf).  Reference: the same spline with every control point divided by 2^E (exact, a
// power of two); the derivatives of the big one must be those of the small one times 2^E, exactly
// (power-of-two scaling commutes with rounding), which is ±inf only where the true value exceeds
// T — the documented saturation — and never NaN.
TYPED_TEST(BSplineCurve, DerivativesNearTheLargestFiniteValueAreTheScaledDerivatives) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(343));
  SCOPED_TRACE(rng.trace());
  for (const int below : {2, 5, 10}) {
  const int top = std::numeric_limits<T>::max_exponent - below;  // points up to 2^top (1e307 in double)
  const int shift = top - 4;                                       // small copy: points up to 2^4
  int not_finite = 0, nan = 0, compared = 0;
  for (int degree = 1; degree <= 5; ++degree) {
    const int count = degree + 9;
    const auto unit = test::random_points<P>(rng, count);
    std::vector<P> big, small;
    for (const P& p : unit) {
      big.push_back(p * std::ldexp(T(1), top));
      small.push_back(p * std::ldexp(T(1), top - shift));
    }
    const auto cb = build_bspline(big, degree).value();
    const auto cs = build_bspline(small, degree).value();
    for (int s = 0; s <= 40; ++s) {
      const T u = T(s) / T(40);
      for (int k = 0; k <= 3; ++k) {
        const P db = cb.derivative(u, k), ds = cs.derivative(u, k);
        for (int i = 0; i < PointTraits<P>::dim; ++i) {
          const T vb = PointTraits<P>::get(db, i), want = std::ldexp(PointTraits<P>::get(ds, i), shift);
          ++compared;
          if (std::isnan(vb)) ++nan;
          if (!std::isfinite(vb)) ++not_finite;
          EXPECT_EQ(vb, want) << "degree " << degree << " u " << u << " k " << k;
        }
      }
    }
  }
  std::printf("[ measured ] B-spline derivatives at 2^%d: %d components, %d NaN, %d infinite\n", top, compared, nan,
              not_finite);
  }
}

TEST(BSplineDouble, ContinuityAtKnotsIsPMinusMultiplicity) {
  test::Random rng(test::seed_for(342));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 4; ++degree) {
    const auto c = build_bspline(test::random_points<Vec3d>(rng, 8), degree, uniform_knots<double>(8, degree)).value();
    for (const auto& j : measure_continuity(c)) EXPECT_EQ(j.c_order(), std::min(degree - 1, 3)) << degree << " u=" << j.u;
  }
  // Cubic with a double knot at 3 and a triple knot at 5: C¹ and C⁰ there, C² elsewhere.
  const std::vector<double> knots{0, 1, 2, 3, 3, 4, 5, 5, 5, 6, 7, 8, 9};
  const auto c = build_bspline(test::random_points<Vec3d>(rng, 9), 3, knots).value();
  for (const auto& j : measure_continuity(c)) {
    const int expected = j.u == 3 ? 1 : j.u == 5 ? 0 : 2;
    EXPECT_EQ(j.c_order(), expected) << "u=" << j.u;
    EXPECT_EQ(c.theoretical_continuity(j.right_segment), expected);
  }
}

TEST(BSplineDouble, LocalControlOverTheSupportOfTheBasisFunction) {
  test::Random rng(test::seed_for(343));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<Vec2d>(rng, 9);
  for (int degree : {2, 3}) {
    test::expect_local_control([&](const std::vector<Vec2d>& p) { return build_bspline(p, degree, uniform_knots<double>(9, degree)).value(); },
                               pts, Vec2d{0.2, 0.1});
    const auto c = build_bspline(pts, degree, uniform_knots<double>(9, degree)).value();
    EXPECT_EQ(c.influence(4), (Interval<double>{4, 4.0 + degree + 1}));
  }
}

TEST(BSplineDouble, DerivativesMatchCentralDifferencesAndPeriodicCurveCloses) {
  test::Random rng(test::seed_for(344));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 5; ++degree)
    test::expect_derivatives_match_differences(build_bspline(test::random_points<Vec3d>(rng, 9), degree).value(), rng);
  const auto loop = build_periodic_bspline(test::random_points<Vec2d>(rng, 6), 3).value();
  EXPECT_TRUE(loop.closed());
  const auto joints = measure_continuity(loop);
  ASSERT_EQ(joints.size(), 6u);  // five interior joints and the seam
  for (const auto& j : joints) EXPECT_EQ(j.c_order(), 2) << j.u;
}

}  // namespace
}  // namespace inbetween

namespace inbetween {
namespace {

TEST(BSplineDouble, ToPiecewiseCubicIsTheSameCurve) {
  test::Random rng(test::seed_for(345));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 3; ++degree) {
    const std::vector<double> cubic_knots{0, 0, 0, 0, 1, 1, 2.5, 3, 3, 3, 3};  // a double knot at 1
    const std::vector<double> knots(cubic_knots.begin() + (3 - degree), cubic_knots.end() - (3 - degree));
    const auto pts = test::random_points<Vec3d>(rng, int(knots.size()) - degree - 1);
    const auto b = build_bspline(pts, degree, knots).value();
    const auto pc = to_piecewise_cubic(b);
    ASSERT_TRUE(pc.has_value()) << pc.error().describe();
    static_assert(PiecewiseCubicCurve<PiecewiseCubic<Vec3d>>);
    EXPECT_EQ(pc->segment_count(), b.segment_count());
    for (int s = 0; s <= 60; ++s) {
      const double u = 3.0 * s / 60;
      // Taylor coefficients from de Boor derivatives, re-evaluated by Horner: ~100 ulp of O(10) values.
      for (int k = 0; k <= 2; ++k) EXPECT_LT(test::max_abs_diff(pc->derivative(u, k), b.derivative(u, k)), 1e-12) << u;
    }
  }
  EXPECT_FALSE(to_piecewise_cubic(build_bspline(test::random_points<Vec3d>(rng, 6), 4).value()).has_value());
}

}  // namespace
}  // namespace inbetween
