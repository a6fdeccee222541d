// Generic keyframed tracks.  Sources: Hermite basis and Catmull-Rom closed forms (texts 000 §2.2,
// 004 §3.1), Kochanek–Bartels (1984) special cases, Fritsch–Carlson monotonicity (plateau), and
// equality with the track's own uncached evaluation for the cursor.
#include "inbetween/tracks/track.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "support/museum_tracks.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
class TrackTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(TrackTest, Scalars);

// A cubic in a handful of operations on values ~10: a few hundred ulp of magnitude 1.
template <class T>
constexpr T kEvalTol = T(512) * std::numeric_limits<T>::epsilon();

template <class V>
TrackKey<V> key(scalar_of<V> f, V v, TangentKind kind = TangentKind::catmull_rom) {
  TrackKey<V> k;
  k.frame = f;
  k.value = v;
  k.tangent = kind;
  return k;
}

TYPED_TEST(TrackTest, UniformCatmullRomMatchesTheClassicFormula) {
  using T = TypeParam;
  // Uniform keys at frames 0..4: on segment 1→2, CR(u) = ½[2p1 + (p2 − p0)u + (2p0 − 5p1 + 4p2 − p3)u²
  // + (−p0 + 3p1 − 3p2 + p3)u³]  (text 000 §2.2).
  const T p[] = {1, 4, 2, 5, 3};
  std::vector<TrackKey<T>> keys;
  for (int i = 0; i < 5; ++i) keys.push_back(key<T>(T(i), p[i]));
  auto tr = build_track(keys);
  ASSERT_TRUE(tr.has_value());
  for (T u = 0; u <= 1; u += T(0.125)) {
    const T expected = T(0.5) * (2 * p[1] + (p[2] - p[0]) * u + (2 * p[0] - 5 * p[1] + 4 * p[2] - p[3]) * u * u +
                                 (-p[0] + 3 * p[1] - 3 * p[2] + p[3]) * u * u * u);
    EXPECT_NEAR(tr->sample(1 + u), expected, kEvalTol<T> * 10);
  }
}

TYPED_TEST(TrackTest, ExplicitHermitePassesThroughKeysWithTheGivenSlopes) {
  using T = TypeParam;
  std::vector<TrackKey<T>> keys;
  const T frames[] = {0, 3, 7};
  const T values[] = {1, -2, 4};
  const T slopes[] = {0.5, -1, 2};
  for (int i = 0; i < 3; ++i) {
    auto k = key<T>(frames[i], values[i], TangentKind::explicit_hermite);
    k.in_tangent = k.out_tangent = slopes[i];
    keys.push_back(k);
  }
  auto tr = build_track(keys);
  ASSERT_TRUE(tr.has_value());
  const T h = std::is_same_v<T, float> ? T(1e-2) : T(1e-5);  // central difference step
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(tr->sample(frames[i]), values[i], kEvalTol<T>);
    if (i > 0 && i < 2) {
      // One-sided second-order differences on each side (the second derivative jumps at a key):
      // error h^2 |f'''|/3 with |f'''| < 10 here, plus rounding eps |f|/h.
      const T t = frames[i];
      const T right = (-3 * tr->sample(t) + 4 * tr->sample(t + h) - tr->sample(t + 2 * h)) / (2 * h);
      const T left = (3 * tr->sample(t) - 4 * tr->sample(t - h) + tr->sample(t - 2 * h)) / (2 * h);
      EXPECT_NEAR(right, slopes[i], T(4) * h * h + T(1e-3));
      EXPECT_NEAR(left, slopes[i], T(4) * h * h + T(1e-3));
    }
  }
}

TYPED_TEST(TrackTest, LinearSteppedAndFlatKinds) {
  using T = TypeParam;
  auto tr = build_track(std::vector<TrackKey<T>>{key<T>(0, 0, TangentKind::linear), key<T>(4, 8, TangentKind::stepped),
                                                 key<T>(6, 1, TangentKind::flat), key<T>(10, 5, TangentKind::flat)});
  ASSERT_TRUE(tr.has_value());
  EXPECT_NEAR(tr->sample(T(1)), T(2), kEvalTol<T>);  // linear ends on both sides of [0, 4] (chord 2/frame)
  EXPECT_NEAR(tr->sample(T(3)), T(6), kEvalTol<T>);
  EXPECT_EQ(tr->sample(T(5.5)), T(8));               // stepped holds
  EXPECT_EQ(tr->sample(T(6)), T(1));
  // Flat–flat segment is the smoothstep: 1 + 4·(3u² − 2u³) at u = ½ → 3.
  EXPECT_NEAR(tr->sample(T(8)), T(3), kEvalTol<T>);
}

TYPED_TEST(TrackTest, KochanekBartelsSpecialCases) {
  using T = TypeParam;
  test::Random rng(test::seed_for(5020));
  SCOPED_TRACE(rng.trace());
  std::vector<TrackKey<T>> cr, tcb0, tense, flat;
  for (int i = 0; i < 6; ++i) {
    const T v = rng.uniform<T>(-3, 3);
    cr.push_back(key<T>(T(2 * i), v));
    tcb0.push_back(key<T>(T(2 * i), v, TangentKind::kochanek_bartels));
    auto k = key<T>(T(2 * i), v, TangentKind::kochanek_bartels);
    k.tension = 1;
    tense.push_back(k);
    flat.push_back(key<T>(T(2 * i), v, TangentKind::flat));
  }
  auto a = build_track(cr), b = build_track(tcb0), c = build_track(tense), d = build_track(flat);
  ASSERT_TRUE(a && b && c && d);
  // Interior keys: with t = c = b = 0 on even spacing TCB is Catmull-Rom; tension 1 is flat.
  for (T f = 2; f <= 8; f += T(0.25)) {
    EXPECT_NEAR(b->sample(f), a->sample(f), kEvalTol<T> * 4) << f;
    EXPECT_NEAR(c->sample(f), d->sample(f), kEvalTol<T> * 4) << f;
  }
}

TYPED_TEST(TrackTest, PlateauNeverOvershootsAndIsFlatAtExtremes) {
  using T = TypeParam;
  test::Random rng(test::seed_for(5021));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<TrackKey<T>> keys;
    T f = 0;
    for (int i = 0; i < 8; ++i) {
      keys.push_back(key<T>(f, rng.uniform<T>(-5, 5), TangentKind::plateau));
      f += rng.uniform<T>(T(0.2), T(5));
    }
    auto tr = build_track(keys);
    ASSERT_TRUE(tr.has_value());
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
      const T lo = std::min(keys[i].value, keys[i + 1].value), hi = std::max(keys[i].value, keys[i + 1].value);
      for (int s = 1; s < 32; ++s) {
        const T t = keys[i].frame + (keys[i + 1].frame - keys[i].frame) * T(s) / 32;
        const T v = tr->sample(t);
        EXPECT_GE(v, lo - kEvalTol<T> * 10);
        EXPECT_LE(v, hi + kEvalTol<T> * 10);
      }
    }
  }
}

TYPED_TEST(TrackTest, ClampedIsFlatNextToAnEqualNeighbour) {
  using T = TypeParam;
  auto tr = build_track(std::vector<TrackKey<T>>{key<T>(0, 0, TangentKind::clamped), key<T>(2, 3, TangentKind::clamped),
                                                 key<T>(4, 3, TangentKind::clamped), key<T>(6, 0, TangentKind::clamped)});
  ASSERT_TRUE(tr.has_value());
  EXPECT_EQ(tr->out_tangents()[1], T(0));
  EXPECT_EQ(tr->in_tangents()[2], T(0));
  for (T f = 2; f <= 4; f += T(0.25)) EXPECT_NEAR(tr->sample(f), T(3), kEvalTol<T>);  // no bump on the plateau
}

TYPED_TEST(TrackTest, ExtendModes) {
  using T = TypeParam;
  const std::vector<TrackKey<T>> keys = {key<T>(0, 1, TangentKind::linear), key<T>(4, 3, TangentKind::linear)};
  auto cyc = build_track(keys, TrackExtend::repeat, TrackExtend::repeat);
  auto off = build_track(keys, TrackExtend::repeat_offset, TrackExtend::repeat_offset);
  auto osc = build_track(keys, TrackExtend::mirror, TrackExtend::mirror);
  auto lin = build_track(keys, TrackExtend::linear, TrackExtend::linear);
  auto con = build_track(keys);
  ASSERT_TRUE(cyc && off && osc && lin && con);
  // Line v = 1 + f/2 on [0, 4].  Closed forms of each extension:
  EXPECT_NEAR(cyc->sample(T(5)), T(1.5), kEvalTol<T>);   // 5 → 1
  EXPECT_NEAR(cyc->sample(T(-1)), T(2.5), kEvalTol<T>);  // −1 → 3
  EXPECT_NEAR(off->sample(T(5)), T(3.5), kEvalTol<T>);   // 1.5 + 2
  EXPECT_NEAR(off->sample(T(-1)), T(0.5), kEvalTol<T>);  // 2.5 − 2
  EXPECT_NEAR(osc->sample(T(5)), T(2.5), kEvalTol<T>);   // mirrored: 5 → 3
  EXPECT_NEAR(osc->sample(T(-1)), T(1.5), kEvalTol<T>);  // mirrored: −1 → 1
  EXPECT_NEAR(osc->sample(T(9)), T(1.5), kEvalTol<T>);   // second copy forwards again: 9 → 1
  EXPECT_NEAR(lin->sample(T(6)), T(4), kEvalTol<T>);
  EXPECT_NEAR(lin->sample(T(-2)), T(0), kEvalTol<T>);
  EXPECT_EQ(con->sample(T(100)), T(3));
  EXPECT_EQ(con->sample(T(-100)), T(1));
}

TYPED_TEST(TrackTest, CursorAndBatchAgreeWithPlainSampling) {
  using T = TypeParam;
  test::Random rng(test::seed_for(5022));
  SCOPED_TRACE(rng.trace());
  std::vector<TrackKey<Vec3<T>>> keys;
  T f = 0;
  for (int i = 0; i < 40; ++i) {
    auto k = key<Vec3<T>>(f, rng.vec3<T>(T(-5), T(5)), TangentKind(rng.integer(1, 7)));
    keys.push_back(k);
    f += rng.uniform<T>(T(0.1), T(3));
  }
  auto tr = build_track(keys, TrackExtend::mirror, TrackExtend::repeat_offset);
  ASSERT_TRUE(tr.has_value());
  std::vector<T> frames;
  for (T t = -20; t < f + 20; t += T(0.37)) frames.push_back(t);            // forwards
  for (T t = f + 5; t > -5; t -= T(0.9)) frames.push_back(t);               // backwards
  for (int i = 0; i < 200; ++i) frames.push_back(rng.uniform<T>(-30, f + 30));  // jumps
  std::vector<Vec3<T>> batch(frames.size());
  TrackCursor cursor, batch_cursor;
  tr->sample(frames, batch, batch_cursor);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Vec3<T> plain = tr->sample(frames[i]);
    EXPECT_EQ(tr->sample(frames[i], cursor), plain) << frames[i];
    EXPECT_EQ(batch[i], plain) << frames[i];
  }
}

// Issue 9, defect 7a: keys 1e-300 apart sampled at frame 1e9 with cycle_offset gave NaN: the cycle
// count 1e9/1e-300 overflows to inf and a component whose per-cycle offset is 0 became 0·inf.
// Closed form: a component with equal first and last values repeats that value whatever the cycle
// count; a component with a non-zero offset grows past T's range (±inf, the documented saturation
// of extension modes, never NaN).
TYPED_TEST(TrackTest, CycleOffsetWithAnOverflowingCycleCountStaysANumber) {
  using T = TypeParam;
  const T gap = sizeof(T) == 4 ? std::numeric_limits<T>::min() : T(1e-300);  // keys this far apart
  const std::vector<TrackKey<Vec3<T>>> keys{key<Vec3<T>>(T(0), Vec3<T>{1, 2, 3}),
                                            key<Vec3<T>>(gap, Vec3<T>{1, 5, 3})};
  auto tr = build_track(keys, TrackExtend::repeat_offset, TrackExtend::repeat_offset);
  ASSERT_TRUE(tr.has_value()) << tr.error().describe();
  for (const T frame : {T(1e9), T(-1e9), std::numeric_limits<T>::max(), -std::numeric_limits<T>::max()}) {
    const Vec3<T> v = tr->sample(frame);
    EXPECT_EQ(v.x, T(1)) << frame;
    EXPECT_EQ(v.z, T(3)) << frame;
    EXPECT_EQ(v.y, frame > 0 ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity()) << frame;
  }
  // A scalar track with equal end values: the offset is 0 and the value stays 7.
  auto flat = build_track(std::vector<TrackKey<T>>{key<T>(T(0), T(7)), key<T>(gap, T(7))},
                          TrackExtend::repeat_offset, TrackExtend::repeat_offset);
  ASSERT_TRUE(flat.has_value());
  EXPECT_EQ(flat->sample(T(1e9)), T(7));
  EXPECT_EQ(flat->sample(T(-1e9)), T(7));
}

TEST(TrackMuseum, EveryExhibitBuildsPassesThroughItsKeysAndStaysFinite) {
  for (const auto& ex : test::museum_track_keys()) {
    SCOPED_TRACE(ex.name);
    for (auto extend : {TrackExtend::constant, TrackExtend::linear, TrackExtend::repeat, TrackExtend::repeat_offset,
                        TrackExtend::mirror}) {
      auto tr = build_track(ex.keys, extend, extend);
      ASSERT_TRUE(tr.has_value()) << tr.error().describe();
      for (const auto& k : ex.keys) EXPECT_EQ(tr->sample(k.frame), k.value);  // exact at keys (u = 0 or 1)
      const double lo = ex.keys.front().frame, hi = ex.keys.back().frame, w = std::max(hi - lo, 1.0);
      TrackCursor cursor;
      for (int i = -300; i <= 600; ++i) {
        const double f = lo + w * i / 300.0;
        const double v = tr->sample(f, cursor);
        EXPECT_TRUE(std::isfinite(v)) << f;
        EXPECT_EQ(v, tr->sample(f)) << f;
      }
      // Contract "never NaN" at the far ends: ±inf acts as ±max (linear extension with a zero
      // tangent was 0·inf, the cycle modes inf − inf).  Steep tangents may overflow to ±inf there.
      constexpr double kMax = std::numeric_limits<double>::max();
      constexpr double kInf = std::numeric_limits<double>::infinity();
      for (double f : {kInf, -kInf, kMax, -kMax}) {
        EXPECT_FALSE(std::isnan(tr->sample(f))) << f;
        EXPECT_FALSE(std::isnan(tr->sample(f, cursor))) << f;
      }
      EXPECT_EQ(tr->sample(kInf), tr->sample(kMax));
      EXPECT_EQ(tr->sample(-kInf), tr->sample(-kMax));
    }
  }
}

TEST(TrackBuild, RejectsBadKeysNamingTheKey) {
  std::vector<TrackKey<double>> keys = {key<double>(0, 0), key<double>(1, 1), key<double>(1, 2)};
  auto r = build_track(keys);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::keys_not_increasing);
  EXPECT_EQ(json_pointer(r.error().location), "/keys/2/frame");
  keys[2].frame = 2;
  keys[1].value = std::numeric_limits<double>::infinity();
  r = build_track(keys);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::not_finite);
  EXPECT_EQ(json_pointer(r.error().location), "/keys/1/value");
  keys[1].value = 0;
  keys[1].tangent = TangentKind::kochanek_bartels;
  keys[1].bias = 2;
  r = build_track(keys);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(json_pointer(r.error().location), "/keys/1/bias");
  EXPECT_TRUE(std::all_of(r.error().location.begin(), r.error().location.end(), is_data_step));  // a document path only
  EXPECT_EQ(json_pointer(build_track(std::vector<TrackKey<double>>{}).error().location), "/keys");
  EXPECT_FALSE(build_track(std::vector<TrackKey<double>>{}).has_value());
  // Finite values whose chord slope overflows: (−1e308 − 1e308) / 1 = −inf at key 0.
  const std::vector<TrackKey<double>> far = {key<double>(0, 1e308), key<double>(1, -1e308), key<double>(2, 1e308)};
  r = build_track(far);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::not_finite);
  EXPECT_EQ(json_pointer(r.error().location), "/keys/0");
}

TEST(TrackBuild, SingleKeyIsConstantEverywhere) {
  auto tr = build_track(std::vector<TrackKey<Vec4f>>{key<Vec4f>(3, Vec4f{0.1f, 0.2f, 0.3f, 1})}, TrackExtend::linear,
                        TrackExtend::mirror);
  ASSERT_TRUE(tr.has_value());
  for (float f : {-1e6f, 0.f, 3.f, 7.5f, 1e6f}) EXPECT_EQ(tr->sample(f), (Vec4f{0.1f, 0.2f, 0.3f, 1}));
}

}  // namespace
}  // namespace inbetween

namespace inbetween {
namespace {
// Issue 12: the track samples through power-form segments built once (and 1/h); an independent
// evaluation of the Hermite basis in long double on the same keys and resolved tangents bounds the
// difference.  Budget (rounding analysis, no fitted number): building a, b, c takes ≤ 4 roundings
// of terms ≤ M = |p₀| + |p₁| + |m₀h| + |m₁h|, Horner ≤ 6 more, and v = (f − t₀)·(1/h) is off by
// ≤ 3 roundings, moving the cubic by ≤ 3ε·|p'(v)| ≤ 3ε·6M: under 32·ε·M all together.
template <class T>
class TrackPowerForm : public ::testing::Test {};
using TrackScalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(TrackPowerForm, TrackScalars);

TYPED_TEST(TrackPowerForm, MatchesTheHermiteBasisInLongDouble) {
  using T = TypeParam;
  using L = long double;
  test::Random rng(test::seed_for(1205));
  SCOPED_TRACE(rng.trace());
  for (int round = 0; round < 20; ++round) {
    std::vector<TrackKey<T>> keys;
    T f = rng.uniform<T>(T(-10), T(10));
    for (int i = 0; i < 12; ++i) {
      TrackKey<T> k;
      k.frame = f;
      k.value = rng.uniform<T>(T(-5), T(5));
      k.tangent = TangentKind(rng.integer(0, 7));
      k.in_tangent = rng.uniform<T>(T(-3), T(3));
      k.out_tangent = rng.uniform<T>(T(-3), T(3));
      keys.push_back(k);
      f += rng.uniform<T>(T(0.01), T(4));
    }
    const auto tr = build_track(keys);
    ASSERT_TRUE(tr.has_value()) << tr.error().describe();
    const auto fr = tr->frames();
    const auto val = tr->values();
    const auto in = tr->in_tangents();
    const auto out = tr->out_tangents();
    TrackCursor cursor;
    for (std::size_t i = 0; i + 1 < fr.size(); ++i) {
      for (int s = 1; s < 16; ++s) {
        const T frame = fr[i] + (fr[i + 1] - fr[i]) * T(s) / T(16);
        if (!(frame > fr[i] && frame < fr[i + 1])) continue;
        const L h = L(fr[i + 1]) - L(fr[i]), v = (L(frame) - L(fr[i])) / h;
        const L m0 = L(out[i]) * h, m1 = L(in[i + 1]) * h;
        const L want = tr->stepped(i) ? L(val[i])
                                      : L(val[i]) * (2 * v * v * v - 3 * v * v + 1) + m0 * (v * v * v - 2 * v * v + v) +
                                            L(val[i + 1]) * (-2 * v * v * v + 3 * v * v) + m1 * (v * v * v - v * v);
        const L scale = std::abs(L(val[i])) + std::abs(L(val[i + 1])) + std::abs(m0) + std::abs(m1);
        const L budget = 32 * L(std::numeric_limits<T>::epsilon()) * scale;
        EXPECT_LE(std::abs(L(tr->sample(frame)) - want), budget) << "segment " << i << " frame " << frame;
        EXPECT_LE(std::abs(L(tr->sample(frame, cursor)) - want), budget) << "cursor, segment " << i;
      }
    }
  }
}
}  // namespace
}  // namespace inbetween
