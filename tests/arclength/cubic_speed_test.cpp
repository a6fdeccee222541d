#include "inbetween/arclength/cubic_speed.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "inbetween/arclength/quadrature_length.hpp"
#include "support/museum_arclength.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// |P'|² from the quartic vs from the derivative vector: both are sums of a few products of numbers
// ~1, so they agree to a few ulp of the largest term (≤ 100 here).
constexpr double kQuarticTol = 1e-12;

TEST(SpeedQuartic, EqualsSquaredDerivativeNormIn3D) {
  test::Random rng(test::seed_for(41));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 200; ++trial) {
    const PowerCubic<Vec3d> c{rng.vec3(), rng.vec3(), rng.vec3(), rng.vec3()};
    const SpeedQuartic<double> q = speed_quartic(c);
    const double v = rng.uniform(0.0, 1.0);
    EXPECT_NEAR(q.squared_speed(v), squared_norm(c.derivative(v, 1)), kQuarticTol);
    // |√a − √b| = |a − b|/(√a + √b) ≤ min(δ/√b, √δ) ≤ 2δ/(√b + √δ) for |a − b| ≤ δ: near zero speed
    // the square root halves the digits (√δ = 1e-6), elsewhere the error stays ~δ/|P'|.
    const double ref = norm(c.derivative(v, 1));
    EXPECT_NEAR(q.speed(v), ref, 2 * kQuarticTol / (ref + std::sqrt(kQuarticTol)));
  }
}

TEST(SpeedQuartic, MatchesEquation37In2D) {
  // Eq. 3.7 spelled out for a 2-D cubic with a = (ax, ay) …
  const double ax = 1.5, ay = -2, bx = 0.25, by = 3, cx = -1, cy = 0.5;
  const PowerCubic<Vec2d> c{{ax, ay}, {bx, by}, {cx, cy}, {7, 8}};
  const SpeedQuartic<double> q = speed_quartic(c);
  EXPECT_DOUBLE_EQ(q.A, 9 * (ax * ax + ay * ay));
  EXPECT_DOUBLE_EQ(q.B, 12 * (ax * bx + ay * by));
  EXPECT_DOUBLE_EQ(q.C, 6 * (ax * cx + ay * cy) + 4 * (bx * bx + by * by));
  EXPECT_DOUBLE_EQ(q.D, 4 * (bx * cx + by * cy));
  EXPECT_DOUBLE_EQ(q.E, cx * cx + cy * cy);
}

TEST(SpeedQuartic, NeverNaNAtZeroSpeed) {
  // P0 = P1: P'(0) = 0, where rounding may push the quartic just below zero.
  const auto curve = test::museum_arc_length_exhibit<double>("P0 = P1").curve;
  const SpeedQuartic<double> q = speed_quartic(curve.segment_power_form(0));
  EXPECT_EQ(q.speed(0.0), 0.0);
  for (double v = 0; v <= 1; v += 1.0 / 64) EXPECT_FALSE(std::isnan(q.speed(v)));
}

TEST(AnalyticCubicLength, AgreesWithTheReferenceOnEveryCubicExhibit) {
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(ex.name);
    const auto dom = ex.curve.domain();
    const double ref = reference_length(ex.curve, dom.lo, dom.hi);
    const double tol = 1e-11 * (ref + 1);
    const double got = analytic_cubic_length(ex.curve, dom.lo, dom.hi, {.tolerance = 1e-12, .order = 10});
    // The quartic loses half the digits where the speed vanishes (cusp, stop, coincident points):
    // there the integrand error is √(ε·C) over a short stretch, still far below 1e-9.
    EXPECT_NEAR(got, ref, ex.name.find("cusp") != std::string::npos ||
                                  ex.name.find("stops") != std::string::npos ||
                                  ex.name.find("P") == 0 || ex.name.find("doubles") != std::string::npos
                              ? 1e-9 * (ref + 1)
                              : tol);
  }
}

}  // namespace
}  // namespace inbetween
