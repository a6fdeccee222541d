// The tracks runtime (runtime/rig_clip.hpp): a RigClip compiled from per-joint T+R+S tracks agrees
// with the scalar per-track API (Track::sample, QuatTrack::sample — the reference) to the named
// tolerances rig_runtime_vec_tolerance and rig_runtime_rotation_tolerance, over seeded random rigs
// of every Vec3 tangent kind (stepped included) and step/slerp rotations, played forwards,
// backwards, with jumps and outside the keys, in float and double; unsupported input is refused
// with its place.
#include "inbetween/tracks/runtime/rig_clip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "support/random.hpp"

namespace inbetween {
namespace {

template <class T>
class RigClipTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(RigClipTyped, Scalars);

// Largest absolute component.
template <class T>
T max_abs(const Vec3<T>& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

template <class T>
struct Rig {
  std::vector<Track<Vec3<T>>> translations, scales;
  std::vector<QuatTrack<T>> rotations;
};

template <class T>
Rig<T> random_rig(test::Random& rng, int joints) {
  Rig<T> rig;
  for (int j = 0; j < joints; ++j) {
    const int n = rng.integer(1, 12);
    std::vector<TrackKey<Vec3<T>>> tk, sk;
    std::vector<QuatKey<T>> rk;
    T f = rng.uniform<T>(T(-3), T(3));
    for (int k = 0; k < n; ++k) {
      TrackKey<Vec3<T>> t;
      t.frame = f;
      t.value = rng.vec3<T>(T(-5), T(5));
      t.tangent = TangentKind(rng.integer(0, 7));  // every kind, explicit Hermite and stepped included
      t.in_tangent = rng.vec3<T>(T(-2), T(2));
      t.out_tangent = rng.vec3<T>(T(-2), T(2));
      t.tension = rng.uniform<T>(T(-1), T(1));
      tk.push_back(t);
      TrackKey<Vec3<T>> s = t;
      s.value = rng.vec3<T>(T(0.5), T(2));
      sk.push_back(s);
      QuatKey<T> r;
      r.frame = f;
      r.value = rng.rotation<T>();
      r.interpolation = rng.integer(0, 3) == 0 ? QuatInterpolation::step : QuatInterpolation::slerp;
      rk.push_back(r);
      f += rng.uniform<T>(T(0.2), T(3));
    }
    rig.translations.push_back(*build_track(tk));
    rig.scales.push_back(*build_track(sk));
    rig.rotations.push_back(*build_quat_track(rk));
  }
  return rig;
}

// Largest |value| + |slope|·h over a track's keys and segments: the scale of the Vec3 tolerance.
template <class T>
T magnitude(const Track<Vec3<T>>& tr) {
  T m = T(1);
  const auto f = tr.frames();
  for (std::size_t i = 0; i < f.size(); ++i) {
    const T h = i + 1 < f.size() ? f[i + 1] - f[i] : T(1);
    const T hp = i > 0 ? f[i] - f[i - 1] : T(1);
    m = std::max({m, max_abs(tr.values()[i]) + max_abs(tr.out_tangents()[i]) * h + max_abs(tr.in_tangents()[i]) * hp});
  }
  return m;
}

TYPED_TEST(RigClipTyped, AgreesWithTheScalarTrackApi) {
  using T = TypeParam;
  test::Random rng(test::seed_for(1203));
  SCOPED_TRACE(rng.trace());
  // Double runs Highway's dynamic dispatch: the best target of this CPU in trials 0–2, at most AVX2
  // (a machine without AVX-512) in trials 3–5.  Float's kernel does not dispatch.
  for (int trial = 0; trial < 6; ++trial) {
    rig_detail::hwy_limit_to_avx2(trial >= 3);
    const Rig<T> rig = random_rig<T>(rng, 20);
    const auto clip = build_rig_clip<T>(rig.translations, rig.rotations, rig.scales);
    ASSERT_TRUE(clip) << clip.error().describe();
    RigContext ctx = make_rig_context(*clip);
    std::vector<JointPose<T>> pose(clip->joints());
    std::vector<T> frames;
    for (T t = -6; t < 40; t += T(0.23)) frames.push_back(t);      // forwards, past both ends
    for (T t = 38; t > -6; t -= T(0.71)) frames.push_back(t);      // backwards
    for (int i = 0; i < 100; ++i) frames.push_back(rng.uniform<T>(T(-8), T(45)));  // jumps
    double worst_vec = 0, worst_rot = 0;
    for (const T frame : frames) {
      sample_rig(*clip, frame, ctx, std::span<JointPose<T>>(pose));
      for (std::size_t j = 0; j < pose.size(); ++j) {
        const T tol_t = rig_runtime_vec_tolerance<T> * magnitude(rig.translations[j]);
        const T tol_s = rig_runtime_vec_tolerance<T> * magnitude(rig.scales[j]);
        const Vec3<T> t_ref = rig.translations[j].sample(frame), s_ref = rig.scales[j].sample(frame);
        EXPECT_LE(max_abs(pose[j].translation - t_ref), tol_t) << "joint " << j << " frame " << frame;
        EXPECT_LE(max_abs(pose[j].scale - s_ref), tol_s) << "joint " << j << " frame " << frame;
        const T angle = angle_between(pose[j].rotation, rig.rotations[j].sample(frame));
        EXPECT_LE(angle, rig_runtime_rotation_tolerance<T>) << "joint " << j << " frame " << frame;
        worst_vec = std::max(worst_vec, double(max_abs(pose[j].translation - t_ref) / magnitude(rig.translations[j])));
        worst_rot = std::max(worst_rot, double(angle));
      }
    }
    if (trial == 0 || trial == 3)
      std::cout << "[ measured ] RigClip vs per-track API (" << (sizeof(T) == 4 ? "float" : "double")
                << (sizeof(T) == 8 && rig_detail::stdx::native_simd<double>::size() < 4
                        ? std::string(", Highway ") + rig_detail::hwy_dynamic_target()
                        : std::string())
                << "): Vec3 " << worst_vec << " of the magnitude, rotation " << worst_rot << " rad\n";
    rig_detail::hwy_limit_to_avx2(false);
  }
}

TEST(RigClip, RefusesWhatItCannotSampleWithThePlace) {
  std::vector<TrackKey<Vec3d>> tk(2);
  tk[1].frame = 1;
  std::vector<QuatKey<double>> rk(2);
  rk[1].frame = 1;
  const std::vector<Track<Vec3d>> ok{*build_track(tk)};
  const std::vector<Track<Vec3d>> cycling{*build_track(tk, TrackExtend::repeat, TrackExtend::constant)};
  const std::vector<QuatTrack<double>> slerp{*build_quat_track(rk)};
  rk[0].interpolation = QuatInterpolation::squad;
  const std::vector<QuatTrack<double>> squad{*build_quat_track(rk)};
  EXPECT_TRUE(build_rig_clip<double>(ok, slerp, ok));
  const auto e1 = build_rig_clip<double>(cycling, slerp, ok);
  ASSERT_FALSE(e1);
  EXPECT_EQ(e1.error().code, ErrorCode::Unsupported);
  EXPECT_EQ(json_pointer(e1.error().location), "/translations/0");
  const auto e2 = build_rig_clip<double>(ok, squad, ok);
  ASSERT_FALSE(e2);
  EXPECT_EQ(json_pointer(e2.error().location), "/rotations/0/keys/0");
  const auto e3 = build_rig_clip<double>(ok, slerp, std::vector<Track<Vec3d>>{});
  ASSERT_FALSE(e3);
  EXPECT_EQ(e3.error().code, ErrorCode::InvalidArgument);
}

}  // namespace
}  // namespace inbetween
