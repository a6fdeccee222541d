// Penner easing in Blender's form.  Sources: the closed forms of Penner's equations (quoted per
// check), and Blender 3.4.1 values measured through FCurve.evaluate (the F-curve tests and the
// Blender agreement test cover every curve × direction against Blender itself).
#include "inbetween/timing/penner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

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

// ------------------------------------------------------------------ penner_ease_velocity
// Central difference of penner_ease in double at a step h = 1e-6 of the duration: truncation
// h²·|e‴|/6 ≤ 1.7e-13·|e‴| (|e‴| < 1e5 even for elastic: ω = 2π/0.3 ≈ 21, ω³ ≈ 9.3e3, times the
// 2^(10x) ≤ 1 envelope and a factor ≤ 10 from its derivative) plus rounding ≈ 4ε/h ≈ 1e-9, so 1e-6
// (relative to max(1, |v|)) separates a right formula from a wrong one (a wrong factor or sign is
// off by ≥ 1e-2).  The grid (i + 0.37)/997 stays ≥ 1e-4 ≫ h away from the in-out midpoint; points
// within 2h of another branch boundary (bounce's arc joins, elastic's blend edge) are recognised
// by one-sided differences that disagree, and skipped; circ is skipped within 1e-2 of where its
// slope is unbounded (there |e‴| ~ (1 − u²)^(−5/2) makes the difference itself inaccurate).
TEST(PennerVelocity, MatchesCentralDifferenceEverywhere) {
  constexpr double h = 1e-6;
  const PennerParams<double> params[] = {{.back = 1.70158, .amplitude = 1, .period = 0.3},
                                         {.back = 0.8, .amplitude = 0.4, .period = 0.45}};  // amplitude < change: the blend
  for (const auto& p : params) {
    for (EasingCurve c : kAll) {
      for (EasingDirection d : kDirs) {
        SCOPED_TRACE(int(c) * 10 + int(d));
        int checked = 0;
        for (int i = 0; i < 997; ++i) {
          const double u = (i + 0.37) / 997.0;
          if (c == EasingCurve::circ) {
            const double vertical = d == EasingDirection::in ? 1.0 : d == EasingDirection::out ? 0.0 : 0.5;
            if (std::abs(u - vertical) < 1e-2) continue;
          }
          const double fm = ease_unit(c, d, u - h, p), f0 = ease_unit(c, d, u, p), fp = ease_unit(c, d, u + h, p);
          const double left = (f0 - fm) / h, right = (fp - f0) / h;
          if (std::abs(left - right) > 1e-3 * std::max(1.0, std::abs(left))) continue;  // a kink
          const double v = ease_unit_velocity(c, d, u, p);
          EXPECT_NEAR(v, (fp - fm) / (2 * h), 1e-6 * std::max(1.0, std::abs(v))) << "u = " << u;
          ++checked;
        }
        EXPECT_GE(checked, 960);  // only the few points next to a kink or circ's vertical are skipped
      }
    }
  }
}

// ------------------------------------------------------------------ penner_ease_acceleration
// Against the central difference of the analytic velocity, with its error estimated by Richardson:
// D(h) = a + h²·v‴/6 + O(h⁴), so |D(h/2) − a| ≈ |D(h) − D(h/2)|/3.  The check |a − D(h/2)| ≤
// |D(h) − D(h/2)| + rounding (64ε·max(1, |v|)/h, the velocity's rounding over the step) can only
// pass for a formula right to the difference's own accuracy; a wrong factor or sign is off by
// O(|a|).  h = 1e-4 (truncation ≈ 1.7e-9·|v‴| even for elastic's |v‴| ~ 1e6: ≈ 2e-3 ≪ |a| ~ 400).
// Points where D(h) and D(h/2) disagree by more than 1e-2·max(1, |a|) straddle a branch join
// (bounce arcs, elastic's blend edge, the in-out midpoint) and are skipped (this does not look at
// a), as is circ within 2e-2 of its vertical.
TEST(PennerAcceleration, MatchesCentralDifferenceOfTheVelocity) {
  constexpr double h = 1e-4;
  const PennerParams<double> params[] = {{.back = 1.70158, .amplitude = 1, .period = 0.3},
                                         {.back = 0.8, .amplitude = 0.4, .period = 0.45}};
  const auto acc = [](EasingCurve c, EasingDirection d, double u, const PennerParams<double>& p) {
    return penner_ease_acceleration(c, d, u, 1.0, 1.0, p);
  };
  double worst = 0;
  for (const auto& p : params) {
    for (EasingCurve c : kAll) {
      for (EasingDirection d : kDirs) {
        SCOPED_TRACE(int(c) * 10 + int(d));
        int checked = 0;
        for (int i = 0; i < 997; ++i) {
          const double u = (i + 0.37) / 997.0;
          if (c == EasingCurve::circ) {
            const double vertical = d == EasingDirection::in ? 1.0 : d == EasingDirection::out ? 0.0 : 0.5;
            if (std::abs(u - vertical) < 2e-2) continue;
          }
          const auto v = [&](double x) { return ease_unit_velocity(c, d, x, p); };
          const double a = acc(c, d, u, p);
          const double d1 = (v(u + h) - v(u - h)) / (2 * h), d2 = (v(u + h / 2) - v(u - h / 2)) / h;
          const double rounding = 64 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(v(u))) / h;
          const bool near_join = std::abs(d1 - d2) > 1e-2 * std::max(1.0, std::abs(a));
          if (near_join) continue;  // a join within h: the difference straddles two branches
          EXPECT_LE(std::abs(a - d2), std::abs(d1 - d2) + rounding) << "u = " << u << ": a " << a << ", D(h/2) " << d2;
          worst = std::max(worst, std::abs(a - d2) / std::max(1.0, std::abs(a)));
          ++checked;
        }
        EXPECT_GE(checked, 940);  // only points next to a join or circ's vertical are skipped
      }
    }
  }
  std::printf("[ penner acceleration ] worst |a − D(h/2)| / max(1, |a|) = %.3g\n", worst);
}

TEST(PennerAcceleration, ClosedForms) {
  const double pi = 3.14159265358979323846;
  // sine in 1 − cos(πu/2) → (π/2)²·cos(πu/2); out sin(πu/2) → −(π/2)²·sin(πu/2); in-out
  // (1 − cos πu)/2 → (π²/2)·cos πu.
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::sine, EasingDirection::in, 0.3, 1.0, 1.0), pi * pi / 4 * std::cos(pi * 0.15), 1e-14);
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::sine, EasingDirection::out, 0.3, 1.0, 1.0), -pi * pi / 4 * std::sin(pi * 0.15), 1e-14);
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::sine, EasingDirection::in_out, 0.3, 1.0, 1.0), pi * pi / 2 * std::cos(pi * 0.3), 1e-14);
  // quad in u² → 2; cubic out 1 − (1 − u)³ → −6(1 − u); quint in-out 16u⁵ → 320u³ on the first half.
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::quad, EasingDirection::in, 0.3, 1.0, 1.0), 2.0, 1e-15);
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::cubic, EasingDirection::out, 0.3, 1.0, 1.0), -6 * 0.7, 1e-14);
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::quint, EasingDirection::in_out, 0.25, 1.0, 1.0), 320 * std::pow(0.25, 3), 1e-13);
  // back in u²((s + 1)u − s) → 6(s + 1)u − 2s.
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::back, EasingDirection::in, 0.2, 1.0, 1.0, PennerParams<double>{}),
              6 * 2.70158 * 0.2 - 2 * 1.70158, 1e-14);
  // bounce out: arcs 7.5625·(u − a)² + c → 15.125.
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::bounce, EasingDirection::out, 0.1, 1.0, 1.0), 15.125, 1e-13);
  // expo in (2^(10(u−1)) − 2⁻¹⁰)/(1 − 2⁻¹⁰) → (10 ln 2)²·2^(10(u−1))/(1 − 2⁻¹⁰); at u = 1: (10 ln 2)²/(1 − 2⁻¹⁰).
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::expo, EasingDirection::in, 1.0, 1.0, 1.0),
              100 * std::log(2.0) * std::log(2.0) / (1 - 1.0 / 1024), 1e-12);
  // circ in 1 − √(1 − u²) → (1 − u²)^(−3/2).
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::circ, EasingDirection::in, 0.6, 1.0, 1.0), std::pow(0.64, -1.5), 1e-13);
  // Change and duration scale it by change/duration².
  EXPECT_NEAR(penner_ease_acceleration(EasingCurve::sine, EasingDirection::in_out, 3.0, 5.0, 10.0),
              5.0 / 100.0 * pi * pi / 2 * std::cos(pi * 0.3), 1e-15);
  EXPECT_TRUE(std::isfinite(penner_ease_acceleration(EasingCurve::circ, EasingDirection::in, 1.0, 1.0, 1.0)));
}

TEST(PennerVelocity, ClosedForms) {
  const double pi = 3.14159265358979323846;
  // sine in: 1 − cos(πu/2) → (π/2)·sin(πu/2); out: sin(πu/2) → (π/2)·cos(πu/2); in-out (1 − cos πu)/2 → (π/2)·sin πu.
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::sine, EasingDirection::in, 0.3), pi / 2 * std::sin(pi * 0.15), 1e-15);
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::sine, EasingDirection::out, 0.3), pi / 2 * std::cos(pi * 0.15), 1e-15);
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::sine, EasingDirection::in_out, 0.3), pi / 2 * std::sin(pi * 0.3), 1e-15);
  // quad in u² → 2u; cubic out 1 − (1 − u)³ → 3(1 − u)²; quint in-out 16u⁵ → 80u⁴ on the first half.
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::quad, EasingDirection::in, 0.3), 0.6, 1e-15);
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::cubic, EasingDirection::out, 0.3), 3 * 0.49, 1e-15);
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::quint, EasingDirection::in_out, 0.25), 80 * std::pow(0.25, 4), 1e-15);
  // expo in (2^(10(u−1)) − 2⁻¹⁰)/(1 − 2⁻¹⁰) → 10·ln2·2^(10(u−1))/(1 − 2⁻¹⁰); at u = 1: 10·ln2/(1 − 2⁻¹⁰).
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::expo, EasingDirection::in, 1.0), 10 * std::log(2.0) / (1 - 1.0 / 1024), 1e-14);
  // back in u²((s + 1)u − s) → 3(s + 1)u² − 2su: zero at u = 0 and negative just after (the pull-back).
  const PennerParams<double> p{};
  EXPECT_EQ(ease_unit_velocity(EasingCurve::back, EasingDirection::in, 0.0, p), 0.0);
  EXPECT_NEAR(ease_unit_velocity(EasingCurve::back, EasingDirection::in, 0.2, p),
              3 * 2.70158 * 0.04 - 2 * 1.70158 * 0.2, 1e-15);
  // Penner's duration and change scale the velocity by change/duration.
  EXPECT_NEAR(penner_ease_velocity(EasingCurve::sine, EasingDirection::in_out, 3.0, 5.0, 10.0),
              5.0 / 10.0 * pi / 2 * std::sin(pi * 0.3), 1e-15);
  // circ in at its vertical end: large but finite.
  EXPECT_TRUE(std::isfinite(ease_unit_velocity(EasingCurve::circ, EasingDirection::in, 1.0)));
}

TEST(PennerVelocity, IntegratesToTheChange) {
  // ∫₀¹ e′(u) du = e(1) − e(0) = 1 for every curve whose formula hits both ends exactly (elastic's
  // time = 0 and end returns are exact, the formula's ends differ by 2⁻¹⁰-scaled terms: skipped).
  // Composite Simpson with 20000 panels, split at the in-out midpoint and bounce's arc joins where
  // the velocity jumps.
  const PennerParams<double> p{.back = 1.70158, .amplitude = 1, .period = 0.3};
  for (EasingCurve c : kAll) {
    if (c == EasingCurve::elastic || c == EasingCurve::circ) continue;  // circ: unbounded slope at an end
    for (EasingDirection d : kDirs) {
      SCOPED_TRACE(int(c) * 10 + int(d));
      std::vector<double> cuts{0.0, 1.0};
      if (d == EasingDirection::in_out) cuts.push_back(0.5);
      if (c == EasingCurve::bounce) {
        for (double b : {1 / 2.75, 2 / 2.75, 2.5 / 2.75}) {
          if (d == EasingDirection::out) cuts.push_back(b);
          if (d == EasingDirection::in) cuts.push_back(1 - b);
          if (d == EasingDirection::in_out) { cuts.push_back((1 - b) / 2); cuts.push_back(0.5 + b / 2); }
        }
      }
      std::sort(cuts.begin(), cuts.end());
      double total = 0;
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double a = cuts[k], b = cuts[k + 1];
        const int n = 20000;
        const double step = (b - a) / n;
        // Evaluate just inside the piece at its ends (the branch there is the neighbour's).
        const auto f = [&](double u) { return ease_unit_velocity(c, d, std::clamp(u, a + 1e-13, b - 1e-13), p); };
        double sum = f(a) + f(b);
        for (int i = 1; i < n; ++i) sum += f(a + i * step) * (i % 2 ? 4 : 2);
        total += sum * step / 3;
      }
      EXPECT_NEAR(total, 1.0, 1e-9);
    }
  }
}

}  // namespace
}  // namespace inbetween
