// Bézier curves of any degree: de Casteljau = Bernstein, end interpolation and end tangents,
// subdivision, degree elevation, derivatives vs central differences, global control.
#include <gtest/gtest.h>

#include "curve_test_util.hpp"
#include "inbetween/curves/bezier.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class Bezier : public ::testing::Test {};
TYPED_TEST_SUITE(Bezier, test::CurvePointTypes);

// de Casteljau and the Bernstein sum round differently; up to degree 8 with points in [−1, 1] each
// is a few dozen roundings of O(1) values: 512 ulp bounds both with margin.
template <class T>
constexpr T kTol = T(512) * test::eps<T>;

TYPED_TEST(Bezier, DeCasteljauEqualsBernsteinAnyDegree) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(311));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 8; ++degree) {
    const auto pts = test::random_points<P>(rng, degree + 1);
    const auto c = build_bezier(pts);
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(c->degree(), degree);
    for (int s = 0; s < 10; ++s) {
      const T u = rng.uniform<T>(T(0), T(1));
      EXPECT_LT(test::max_abs_diff(c->point(u), bernstein_sum(std::span<const P>(pts), u)), kTol<T>);
    }
    EXPECT_EQ(c->point(T(0)), pts.front());  // de Casteljau at 0 and 1 returns the end points exactly
    EXPECT_EQ(c->point(T(1)), pts.back());
    // End tangents n (P1 − P0), n (Pn − Pn−1).
    EXPECT_LT(test::max_abs_diff(c->derivative(T(0), 1), P((pts[1] - pts[0]) * T(degree))), kTol<T>);
    EXPECT_LT(test::max_abs_diff(c->derivative(T(1), 1), P((pts[degree] - pts[degree - 1]) * T(degree))), kTol<T>);
  }
}

TYPED_TEST(Bezier, SubdivisionHalvesReproduceTheCurve) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(312));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 6; ++degree) {
    const auto c = build_bezier(test::random_points<P>(rng, degree + 1)).value();
    const T at = rng.uniform<T>(T(0.1), T(0.9));
    const auto [left, right] = c.subdivide(at);
    for (int s = 0; s <= 8; ++s) {
      const T v = T(s) / T(8);
      EXPECT_LT(test::max_abs_diff(left.point(v), c.point(at * v)), T(4) * kTol<T>);
      EXPECT_LT(test::max_abs_diff(right.point(v), c.point(at + (T(1) - at) * v)), T(4) * kTol<T>);
    }
  }
}

TYPED_TEST(Bezier, DegreeElevationKeepsTheCurve) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(313));
  SCOPED_TRACE(rng.trace());
  const auto c = build_bezier(test::random_points<P>(rng, 4)).value();
  const auto e = c.elevate_degree();
  EXPECT_EQ(e.degree(), 4);
  for (int s = 0; s <= 10; ++s) {
    const T u = T(s) / T(10);
    EXPECT_LT(test::max_abs_diff(e.point(u), c.point(u)), kTol<T>);
  }
}

TEST(BezierDouble, DerivativesMatchCentralDifferencesAndHigherOrdersVanish) {
  test::Random rng(test::seed_for(314));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 7; ++degree) {
    const auto c = build_bezier(test::random_points<Vec3d>(rng, degree + 1)).value();
    test::expect_derivatives_match_differences(c, rng, 10);
    EXPECT_EQ(c.derivative(0.3, degree + 1), Vec3d{});
  }
  // A degree-6 curve's 4th derivative (the allocation path) against differences of the 3rd.
  const auto c = build_bezier(test::random_points<Vec3d>(rng, 7)).value();
  const double h = 1e-5, u = 0.4;
  const Vec3d fd = (c.derivative(u + h, 3) - c.derivative(u - h, 3)) / (2 * h);
  EXPECT_LT(test::max_abs_diff(fd, c.derivative(u, 4)), 1e-6 * (1 + norm(fd)));
}

TEST(BezierDouble, GlobalControlEveryPointMovesTheWholeInterior) {
  test::Random rng(test::seed_for(315));
  SCOPED_TRACE(rng.trace());
  auto pts = test::random_points<Vec2d>(rng, 5);
  const auto before = build_bezier(pts).value();
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(before.influence(i), (Interval<double>{0, 1}));
    auto moved = pts;
    moved[i] += Vec2d{0.1, 0.2};
    const auto after = build_bezier(moved).value();
    for (double u : {0.05, 0.3, 0.5, 0.7, 0.95}) EXPECT_NE(after.point(u), before.point(u)) << i << " " << u;
  }
  EXPECT_FALSE(before.interpolates_control_points());
}

TEST(BezierDouble, RejectsTooFewAndNonFinitePoints) {
  const auto one = build_bezier(std::vector<Vec2d>{{0, 0}});
  ASSERT_FALSE(one.has_value());
  EXPECT_EQ(one.error().code, ErrorCode::too_few_points);
  const auto nan = build_bezier(std::vector<Vec2d>{{0, 0}, {1, std::nan("")}, {2, 0}});
  ASSERT_FALSE(nan.has_value());
  EXPECT_EQ(json_pointer(nan.error().location), "/points/1");
}

}  // namespace
}  // namespace inbetween

namespace inbetween {
namespace {

TEST(BezierDouble, LowDegreesConvertToPiecewiseCubic) {
  test::Random rng(test::seed_for(316));
  SCOPED_TRACE(rng.trace());
  for (int degree = 1; degree <= 3; ++degree) {
    const auto c = build_bezier(test::random_points<Vec2d>(rng, degree + 1)).value();
    const auto pc = to_piecewise_cubic(c).value();
    for (double u : {0.0, 0.3, 0.77, 1.0})
      for (int k = 0; k <= 3; ++k) EXPECT_LT(test::max_abs_diff(pc.derivative(u, k), c.derivative(u, k)), 1e-13) << degree;
  }
  EXPECT_FALSE(to_piecewise_cubic(build_bezier(test::random_points<Vec2d>(rng, 5)).value()).has_value());
}

}  // namespace
}  // namespace inbetween
