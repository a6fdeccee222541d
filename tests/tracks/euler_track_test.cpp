// Euler-angle tracks in all 24 conventions.  Sources: quat_from_euler of the keys (math module),
// slerp's geodesic property (the shortest path between two rotations has length equal to their
// angle), and closed forms for rotations about one axis.
#include "inbetween/tracks/euler_track.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

// Conversions and a few dozen slerps of unit quaternions: 1e-12 rad.
constexpr double kAngleTol = 1e-12;

EulerKey<double> ekey(double frame, EulerTriple<double> a) {
  EulerKey<double> k;
  k.frame = frame;
  k.angles_rad = a;
  return k;
}

TEST(EulerTrack, BothModesPassThroughKeysInEveryConvention) {
  test::Random rng(test::seed_for(5050));
  SCOPED_TRACE(rng.trace());
  for (const EulerSequence& seq : all_euler_sequences()) {
    SCOPED_TRACE(seq.name());
    std::vector<EulerKey<double>> keys;
    for (int i = 0; i < 5; ++i) {
      keys.push_back(ekey(2.0 * i, {rng.uniform(-3.0, 3.0), rng.uniform(-1.5, 1.5), rng.uniform(-3.0, 3.0)}));
    }
    for (auto mode : {EulerTrackMode::angles, EulerTrackMode::quaternion}) {
      auto tr = build_euler_track(keys, {.sequence = seq, .mode = mode});
      ASSERT_TRUE(tr.has_value());
      for (const auto& k : keys) {
        EXPECT_TRUE(same_rotation(tr->sample(k.frame), quat_from_euler(seq, k.angles_rad), kAngleTol));
        EXPECT_TRUE(same_rotation(quat_from_euler(seq, tr->sample_angles(k.frame)), quat_from_euler(seq, k.angles_rad),
                                  kAngleTol));
      }
    }
  }
}

template <class T>
class EulerTrackTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(EulerTrackTyped, Scalars);

// The same property in float and double.  Tolerance: a key's orientation goes through
// quat_from_euler (three half-angle sin/cos and two quaternion products) on both sides, plus a
// normalisation; 256 ulp of 1 rad (5.7e-14 in double, 3.1e-5 in float).
template <class T>
constexpr T kKeyAngleTol = T(256) * std::numeric_limits<T>::epsilon();

TYPED_TEST(EulerTrackTyped, BothModesPassThroughKeysInEveryConvention) {
  using T = TypeParam;
  test::Random rng(test::seed_for(5054));
  SCOPED_TRACE(rng.trace());
  for (const EulerSequence& seq : all_euler_sequences()) {
    SCOPED_TRACE(seq.name());
    std::vector<EulerKey<T>> keys;
    for (int i = 0; i < 5; ++i) {
      EulerKey<T> k;
      k.frame = T(2 * i);
      k.angles_rad = {rng.uniform(T(-3), T(3)), rng.uniform(T(-1.5), T(1.5)), rng.uniform(T(-3), T(3))};
      keys.push_back(k);
    }
    for (auto mode : {EulerTrackMode::angles, EulerTrackMode::quaternion}) {
      auto tr = build_euler_track(keys, {.sequence = seq, .mode = mode});
      ASSERT_TRUE(tr.has_value());
      for (const auto& k : keys) {
        const Quat<T> want = quat_from_euler(seq, k.angles_rad);
        EXPECT_TRUE(same_rotation(tr->sample(k.frame), want, kKeyAngleTol<T>)) << int(mode);
        EXPECT_TRUE(same_rotation(quat_from_euler(seq, tr->sample_angles(k.frame)), want, kKeyAngleTol<T>)) << int(mode);
        EXPECT_NEAR(norm(tr->sample(k.frame + T(0.5))), T(1), test::few_ulp<T>);
      }
    }
  }
}

TEST(EulerTrack, FilterTakesTheShortWayAcrossTheWrap) {
  // X angle 170° → −170°: filtered, the angle curve moves 20° through 180°; unfiltered, 340° through 0.
  const double d = pi_v<double> / 180;
  const std::vector keys = {ekey(0, {170 * d, 0, 0}), ekey(10, {-170 * d, 0, 0})};
  const EulerSequence xyz{};
  auto filtered = build_euler_track(keys, {.sequence = xyz});
  auto raw = build_euler_track(keys, {.sequence = xyz, .filter = false});
  ASSERT_TRUE(filtered && raw);
  const Vec3d x{1, 0, 0};
  EXPECT_TRUE(same_rotation(filtered->sample(5.0), Quatd::from_axis_angle(x, pi_v<double>), kAngleTol));
  EXPECT_TRUE(same_rotation(raw->sample(5.0), Quatd{}, kAngleTol));
  EXPECT_NEAR(filtered->key_angles()[1].x, 190 * d, 1e-12);
}

double path_length(const EulerTrack<double>& tr, double t0, double t1) {
  double len = 0;
  Quatd prev = tr.sample(t0);
  for (int i = 1; i <= 2000; ++i) {
    const Quatd q = tr.sample(t0 + (t1 - t0) * i / 2000.0);
    len += angle_between(prev, q);
    prev = q;
  }
  return len;
}

TEST(EulerTrack, AngleInterpolationNeverBeatsTheGeodesicAndNeedsTheFilter) {
  test::Random rng(test::seed_for(5051));
  SCOPED_TRACE(rng.trace());
  const EulerSequence xyz{};
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<EulerKey<double>> keys = {
        ekey(0, {rng.uniform(-1.0, 1.0), rng.uniform(-1.4, 1.4), rng.uniform(-1.0, 1.0)}),
        ekey(1, {rng.uniform(-1.0, 1.0), rng.uniform(-1.4, 1.4), rng.uniform(-1.0, 1.0)})};
    for (auto& k : keys) k.tangent = TangentKind::linear;
    auto by_angles = build_euler_track(keys, {.sequence = xyz});
    auto by_quat = build_euler_track(keys, {.sequence = xyz, .mode = EulerTrackMode::quaternion});
    ASSERT_TRUE(by_angles && by_quat);
    const double geodesic = angle_between(by_quat->sample(0.0), by_quat->sample(1.0));
    // Slerp is the geodesic: its sampled path length equals the angle between the keys (the sum
    // of the angles of 2000 steps along a great circle is exact up to rounding).
    // Sum of 2000 angle_between values, each within a few ulp: 2000 · 4e-16 ≈ 1e-12 at worst
    // (measured < 1e-14).
    constexpr double kPathLengthTol = 1e-12;
    EXPECT_NEAR(path_length(*by_quat, 0, 1), geodesic, kPathLengthTol);
    EXPECT_GE(path_length(*by_angles, 0, 1), geodesic - kPathLengthTol);
  }
  // Two nearly equal rotations written with the two different Euler solutions, (a, b, c) and
  // (a + π, π − b, c + π) + small δ: without the filter the angles sweep half a turn and back
  // (a long detour through other orientations); with it the second key is rewritten on the first
  // one's branch and the path is the short one.
  const std::vector<EulerKey<double>> twins = {ekey(0, {0.3, 1.2, -0.4}),
                                               ekey(1, {0.3 + pi_v<double> + 0.02, pi_v<double> - 1.2 - 0.01,
                                                        -0.4 + pi_v<double> - 0.015})};
  auto unfiltered = build_euler_track(twins, {.sequence = xyz, .filter = false});
  auto filtered = build_euler_track(twins, {.sequence = xyz});
  auto geodesic = build_euler_track(twins, {.sequence = xyz, .mode = EulerTrackMode::quaternion});
  ASSERT_TRUE(unfiltered && filtered && geodesic);
  const double g = path_length(*geodesic, 0, 1), f = path_length(*filtered, 0, 1), u = path_length(*unfiltered, 0, 1);
  std::printf("XYZ twin keys: geodesic %.4f rad, filtered angles %.4f rad, unfiltered angles %.4f rad\n", g, f, u);
  EXPECT_LT(g, 0.05);
  EXPECT_LT(f, 2 * g);
  EXPECT_GT(u, 1.0);
}

TEST(EulerTrack, ConstantAxisTurnThroughGimbalLockSideBySide) {
  // A turn at constant speed about one fixed axis, keyed every 0.5 rad as XYZ Euler angles.  About
  // (1, 1, 1)/√3 the pitch reaches 89.97° at 2.09 rad (frame 4.19; SciPy as_euler("XYZ")): the
  // path runs through gimbal lock.
  // Quaternion mode (Bézier spline): keys on one great circle at even spacing give back the exact
  // turn (Catmull-Rom of a linear angle is linear).  Angle mode follows the Euler angles instead.
  const Vec3d axis = Vec3d{1, 1, 1} / std::sqrt(3.0);
  const EulerSequence xyz{};
  std::vector<EulerKey<double>> keys;
  EulerTriple<double> prev{};
  for (int i = 0; i <= 12; ++i) {
    const Quatd q = Quatd::from_axis_angle(axis, 0.5 * i);
    EulerTriple<double> a = euler_from_quat(xyz, q).angles_rad;
    if (i > 0) a = euler_filter(xyz, prev, a);
    prev = a;
    EulerKey<double> k = ekey(i, a);
    k.interpolation = QuatInterpolation::bezier;
    keys.push_back(k);
  }
  auto by_angles = build_euler_track(keys, {.sequence = xyz});
  auto by_quat = build_euler_track(keys, {.sequence = xyz, .mode = EulerTrackMode::quaternion});
  ASSERT_TRUE(by_angles && by_quat);
  double worst_angles = 0, worst_quat = 0, worst_frame = 0;
  for (double f = 0; f <= 12; f += 0.01) {
    const Quatd truth = Quatd::from_axis_angle(axis, 0.5 * f);
    const double ea = angle_between(by_angles->sample(f), truth);
    if (ea > worst_angles) {
      worst_angles = ea;
      worst_frame = f;
    }
    worst_quat = std::max(worst_quat, angle_between(by_quat->sample(f), truth));
  }
  std::printf("turn about (1,1,1) keyed as XYZ Euler every 0.5 rad: quaternion spline error %.2g rad, "
              "Euler-angle interpolation error %.3g rad (at frame %.2f)\n",
              worst_quat, worst_angles, worst_frame);
  EXPECT_LT(worst_quat, 1e-12);
  EXPECT_GT(worst_angles, 1e-2);
}

TEST(EulerTrackBuild, RejectsBadInput) {
  auto r = build_euler_track(std::vector{ekey(0, {0, 0, 0}), ekey(1, {std::nan(""), 0, 0})});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(json_pointer(r.error().location), "/keys/1");
  r = build_euler_track(std::vector{ekey(1, {0, 0, 0}), ekey(1, {0, 0, 0})});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::keys_not_increasing);
  EulerTrackOptions<double> bad;
  bad.sequence.axes = {0, 0, 1};
  EXPECT_FALSE(build_euler_track(std::vector{ekey(0, {0, 0, 0})}, bad).has_value());
}

}  // namespace
}  // namespace inbetween
