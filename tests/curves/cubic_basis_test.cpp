// The cubic segment in its four forms (000 §2.3): matrix form U·M·B, blending functions, power
// form, de Casteljau and Bernstein agree; the basis matrices encode the constraints the texts
// derive them from.
#include <gtest/gtest.h>

#include "curve_test_util.hpp"
#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/cubic_basis.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class CubicBasis : public ::testing::Test {};
TYPED_TEST_SUITE(CubicBasis, test::CurvePointTypes);

// Each evaluation form is ~16 roundings of terms no larger than 12 (basis entries ≤ 6 times points
// in [−1, 1], summed); 256 ulp bounds 16·12 ulp with margin, far below any formula error (O(1)).
template <class T>
constexpr T kFormsAgree = T(256) * test::eps<T>;

TYPED_TEST(CubicBasis, MatrixBlendingPowerDeCasteljauAndBernsteinAgree) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(301));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 200; ++trial) {
    auto g = test::random_points<P>(rng, 4);
    const T u = rng.uniform<T>(T(0), T(1));
    const P matrix = evaluate_matrix_form(bezier_basis<T>(), g[0], g[1], g[2], g[3], u);
    const P power = power_form(bezier_basis<T>(), g[0], g[1], g[2], g[3]).point(u);
    std::vector<P> scratch = g;
    const P casteljau = de_casteljau(std::span<P>(scratch), u);
    const P bern = bernstein_sum(std::span<const P>(g), u);
    EXPECT_LT(test::max_abs_diff(matrix, casteljau), kFormsAgree<T>);
    EXPECT_LT(test::max_abs_diff(power, casteljau), kFormsAgree<T>);
    EXPECT_LT(test::max_abs_diff(bern, casteljau), kFormsAgree<T>);
    // The Bernstein cubic blending functions as printed in 000 §2.3.2.
    const auto w = blending_functions(bezier_basis<T>(), u);
    const T v = T(1) - u;
    EXPECT_NEAR(w[0], v * v * v, kFormsAgree<T>);
    EXPECT_NEAR(w[1], T(3) * u * v * v, kFormsAgree<T>);
    EXPECT_NEAR(w[2], T(3) * u * u * v, kFormsAgree<T>);
    EXPECT_NEAR(w[3], u * u * u, kFormsAgree<T>);
  }
}

TYPED_TEST(CubicBasis, BezierEqualsHermiteWithTangentsThreeTimesTheHandles) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(302));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 200; ++trial) {
    auto g = test::random_points<P>(rng, 4);
    const auto bez = power_form(bezier_basis<T>(), g[0], g[1], g[2], g[3]);
    // 000 §2.3.2: start tangent 3(P1 − P0), end tangent 3(P3 − P2).
    const auto her = power_form(hermite_basis<T>(), g[0], g[3], P((g[1] - g[0]) * T(3)), P((g[3] - g[2]) * T(3)));
    const T u = rng.uniform<T>(T(0), T(1));
    for (int k = 0; k <= 3; ++k)
      EXPECT_LT(test::max_abs_diff(bez.derivative(u, k), her.derivative(u, k)), T(8) * kFormsAgree<T>) << k;
  }
}

TYPED_TEST(CubicBasis, HermiteBlendingFunctionsMatchTheTextAndMeetTheirConstraints) {
  using P = TypeParam;
  using T = scalar_of<P>;
  const auto m = hermite_basis<T>();
  for (T u : {T(0), T(0.25), T(0.5), T(0.8), T(1)}) {
    const auto w = blending_functions(m, u);
    // 000 §2.3.1: (2u³ − 3u² + 1), (−2u³ + 3u²), (u³ − 2u² + u), (u³ − u²).
    EXPECT_NEAR(w[0], 2 * u * u * u - 3 * u * u + 1, kFormsAgree<T>);
    EXPECT_NEAR(w[1], -2 * u * u * u + 3 * u * u, kFormsAgree<T>);
    EXPECT_NEAR(w[2], u * u * u - 2 * u * u + u, kFormsAgree<T>);
    EXPECT_NEAR(w[3], u * u * u - u * u, kFormsAgree<T>);
  }
  // Constraints: P(0) = P0, P(1) = P1, P'(0) = P0', P'(1) = P1' (exact small integers).
  const auto w0 = blending_functions(m, T(0)), w1 = blending_functions(m, T(1));
  const auto d0 = blending_function_derivatives(m, T(0), 1), d1 = blending_function_derivatives(m, T(1), 1);
  EXPECT_EQ(w0, (std::array<T, 4>{1, 0, 0, 0}));
  EXPECT_EQ(w1, (std::array<T, 4>{0, 1, 0, 0}));
  EXPECT_EQ(d0, (std::array<T, 4>{0, 0, 1, 0}));
  EXPECT_EQ(d1, (std::array<T, 4>{0, 0, 0, 1}));
  (void)sizeof(P);
}

TYPED_TEST(CubicBasis, CatmullRomMatrixInterpolatesWithTangentSTimesNeighbourDifference) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(303));
  SCOPED_TRACE(rng.trace());
  for (T s : {T(0.5), T(0.3), T(1)}) {
    auto g = test::random_points<P>(rng, 4);
    const auto seg = power_form(catmull_rom_basis<T>(s), g[0], g[1], g[2], g[3]);
    EXPECT_LT(test::max_abs_diff(seg.point(T(0)), g[1]), kFormsAgree<T>);
    EXPECT_LT(test::max_abs_diff(seg.point(T(1)), g[2]), kFormsAgree<T>);
    // 000 §2.3.3: P'_i = s (P_{i+1} − P_{i−1}).
    EXPECT_LT(test::max_abs_diff(seg.derivative(T(0), 1), P((g[2] - g[0]) * s)), kFormsAgree<T>);
    EXPECT_LT(test::max_abs_diff(seg.derivative(T(1), 1), P((g[3] - g[1]) * s)), kFormsAgree<T>);
  }
}

TYPED_TEST(CubicBasis, BlendingFunctionsOfPointBasesSumToOne) {
  using T = scalar_of<TypeParam>;
  test::Random rng(test::seed_for(304));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 50; ++trial) {
    const T u = rng.uniform<T>(T(0), T(1));
    for (const auto& m : {bezier_basis<T>(), catmull_rom_basis<T>(T(0.7)), uniform_bspline_basis<T>(),
                          parabolic_blend_basis<T>()}) {
      const auto w = blending_functions(m, u);
      // Affine invariance: weights of points sum to 1.
      EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], T(1), kFormsAgree<T>);
    }
  }
}

TYPED_TEST(CubicBasis, UniformBSplineMatrixEqualsDeBoorOnUniformKnots) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(305));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<P>(rng, 7);
  const auto spline = build_bspline(pts, 3, uniform_knots<T>(7, 3));
  ASSERT_TRUE(spline.has_value());
  ASSERT_EQ(spline->segment_count(), 4);
  for (int seg = 0; seg < 4; ++seg) {
    for (T v : {T(0), T(0.3), T(0.9)}) {
      const P matrix = evaluate_matrix_form(uniform_bspline_basis<T>(), pts[seg], pts[seg + 1], pts[seg + 2], pts[seg + 3], v);
      EXPECT_LT(test::max_abs_diff(matrix, spline->point(T(3 + seg) + v)), kFormsAgree<T>) << seg;
    }
  }
}

TYPED_TEST(CubicBasis, ParabolicBlendMatrixEqualsCatmullRomHalf) {
  using T = scalar_of<TypeParam>;
  // Derived in cubic_basis.hpp from (1 − u)Q + uR; equality with s = 1/2 is the known identity
  // (Overhauser / parabolic blending = uniform Catmull-Rom), exact in binary fractions.
  EXPECT_EQ(parabolic_blend_basis<T>(), catmull_rom_basis<T>(T(0.5)));
}

}  // namespace
}  // namespace inbetween
