// F-curve modifiers (tracks/fmodifier.hpp) on curves whose keys are a straight line y = t, so each
// modifier's value has a closed form (Blender 3.4's fmodifier.c formulas, documented in
// docs/tracks.md); the stack's order (time last → first, value first → last), influence and range
// ramps; build errors with their locations; the derivative against central differences on seeded
// random stacks; totality (never NaN).  Agreement with Blender itself: tests/io/fmodifier_blender_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "inbetween/tracks/fcurve.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// y = t on [0, 10] with linear extrapolation both ways: the keys' value at t is t (exact in float
// for the frames used below).
RawFCurve line(std::vector<FCurveModifier> modifiers) {
  RawFCurve raw;
  for (double f : {0.0, 10.0}) {
    FCurveKey k;
    k.frame = f;
    k.value = f;
    k.interpolation = Interpolation::linear;
    raw.keys.push_back(k);
  }
  raw.extrapolation = Extrapolation::linear;
  raw.modifiers = std::move(modifiers);
  return raw;
}

FCurve build(const RawFCurve& raw) {
  auto c = build_fcurve(raw);
  EXPECT_TRUE(c.has_value()) << c.error().describe();
  return std::move(c).value();
}

FCurveModifier mod(auto kind) { return FCurveModifier{.kind = kind}; }

TEST(FCurveModifiers, GeneratorExpandedAndFactorised) {
  // 1 + 2t − 0.5t² (closed form; exact in float at these frames).
  const FCurve expanded = build(line({mod(FCurveGenerator{.coefficients = {1, 2, -0.5}})}));
  for (float t : {-4.0f, 0.0f, 2.5f, 7.0f, 30.0f}) EXPECT_EQ(expanded.sample(t), 1 + 2 * t - 0.5f * t * t) << t;
  // (2t + 1)(t − 3), added to y = t.
  const FCurve factorised = build(
      line({mod(FCurveGenerator{.mode = GeneratorMode::factorised, .additive = true, .coefficients = {2, 1, 1, -3}})}));
  for (float t : {-4.0f, 0.0f, 2.5f, 7.0f}) EXPECT_EQ(factorised.sample(t), t + (2 * t + 1) * (t - 3)) << t;
  EXPECT_DOUBLE_EQ(expanded.derivative(2.5f), 2 - 2.5);                    // 2 − t
  EXPECT_DOUBLE_EQ(factorised.derivative(2.5f), 1 + 2 * (2.5 - 3) + (2 * 2.5 + 1));  // 1 + product rule
}

TEST(FCurveModifiers, FunctionAndBlendersDomainGuards) {
  const double pi = std::numbers::pi;
  const FCurve s = build(line({mod(FCurveFunction{.function = BuiltinFunction::sin, .amplitude = 2, .phase_multiplier = 0.5,
                                                  .phase_offset = 1, .value_offset = 3})}));
  for (float t : {-3.0f, 0.0f, 1.25f, 9.0f}) {
    EXPECT_NEAR(s.sample(t), 2 * std::sin(0.5 * t + 1) + 3, 1e-6) << t;
    EXPECT_NEAR(s.derivative(t), 2 * 0.5 * std::cos(0.5 * t + 1), 1e-6) << t;
  }
  // sqrt and ln outside their domain: Blender writes 0 (not value_offset); additive leaves the value.
  const FCurve root = build(line({mod(FCurveFunction{.function = BuiltinFunction::sqrt, .value_offset = 5})}));
  EXPECT_EQ(root.sample(-2.0f), 0.0f);
  EXPECT_EQ(root.sample(0.0f), 0.0f);
  EXPECT_NEAR(root.sample(4.0f), 7.0f, 1e-6);
  const FCurve ln = build(line({mod(FCurveFunction{.function = BuiltinFunction::ln, .additive = true})}));
  EXPECT_EQ(ln.sample(0.5f), 0.5f);  // ln needs arg > 1 in Blender: 0.5 is guarded, the value stays
  EXPECT_EQ(ln.sample(1.0f), 1.0f);
  EXPECT_NEAR(ln.sample(4.0f), 4 + std::log(4.0), 1e-6);
  // tan at its poles (arg = π/2·t at odd t) gives 0; sinc(0) = 1.
  const FCurve tan = build(line({mod(FCurveFunction{.function = BuiltinFunction::tan, .phase_multiplier = pi / 2})}));
  EXPECT_EQ(tan.sample(1.0f), 0.0f);
  EXPECT_EQ(tan.sample(3.0f), 0.0f);
  EXPECT_NEAR(tan.sample(0.5f), 1.0f, 1e-6);
  EXPECT_TRUE(std::isfinite(tan.derivative(1.0f)));
  const FCurve sinc = build(line({mod(FCurveFunction{.function = BuiltinFunction::sinc})}));
  EXPECT_EQ(sinc.sample(0.0f), 1.0f);
  EXPECT_NEAR(sinc.sample(0.5f), std::sin(pi / 2) / (pi / 2), 1e-7);
  EXPECT_NEAR(sinc.sample(2.0f), 0.0f, 1e-7);
}

TEST(FCurveModifiers, EnvelopeMapsTheBandBetweenPoints) {
  // Band [−1, 1] around reference 0; points (0: −2..2) and (10: 0..4).  At t = 5 the band is
  // [−1, 3]; the value 5 of y = t maps to −1 + (5 + 1)/2 · 4 = 11.  Before the first point: held.
  const FCurve e = build(line({mod(FCurveEnvelope{.points = {{0, -2, 2}, {10, 0, 4}}})}));
  EXPECT_EQ(e.sample(5.0f), 11.0f);
  EXPECT_EQ(e.sample(-1.0f), -2 + (-1 + 1) / 2.0f * 4);  // first point's band [−2, 2]
  EXPECT_EQ(e.sample(12.0f), 0 + (12 + 1) / 2.0f * 4);   // last point's band [0, 4]
  // d/dt: dmin/dt + fac·(dmax − dmin)/dt (both 0.2 per frame) + (band 4)/(reference width 2)·(dy/dt = 1).
  EXPECT_NEAR(e.derivative(5.0f), 0.2 + 0.75 * 0.0 + 2.0, 1e-6);
  const FCurve none = build(line({mod(FCurveEnvelope{})}));
  EXPECT_EQ(none.sample(3.0f), 3.0f);
}

TEST(FCurveModifiers, SteppedTruncatesTowardZeroAndLimitsClamp) {
  const FCurve st = build(line({mod(FCurveStepped{.step = 2, .offset = 0.5})}));
  EXPECT_EQ(st.sample(3.7f), 2.5f);   // (int)(3.2/2) = 1
  EXPECT_EQ(st.sample(-0.7f), 0.5f);  // (int)(−0.6) = 0: toward zero, not floor
  EXPECT_EQ(st.derivative(3.7f), 0.0);
  const FCurve from5 = build(line({mod(FCurveStepped{.step = 2, .start = 5.0})}));
  EXPECT_EQ(from5.sample(3.7f), 3.7f);
  EXPECT_EQ(from5.sample(7.7f), 6.0f);
  const FCurve lim = build(line({mod(FCurveLimits{.max_x = 8.0, .min_y = 1.0})}));
  EXPECT_EQ(lim.sample(9.0f), 8.0f);
  EXPECT_EQ(lim.sample(0.5f), 1.0f);
  EXPECT_EQ(lim.sample(4.0f), 4.0f);
}

TEST(FCurveModifiers, StackOrderInfluenceAndRange) {
  // Time modifiers run last → first: [Limits max_x 5, Stepped 2] steps 7.3 to 6 then limits to 5;
  // the other order limits to 5 then steps to 4.
  EXPECT_EQ(build(line({mod(FCurveLimits{.max_x = 5.0}), mod(FCurveStepped{})})).sample(7.3f), 5.0f);
  EXPECT_EQ(build(line({mod(FCurveStepped{}), mod(FCurveLimits{.max_x = 5.0})})).sample(7.3f), 4.0f);
  // Value modifiers run first → last: [+10, clamp ≤ 12] vs [clamp ≤ 12, +10] at t = 4.
  const FCurveModifier plus10 = mod(FCurveGenerator{.additive = true, .coefficients = {10, 0}});
  const FCurveModifier clamp12 = mod(FCurveLimits{.max_y = 12.0});
  EXPECT_EQ(build(line({plus10, clamp12})).sample(4.0f), 12.0f);
  EXPECT_EQ(build(line({clamp12, plus10})).sample(4.0f), 14.0f);
  // Influence 0.25: 0.25·generator + 0.75·keys (Blender's interpf).
  FCurveModifier quarter = mod(FCurveGenerator{.coefficients = {8, 0}});
  quarter.influence = 0.25;
  EXPECT_EQ(build(line({quarter})).sample(4.0f), 0.25f * 8 + 0.75f * 4);
  // Range [2, 8] with blend in 2 and out 2: skipped outside, half influence in the middle of a ramp.
  FCurveModifier ranged = mod(FCurveGenerator{.coefficients = {8, 0}});
  ranged.range = FModifierRange{.start = 2, .end = 8, .blend_in = 2, .blend_out = 2};
  const FCurve r = build(line({ranged}));
  EXPECT_EQ(r.sample(1.0f), 1.0f);
  EXPECT_EQ(r.sample(3.0f), 0.5f * 8 + 0.5f * 3);
  EXPECT_EQ(r.sample(5.0f), 8.0f);
  EXPECT_EQ(r.sample(7.0f), 0.5f * 8 + 0.5f * 7);
  EXPECT_EQ(r.sample(9.0f), 9.0f);
  EXPECT_NEAR(r.derivative(3.0f), 0.5 * 0 + 0.5 * 1 + 0.5 * (8 - 3), 1e-12);  // w′ = 1/2 per frame
  // Muted: nothing.
  FCurveModifier muted = mod(FCurveGenerator{.coefficients = {8, 0}});
  muted.mute = true;
  EXPECT_EQ(build(line({muted})).sample(4.0f), 4.0f);
}

TEST(FCurveModifiers, CyclesFirstThenMoreAndCyclesBelowTheTopDisabled) {
  // Cycles (repeat) maps 15 to 5; the value modifiers below it see the mapped frame: additive t.
  const FCurve first = build(line({mod(FCurveCycles{}), mod(FCurveGenerator{.additive = true})}));
  EXPECT_EQ(first.sample(15.0f), 10.0f);
  EXPECT_EQ(first.simple_cycles(), nullptr);
  // Below the top Blender disables Cycles: the curve extrapolates linearly.
  const FCurve below = build(line({mod(FCurveLimits{}), mod(FCurveCycles{})}));
  EXPECT_EQ(below.sample(15.0f), 15.0f);
  // Alone, unmuted, full influence, no range: the fast path.
  EXPECT_NE(build(line({mod(FCurveCycles{})})).simple_cycles(), nullptr);
  FCurveModifier half = mod(FCurveCycles{});
  half.influence = 0.5;
  const FCurve partial = build(line({half}));
  EXPECT_EQ(partial.simple_cycles(), nullptr);
  EXPECT_EQ(partial.sample(15.0f), 0.5f * 5 + 0.5f * 15);
}

TEST(FCurveModifiers, BuildErrorsNameTheModifierMember) {
  auto where = [](const RawFCurve& raw) {
    auto c = build_fcurve(raw);
    return c ? std::string("ok") : json_pointer(c.error().location);
  };
  EXPECT_EQ(where(line({mod(FCurveLimits{}), mod(FCurveGenerator{.coefficients = {1}})})), "/modifiers/1/coefficients");
  EXPECT_EQ(where(line({mod(FCurveGenerator{.mode = GeneratorMode::factorised, .coefficients = {1, 2, 3}})})),
            "/modifiers/0/coefficients");
  EXPECT_EQ(where(line({mod(FCurveGenerator{.coefficients = {1, std::nan("")}})})), "/modifiers/0/coefficients/1");
  EXPECT_EQ(where(line({mod(FCurveStepped{.step = 0})})), "/modifiers/0/step");
  EXPECT_EQ(where(line({mod(FCurveEnvelope{.points = {{2, 0, 1}, {1, 0, 1}}})})), "/modifiers/0/points/1/frame");
  EXPECT_EQ(where(line({mod(FCurveEnvelope{.default_min = 1, .default_max = 1})})), "/modifiers/0/default_max");
  EXPECT_EQ(where(line({mod(FCurveNoise{.depth = -1})})), "/modifiers/0/depth");
  FCurveModifier m = mod(FCurveNoise{});
  m.influence = 1.5;
  EXPECT_EQ(where(line({m})), "/modifiers/0/influence");
  m.influence.reset();
  m.range = FModifierRange{.start = 5, .end = 1};
  EXPECT_EQ(where(line({m})), "/modifiers/0/range/end");
  m.range = FModifierRange{.start = 1, .end = 5, .blend_in = -1};
  EXPECT_EQ(where(line({m})), "/modifiers/0/range/blend_in");
}

// A random stack of the smooth modifiers (so that central differences of sample() estimate the
// derivative) with influences and blended ranges.
RawFCurve random_smooth_stack(test::Random& rng) {
  std::vector<FCurveModifier> mods;
  const int n = rng.integer(1, 3);
  for (int i = 0; i < n; ++i) {
    FCurveModifier m;
    switch (rng.integer(0, 2)) {
      case 0:
        m.kind = FCurveGenerator{.mode = rng.integer(0, 1) ? GeneratorMode::expanded : GeneratorMode::factorised,
                                 .additive = rng.integer(0, 1) == 1,
                                 .coefficients = {rng.uniform(-2.0, 2.0), rng.uniform(-1.0, 1.0), rng.uniform(-0.3, 0.3),
                                                  rng.uniform(-0.3, 0.3)}};
        break;
      case 1:
        m.kind = FCurveFunction{.function = rng.integer(0, 1) ? BuiltinFunction::sin : BuiltinFunction::cos,
                                .amplitude = rng.uniform(-2.0, 2.0), .phase_multiplier = rng.uniform(-1.0, 1.0),
                                .phase_offset = rng.uniform(-3.0, 3.0), .additive = rng.integer(0, 1) == 1};
        break;
      default:
        m.kind = FCurveEnvelope{.reference = rng.uniform(-1.0, 1.0),
                                .points = {{rng.uniform(-5.0, 0.0), -1, 1}, {rng.uniform(5.0, 15.0), rng.uniform(-3.0, 0.0), 2}}};
    }
    if (rng.integer(0, 1)) m.influence = rng.uniform(0.0, 1.0);
    if (rng.integer(0, 1)) {
      const double a = rng.uniform(-5.0, 5.0);
      m.range = FModifierRange{.start = a, .end = a + rng.uniform(4.0, 12.0), .blend_in = rng.uniform(0.0, 2.0),
                               .blend_out = rng.uniform(0.0, 2.0)};
    }
    mods.push_back(m);
  }
  return line(std::move(mods));
}

TEST(FCurveModifiers, DerivativeMatchesCentralDifferencesOnRandomStacks) {
  test::Random rng(test::seed_for(23));
  SCOPED_TRACE(rng.trace());
  double worst = 0;
  int checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const RawFCurve raw = random_smooth_stack(rng);
    const FCurve c = build(raw);
    // Kinks: keys, range ends and ramp ends, envelope points; stay 0.05 frame away from them.
    std::vector<double> kinks = {0, 10};
    for (const auto& m : raw.modifiers) {
      if (m.range) kinks.insert(kinks.end(), {m.range->start, m.range->end, m.range->start + m.range->blend_in,
                                              m.range->end - m.range->blend_out});
      if (const auto* e = std::get_if<FCurveEnvelope>(&m.kind)) {
        for (const auto& p : e->points) kinks.push_back(p.frame);
      }
    }
    for (int s = 0; s < 20; ++s) {
      const float t = rng.uniform(-8.0f, 18.0f);
      bool near = false;
      for (double k : kinks) near = near || std::abs(t - k) < 0.05;
      if (near) continue;
      constexpr float h = 1.0f / 64;
      const double fd = (double(c.sample(t + h)) - double(c.sample(t - h))) / (2.0 * h);
      const double d = c.derivative(t);
      // Central difference: O(h²)·f‴ (smooth pieces, |f‴| ≲ 10 here) plus float rounding of sample
      // (≈ 1e-6·|value| / h).
      const double scale = 1 + std::abs(d) + std::abs(double(c.sample(t)));
      worst = std::max(worst, std::abs(d - fd) / scale);
      EXPECT_NEAR(d, fd, 2e-3 * scale) << "trial " << trial << " frame " << t;
      ++checked;
    }
  }
  std::printf("[ fmodifier derivative ] %d frames of 60 random stacks: worst |analytic − central difference| %.3g (relative)\n",
              checked, worst);
}

TEST(FCurveModifiers, NeverNaN) {
  test::Random rng(test::seed_for(7));
  SCOPED_TRACE(rng.trace());
  const float frames[] = {0.0f, 3.5f, -1e30f, 1e30f, std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(), 2.1e9f};
  std::vector<RawFCurve> raws;
  raws.push_back(line({mod(FCurveGenerator{.coefficients = {1e30, 1e30, 1e30}}), mod(FCurveNoise{.depth = 3})}));
  raws.push_back(line({mod(FCurveCycles{.after = CycleMode::repeat_offset}), mod(FCurveStepped{.step = 1e-30}),
                       mod(FCurveFunction{.function = BuiltinFunction::tan})}));
  raws.push_back(line({mod(FCurveEnvelope{.default_min = 0, .default_max = 1e-30, .points = {{0, -1e30, 1e30}}})}));
  for (int i = 0; i < 20; ++i) raws.push_back(random_smooth_stack(rng));
  for (const auto& raw : raws) {
    const FCurve c = build(raw);
    for (float t : frames) {
      EXPECT_FALSE(std::isnan(c.sample(t))) << t;
      EXPECT_TRUE(std::isfinite(c.derivative(t))) << t;
      EXPECT_TRUE(std::isfinite(c.second_derivative(t))) << t;
    }
  }
}

}  // namespace
}  // namespace inbetween
