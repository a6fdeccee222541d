// Non-uniform parameters t_i for the natural, clamped and closed C² splines, Hermite,
// Kochanek–Bartels and parabolic-blend curves: uniform params reproduce the default curves bit for
// bit, the continuity the family promises holds in t, and closed forms are reproduced (a cubic
// polynomial by the clamped spline with its own end tangents and by Hermite with its own tangents,
// a quadratic by the parabolic blend, a straight line at uneven times by Kochanek–Bartels, a circle
// by the closed spline within the Hall–Meyer bound).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "curve_test_util.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class NonUniformParamsTest : public ::testing::Test {};
using PlaneTypes = ::testing::Types<Vec2f, Vec2d>;
TYPED_TEST_SUITE(NonUniformParamsTest, PlaneTypes);

// Strictly increasing, uneven parameters: gaps uniform in [0.3, 1.7] (spacing ratios up to ≈ 6).
template <class T>
std::vector<T> uneven_params(test::Random& rng, int n, T start = T(0)) {
  std::vector<T> t{start};
  for (int i = 1; i < n; ++i) t.push_back(t.back() + rng.uniform<T>(T(0.3), T(1.7)));
  return t;
}

template <class C1, class C2>
void expect_same_segments(const C1& a, const C2& b) {
  ASSERT_EQ(a.segment_count(), b.segment_count());
  for (int i = 0; i < a.segment_count(); ++i) {
    const auto x = a.segment_power_form(i), y = b.segment_power_form(i);
    EXPECT_EQ(x.a, y.a) << i;
    EXPECT_EQ(x.b, y.b) << i;
    EXPECT_EQ(x.c, y.c) << i;
    EXPECT_EQ(x.d, y.d) << i;
  }
}

// Uniform params 0, 1, … are the default; params k + 2^m i (shifted, spacing a power of two) scale
// every tangent dP/dt by 2^−m and every local tangent h D back by 2^m: exact in binary, so the
// segments in their local v must be bit for bit those of the default curve.
TYPED_TEST(NonUniformParamsTest, UniformParamsReproduceTheDefaultCurvesBitForBit) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(1301));
  SCOPED_TRACE(rng.trace());
  const int n = 7;
  const auto pts = test::random_points<P>(rng, n);
  const auto tans = test::random_points<P>(rng, n);
  std::vector<TcbParams<T>> keys(n);
  for (auto& k : keys) k = {rng.uniform<T>(T(-0.5), T(0.5)), rng.uniform<T>(T(-0.5), T(0.5)), rng.uniform<T>(T(-0.5), T(0.5))};
  for (const auto& [shift, spacing] : {std::pair{T(0), T(1)}, std::pair{T(5), T(1)}, std::pair{T(-3), T(2)}, std::pair{T(8), T(0.25)}}) {
    SCOPED_TRACE(::testing::Message() << "shift " << shift << " spacing " << spacing);
    std::vector<T> t(n);
    for (int i = 0; i < n; ++i) t[i] = shift + spacing * T(i);
    expect_same_segments(build_natural_spline(pts).value(), build_natural_spline(pts, t).value());
    expect_same_segments(build_parabolic_blend(pts).value(), build_parabolic_blend(pts, t).value());
    expect_same_segments(build_kochanek_bartels(pts, keys).value(), build_kochanek_bartels(pts, keys, t).value());
    // Hermite and clamped tangents are dP/dt: scale them with the spacing to keep the same shape.
    std::vector<P> scaled(n);
    for (int i = 0; i < n; ++i) scaled[i] = tans[i] / spacing;
    expect_same_segments(build_hermite_spline(pts, tans).value(), build_hermite_spline(pts, scaled, t).value());
    expect_same_segments(build_clamped_spline(pts, tans[0], tans[1]).value(),
                         build_clamped_spline(pts, scaled[0], scaled[1], t).value());
    std::vector<T> tc(n + 1);
    for (int i = 0; i <= n; ++i) tc[i] = shift + spacing * T(i);
    expect_same_segments(build_closed_spline(pts).value(), build_closed_spline(pts, tc).value());
  }
}

// f(t) = a + b t + c t² + d t³ per component, sampled at uneven t_i.  The clamped spline with end
// tangents f'(t_0), f'(t_{n−1}) is the unique C² cubic spline with those data, and f is one: it must
// be reproduced everywhere.  Hermite with tangents f'(t_i) reproduces it segment by segment.
TYPED_TEST(NonUniformParamsTest, CubicPolynomialIsReproducedByClampedAndHermite) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(1302));
  SCOPED_TRACE(rng.trace());
  const int n = 8;
  const auto t = uneven_params<T>(rng, n, T(-2));
  const auto co = test::random_points<P>(rng, 4);
  auto f = [&](T u) { return co[0] + co[1] * u + co[2] * (u * u) + co[3] * (u * u * u); };
  auto df = [&](T u) { return co[1] + co[2] * (T(2) * u) + co[3] * (T(3) * u * u); };
  std::vector<P> pts, tans;
  for (T u : t) pts.push_back(f(u)), tans.push_back(df(u));
  const auto clamped = build_clamped_spline(pts, tans.front(), tans.back(), t).value();
  const auto hermite = build_hermite_spline(pts, tans, t).value();
  // |f| ≲ 1 + |t| + |t|² + |t|³ ≤ ~10³ on t ∈ [−2, 10]; the solve and the Horner steps lose a few
  // hundred ulp of that (measured ≈ 30–60 ulp in double), so 4096 ulp of the scale.
  T scale = 0;
  for (const auto& p : pts) scale = std::max(scale, T(test::max_abs_diff(p, P{})));
  const T tol = T(4096) * test::eps<T> * scale;
  for (int k = 0; k <= 200; ++k) {
    const T u = t.front() + (t.back() - t.front()) * T(k) / T(200);
    EXPECT_LT(test::max_abs_diff(clamped.point(u), f(u)), tol) << u;
    EXPECT_LT(test::max_abs_diff(hermite.point(u), f(u)), tol) << u;
    EXPECT_LT(test::max_abs_diff(clamped.derivative(u, 1), df(u)), tol * T(10)) << u;
  }
  for (const auto& j : measure_continuity(clamped)) EXPECT_EQ(j.c_order(), 3) << j.u;  // f is C∞: even f''' matches
}

// Points on a parabola g(t) = a + b t + c t² at uneven t_i: both blended parabolas are g itself, so
// the blend is g (first and last segments included).  Points on a line at uneven times: every KB
// tangent (t = c = b = 0) rescaled by 2h_i/(h_{i−1} + h_i) is h_i g', so KB reproduces the line with
// its speed.
TYPED_TEST(NonUniformParamsTest, ParabolaByParabolicBlendAndLineByKochanekBartels) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(1303));
  SCOPED_TRACE(rng.trace());
  const int n = 7;
  const auto t = uneven_params<T>(rng, n, T(-1));
  const auto co = test::random_points<P>(rng, 3);
  auto g = [&](T u) { return co[0] + co[1] * u + co[2] * (u * u); };
  auto line = [&](T u) { return co[0] + co[1] * u; };
  std::vector<P> on_g, on_line;
  for (T u : t) on_g.push_back(g(u)), on_line.push_back(line(u));
  const auto pb = build_parabolic_blend(on_g, t).value();
  const auto kb = build_kochanek_bartels(on_line, std::vector<TcbParams<T>>{TcbParams<T>{}}, t).value();
  const T tol = T(1024) * test::eps<T> * T(100);  // |g| ≤ 1 + 9 + 81 on t ∈ [−1, 9]
  for (int k = 0; k <= 200; ++k) {
    const T u = t.front() + (t.back() - t.front()) * T(k) / T(200);
    EXPECT_LT(test::max_abs_diff(pb.point(u), g(u)), tol) << u;
    EXPECT_LT(test::max_abs_diff(kb.point(u), line(u)), tol) << u;
    EXPECT_LT(test::max_abs_diff(kb.derivative(u, 1), co[1]), tol) << u;
  }
}

// Random points at uneven t: natural and closed are C² at every joint (the closed one also at the
// seam), Hermite, parabolic blend and KB with c = 0 are C¹ in t, and all interpolate at t_i.
TYPED_TEST(NonUniformParamsTest, ContinuityInTheParameter) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(1304));
  SCOPED_TRACE(rng.trace());
  const int n = 9;
  const auto pts = test::random_points<P>(rng, n);
  const auto tans = test::random_points<P>(rng, n);
  const auto t = uneven_params<T>(rng, n + 1, T(0.5));
  const std::vector<T> tn(t.begin(), t.end() - 1);
  std::vector<TcbParams<T>> keys(n);
  for (auto& k : keys) k = {rng.uniform<T>(T(-0.5), T(0.5)), T(0), rng.uniform<T>(T(-0.5), T(0.5))};
  const auto natural = build_natural_spline(pts, tn).value();
  const auto closed = build_closed_spline(pts, t).value();
  EXPECT_TRUE(closed.closed());
  ASSERT_EQ(closed.segment_count(), n);
  int joints = 0;
  for (const auto& j : measure_continuity(natural)) {
    EXPECT_GE(j.c_order(), 2) << j.u;
    ++joints;
  }
  EXPECT_EQ(joints, n - 2);
  joints = 0;
  for (const auto& j : measure_continuity(closed)) {
    EXPECT_GE(j.c_order(), 2) << j.u;
    ++joints;
  }
  EXPECT_EQ(joints, n);  // n − 1 inner joints and the seam
  for (const auto& j : measure_continuity(build_hermite_spline(pts, tans, tn).value())) EXPECT_GE(j.c_order(), 1) << j.u;
  for (const auto& j : measure_continuity(build_parabolic_blend(pts, tn).value())) EXPECT_GE(j.c_order(), 1) << j.u;
  for (const auto& j : measure_continuity(build_kochanek_bartels(pts, keys, tn).value())) EXPECT_GE(j.c_order(), 1) << j.u;
  const T tol = T(1024) * test::eps<T>;
  for (int i = 0; i < n; ++i) {
    EXPECT_LT(test::max_abs_diff(natural.point(tn[i]), pts[i]), tol);
    EXPECT_LT(test::max_abs_diff(closed.point(t[i]), pts[i]), tol);
  }
  EXPECT_LT(test::max_abs_diff(closed.point(t[n]), pts[0]), tol);
  EXPECT_LT(test::max_abs_diff(natural.derivative(tn.front(), 2), P{}), tol * T(100));
  EXPECT_LT(test::max_abs_diff(natural.derivative(tn.back(), 2), P{}), tol * T(100));
}

// The closed spline through points of the unit circle at uneven angles θ_i (params = θ_i, closing at
// 2π) interpolates the periodic functions cos and sin, whose fourth derivatives are bounded by 1; the
// periodic cubic spline error is ≤ 5/384 · h⁴ · max|f⁗| per component (Hall & Meyer 1976, whose
// proof holds on a periodic grid), so the distance to the circle is ≤ √2 · 5/384 · h⁴, h the largest
// angle gap.
TEST(NonUniformParamsDouble, ClosedSplineApproximatesACircleWithinTheHallMeyerBound) {
  test::Random rng(test::seed_for(1305));
  SCOPED_TRACE(rng.trace());
  const double two_pi = 2 * std::numbers::pi;
  for (int n : {12, 24, 48}) {
    std::vector<double> th{0};
    const double mean = two_pi / n;
    for (int i = 1; i < n; ++i) th.push_back(th.back() + mean * rng.uniform(0.7, 1.3));
    const double scale = two_pi / (th.back() + mean);  // the closing gap is ≈ mean too
    for (double& x : th) x *= scale;
    th.push_back(two_pi);
    double h = 0;
    for (int i = 0; i < n; ++i) h = std::max(h, th[i + 1] - th[i]);
    std::vector<Vec2d> pts;
    for (int i = 0; i < n; ++i) pts.push_back({std::cos(th[i]), std::sin(th[i])});
    const auto c = build_closed_spline(pts, th).value();
    double worst = 0;
    for (int k = 0; k <= 4000; ++k) {
      const double u = two_pi * k / 4000;
      worst = std::max(worst, norm(c.point(u) - Vec2d{std::cos(u), std::sin(u)}));
    }
    const double bound = std::sqrt(2.0) * 5.0 / 384.0 * h * h * h * h;
    EXPECT_LE(worst, bound) << n;
    EXPECT_GT(worst, bound / 1000) << n;  // it is a real approximation, not a coincidence
    std::printf("closed circle n=%d h=%.4f error %.3e bound %.3e\n", n, h, worst, bound);
  }
}

TEST(NonUniformParamsDouble, BadParamsAreErrorsWithAPlace) {
  const std::vector<Vec2d> pts{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  auto e = build_natural_spline(pts, std::vector<double>{0, 1, 1, 2});
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::keys_not_increasing);
  EXPECT_NE(e.error().message.find("param 2"), std::string::npos) << e.error().message;
  auto w = build_closed_spline(pts, std::vector<double>{0, 1, 2, 3});  // closed needs n + 1
  ASSERT_FALSE(w);
  EXPECT_EQ(w.error().code, ErrorCode::wrong_arity);
  auto nf = build_parabolic_blend(pts, std::vector<double>{0, 1, NAN, 3});
  ASSERT_FALSE(nf);
  EXPECT_EQ(nf.error().code, ErrorCode::not_finite);
  auto ov = build_hermite_spline(pts, pts, std::vector<double>{-1e308, 1e308, 1.1e308, 1.2e308});
  ASSERT_FALSE(ov);
  EXPECT_EQ(ov.error().code, ErrorCode::not_finite);
  EXPECT_FALSE(build_closed_spline(std::vector<Vec2d>{{0, 0}, {1, 0}}));  // two points: no closed C² curve
}

}  // namespace
}  // namespace inbetween
