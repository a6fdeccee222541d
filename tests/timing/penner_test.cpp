// Penner easing in Blender's form.  Sources: the closed forms of Penner's equations (quoted per
// check), and Blender 3.4.1 values measured through FCurve.evaluate (the F-curve tests and the
// Blender agreement test cover every curve × direction against Blender itself).
#include "inbetween/timing/penner.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

constexpr EasingCurve kAll[] = {EasingCurve::sine,  EasingCurve::quad, EasingCurve::cubic, EasingCurve::quart,
                                EasingCurve::quint, EasingCurve::expo, EasingCurve::circ,  EasingCurve::back,
                                EasingCurve::bounce, EasingCurve::elastic};
constexpr EasingDirection kDirs[] = {EasingDirection::in, EasingDirection::out, EasingDirection::in_out};

template <class T>
class PennerTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PennerTest, Scalars);

// A handful of operations (a power, a sine) on values of magnitude ~1.
template <class T>
constexpr T kFormulaTol = T(64) * std::numeric_limits<T>::epsilon();

TYPED_TEST(PennerTest, HitsBothEnds) {
  using T = TypeParam;
  // Classic Penner parameters (amplitude = |change| disables Blender's blend, period 0 → 0.3·d).
  const PennerParams<T> p{.back = T(1.70158), .amplitude = T(1), .period = T(0)};
  for (EasingCurve c : kAll) {
    for (EasingDirection d : kDirs) {
      SCOPED_TRACE(int(c) * 10 + int(d));
      EXPECT_NEAR(ease_unit(c, d, T(0), p), T(0), kFormulaTol<T>);
      EXPECT_NEAR(ease_unit(c, d, T(1), p), T(1), kFormulaTol<T>);
    }
  }
}

TYPED_TEST(PennerTest, ClosedFormsOfThePowerFamily) {
  using T = TypeParam;
  for (T u = 0; u <= T(1); u += T(0.03125)) {
    // Penner: in = u^k, out = 1 − (1 − u)^k, sine in = 1 − cos(uπ/2), circ in = 1 − √(1 − u²).
    EXPECT_NEAR(ease_unit(EasingCurve::quad, EasingDirection::in, u), u * u, kFormulaTol<T>);
    EXPECT_NEAR(ease_unit(EasingCurve::cubic, EasingDirection::out, u), T(1) - std::pow(T(1) - u, T(3)), kFormulaTol<T>);
    EXPECT_NEAR(ease_unit(EasingCurve::quart, EasingDirection::in, u), std::pow(u, T(4)), kFormulaTol<T>);
    EXPECT_NEAR(ease_unit(EasingCurve::quint, EasingDirection::out, u), T(1) - std::pow(T(1) - u, T(5)), kFormulaTol<T>);
    EXPECT_NEAR(ease_unit(EasingCurve::sine, EasingDirection::in, u), T(1) - std::cos(u * pi_v<T> / 2), kFormulaTol<T>);
    EXPECT_NEAR(ease_unit(EasingCurve::circ, EasingDirection::in, u), T(1) - std::sqrt(T(1) - u * u), kFormulaTol<T>);
    // Blender's expo: (2^(10(u−1)) − 2⁻¹⁰)/(1 − 2⁻¹⁰).
    const T m = std::pow(T(2), T(-10));
    if (u > 0) {
      EXPECT_NEAR(ease_unit(EasingCurve::expo, EasingDirection::in, u), (std::pow(T(2), T(10) * (u - 1)) - m) / (1 - m),
                  kFormulaTol<T>);
    }
    // back in: u²((s+1)u − s).
    const T s = T(1.70158);
    EXPECT_NEAR(ease_unit(EasingCurve::back, EasingDirection::in, u), u * u * ((s + 1) * u - s), kFormulaTol<T>);
  }
}

TYPED_TEST(PennerTest, OutMirrorsInAndInOutJoinsThem) {
  using T = TypeParam;
  const PennerParams<T> p{.back = T(1.2), .amplitude = T(1), .period = T(0.3)};
  for (EasingCurve c : kAll) {
    SCOPED_TRACE(int(c));
    for (T u = T(0.015625); u < T(1); u += T(0.0625)) {
      if (c != EasingCurve::elastic) {  // elastic out uses its own phase origin (Penner's definition)
        EXPECT_NEAR(ease_unit(c, EasingDirection::out, u, p), T(1) - ease_unit(c, EasingDirection::in, T(1) - u, p),
                    kFormulaTol<T>);
      }
      // in-out: the in curve on [0, ½] at half height (back uses a scaled overshoot, 1.525·s,
      // and elastic a 1.5× period, so they are excluded here).
      if (c != EasingCurve::back && c != EasingCurve::elastic && u < T(0.5)) {
        EXPECT_NEAR(ease_unit(c, EasingDirection::in_out, u, p), ease_unit(c, EasingDirection::in, 2 * u, p) / 2,
                    kFormulaTol<T>);
      }
    }
  }
}

TYPED_TEST(PennerTest, ScalesWithBeginChangeDuration) {
  using T = TypeParam;
  test::Random rng(test::seed_for(5010));
  SCOPED_TRACE(rng.trace());
  const PennerParams<T> p{.back = T(1.70158), .amplitude = T(0), .period = T(0)};
  for (int i = 0; i < 200; ++i) {
    const EasingCurve c = kAll[rng.integer(0, 9)];
    const EasingDirection d = kDirs[rng.integer(0, 2)];
    const T b = rng.uniform<T>(-5, 5), ch = rng.uniform<T>(0.5, 5), dur = rng.uniform<T>(0.5, 20);
    const T u = rng.uniform<T>(0, 1);
    // Affine in value and scale-free in time: f(u·d; b, c, d) = b + c·e(u)  (elastic's default
    // period is relative to d, amplitude 0 is relative to c).
    EXPECT_NEAR(penner_ease(c, d, u * dur, b, ch, dur, p), b + ch * ease_unit(c, d, u, p),
                T(16) * kFormulaTol<T> * (std::abs(b) + ch));
  }
}

TEST(Penner, AutomaticDirectionIsBlenders) {
  EXPECT_EQ(automatic_direction(EasingCurve::back), EasingDirection::out);
  EXPECT_EQ(automatic_direction(EasingCurve::bounce), EasingDirection::out);
  EXPECT_EQ(automatic_direction(EasingCurve::elastic), EasingDirection::out);
  EXPECT_EQ(automatic_direction(EasingCurve::sine), EasingDirection::in);
  EXPECT_EQ(automatic_direction(EasingCurve::expo), EasingDirection::in);
}

TEST(Penner, BlenderElasticAndBackNumbers) {
  // Blender 3.4.1, segment (0,0)→(10,1) with insert() defaults (amplitude 0.8, period 4.1, back 1.70158).
  const PennerParams<float> p{};
  EXPECT_NEAR(penner_ease(EasingCurve::elastic, EasingDirection::out, 1.f, 0.f, 1.f, 10.f, p), 0.9845857f, 1e-6f);
  EXPECT_NEAR(penner_ease(EasingCurve::elastic, EasingDirection::out, 2.5f, 0.f, 1.f, 10.f, p), 1.109105f, 1e-6f);
  EXPECT_NEAR(penner_ease(EasingCurve::back, EasingDirection::out, 1.f, 0.f, 1.f, 10.f, p), 0.4088281f, 1e-6f);
}

}  // namespace
}  // namespace inbetween
