#include "inbetween/timing/distance_time.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "inbetween/timing/ease.hpp"

namespace inbetween {
namespace {

using Curve = DistanceTimeCurve<double>;

TEST(DistanceTime, ZeroOrderKeysAreMetWithLinearPieces) {
  // Texts 004 §3.2.1: frames (0, A), (10, B), (35, C), (60, D) → here as distances 0, 2, 3, 6.
  const std::vector<TimeDistanceKey<double>> keys = {{0, 0}, {10, 2}, {35, 3}, {60, 6}};
  auto c = Curve::from_positions(keys);
  ASSERT_TRUE(c) << c.error().describe();
  for (const auto& k : keys) EXPECT_DOUBLE_EQ((*c)(k.t), k.s);
  // Position continuous, velocity piecewise constant: 0.2, then 0.04, then 0.12 (secants).
  EXPECT_DOUBLE_EQ(c->sample(5).velocity, 0.2);
  EXPECT_DOUBLE_EQ(c->sample(10).velocity, 0.04);  // right limit at a key
  EXPECT_DOUBLE_EQ(c->sample(60).velocity, 0.12);
  EXPECT_DOUBLE_EQ((*c)(-5), 0.0);  // clamped
  EXPECT_TRUE(c->check_monotone());
}

TEST(DistanceTime, FirstOrderKeysMatchPositionAndVelocity) {
  const std::vector<TimeDistanceVelocityKey<double>> keys = {{0, 0, 0}, {0.4, 0.5, 1.5}, {1, 1, 0}};
  auto c = Curve::from_constraints(keys);
  ASSERT_TRUE(c);
  for (const auto& k : keys) {
    EXPECT_NEAR((*c)(k.t), k.s, 1e-15);
    EXPECT_NEAR(c->sample(k.t).velocity, k.v, 1e-14);
  }
  // C¹ at the interior key: left and right velocity agree.
  EXPECT_NEAR(c->sample(0.4 - 1e-9).velocity, c->sample(0.4).velocity, 1e-7);
  // A single interval with v = 0 at both ends is Eq. 3.20.
  const std::vector<TimeDistanceVelocityKey<double>> ends = {{0, 0, 0}, {1, 1, 0}};
  auto cubic = Curve::from_constraints(ends);
  ASSERT_TRUE(cubic);
  const CubicEase<double> eq320;
  for (double t = 0; t <= 1; t += 0.125) EXPECT_NEAR((*cubic)(t), eq320(t), 1e-15);
}

TEST(DistanceTime, ValidationNamesTheKey) {
  const std::vector<TimeDistanceKey<double>> back = {{0, 0}, {1, 1}, {1, 2}};
  auto c = Curve::from_positions(back);
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().code, ErrorCode::KeysNotIncreasing);
  EXPECT_EQ(json_pointer(c.error().location), "/2");
  const std::vector<TimeDistanceKey<double>> one = {{0, 0}};
  EXPECT_EQ(Curve::from_positions(one).error().code, ErrorCode::TooFewPoints);
  const std::vector<TimeDistanceVelocityKey<double>> nan = {{0, 0, 0}, {1, 1, std::nan("")}};
  EXPECT_EQ(json_pointer(Curve::from_constraints(nan).error().location), "/1");
}

TEST(DistanceTime, BackingUpIsReportedWithWhere) {
  // Too much velocity at the middle key makes the Hermite overshoot and come back.
  const std::vector<TimeDistanceVelocityKey<double>> keys = {{0, 0, 0}, {0.5, 0.5, 4}, {1, 1, 0}};
  auto c = Curve::from_constraints(keys);
  ASSERT_TRUE(c);
  const auto b = c->find_backing_up();
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->segment, 0);
  EXPECT_LT(b->min_velocity, 0.0);
  // Where it is: the velocity is negative on (t_begin, t_end) and non-negative just outside.
  EXPECT_LT(c->sample((b->t_begin + b->t_end) / 2).velocity, 0.0);
  EXPECT_NEAR(c->sample(b->t_begin).velocity, 0.0, 1e-12);
  EXPECT_NEAR(c->sample(b->t_end).velocity, 0.0, 1e-12);
  EXPECT_NEAR(c->sample(b->t_min_velocity).velocity, b->min_velocity, 1e-12);
  const auto check = c->check_monotone();
  ASSERT_FALSE(check);
  EXPECT_EQ(check.error().code, ErrorCode::NotMonotone);
  EXPECT_EQ(check.error().where, "segment 0");
}

TEST(DistanceTime, MonotoneRepairKeepsTheKeysAndNeverBacksUp) {
  const std::vector<TimeDistanceVelocityKey<double>> keys = {{0, 0, 0}, {0.5, 0.5, 4}, {0.8, 0.6, -1}, {1, 1, 0}};
  auto c = Curve::from_constraints(keys);
  ASSERT_TRUE(c);
  ASSERT_FALSE(c->check_monotone());
  auto r = c->monotone_repair();
  ASSERT_TRUE(r) << r.error().describe();
  EXPECT_TRUE(r->check_monotone());
  for (const auto& k : keys) EXPECT_NEAR((*r)(k.t), k.s, 1e-15);
  // Dense check independent of find_backing_up: s never decreases.
  double prev = -1;
  for (double t = 0; t <= 1; t += 1.0 / 1024) {
    EXPECT_GE((*r)(t), prev - 1e-15) << t;
    prev = (*r)(t);
  }
  // Keys that themselves go backwards cannot be repaired: the error names the key.
  const std::vector<TimeDistanceKey<double>> down = {{0, 0}, {0.5, 0.7}, {0.7, 0.6}, {1, 1}};
  auto lin = Curve::from_positions(down);
  ASSERT_TRUE(lin);
  EXPECT_EQ(lin->check_monotone().error().where, "segment 1");
  EXPECT_EQ(json_pointer(lin->monotone_repair().error().location), "/2");
}

TEST(DistanceTime, CatmullRomMayOvershootMonotoneCubicDoesNot) {
  // A step-like key set: Catmull-Rom overshoots (backs up after the jump); Fritsch–Carlson does not.
  const std::vector<TimeDistanceKey<double>> keys = {{0, 0}, {0.3, 0}, {0.4, 0.9}, {0.6, 1}, {1, 1}};
  auto cr = Curve::from_positions(keys, PositionInterpolation::CatmullRom);
  auto mc = Curve::from_positions(keys, PositionInterpolation::MonotoneCubic);
  ASSERT_TRUE(cr && mc);
  EXPECT_FALSE(cr->check_monotone());
  EXPECT_TRUE(mc->check_monotone());
  for (const auto& k : keys) EXPECT_NEAR((*mc)(k.t), k.s, 1e-15);
}

TEST(DistanceTime, VelocityCurveFloatingKeepsTheAverage) {
  // User velocity keys (area 0.5 over [0, 1]); floating adds 0.5 everywhere to cover distance 1.
  const std::vector<TimeVelocityKey<double>> keys = {{0, 0}, {0.5, 1}, {1, 0}};
  auto c = Curve::from_velocity_curve(keys, VelocityFit::FloatToKeepAverage);
  ASSERT_TRUE(c);
  EXPECT_NEAR((*c)(1), 1.0, 1e-15);
  EXPECT_NEAR(c->sample(0).velocity, 0.5, 1e-15);  // the keys' velocities moved by +0.5
  EXPECT_NEAR(c->sample(0.5).velocity, 1.5, 1e-15);
  EXPECT_NEAR(c->sample(0.25).velocity, 1.0, 1e-15);  // linear in between
  EXPECT_TRUE(c->check_monotone());
}

TEST(DistanceTime, VelocityCurveFixedKeysAdjustTheInterior) {
  const std::vector<TimeVelocityKey<double>> keys = {{0, 0}, {0.5, 1}, {1, 0}};
  auto c = Curve::from_velocity_curve(keys, VelocityFit::FixKeysAdjustInterior);
  ASSERT_TRUE(c);
  EXPECT_NEAR((*c)(1), 1.0, 1e-15);
  for (const auto& k : keys) EXPECT_NEAR(c->sample(k.t).velocity, k.v, 1e-14) << k.t;
  // Interior bump 6c·τ(1−τ) with c = (1 − 0.5)/1 = 0.5: at t = 0.25 (τ = 1/2) the velocity is
  // the linear 0.5 plus 6·0.5·0.25.
  EXPECT_NEAR(c->sample(0.25).velocity, 0.5 + 0.75, 1e-14);
  // Two keys at rest: exactly the cubic −2t³ + 3t² (Eq. 3.20).
  const std::vector<TimeVelocityKey<double>> rest = {{0, 0}, {1, 0}};
  auto cubic = Curve::from_velocity_curve(rest, VelocityFit::FixKeysAdjustInterior);
  ASSERT_TRUE(cubic);
  for (double t = 0; t <= 1; t += 0.125) EXPECT_NEAR((*cubic)(t), CubicEase<double>{}(t), 1e-15);
  // Fixed velocities that already cover more than the distance force a dip below zero (the spikes
  // and negative velocities of Figure 3.19): reported, not hidden.
  // Velocity 4 everywhere covers 4: c = −3, so v = 4 − 18τ(1 − τ) dips to −0.5 mid-interval.
  const std::vector<TimeVelocityKey<double>> fast = {{0, 4}, {0.5, 4}, {1, 4}};
  auto dip = Curve::from_velocity_curve(fast, VelocityFit::FixKeysAdjustInterior);
  ASSERT_TRUE(dip);
  EXPECT_FALSE(dip->check_monotone());
}

}  // namespace
}  // namespace inbetween
