#include "inbetween/timing/ease.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <limits>
#include <numbers>
#include <vector>

namespace inbetween {
namespace {

// Central differences of s and v with step 1e-5 agree with the analytic derivatives to ~1e-9
// (truncation h² ≈ 1e-10 times the third derivative, ~π³; rounding eps/h ≈ 2e-11).
constexpr double kFdStep = 1e-5;
constexpr double kFdTol = 1e-7;

template <class E>
void expect_derivatives_consistent(const E& e, double t) {
  const auto c = e.sample(t);
  const auto p = e.sample(t + kFdStep), m = e.sample(t - kFdStep);
  EXPECT_NEAR((p.s - m.s) / (2 * kFdStep), c.velocity, kFdTol) << "t=" << t;
  EXPECT_NEAR((p.velocity - m.velocity) / (2 * kFdStep), c.acceleration, kFdTol * 100) << "t=" << t;
}

template <class E>
void expect_endpoints(const E& e, double v0, double v1) {
  EXPECT_NEAR(e.sample(0.0).s, 0.0, 1e-15);
  EXPECT_NEAR(e.sample(1.0).s, 1.0, 1e-15);
  EXPECT_NEAR(e.sample(0.0).velocity, v0, 1e-12);
  EXPECT_NEAR(e.sample(1.0).velocity, v1, 1e-12);
  EXPECT_EQ(e.sample(-2.0).s, e.sample(0.0).s);  // clamped
  EXPECT_EQ(e.sample(3.0).s, e.sample(1.0).s);
}

TEST(Ease, SineReproducesTheTextsWorkedNumbers) {
  const SineEase<double> e;
  // Texts 004 after Eq. 3.18: ease(0.25) = 0.1465 and ease(0.75) = 0.8535.  The exact values are
  // 0.146447 and 0.853553, which round to 0.1464 and 0.8536: the printed digits were rounded twice
  // (0.146447 → 0.14645 → 0.1465), so they agree to one unit in the 4th decimal, not half a unit.
  EXPECT_NEAR(e(0.25), 0.1465, 1e-4);
  EXPECT_NEAR(e(0.75), 0.8535, 1e-4);
  EXPECT_NEAR(e(0.25), 0.1464, 5e-5);  // correctly rounded to 4 decimals
  EXPECT_NEAR(e(0.75), 0.8536, 5e-5);
  // Closed form (1 − cos(π/4))/2 = (2 − √2)/4.
  EXPECT_NEAR(e(0.25), (2 - std::sqrt(2.0)) / 4, 1e-16);
  expect_endpoints(e, 0.0, 0.0);
  for (double t = 0.05; t < 1; t += 0.1) expect_derivatives_consistent(e, t);
  EXPECT_NEAR(e.sample(0.5).velocity, std::numbers::pi / 2, 1e-15);  // (π/2) sin(π/2)
}

TEST(Ease, LinearAndCubic) {
  const LinearEase<double> lin;
  expect_endpoints(lin, 1.0, 1.0);
  EXPECT_EQ(lin(0.3), 0.3);
  const CubicEase<double> cub;
  expect_endpoints(cub, 0.0, 0.0);  // "horizontal beginning and ending tangents" (after Eq. 3.20)
  EXPECT_DOUBLE_EQ(cub(0.5), 0.5);
  EXPECT_DOUBLE_EQ(cub.sample(0.5).velocity, 1.5);  // 6·0.5·0.5
  for (double t = 0.05; t < 1; t += 0.1) expect_derivatives_consistent(cub, t);
  // "accuracy within a couple of decimal points" of the sine ease (texts): max gap is < 0.02.
  const SineEase<double> sine;
  for (double t = 0; t <= 1; t += 0.01) EXPECT_LT(std::fabs(cub(t) - sine(t)), 0.02) << t;
}

TEST(Ease, SineAccelDecelUsesTheCorrectedNormaliser) {
  auto e = SineAccelDecelEase<double>::make(0.3, 0.75);  // the texts' example k1 = 0.3, k2 = 0.75
  ASSERT_TRUE(e);
  const double f = 2 * 0.3 / std::numbers::pi + (0.75 - 0.3) + 2 * (1 - 0.75) / std::numbers::pi;
  EXPECT_DOUBLE_EQ(e->f(), f);  // errata: f = 2k1/π + (k2 − k1) + 2(1 − k2)/π
  expect_endpoints(*e, 0.0, 0.0);
  // The printed f = k1(2/π + k2 − k1 + (1 − k2)(2/π)) would not end at 1:
  const double printed = 0.3 * (2 / std::numbers::pi + 0.75 - 0.3 + (1 - 0.75) * 2 / std::numbers::pi);
  EXPECT_GT(std::fabs(e->f() / printed - 1), 0.5);
  // Constant velocity 1/f in the middle; C¹ at k1 and k2 (one-sided limits match).
  EXPECT_DOUBLE_EQ(e->sample(0.5).velocity, 1 / f);
  EXPECT_NEAR(e->sample(0.3 - 1e-12).velocity, 1 / f, 1e-9);
  EXPECT_NEAR(e->sample(0.75 + 1e-12).velocity, 1 / f, 1e-9);
  EXPECT_NEAR(e->sample(0.3 - 1e-12).s, e->sample(0.3).s, 1e-11);
  for (double t : {0.05, 0.2, 0.5, 0.8, 0.95}) expect_derivatives_consistent(*e, t);
  // Figure 3.13 code, evaluated literally, agrees with the class.
  auto fig313 = [](double t, double k1, double k2) {
    const double PI = std::numbers::pi;
    double ff = k1 * 2 / PI + k2 - k1 + (1.0 - k2) * 2 / PI, s;
    if (t < k1) s = k1 * (2 / PI) * (std::sin((t / k1) * PI / 2 - PI / 2) + 1);
    else if (t < k2) s = (2 * k1 / PI + t - k1);
    else s = 2 * k1 / PI + k2 - k1 + ((1 - k2) * (2 / PI)) * std::sin(((t - k2) / (1.0 - k2)) * PI / 2);
    return s / ff;
  };
  for (double t = 0; t <= 1; t += 0.05) EXPECT_NEAR((*e)(t), fig313(t, 0.3, 0.75), 1e-15) << t;
}

TEST(Ease, SineAccelDecelEdgeParameters) {
  auto lin = SineAccelDecelEase<double>::make(0, 1);  // no acceleration phases: s = t
  ASSERT_TRUE(lin);
  for (double t = 0; t <= 1; t += 0.125) EXPECT_NEAR((*lin)(t), t, 1e-15);
  auto full = SineAccelDecelEase<double>::make(0.5, 0.5);  // no constant phase
  ASSERT_TRUE(full);
  expect_endpoints(*full, 0.0, 0.0);
  EXPECT_FALSE(SineAccelDecelEase<double>::make(-0.1, 0.5));
  EXPECT_EQ(SineAccelDecelEase<double>::make(0.6, 0.5).error().location, (std::vector<LocationStep>{std::string("k2")}));
  EXPECT_EQ(SineAccelDecelEase<double>::make(std::nan(""), 0.5).error().code, ErrorCode::not_finite);
}

TEST(Ease, ConstantAccelerationVelocityAndAccelerationCurves) {
  auto e = ConstantAccelerationEase<double>::make(0.2, 0.7);
  ASSERT_TRUE(e);
  // Eq. 3.22 corrected: v0 = 2/(t2 − t1 + 1) (from Eq. 3.21's area = 1).
  EXPECT_DOUBLE_EQ(e->v0(), 2 / (0.7 - 0.2 + 1));
  expect_endpoints(*e, 0.0, 0.0);
  // Velocity: a trapezoid (Figure 3.17); acceleration: v0/t1, 0, −v0/(1 − t2) (Figure 3.16).
  const double v0 = e->v0();
  for (double t = 0; t <= 1.0; t += 1.0 / 64) {
    const double v_formula = t < 0.2 ? v0 * t / 0.2 : (t <= 0.7 ? v0 : v0 * (1 - t) / 0.3);
    const double a_formula = t < 0.2 ? v0 / 0.2 : (t <= 0.7 ? 0.0 : -v0 / 0.3);
    EXPECT_NEAR(e->velocity(t), v_formula, 1e-14) << t;
    EXPECT_NEAR(e->acceleration(t), a_formula, 1e-14) << t;
  }
  // Distance = area under the velocity (trapezoid rule is exact on each linear piece).
  double area = 0;
  const int n = 1000;
  for (int i = 0; i < n; ++i) area += (e->velocity(double(i) / n) + e->velocity(double(i + 1) / n)) / (2 * n);
  EXPECT_NEAR(area, 1.0, 1e-12);  // t1 and t2 are grid points, so the rule is exact up to rounding
  for (double t : {0.1, 0.4, 0.85}) expect_derivatives_consistent(*e, t);
  EXPECT_EQ(ConstantAccelerationEase<double>::make(0.5, 0.4).error().location, (std::vector<LocationStep>{std::string("t2")}));
}

TEST(Ease, FloatInstantiationsWork) {
  EXPECT_NEAR(SineEase<float>{}(0.25f), 0.1464466f, 1e-7f);  // (2 − √2)/4 to float precision
  auto e = ConstantAccelerationEase<float>::make(0.25f, 0.75f);
  ASSERT_TRUE(e);
  EXPECT_NEAR((*e)(1.0f), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace inbetween

namespace inbetween {
namespace {

// Every ease, in float and double: passes (0, 0) and (1, 1) with its stated end slopes, and the
// reported velocity is the derivative of s (central difference; step and tolerance per precision:
// h = eps^(1/3) balances truncation h² against rounding eps/h).
template <class T>
class EaseTyped : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(EaseTyped, Precisions);

template <class T, class E>
void check_ease(const E& e, T v0, T v1, const char* name) {
  SCOPED_TRACE(name);
  const T eps = std::numeric_limits<T>::epsilon();
  EXPECT_NEAR(e.sample(T(0)).s, T(0), 4 * eps);
  EXPECT_NEAR(e.sample(T(1)).s, T(1), 4 * eps);
  EXPECT_NEAR(e.sample(T(0)).velocity, v0, 16 * eps);
  EXPECT_NEAR(e.sample(T(1)).velocity, v1, 16 * eps);
  // Total: t outside [0, 1] clamps, and a NaN time is the start (it used to give s = NaN for the
  // eases of ease.hpp while CubicBezierTiming already answered 0).
  for (const auto& [t_in, t_eq] : {std::pair<T, T>{std::numeric_limits<T>::quiet_NaN(), T(0)}, {T(-3), T(0)},
                                   {T(7), T(1)}}) {
    const auto got = e.sample(t_in), want = e.sample(t_eq);
    EXPECT_EQ(got.s, want.s) << "t=" << t_in;
    EXPECT_EQ(got.velocity, want.velocity) << "t=" << t_in;
    EXPECT_EQ(got.acceleration, want.acceleration) << "t=" << t_in;
  }
  const T h = std::cbrt(eps);
  // |s'''| ≤ ~30 for these eases (π³ for the sine), plus rounding eps/h; the probes stay away from
  // the phase joints (0.25, 0.65), where s'' jumps.
  const T tol = T(50) * h * h;
  for (T t = T(0.1); t < T(0.95); t += T(0.1)) {
    const T fd = (e.sample(t + h).s - e.sample(t - h).s) / (2 * h);
    EXPECT_NEAR(fd, e.sample(t).velocity, tol) << "t=" << t;
  }
}

TYPED_TEST(EaseTyped, EndpointsSlopesAndVelocity) {
  using T = TypeParam;
  check_ease<T>(LinearEase<T>{}, T(1), T(1), "linear");
  check_ease<T>(SineEase<T>{}, T(0), T(0), "sine");
  check_ease<T>(CubicEase<T>{}, T(0), T(0), "cubic");
  check_ease<T>(*SineAccelDecelEase<T>::make(T(0.25), T(0.65)), T(0), T(0), "sine accel/decel");
  check_ease<T>(*ConstantAccelerationEase<T>::make(T(0.25), T(0.65)), T(0), T(0), "constant acceleration");
}

}  // namespace
}  // namespace inbetween
