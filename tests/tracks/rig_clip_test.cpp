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
#include "support/random_rig.hpp"

namespace inbetween {
namespace {

template <class T>
class RigClipTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(RigClipTyped, Scalars);

using test::magnitude;
using test::max_abs;
using test::random_rig;
using test::Rig;


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
    RigClipCursor ctx = make_rig_clip_cursor(*clip);
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
