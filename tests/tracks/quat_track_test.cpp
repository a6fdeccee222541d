// Orientation tracks.  Sources: the errata's closed form (with k = 1/3 the Bézier quaternion spline
// of keys about one axis is Catmull-Rom on the angle, checked against Track<double>'s
// catmull_rom), slerp's closed form for rotations about one axis, and measured one-sided angular
// velocities at the keys.
#include "inbetween/tracks/quat_track.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/museum.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

using Q = Quatd;
const Vec3d kZ{0, 0, 1};

// Rotation-angle agreement for results of a few dozen slerps (each a few ulp): 1e-12 rad.
constexpr double kAngleTol = 1e-12;

QuatKey<double> qkey(double frame, const Q& q, QuatInterpolation mode = QuatInterpolation::bezier) {
  QuatKey<double> k;
  k.frame = frame;
  k.value = q;
  k.interpolation = mode;
  return k;
}

// Signed rotation angle about z of a quaternion whose axis is z (continuous branch near `near`).
double z_angle(const Q& q, double near) {
  double a = 2 * std::atan2(q.z, q.w);
  while (a - near > pi_v<double>) a -= 2 * pi_v<double>;
  while (a - near < -pi_v<double>) a += 2 * pi_v<double>;
  return a;
}

TEST(QuatTrack, OneAxisBezierIsCatmullRomOnTheAngle) {
  test::Random rng(test::seed_for(5030));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 20; ++trial) {
    const bool uniform = trial % 2 == 0;
    std::vector<QuatKey<double>> qkeys;
    std::vector<TrackKey<double>> akeys;
    double frame = 0, angle = rng.uniform(-1.0, 1.0);
    for (int i = 0; i < 7; ++i) {
      qkeys.push_back(qkey(frame, Q::from_axis_angle(kZ, angle)));
      TrackKey<double> a;
      a.frame = frame;
      a.value = angle;
      akeys.push_back(a);
      frame += uniform ? 1.0 : rng.uniform(0.3, 3.0);
      angle += rng.uniform(-2.0, 2.0);  // successive keys < 180° apart: the short way is the keyed way
    }
    auto qt = build_quat_track(qkeys);
    auto at = build_track(akeys);
    ASSERT_TRUE(qt && at);
    for (double f = 0; f <= qkeys.back().frame; f += 0.01) {
      const double expected = at->sample(f);
      // measured worst 1.8e-15 (angles up to ~10 rad)
      EXPECT_NEAR(z_angle(qt->sample(f), expected), expected, kAngleTol) << "frame " << f;
    }
  }
}

TEST(QuatTrack, PassesThroughKeysWithUnitNormInEveryMode) {
  test::Random rng(test::seed_for(5031));
  SCOPED_TRACE(rng.trace());
  for (auto mode : {QuatInterpolation::step, QuatInterpolation::slerp, QuatInterpolation::bezier,
                    QuatInterpolation::squad, QuatInterpolation::gltf_cubic}) {
    std::vector<QuatKey<double>> keys;
    std::vector<QuatKeyTangents<double>> tangents;
    for (int i = 0; i < 8; ++i) {
      keys.push_back(qkey(i * 1.5, rng.rotation() * rng.uniform(0.5, 2.0), mode));  // not unit on input
      const Q t = Q::from_wxyz(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.1, 0.2);
      tangents.push_back({t, t});
    }
    auto tr = build_quat_track(keys, tangents);
    ASSERT_TRUE(tr.has_value());
    for (std::size_t i = 0; i < keys.size(); ++i) {
      EXPECT_TRUE(same_rotation(tr->sample(keys[i].frame), normalized(keys[i].value), kAngleTol)) << int(mode);
    }
    for (double f = -1; f < 12; f += 0.013) EXPECT_NEAR(norm(tr->sample(f)), 1.0, test::few_ulp<double>) << f;
  }
}

// Angular velocity (rad/frame, world frame) from q(t) to q(t + h): 2·log(q(t+h) q(t)⁻¹)/h.
Vec3d angular_velocity(const QuatTrack<double>& tr, double t, double h) {
  Q d = tr.sample(t + h) * conjugate(tr.sample(t));
  if (d.w < 0) d = -d;
  return log(d).vec() * (2 / h);
}

TEST(QuatTrack, BezierAngularVelocityIsContinuousAtKeys) {
  test::Random rng(test::seed_for(5032));
  SCOPED_TRACE(rng.trace());
  double worst_bezier = 0, worst_slerp_min = 1e9;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<QuatKey<double>> bez, lin;
    double f = 0;
    Q q = rng.rotation();
    for (int i = 0; i < 6; ++i) {
      bez.push_back(qkey(f, q));
      lin.push_back(qkey(f, q, QuatInterpolation::slerp));
      f += rng.uniform(0.5, 3.0);  // uneven spacing: the time-aware control points keep C¹ in time
      q = normalized(Q::from_axis_angle(rng.unit_vec3(), rng.uniform(0.3, 1.2)) * q);
    }
    auto b = build_quat_track(bez);
    auto l = build_quat_track(lin);
    ASSERT_TRUE(b && l);
    const double h = 1e-4;
    for (std::size_t i = 1; i + 1 < bez.size(); ++i) {
      const double t = bez[i].frame;
      // Richardson extrapolation of the one-sided differences removes their O(h) term.
      const Vec3d left = angular_velocity(*b, t - h / 2, h / 2) * 2.0 - angular_velocity(*b, t - h, h);
      const Vec3d right = angular_velocity(*b, t, h / 2) * 2.0 - angular_velocity(*b, t, h);
      worst_bezier = std::max(worst_bezier, norm(right - left) / norm(right));
      const Vec3d ll = angular_velocity(*l, t - h, h), lr = angular_velocity(*l, t, h);
      worst_slerp_min = std::min(worst_slerp_min, norm(lr - ll) / norm(lr));
    }
  }
  // Extrapolated one-sided differences with h = 1e-4 frame: O(h²·|ω''|/|ω|) ≈ 1e-8·100 plus
  // rounding ~1e-16/1e-4.  Piecewise slerp, for contrast, jumps by a sizeable fraction at every key.
  EXPECT_LT(worst_bezier, 1e-5);
  EXPECT_GT(worst_slerp_min, 1e-2);
  std::printf("relative angular-velocity jump at keys: bezier max %.3g, slerp min %.3g\n", worst_bezier,
              worst_slerp_min);
}

TEST(QuatTrack, NoFlipsWhenNeighbouringKeysHaveOppositeSigns) {
  test::Random rng(test::seed_for(5033));
  SCOPED_TRACE(rng.trace());
  for (auto mode : {QuatInterpolation::slerp, QuatInterpolation::bezier, QuatInterpolation::squad}) {
    std::vector<QuatKey<double>> keys, flipped;
    Q q = rng.rotation();
    for (int i = 0; i < 10; ++i) {
      keys.push_back(qkey(i, q, mode));
      flipped.push_back(qkey(i, i % 2 ? -q : q, mode));  // every other key with the other sign
      q = normalized(Q::from_axis_angle(rng.unit_vec3(), rng.uniform(0.2, 1.0)) * q);
    }
    auto a = build_quat_track(keys), b = build_quat_track(flipped);
    ASSERT_TRUE(a && b);
    Q prev = b->sample(0.0);
    for (double f = 0.01; f <= 9; f += 0.01) {
      const Q s = b->sample(f);
      EXPECT_TRUE(same_rotation(s, a->sample(f), 1e-12)) << f;
      // Steps of 0.01 frame at < 1.2 rad/frame (plus the spline's overshoot) never exceed 0.05 rad.
      EXPECT_LT(angle_between(prev, s), 0.05) << f;
      prev = s;
    }
  }
}

TEST(QuatTrack, LongWayKeyTurnsTheOtherWay) {
  auto k1 = qkey(1, Q::from_axis_angle(kZ, pi_v<double> / 2), QuatInterpolation::slerp);
  k1.long_way = true;
  auto tr = build_quat_track(std::vector{qkey(0, Q{}, QuatInterpolation::slerp), k1});
  ASSERT_TRUE(tr.has_value());
  // 0 → +90° the long way is 0 → −270°: the midpoint is −135° about z.
  EXPECT_TRUE(same_rotation(tr->sample(0.5), Q::from_axis_angle(kZ, -3 * pi_v<double> / 4), kAngleTol));
}

TEST(QuatTrack, DyadicEvaluationMatchesDeCasteljau) {
  test::Random rng(test::seed_for(5034));
  SCOPED_TRACE(rng.trace());
  std::vector<QuatKey<double>> keys;
  for (int i = 0; i < 5; ++i) keys.push_back(qkey(i, rng.rotation()));
  auto tr = build_quat_track(keys);
  ASSERT_TRUE(tr.has_value());
  for (std::size_t seg = 0; seg < 4; ++seg) {
    for (int m : {1, 2, 3, 5, 8}) {
      for (std::uint64_t j = 0; j <= (std::uint64_t(1) << m); ++j) {
        const double u = double(j) / double(std::uint64_t(1) << m);
        EXPECT_TRUE(same_rotation(tr->bezier_dyadic(seg, j, m), tr->bezier(seg, u), 1e-13)) << seg << " " << j << "/" << m;
      }
    }
  }
}

// build_quat_track computes Bézier/squad control points only at keys of Bézier or squad segments
// (issue 20: a BVH clip's 140 000 slerp keys never read them).  A slerp-only track must sample
// exactly as before: each segment the math module's slerp of its two keys, to the bit; and the
// Bézier and squad segments of a mixed track exactly as in a track where every key has them.
bool same_bits(const Q& a, const Q& b) { return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z; }

TEST(QuatTrack, ControlPointsOnlyWhereUsedChangeNoSample) {
  test::Random rng(test::seed_for(5036));
  SCOPED_TRACE(rng.trace());
  constexpr int kKeys = 12;
  std::vector<Q> values;
  std::vector<double> frames;
  double frame = 0;
  for (int i = 0; i < kKeys; ++i) {
    values.push_back(rng.rotation());
    frames.push_back(frame);
    frame += rng.uniform(0.3, 3.0);
  }
  auto keys_with = [&](auto mode_of) {
    std::vector<QuatKey<double>> keys;
    for (int i = 0; i < kKeys; ++i) keys.push_back(qkey(frames[std::size_t(i)], values[std::size_t(i)], mode_of(i)));
    return keys;
  };
  auto all = [](QuatInterpolation m) { return [m](int) { return m; }; };
  auto slerp_only = build_quat_track(keys_with(all(QuatInterpolation::slerp)));
  auto all_bezier = build_quat_track(keys_with(all(QuatInterpolation::bezier)));
  auto all_squad = build_quat_track(keys_with(all(QuatInterpolation::squad)));
  // Segments 0-1 and 6 Bézier, 3-4 squad, 9 step, the rest slerp.
  auto mixed_mode = [](int i) {
    if (i <= 1 || i == 6) return QuatInterpolation::bezier;
    if (i == 3 || i == 4) return QuatInterpolation::squad;
    return i == 9 ? QuatInterpolation::step : QuatInterpolation::slerp;
  };
  auto mixed = build_quat_track(keys_with(mixed_mode));
  ASSERT_TRUE(slerp_only && all_bezier && all_squad && mixed);
  const auto keys = slerp_only->keys();
  // A track without Bézier and squad keys stores no control points: they read as the keys.
  for (std::size_t i = 0; i < keys.size(); ++i) {
    EXPECT_TRUE(same_bits(slerp_only->control_after(i), keys[i]) && same_bits(slerp_only->control_before(i), keys[i])) << i;
  }
  int compared = 0;
  for (std::size_t seg = 0; seg + 1 < std::size_t(kKeys); ++seg) {
    for (int j = 1; j < 16; ++j) {  // inside the segment: the keys themselves are returned as they are
      const double u = j / 16.0;
      const double f = frames[seg] + u * (frames[seg + 1] - frames[seg]);
      const double uu = std::clamp((f - frames[seg]) / (frames[seg + 1] - frames[seg]), 0.0, 1.0);  // as sample() computes it
      const Q want_slerp = slerp(keys[seg], keys[seg + 1], uu, SlerpOptions{.path = RotationPath::as_given});
      EXPECT_TRUE(same_bits(slerp_only->sample(f), want_slerp)) << "slerp segment " << seg << " u " << u;
      const QuatInterpolation m = mixed_mode(int(seg));
      const Q want = m == QuatInterpolation::bezier  ? all_bezier->sample(f)
                     : m == QuatInterpolation::squad ? all_squad->sample(f)
                     : m == QuatInterpolation::step  ? keys[seg]
                                                     : want_slerp;
      EXPECT_TRUE(same_bits(mixed->sample(f), want)) << "mixed segment " << seg << " u " << u;
      ++compared;
    }
    // The control points a Bézier segment reads are the all-Bézier track's, bit for bit.
    if (mixed_mode(int(seg)) == QuatInterpolation::bezier) {
      EXPECT_TRUE(same_bits(mixed->control_after(seg), all_bezier->control_after(seg))) << seg;
      EXPECT_TRUE(same_bits(mixed->control_before(seg + 1), all_bezier->control_before(seg + 1))) << seg;
    }
  }
  EXPECT_EQ(compared, 15 * (kKeys - 1));
}

// sample() without a cursor first tries the segment at the frame's proportion of the keyed range
// (right at once for evenly spaced keys) and checks it; the segment must always be the one a
// linear search finds (frames[i] ≤ f < frames[i + 1]), for even and uneven keys, at the keys
// themselves and between them.
TEST(QuatTrack, SegmentLookupMatchesLinearSearch) {
  test::Random rng(test::seed_for(5037));
  SCOPED_TRACE(rng.trace());
  for (const bool even : {true, false}) {
    std::vector<QuatKey<double>> keys;
    double frame = 10;
    for (int i = 0; i < 300; ++i) {
      keys.push_back(qkey(frame, rng.rotation(), QuatInterpolation::slerp));
      frame += even ? 0.5 : rng.uniform(0.01, 2.0);
    }
    auto tr = build_quat_track(keys);
    ASSERT_TRUE(tr.has_value());
    const auto f = tr->frames();
    const auto q = tr->keys();
    auto reference = [&](double x) {
      if (x <= f.front()) return q.front();
      if (x >= f.back()) return q.back();
      std::size_t i = 0;
      while (!(f[i] <= x && x < f[i + 1])) ++i;
      const double u = std::clamp((x - f[i]) / (f[i + 1] - f[i]), 0.0, 1.0);
      return slerp(q[i], q[i + 1], u, SlerpOptions{.path = RotationPath::as_given});
    };
    std::vector<double> probes(f.begin(), f.end());
    for (std::size_t i = 0; i + 1 < f.size(); ++i) {
      probes.push_back(0.5 * (f[i] + f[i + 1]));
      probes.push_back(std::nextafter(f[i + 1], 0.0));
    }
    for (int r = 0; r < 2000; ++r) probes.push_back(rng.uniform(f.front() - 1, f.back() + 1));
    for (double x : probes) EXPECT_TRUE(same_bits(tr->sample(x), reference(x))) << (even ? "even" : "uneven") << " frame " << x;
  }
}

TEST(QuatTrack, SlerpSegmentsHaveConstantSpeedOnMuseumPairs) {
  for (const auto& ex : test::museum_quat_pairs<double>()) {
    SCOPED_TRACE(ex.name);
    auto tr = build_quat_track(std::vector{qkey(0, ex.a, QuatInterpolation::slerp), qkey(1, ex.b, QuatInterpolation::slerp)});
    ASSERT_TRUE(tr.has_value());
    const double total = angle_between(ex.a, ex.b);
    for (double u = 0; u <= 1; u += 0.125) {
      const Q s = tr->sample(u);
      EXPECT_NEAR(norm(s), 1.0, test::few_ulp<double>);
      // slerp: angle grows linearly (Eq. 3.29); measured worst < 1e-15 over the museum pairs
      EXPECT_NEAR(angle_between(ex.a, s), u * total, kAngleTol);
    }
  }
}

// A key is what a motion-capture clip stores per frame and joint: the glTF tangents live beside
// the keys (QuatKeyTangents), so a key is its frame, quaternion and two flags.
static_assert(sizeof(QuatKey<double>) == 48, "QuatKey<double>: frame, value, interpolation, long_way");
static_assert(sizeof(QuatKey<float>) == 24, "QuatKey<float>: frame, value, interpolation, long_way");

TEST(QuatTrack, GltfCubicIsNormalisedHermite) {
  auto a = qkey(0, Q{}, QuatInterpolation::gltf_cubic);
  auto b = qkey(2, Q::from_axis_angle(Vec3d{1, 0, 0}, 1.0), QuatInterpolation::gltf_cubic);
  const std::vector<QuatKeyTangents<double>> tangents = {{.out = Q::from_wxyz(0, 0.2, 0, 0)},
                                                        {.in = Q::from_wxyz(0, 0.1, 0.1, 0)}};
  auto tr = build_quat_track(std::vector{a, b}, tangents);
  ASSERT_TRUE(tr.has_value());
  // u = ½: h00 = h01 = ½, h10 = ⅛, h11 = −⅛, frame step 2 (glTF's tangent scaling by the interval).
  const Q expected =
      normalized(a.value * 0.5 + tangents[0].out * (0.125 * 2) + b.value * 0.5 + tangents[1].in * (-0.125 * 2));
  EXPECT_TRUE(same_rotation(tr->sample(1.0), expected, kAngleTol));
  // Tangents are none or one per key.
  auto wrong = build_quat_track(std::vector{a, b}, std::vector{tangents[0]});
  ASSERT_FALSE(wrong.has_value());
  EXPECT_EQ(wrong.error().code, ErrorCode::WrongArity);
  EXPECT_EQ(json_pointer(wrong.error().location), "/tangents");
}

template <class T>
class QuatTrackTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(QuatTrackTyped, Scalars);

TYPED_TEST(QuatTrackTyped, EveryModeIsUnitAndThroughKeysWithoutFlips) {
  using T = TypeParam;
  // A few dozen slerps of unit quaternions: a few hundred ulp of angle.
  const T angle_tol = T(256) * std::numeric_limits<T>::epsilon();
  test::Random rng(test::seed_for(5035));
  SCOPED_TRACE(rng.trace());
  for (auto mode : {QuatInterpolation::slerp, QuatInterpolation::bezier, QuatInterpolation::squad}) {
    std::vector<QuatKey<T>> keys;
    Quat<T> q = rng.rotation<T>();
    for (int i = 0; i < 8; ++i) {
      QuatKey<T> k;
      k.frame = T(i) * T(1.5);
      k.value = i % 3 == 1 ? -q : q;
      k.interpolation = mode;
      keys.push_back(k);
      q = normalized(Quat<T>::from_axis_angle(rng.unit_vec3<T>(), rng.uniform<T>(T(0.2), T(1))) * q);
    }
    auto tr = build_quat_track(keys);
    ASSERT_TRUE(tr.has_value());
    for (const auto& k : keys) EXPECT_TRUE(same_rotation(tr->sample(k.frame), k.value, angle_tol));
    Quat<T> prev = tr->sample(T(0));
    for (T f = 0; f < T(11); f += T(0.01)) {
      const Quat<T> s = tr->sample(f);
      EXPECT_NEAR(norm(s), T(1), test::few_ulp<T>);
      EXPECT_LT(angle_between(prev, s), T(0.05));  // 0.01 frame at < 1 rad per 1.5 frames (+ overshoot)
      prev = s;
    }
  }
}

TEST(QuatTrackBuild, RejectsBadKeys) {
  auto r = build_quat_track(std::vector{qkey(0, Q{}), qkey(1, Q::from_wxyz(0, 0, 0, 0))});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(json_pointer(r.error().location), "/keys/1/value");
  r = build_quat_track(std::vector{qkey(0, Q{}), qkey(0, Q{})});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::KeysNotIncreasing);
  r = build_quat_track(std::vector{qkey(0, Q::from_wxyz(std::nan(""), 0, 0, 0))});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::NotFinite);
  EXPECT_FALSE(build_quat_track(std::vector<QuatKey<double>>{}).has_value());
}

}  // namespace
}  // namespace inbetween
