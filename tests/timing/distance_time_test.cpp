#include "inbetween/timing/distance_time.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "inbetween/timing/ease.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

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
  auto cr = Curve::from_positions(keys, PositionInterpolation::catmull_rom);
  auto mc = Curve::from_positions(keys, PositionInterpolation::monotone_cubic);
  ASSERT_TRUE(cr && mc);
  EXPECT_FALSE(cr->check_monotone());
  EXPECT_TRUE(mc->check_monotone());
  for (const auto& k : keys) EXPECT_NEAR((*mc)(k.t), k.s, 1e-15);
}

TEST(DistanceTime, VelocityCurveFloatingKeepsTheAverage) {
  // User velocity keys (area 0.5 over [0, 1]); floating adds 0.5 everywhere to cover distance 1.
  const std::vector<TimeVelocityKey<double>> keys = {{0, 0}, {0.5, 1}, {1, 0}};
  auto c = Curve::from_velocity_curve(keys, VelocityFit::float_to_keep_average);
  ASSERT_TRUE(c);
  EXPECT_NEAR((*c)(1), 1.0, 1e-15);
  EXPECT_NEAR(c->sample(0).velocity, 0.5, 1e-15);  // the keys' velocities moved by +0.5
  EXPECT_NEAR(c->sample(0.5).velocity, 1.5, 1e-15);
  EXPECT_NEAR(c->sample(0.25).velocity, 1.0, 1e-15);  // linear in between
  EXPECT_TRUE(c->check_monotone());
}

TEST(DistanceTime, VelocityCurveFixedKeysAdjustTheInterior) {
  const std::vector<TimeVelocityKey<double>> keys = {{0, 0}, {0.5, 1}, {1, 0}};
  auto c = Curve::from_velocity_curve(keys, VelocityFit::fix_keys_adjust_interior);
  ASSERT_TRUE(c);
  EXPECT_NEAR((*c)(1), 1.0, 1e-15);
  for (const auto& k : keys) EXPECT_NEAR(c->sample(k.t).velocity, k.v, 1e-14) << k.t;
  // Interior bump 6c·τ(1−τ) with c = (1 − 0.5)/1 = 0.5: at t = 0.25 (τ = 1/2) the velocity is
  // the linear 0.5 plus 6·0.5·0.25.
  EXPECT_NEAR(c->sample(0.25).velocity, 0.5 + 0.75, 1e-14);
  // Two keys at rest: exactly the cubic −2t³ + 3t² (Eq. 3.20).
  const std::vector<TimeVelocityKey<double>> rest = {{0, 0}, {1, 0}};
  auto cubic = Curve::from_velocity_curve(rest, VelocityFit::fix_keys_adjust_interior);
  ASSERT_TRUE(cubic);
  for (double t = 0; t <= 1; t += 0.125) EXPECT_NEAR((*cubic)(t), CubicEase<double>{}(t), 1e-15);
  // Fixed velocities that already cover more than the distance force a dip below zero (the spikes
  // and negative velocities of Figure 3.19): reported, not hidden.
  // Velocity 4 everywhere covers 4: c = −3, so v = 4 − 18τ(1 − τ) dips to −0.5 mid-interval.
  const std::vector<TimeVelocityKey<double>> fast = {{0, 4}, {0.5, 4}, {1, 4}};
  auto dip = Curve::from_velocity_curve(fast, VelocityFit::fix_keys_adjust_interior);
  ASSERT_TRUE(dip);
  EXPECT_FALSE(dip->check_monotone());
}


// ------------------------------------------------- velocity keys: the speed stays between keys

template <class T>
class VelocityKeysTyped : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(VelocityKeysTyped, Precisions);

// The velocity of interval i is v_i + Δv·τ + 6bτ(1 − τ), evaluated from the power form of s (three
// products and sums in the derivative, one scaling by 1/h): a handful of roundings of terms no
// larger than the keys' speeds.  16 ulp of the larger key speed leaves room for that and still
// catches any bump of the old even spread (≥ 1e-3 of the speed in the cases below).
template <class T>
T speed_range_tol(T v0, T v1) {
  return T(16) * test::eps<T> * std::max({std::fabs(v0), std::fabs(v1), T(1e-30)});
}

// Σ h_i(v_i + v_{i+1})/2 and Σ h_i|Δv_i|/6 in double (the room the keys leave, see VelocityFit).
template <class T>
std::pair<double, double> area_and_room(const std::vector<TimeVelocityKey<T>>& k) {
  double area = 0, room = 0;
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    const double h = double(k[i + 1].t) - double(k[i].t);
    area += h * (double(k[i].v) + double(k[i + 1].v)) / 2;
    room += h * std::fabs(double(k[i + 1].v) - double(k[i].v)) / 6;
  }
  return {area, room};
}

// Samples every interval at 33 points (τ = j/32, the last a left limit just before the next key)
// and checks that the speed stays within [min, max] of the interval's two keys.
template <class T>
void expect_speed_between_keys(const DistanceTimeCurve<T>& c, const std::vector<TimeVelocityKey<T>>& k) {
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    const T lo = std::min(k[i].v, k[i + 1].v), hi = std::max(k[i].v, k[i + 1].v);
    const T tol = speed_range_tol(k[i].v, k[i + 1].v);
    for (int j = 0; j <= 32; ++j) {
      T t = k[i].t + (k[i + 1].t - k[i].t) * T(j) / T(32);
      if (j == 32) t = std::nextafter(k[i + 1].t, k[i].t);
      const EaseSample<T> e = c.sample(t);
      ASSERT_TRUE(std::isfinite(e.s) && std::isfinite(e.velocity)) << "interval " << i << " t " << t;
      EXPECT_GE(e.velocity, lo - tol) << "interval " << i << " t " << t;
      EXPECT_LE(e.velocity, hi + tol) << "interval " << i << " t " << t;
    }
  }
}

TYPED_TEST(VelocityKeysTyped, SpeedStaysBetweenNeighbouringKeysOverRandomKeySets) {
  using T = TypeParam;
  test::Random rng(test::seed_for(2408));
  SCOPED_TRACE(rng.trace());
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const int n = rng.integer(2, 7);
    std::vector<TimeVelocityKey<T>> k;
    T t = rng.uniform<T>(T(-50), T(50));
    for (int i = 0; i < n; ++i) {
      // About one key in three repeats the previous speed (the flat pieces users key).
      const T v = i > 0 && rng.integer(0, 2) == 0 ? k.back().v : rng.uniform<T>(T(0), T(3));
      k.push_back({t, v});
      t += rng.uniform<T>(T(0.25), T(20));
    }
    const auto [area, room] = area_and_room(k);
    // Any total the keys can reach without leaving their range: area ± the room (a bit inside it
    // so that float's rounding of the room cannot tip it over).
    const T total = T(area + rng.uniform(-0.999, 0.999) * room);
    auto c = DistanceTimeCurve<T>::from_velocity_curve(k, VelocityFit::fix_keys_adjust_interior, total);
    ASSERT_TRUE(c) << c.error().describe();
    expect_speed_between_keys(*c, k);
    // The ends: 0 at the first key, exactly the total at the last; each key's speed is kept.
    EXPECT_EQ((*c)(k.front().t), T(0));
    EXPECT_EQ((*c)(k.back().t), total);
    for (std::size_t i = 0; i + 1 < k.size(); ++i) EXPECT_NEAR(c->sample(k[i].t).velocity, k[i].v, speed_range_tol(k[i].v, k[i].v));
    // Speeds ≥ 0 that stay between keys cannot back up.
    EXPECT_TRUE(c->check_monotone());
    ++checked;
  }
  EXPECT_EQ(checked, 400);
}

TYPED_TEST(VelocityKeysTyped, TwoEqualKeysGiveAFlatSpeed) {
  using T = TypeParam;
  // tests/data/scenes/plot_speed_forms.json's "velocity": 0, 0.8, 0.8, 0 (fraction per second) at
  // frames 4, 16, 30, 46 and 24 fps → per frame 0, 1/30, 1/30, 0, covering the whole length 1.
  const T v = T(0.8) / T(24);
  const std::vector<TimeVelocityKey<T>> k = {{4, 0}, {16, v}, {30, v}, {46, 0}};
  auto c = DistanceTimeCurve<T>::from_velocity_curve(k, VelocityFit::fix_keys_adjust_interior, T(1));
  ASSERT_TRUE(c) << c.error().describe();
  expect_speed_between_keys(*c, k);
  // Between frames 16 and 30 the speed is the keys' 1/30 per frame, flat (the old even spread gave
  // 1/30 + 6·(1/630)/4 = 0.0357 at frame 23).
  for (T f = 16; f < 30; f += T(0.5)) EXPECT_NEAR(c->sample(f).velocity, v, speed_range_tol(v, v)) << f;
  // Closed form: key lines cover 12v/2 + 14v + 16v/2 = 28v = 14/15; missing 1/15; room (12 + 16)v/6
  // = 7/45; share 3/7; ramp bumps b = (3/7)·v/6 = 1/420.  s(16) = 12(v/2 + b) = 8/35; the ramp's
  // middle speed v/2 + 6b/4 = 1/60 + 1/280.
  const double tol = 64 * double(test::eps<T>);
  EXPECT_NEAR(double((*c)(16)), 8.0 / 35, tol);
  EXPECT_NEAR(double((*c)(30)), 8.0 / 35 + 14.0 / 30, tol);
  EXPECT_EQ((*c)(46), T(1));
  EXPECT_NEAR(double(c->sample(10).velocity), 1.0 / 60 + 1.0 / 280, tol);
  EXPECT_NEAR(double(c->sample(38).velocity), 1.0 / 60 + 1.0 / 280, tol);
  // Beyond the room (total 1.2: missing 4/15 > 7/45) the rest, 1/9, is spread evenly over the 42
  // frames as the texts do: the flat piece gets 6·(1/378)·τ(1 − τ), 1/30 + 1/252 at frame 23.
  auto over = DistanceTimeCurve<T>::from_velocity_curve(k, VelocityFit::fix_keys_adjust_interior, T(1.2));
  ASSERT_TRUE(over);
  EXPECT_NEAR(double(over->sample(23).velocity), 1.0 / 30 + 1.0 / 252, tol);
  EXPECT_EQ((*over)(46), T(1.2));
}

TYPED_TEST(VelocityKeysTyped, Museum) {
  using T = TypeParam;
  using K = std::vector<TimeVelocityKey<T>>;
  {  // a single key: too few, named
    auto c = DistanceTimeCurve<T>::from_velocity_curve(K{{3, 1}}, VelocityFit::fix_keys_adjust_interior);
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, ErrorCode::TooFewPoints);
  }
  {  // zero speeds and no distance: the object rests, speed exactly 0
    auto c = DistanceTimeCurve<T>::from_velocity_curve(K{{0, 0}, {5, 0}, {9, 0}}, VelocityFit::fix_keys_adjust_interior, T(0));
    ASSERT_TRUE(c);
    for (T t : {T(0), T(2), T(5), T(7.5), T(9)}) {
      EXPECT_EQ(c->sample(t).s, T(0));
      EXPECT_EQ(c->sample(t).velocity, T(0));
    }
  }
  {  // zero speeds that must cover a distance: no room, the texts' Eq. 3.20 on each interval
    auto c = DistanceTimeCurve<T>::from_velocity_curve(K{{0, 0}, {1, 0}}, VelocityFit::fix_keys_adjust_interior, T(1));
    ASSERT_TRUE(c);
    for (T t = 0; t <= 1; t += T(0.125)) EXPECT_NEAR((*c)(t), CubicEase<T>{}(t), test::roundtrip_tol<T>);
  }
  {  // huge frame numbers (2^40 in double, 2^20 in float: keys 24 frames apart are exact there)
    const T base = std::is_same_v<T, double> ? T(1099511627776.0) : T(1048576);
    const K k = {{base, 0}, {base + 24, 2}, {base + 48, 2}, {base + 96, 1}};
    const auto [area, room] = area_and_room(k);
    const T total = T(area + 0.5 * room);
    auto c = DistanceTimeCurve<T>::from_velocity_curve(k, VelocityFit::fix_keys_adjust_interior, total);
    ASSERT_TRUE(c) << c.error().describe();
    expect_speed_between_keys(*c, k);
    EXPECT_EQ((*c)(base + 96), total);
    EXPECT_EQ((*c)(std::numeric_limits<T>::quiet_NaN()), T(0));  // NaN reads as the start
  }
  {  // finite speeds whose area overflows: an error, never a NaN curve
    const T big = std::numeric_limits<T>::max() / T(4);
    auto c = DistanceTimeCurve<T>::from_velocity_curve(K{{0, big}, {100, big}}, VelocityFit::fix_keys_adjust_interior);
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, ErrorCode::NotFinite);
  }
  {  // a NaN or infinite key: named
    auto c = DistanceTimeCurve<T>::from_velocity_curve(K{{0, 0}, {1, std::numeric_limits<T>::infinity()}},
                                                       VelocityFit::fix_keys_adjust_interior);
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, ErrorCode::NotFinite);
    EXPECT_EQ(json_pointer(c.error().location), "/1");
  }
}

}  // namespace
}  // namespace inbetween
