#include "inbetween/timing/piecewise_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/timing/ease.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

using test::roundtrip_tol;

template <class T>
using Curve = PiecewiseDistanceCurve<T>;

template <class T>
class PiecewiseDistanceTyped : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PiecewiseDistanceTyped, Precisions);

// A constraint tuple read off a polynomial p with derivatives dp, ddp (closed forms).
template <class T, class P, class D, class A>
MotionConstraint<T> tuple_of(T t, P p, D dp, A ddp, bool with_v, bool with_a) {
  MotionConstraint<T> c{t, p(t)};
  if (with_v) c.v = dp(t);
  if (with_a) c.a = ddp(t);
  return c;
}

// Closed forms: Hermite interpolation of degree 3 + (number of given accelerations) reproduces any
// polynomial of that degree exactly (uniqueness of the interpolant).
TYPED_TEST(PiecewiseDistanceTyped, ReproducesPolynomialsOfItsDegree) {
  using T = TypeParam;
  // p(t) = 0.3 + t + t²/2 + t⁵/5 is increasing (p' = 1 + t + t⁴ > 0 for t ≥ 0).
  auto p5 = [](T t) { return T(0.3) + t + t * t / 2 + t * t * t * t * t / 5; };
  auto d5 = [](T t) { return T(1) + t + t * t * t * t; };
  auto a5 = [](T t) { return T(1) + 4 * t * t * t; };
  // q(t) = t + t²/4 + t⁴/8: a quartic, increasing on t ≥ 0.
  auto p4 = [](T t) { return t + t * t / 4 + t * t * t * t / 8; };
  auto d4 = [](T t) { return T(1) + t / 2 + t * t * t / 2; };
  auto a4 = [](T t) { return T(0.5) + T(1.5) * t * t; };
  // r(t) = t + t³: a cubic.
  auto p3 = [](T t) { return t + t * t * t; };
  auto d3 = [](T t) { return T(1) + 3 * t * t; };
  auto a3 = [](T t) { return 6 * t; };
  const T t0 = T(0.25), t1 = T(1.5);
  struct Case {
    const char* name;
    std::vector<MotionConstraint<T>> k;
    std::function<T(T)> p, d, a;
  };
  const std::vector<Case> cases = {
      {"quintic", {tuple_of(t0, p5, d5, a5, true, true), tuple_of(t1, p5, d5, a5, true, true)}, p5, d5, a5},
      {"quartic, acceleration at the start", {tuple_of(t0, p4, d4, a4, true, true), tuple_of(t1, p4, d4, a4, true, false)}, p4, d4, a4},
      {"quartic, acceleration at the end", {tuple_of(t0, p4, d4, a4, true, false), tuple_of(t1, p4, d4, a4, true, true)}, p4, d4, a4},
      {"cubic", {tuple_of(t0, p3, d3, a3, true, false), tuple_of(t1, p3, d3, a3, true, false)}, p3, d3, a3},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    auto curve = Curve<T>::from_constraints(c.k);
    ASSERT_TRUE(curve) << curve.error().describe();
    for (int j = 0; j <= 16; ++j) {
      const T t = t0 + (t1 - t0) * T(j) / T(16);
      const EaseSample<T> s = curve->sample(t);
      // Scale ~10 (p5(1.5) ≈ 3.9, its second derivative ≈ 14.5): 64 ulp of that.
      EXPECT_NEAR(s.s, c.p(t), T(16) * roundtrip_tol<T>) << "t = " << t;
      EXPECT_NEAR(s.velocity, c.d(t), T(16) * roundtrip_tol<T>) << "t = " << t;
      EXPECT_NEAR(s.acceleration, c.a(t), T(16) * roundtrip_tol<T>) << "t = " << t;
    }
  }
}

// Property: random monotone constraint sets (some speeds and accelerations missing) are met
// exactly at every tuple, the curve is C¹ at every tuple and C² where an acceleration is given,
// and a set that is accepted never backs up while a refused one does (checked by dense sampling,
// independently of the Bernstein test).
TYPED_TEST(PiecewiseDistanceTyped, RandomConstraintsAreMetExactly) {
  using T = TypeParam;
  test::Random rng(test::seed_for(1324));
  SCOPED_TRACE(rng.trace());
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = rng.integer(2, 6);
    std::vector<MotionConstraint<T>> k;
    T t = rng.uniform<T>(-2, 2), s = rng.uniform<T>(0, 3);
    for (int i = 0; i < n; ++i) {
      MotionConstraint<T> c{t, s};
      if (rng.integer(0, 3) > 0) c.v = rng.uniform<T>(0, 3);
      if (rng.integer(0, 2) > 0) c.a = rng.uniform<T>(-2, 2);
      k.push_back(c);
      t += rng.uniform<T>(T(0.2), T(2));
      s += rng.uniform<T>(0, 3);
    }
    auto curve = Curve<T>::from_constraints(k);
    // Dense sampling of the speed, as the independent witness.
    const auto segs_min_speed = [&](const Curve<T>& c) {
      T lo = std::numeric_limits<T>::max();
      for (std::size_t i = 0; i + 1 < k.size(); ++i)
        for (int j = 0; j <= 2000; ++j) {
          const T tt = k[i].t + (k[i + 1].t - k[i].t) * T(j) / T(2000);
          lo = std::min(lo, c.sample(tt).velocity);
        }
      return lo;
    };
    if (!curve) {
      ASSERT_EQ(curve.error().code, ErrorCode::NotMonotone) << curve.error().describe();
      ASSERT_EQ(curve.error().location.size(), 1u);
      ++refused;
      continue;
    }
    ++accepted;
    const T scale = std::max(T(1), std::abs(k.back().s));
    const auto segs = curve->segments();
    for (std::size_t i = 0; i < k.size(); ++i) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " tuple " + std::to_string(i));
      const EaseSample<T> at = curve->sample(k[i].t);
      EXPECT_NEAR(at.s, k[i].s, roundtrip_tol<T> * scale);
      // Per-τ derivatives are scaled by 1/h, 1/h² (h ≥ 0.2): allow that.  Measured (seed 1324, 167
      // accepted of 300): relative errors s 2.1e-15 / v 1.9e-14 / a 2.3e-13 in double, 1.1e-6 /
      // 1.2e-5 / 1.9e-4 in float — each below its bound (64, 32·64, 256·64 ulp) by 4–16×.
      if (k[i].v) EXPECT_NEAR(at.velocity, *k[i].v, T(32) * roundtrip_tol<T> * scale);
      if (k[i].a) EXPECT_NEAR(at.acceleration, *k[i].a, T(256) * roundtrip_tol<T> * scale);
      if (i > 0 && i + 1 < k.size()) {
        // Left limit from interval i − 1 at τ = 1.
        const T h = k[i].t - k[i - 1].t;
        const auto& c = segs[i - 1];
        const T left_v = (c[1] + 2 * c[2] + 3 * c[3] + 4 * c[4] + 5 * c[5]) / h;
        const T left_a = (2 * c[2] + 6 * c[3] + 12 * c[4] + 20 * c[5]) / (h * h);
        EXPECT_NEAR(left_v, at.velocity, T(32) * roundtrip_tol<T> * scale);
        if (k[i].a) EXPECT_NEAR(left_a, at.acceleration, T(256) * roundtrip_tol<T> * scale);
      }
    }
    const T lo = segs_min_speed(*curve);
    EXPECT_GE(lo, -T(32) * roundtrip_tol<T> * scale) << "trial " << trial;
  }
  // Both outcomes occur, so both branches were exercised.
  EXPECT_GT(accepted, 30);
  EXPECT_GT(refused, 10);
}

// A refused set really runs backwards: the witness is found by sampling.
TYPED_TEST(PiecewiseDistanceTyped, RefusalNamesTheTupleAndIsReal) {
  using T = TypeParam;
  // Tuple 1 → 2: the object arrives fast at s = 1, must stop at s = 1.1 with a large braking
  // acceleration at tuple 2: a quintic with a0 = 0, a1 = −40 overshoots and comes back.
  const std::vector<MotionConstraint<T>> k = {{0, 0, T(1), std::nullopt},
                                              {1, 1, T(2), T(0)},
                                              {2, T(1.1), T(0), T(-40)}};
  auto c = Curve<T>::from_constraints(k);
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().code, ErrorCode::NotMonotone);
  EXPECT_EQ(json_pointer(c.error().location), "/1");
  EXPECT_NE(c.error().message.find("tuples 1 → 2"), std::string::npos) << c.error().message;
  // The same polynomial, evaluated independently: the speed of the quintic Hermite with
  // p0 = 1, d0 = 2, a0 = 0, p1 = 1.1, d1 = 0, a1 = −40 (h = 1) dips below zero.
  const double c3 = 10 * 0.1 - 6 * 2 - 0 - (0 - (-40)) / 2.0;
  const double c4 = -15 * 0.1 + 8 * 2 + 0 + (0 - 2 * (-40)) / 2.0;
  const double c5 = 6 * 0.1 - 3 * 2 - 0 - (0 - (-40)) / 2.0;
  double lo = 1e9;
  for (int j = 0; j <= 1000; ++j) {
    const double x = j / 1000.0;
    lo = std::min(lo, 2 + 3 * c3 * x * x + 4 * c4 * x * x * x + 5 * c5 * x * x * x * x);
  }
  EXPECT_LT(lo, 0.0);
}

// Issue 21: finite tuples whose interval polynomial overflows (a speed near the type's largest
// value times an interval of 10) are refused at once, naming the tuples.  Before, the backing-up
// search subdivided the infinite/NaN speed hull to its full depth (2^40 pieces) and never returned.
TYPED_TEST(PiecewiseDistanceTyped, OverflowingSpeedIsRefusedNotSearched) {
  using T = TypeParam;
  const T huge = std::numeric_limits<T>::max() / T(2);
  for (const std::vector<MotionConstraint<T>>& k :
       {std::vector<MotionConstraint<T>>{{0, 0, std::nullopt, std::nullopt}, {10, T(0.5), huge, std::nullopt}},
        std::vector<MotionConstraint<T>>{{0, 0, huge, std::nullopt}, {10, T(0.5), T(0), std::nullopt}, {20, 1, std::nullopt, std::nullopt}},
        std::vector<MotionConstraint<T>>{{0, 0, T(0), huge}, {10, 1, T(0), std::nullopt}}}) {
    auto c = Curve<T>::from_constraints(k);
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, ErrorCode::NotFinite) << c.error().message;
    EXPECT_EQ(json_pointer(c.error().location), "/0") << c.error().message;
    EXPECT_NE(c.error().message.find("tuples 0 → 1"), std::string::npos) << c.error().message;
  }
}

// The museum of degenerate constraint sets.
TYPED_TEST(PiecewiseDistanceTyped, Museum) {
  using T = TypeParam;
  using K = std::vector<MotionConstraint<T>>;
  {  // zero speed everywhere and no distance: the object rests
    const K k = {{0, 2, T(0), T(0)}, {5, 2, T(0), T(0)}, {9, 2, T(0), std::nullopt}};
    auto c = Curve<T>::from_constraints(k);
    ASSERT_TRUE(c) << c.error().describe();
    for (T t : {T(0), T(1), T(4.5), T(9)}) {
      EXPECT_EQ(c->sample(t).s, T(2));
      EXPECT_EQ(c->sample(t).velocity, T(0));
    }
  }
  {  // stop-and-go: zero speed at an interior tuple is met and the object never backs up
    const K k = {{0, 0, std::nullopt, std::nullopt}, {1, 1, T(0), T(0)}, {2, 2, std::nullopt, std::nullopt}};
    auto c = Curve<T>::from_constraints(k);
    ASSERT_TRUE(c) << c.error().describe();
    EXPECT_EQ(c->sample(1).velocity, T(0));
  }
  {  // a single tuple: rests at its distance, total evaluation
    const K k = {{3, T(0.5), std::nullopt, std::nullopt}};
    auto c = Curve<T>::from_constraints(k);
    ASSERT_TRUE(c) << c.error().describe();
    EXPECT_EQ((*c)(-100), T(0.5));
    EXPECT_EQ((*c)(std::numeric_limits<T>::quiet_NaN()), T(0.5));
    EXPECT_EQ(c->sample(3).velocity, T(0));
    const K moving = {{3, T(0.5), T(1), std::nullopt}};
    EXPECT_EQ(Curve<T>::from_constraints(moving).error().code, ErrorCode::InvalidArgument);
  }
  {  // no tuple
    EXPECT_EQ(Curve<T>::from_constraints(K{}).error().code, ErrorCode::TooFewPoints);
  }
  {  // equal frames → error naming the second tuple
    const K k = {{0, 0, std::nullopt, std::nullopt}, {1, 1, std::nullopt, std::nullopt}, {1, 2, std::nullopt, std::nullopt}};
    auto c = Curve<T>::from_constraints(k);
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, ErrorCode::KeysNotIncreasing);
    EXPECT_EQ(json_pointer(c.error().location), "/2");
  }
  {  // negative speed, decreasing distance, NaN
    const K neg = {{0, 0, T(-1), std::nullopt}, {1, 1, std::nullopt, std::nullopt}};
    EXPECT_EQ(json_pointer(Curve<T>::from_constraints(neg).error().location), "/0");
    const K dec = {{0, 0, std::nullopt, std::nullopt}, {1, 1, std::nullopt, std::nullopt}, {2, T(0.5), std::nullopt, std::nullopt}};
    auto d = Curve<T>::from_constraints(dec);
    EXPECT_EQ(d.error().code, ErrorCode::NotMonotone);
    EXPECT_EQ(json_pointer(d.error().location), "/2");
    const K nan = {{0, 0, std::nullopt, std::nullopt}, {1, 1, std::nullopt, std::numeric_limits<T>::quiet_NaN()}};
    EXPECT_EQ(Curve<T>::from_constraints(nan).error().code, ErrorCode::NotFinite);
  }
  {  // missing speeds only: estimated, monotone (Fritsch–Butland), no NaN with a flat piece
    const K k = {{0, 0, std::nullopt, std::nullopt}, {1, 1, std::nullopt, std::nullopt}, {2, 1, std::nullopt, std::nullopt},
                 {3, 4, std::nullopt, std::nullopt}};
    auto c = Curve<T>::from_constraints(k);
    ASSERT_TRUE(c) << c.error().describe();
    for (int j = 0; j <= 300; ++j) {
      const EaseSample<T> s = c->sample(T(j) / T(100));
      EXPECT_TRUE(std::isfinite(s.s) && std::isfinite(s.velocity));
    }
    EXPECT_EQ(c->key_speeds()[1], T(0));  // a flat neighbour: zero speed at the key
  }
}

// ------------------------------------------------------------------ acceleration–time curves

// Closed forms: constant acceleration a from speed v0: s = s0 + v0 t + a t²/2; linear acceleration
// (jerk j from a0): s = s0 + v0 t + a0 t²/2 + j t³/6.
TYPED_TEST(PiecewiseDistanceTyped, AccelerationCurvesIntegrateInClosedForm) {
  using T = TypeParam;
  const std::vector<TimeAccelerationKey<T>> constant = {{0, T(2)}, {3, T(7)}};
  auto c = Curve<T>::from_acceleration_curve(constant, {.start_speed = T(0.5), .start_distance = T(1)});
  ASSERT_TRUE(c) << c.error().describe();
  const std::vector<TimeAccelerationKey<T>> linear = {{0, T(2)}, {3, T(-1)}};  // j = −1
  auto l = Curve<T>::from_acceleration_curve(linear, {.shape = AccelerationShape::linear, .start_speed = T(4)});
  ASSERT_TRUE(l) << l.error().describe();
  for (int j = 0; j <= 12; ++j) {
    const T t = T(j) / T(4);
    // Scale: s ≈ 10 at t = 3: 16 × 64 ulp.
    EXPECT_NEAR(c->sample(t).s, T(1) + T(0.5) * t + t * t, T(16) * roundtrip_tol<T>);
    EXPECT_NEAR(c->sample(t).velocity, T(0.5) + 2 * t, T(16) * roundtrip_tol<T>);
    EXPECT_NEAR(c->sample(t).acceleration, T(2), T(16) * roundtrip_tol<T>);
    EXPECT_NEAR(l->sample(t).s, 4 * t + t * t - t * t * t / 6, T(16) * roundtrip_tol<T>);
    EXPECT_NEAR(l->sample(t).velocity, 4 + 2 * t - t * t / 2, T(16) * roundtrip_tol<T>);
    EXPECT_NEAR(l->sample(t).acceleration, 2 - t, T(16) * roundtrip_tol<T>);
  }
}

// Figure 3.16 → 3.17 → 3.18: acceleration acc on [0, t1], 0 on [t1, t2], −dec on [t2, 1] from rest,
// integrated, is the constant-acceleration ease (Eqs. 3.21–3.22 corrected), implemented
// independently in ConstantAccelerationEase.  With end_distance = 1 the accelerations may be given
// in any units (only acc·t1 = dec·(1 − t2) matters): the scale factor recovers v0 = 2/(t2 − t1 + 1).
TYPED_TEST(PiecewiseDistanceTyped, Figure316IsTheConstantAccelerationEase) {
  using T = TypeParam;
  const T t1 = T(0.2), t2 = T(0.7);
  auto ease = ConstantAccelerationEase<T>::make(t1, t2);
  ASSERT_TRUE(ease);
  const T acc = T(1), dec = acc * t1 / (T(1) - t2);  // equal areas: the speed returns to 0
  const std::vector<TimeAccelerationKey<T>> keys = {{0, acc}, {t1, 0}, {t2, -dec}, {1, 0}};
  auto c = Curve<T>::from_acceleration_curve(keys, {.end_distance = T(1)});
  ASSERT_TRUE(c) << c.error().describe();
  for (int j = 0; j <= 40; ++j) {
    const T t = T(j) / T(40);
    EXPECT_NEAR(c->sample(t).s, ease->sample(t).s, T(4) * roundtrip_tol<T>) << "t = " << t;
    EXPECT_NEAR(c->sample(t).velocity, ease->sample(t).velocity, T(4) * roundtrip_tol<T>) << "t = " << t;
  }
  EXPECT_NEAR(c->key_speeds()[1], ease->v0(), T(4) * roundtrip_tol<T>);
}

TYPED_TEST(PiecewiseDistanceTyped, AccelerationMuseum) {
  using T = TypeParam;
  using K = std::vector<TimeAccelerationKey<T>>;
  {  // braking past a stop: the speed would turn negative in interval 1
    const K k = {{0, 0}, {1, T(-1)}, {4, 0}};
    auto c = Curve<T>::from_acceleration_curve(k, {.start_speed = T(2)});
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, ErrorCode::NotMonotone);
    EXPECT_EQ(json_pointer(c.error().location), "/1");
  }
  {  // braking exactly to a stop is fine (speed 0 at the end, never below)
    const K k = {{0, T(-1)}, {2, 0}};
    auto c = Curve<T>::from_acceleration_curve(k, {.start_speed = T(2)});
    ASSERT_TRUE(c) << c.error().describe();
    EXPECT_NEAR(c->sample(2).s, T(2), T(4) * roundtrip_tol<T>);  // v0²/(2a) = 4/2
  }
  {  // zero acceleration from rest: no end distance can be reached
    const K k = {{0, 0}, {1, 0}};
    EXPECT_TRUE(Curve<T>::from_acceleration_curve(k));
    auto c = Curve<T>::from_acceleration_curve(k, {.end_distance = T(1)});
    ASSERT_FALSE(c);
    EXPECT_EQ(json_pointer(c.error().location), "/end_distance");
  }
  {  // equal frames, one key, negative start speed
    EXPECT_EQ(json_pointer(Curve<T>::from_acceleration_curve(K{{0, 1}, {0, 2}}).error().location), "/1");
    EXPECT_EQ(Curve<T>::from_acceleration_curve(K{{0, 1}}).error().code, ErrorCode::TooFewPoints);
    EXPECT_EQ(json_pointer(Curve<T>::from_acceleration_curve(K{{0, 1}, {1, 1}}, {.start_speed = T(-1)}).error().location),
              "/start_speed");
  }
}

}  // namespace
}  // namespace inbetween
