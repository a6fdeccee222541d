#include "inbetween/timing/cubic_bezier_timing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/random.hpp"

namespace inbetween {
namespace {

// Independent reference: plain bisection on x(p) = t (200 halvings) and y at that p, written from
// the Bernstein form rather than the power form the class uses.
double bernstein(double c1, double c2, double p) {
  const double q = 1 - p;
  return 3 * q * q * p * c1 + 3 * q * p * p * c2 + p * p * p;
}
double reference_s(double x1, double y1, double x2, double y2, double t) {
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    (bernstein(x1, x2, mid) < t ? lo : hi) = mid;
  }
  return bernstein(y1, y2, (lo + hi) / 2);
}

// The issue asks for 1e-7; the solver reaches a few ulp, which we check against the reference with
// the slope bound: |Δs| ≤ |dy/dx|·|Δx| and |dy/dx| < 20 on these curves.
constexpr double kSolveTol = 1e-7;

TEST(CubicBezierTiming, MatchesIndependentBisectionForCssPresetsAndRandomCurves) {
  test::Random rng(test::seed_for(99));
  SCOPED_TRACE(rng.trace());
  std::vector<CubicBezierTiming<double>> fns = {CubicBezierTiming<double>::css_ease(),
                                                 CubicBezierTiming<double>::css_ease_in(),
                                                 CubicBezierTiming<double>::css_ease_out(),
                                                 CubicBezierTiming<double>::css_ease_in_out()};
  for (int i = 0; i < 20; ++i) {
    fns.push_back(*CubicBezierTiming<double>::make(rng.uniform(0.05, 0.95), rng.uniform(-1.0, 2.0),
                                                   rng.uniform(0.05, 0.95), rng.uniform(-1.0, 2.0)));
  }
  for (const auto& f : fns) {
    for (double t = 0; t <= 1.0; t += 1.0 / 32) {
      const double p = f.solve_parameter(t);
      EXPECT_NEAR(bernstein(f.x1(), f.x2(), p), t, kSolveTol / 1000);  // x(p) = t to 1e-10 or better
      EXPECT_NEAR(f(t), reference_s(f.x1(), f.y1(), f.x2(), f.y2(), t), kSolveTol);
    }
    EXPECT_EQ(f(0.0), 0.0);
    EXPECT_EQ(f(1.0), 1.0);
  }
}

// The same property in float and double, at the precision the solver actually reaches (the issue's
// 1e-7 above is only the floor).  Sources of the tolerances: the solver stops when x(p) − t,
// evaluated in T in power form, is within 2·eps; that evaluation itself rounds by up to about
// eps·(|a| + |b| + |c|)·3 ≤ 12·eps for x1, x2 ∈ [0, 1], so the true residual (Bernstein form in
// double) is below 16·eps (measured worst: 7 eps).  s differs from the bisection reference (double,
// 200 halvings, exact on the float inputs) by the slope times that residual plus the rounding of
// y(p): 32·eps·(1 + |ds/dt|) (measured worst: 8).
template <class T>
class CubicBezierTimingTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(CubicBezierTimingTyped, Scalars);

TYPED_TEST(CubicBezierTimingTyped, SolvesToAFewUlpOverSeededRandomCurves) {
  using T = TypeParam;
  const double eps = std::numeric_limits<T>::epsilon();
  test::Random rng(test::seed_for(98));
  SCOPED_TRACE(rng.trace());
  double worst_x = 0, worst_s = 0;
  for (int i = 0; i < 200; ++i) {
    const auto f = CubicBezierTiming<T>::make(rng.uniform<T>(T(0), T(1)), rng.uniform<T>(T(-1), T(2)),
                                              rng.uniform<T>(T(0), T(1)), rng.uniform<T>(T(-1), T(2)));
    ASSERT_TRUE(f);
    for (int k = 0; k <= 64; ++k) {
      const T t = T(k) / T(64);
      const double p = double(f->solve_parameter(t));
      ASSERT_GE(p, 0.0);
      ASSERT_LE(p, 1.0);
      const double x_err = std::abs(bernstein(double(f->x1()), double(f->x2()), p) - double(t));
      const auto smp = f->sample(t);
      ASSERT_TRUE(std::isfinite(double(smp.s)));
      const double ref = reference_s(double(f->x1()), double(f->y1()), double(f->x2()), double(f->y2()), double(t));
      const double slope = std::isfinite(double(smp.velocity)) ? std::abs(double(smp.velocity)) : 0.0;
      const double s_err = std::abs(double(smp.s) - ref);
      worst_x = std::max(worst_x, x_err / eps);
      worst_s = std::max(worst_s, s_err / (eps * (1 + slope)));
      // Where x' vanishes (x1 or x2 at 0 or 1) the slope is unbounded and only x is checked.
      EXPECT_LE(x_err, 16 * eps) << "t=" << t;
      if (std::isfinite(double(smp.velocity)) && slope < 1e3) EXPECT_LE(s_err, 32 * eps * (1 + slope)) << "t=" << t;
    }
  }
  this->RecordProperty("worst_x_residual_eps", std::to_string(worst_x));
  this->RecordProperty("worst_s_error_eps_per_slope", std::to_string(worst_s));
}

TEST(CubicBezierTiming, ControlPointsOutsideTheUnitSquareOvershoot) {
  // easeInOutBack-style curve: y1 < 0 and y2 > 1 make the motion back up first and overshoot last.
  auto f = CubicBezierTiming<double>::make(0.68, -0.55, 0.265, 1.55);
  ASSERT_TRUE(f);
  double lo = 1, hi = 0;
  for (double t = 0; t <= 1; t += 1.0 / 256) {
    lo = std::min(lo, (*f)(t));
    hi = std::max(hi, (*f)(t));
  }
  EXPECT_LT(lo, -0.05);
  EXPECT_GT(hi, 1.05);
}

TEST(CubicBezierTiming, ValidatesXAndFiniteness) {
  auto bad = CubicBezierTiming<double>::make(1.2, 0, 0.5, 1);
  ASSERT_FALSE(bad);
  EXPECT_EQ(json_pointer(bad.error().location), "/x1");
  EXPECT_EQ(json_pointer(CubicBezierTiming<double>::make(0.2, 0, -0.1, 1).error().location), "/x2");
  EXPECT_EQ(CubicBezierTiming<double>::make(0.2, std::nan(""), 0.1, 1).error().code, ErrorCode::not_finite);
  EXPECT_TRUE(CubicBezierTiming<double>::make(0, -3, 1, 4));  // y anywhere, x at the bounds
}

TEST(CubicBezierTiming, VelocityAndAccelerationMatchFiniteDifferences) {
  const auto f = CubicBezierTiming<double>::css_ease_in_out();
  for (double t = 0.05; t < 1; t += 0.05) {
    const double h = 1e-5;
    const auto c = f.sample(t);
    EXPECT_NEAR((f(t + h) - f(t - h)) / (2 * h), c.velocity, 1e-7) << t;
    EXPECT_NEAR((f.sample(t + h).velocity - f.sample(t - h).velocity) / (2 * h), c.acceleration, 1e-5) << t;
  }
  // ease-in-out starts and ends at rest: x' > 0 and y' = 0 at both ends (y1 = 0, y2 = 1).
  EXPECT_EQ(f.sample(0).velocity, 0.0);
  EXPECT_NEAR(f.sample(1).velocity, 0.0, 1e-15);
}

TEST(CubicBezierTiming, DegenerateTangentsNeverGiveNaN) {
  // x1 = y1 and x2 = y2: y ≡ x, so s = t with velocity 1, also where x' = y' = 0 (l'Hôpital).
  auto ident = CubicBezierTiming<double>::make(0, 0, 1, 1);
  ASSERT_TRUE(ident);
  for (double t : {0.0, 0.3, 1.0}) {
    EXPECT_NEAR((*ident)(t), t, 1e-12);
    EXPECT_NEAR(ident->sample(t).velocity, 1.0, 1e-9) << t;
  }
  // x1 = 0, y1 = 1: vertical start, velocity +infinity at t = 0 (documented), finite after.
  auto vert = CubicBezierTiming<double>::make(0, 1, 1, 0);
  ASSERT_TRUE(vert);
  EXPECT_EQ(vert->sample(0).velocity, std::numeric_limits<double>::infinity());
  for (double t = 0; t <= 1; t += 1.0 / 64) {
    const auto s = vert->sample(t);
    EXPECT_FALSE(std::isnan(s.s) || std::isnan(s.velocity) || std::isnan(s.acceleration)) << t;
  }
}

}  // namespace
}  // namespace inbetween
