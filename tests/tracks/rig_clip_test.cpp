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
  // The default SSE2 build runs Highway's dynamic dispatch: the best target of this CPU in trials
  // 0–2, at most AVX2 (a machine without AVX-512) in trials 3–5.
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
                << (rig_detail::stdx::native_simd<T>::size() * sizeof(T) < 32
                        ? std::string(", Highway ") + rig_detail::hwy_dynamic_target()
                        : std::string())
                << "): Vec3 " << worst_vec << " of the magnitude, rotation " << worst_rot << " rad\n";
    rig_detail::hwy_limit_to_avx2(false);
  }
}

// The compact forms (issue 24): a rig of linear and stepped Vec3 keys, step/slerp rotations and
// constant channels (equal keys) keeps the 8-field Vec3 cache layout, its constant channels cost
// the same whatever their key count, and it agrees with the scalar API as the general rigs do,
// played forwards (stream records), backwards and with jumps (records found per channel); with
// every joint keyed on the same frames (a sampled clip) most frames become dense groups, the steps,
// holds and constant channels stay general records between them.
TYPED_TEST(RigClipTyped, LinesStepsAndConstantChannelsTakeTheCompactForms) {
  using T = TypeParam;
  test::Random rng(test::seed_for(2424));
  SCOPED_TRACE(rng.trace());
  // shift0: joint 0's keys a quarter frame later (no frame is shared by every joint any more);
  // cubic0: joint 0's translation Catmull-Rom (the clip takes the cubic cache layout) and no
  // stepped scale (the scales' dense groups then clear c2 and c3).
  const auto make = [](test::Random& rng, int keys, bool all_constant, bool shared_frames, bool shift0 = false,
                       bool cubic0 = false) {
    Rig<T> rig;
    for (int j = 0; j < 21; ++j) {
      std::vector<TrackKey<Vec3<T>>> tk, sk;
      std::vector<QuatKey<T>> rk;
      T f = shared_frames ? (shift0 && j == 0 ? T(-1.75) : T(-2)) : rng.uniform<T>(T(-3), T(3));
      const Quat<T> fixed = rng.rotation<T>();
      // Shared frames: no constant channel, translations without steps (every frame a dense group
      // of translations; scales and rotations dense where no channel steps).
      const bool constant_t = all_constant || (!shared_frames && j % 4 == 0);
      const bool constant_s = all_constant || (!shared_frames && j % 2 == 0);
      const bool constant_r = all_constant || (!shared_frames && j % 3 == 0);
      for (int k = 0; k < keys; ++k) {
        TrackKey<Vec3<T>> t;
        t.frame = f;
        t.value = constant_t ? Vec3<T>{T(1), T(-2), T(0.5)} : rng.vec3<T>(T(-5), T(5));
        t.tangent = !shared_frames && rng.integer(0, 5) == 0 ? TangentKind::stepped : TangentKind::linear;
        if (cubic0 && j == 0) t.tangent = TangentKind::catmull_rom;
        tk.push_back(t);
        TrackKey<Vec3<T>> s = t;
        s.tangent = rng.integer(0, 5) == 0 && !cubic0 ? TangentKind::stepped : TangentKind::linear;
        s.value = constant_s ? Vec3<T>{T(1), T(1), T(1)} : rng.vec3<T>(T(0.5), T(2));
        sk.push_back(s);
        QuatKey<T> r;
        r.frame = f;
        r.value = constant_r ? fixed : rng.rotation<T>();
        r.interpolation = rng.integer(0, 3) == 0 ? QuatInterpolation::step : QuatInterpolation::slerp;
        rk.push_back(r);
        f += shared_frames ? T(1.5) + T(k % 3) : rng.uniform<T>(T(0.2), T(3));
      }
      rig.translations.push_back(*build_track(tk));
      rig.scales.push_back(*build_track(sk));
      rig.rotations.push_back(*build_quat_track(rk));
    }
    return rig;
  };
  // Constant channels: one record each, whatever the key count.
  const Rig<T> few = make(rng, 3, true, false), many = make(rng, 40, true, false);
  const auto few_clip = build_rig_clip<T>(few.translations, few.rotations, few.scales);
  const auto many_clip = build_rig_clip<T>(many.translations, many.rotations, many.scales);
  ASSERT_TRUE(few_clip && many_clip);
  EXPECT_EQ(few_clip->bytes(), many_clip->bytes());

  for (const int variant : {0, 1, 2}) {
  const bool shared = variant > 0, cubic = variant == 2;
  SCOPED_TRACE(shared ? (cubic ? "shared key frames, one cubic channel" : "shared key frames") : "own key frames");
  test::Random rig_rng = rng;  // the same draws for the shifted copy below
  const Rig<T> rig = make(rng, 12, false, shared, false, cubic);
  const auto clip = build_rig_clip<T>(rig.translations, rig.rotations, rig.scales);
  ASSERT_TRUE(clip) << clip.error().describe();
  if (shared) {
    // Dense groups hold a key in N scalars, a general record in N + 2 and a channel: the same rig
    // with one joint off the shared frames (no dense group) is larger.
    const Rig<T> off = make(rig_rng, 12, false, true, true, cubic);
    const auto off_clip = build_rig_clip<T>(off.translations, off.rotations, off.scales);
    ASSERT_TRUE(off_clip);
    EXPECT_LT(clip->bytes(), off_clip->bytes());
  }
  RigClipCursor ctx = make_rig_clip_cursor(*clip);
  // Only a cubic segment makes the cursors cache c2 and c3.
  EXPECT_EQ(ctx.vec_fields, cubic ? rig_detail::vec_fields_cubic : rig_detail::vec_fields_line);
  std::vector<JointPose<T>> pose(clip->joints());
  std::vector<T> frames;
  for (T t = -6; t < 40; t += T(0.23)) frames.push_back(t);
  for (T t = 38; t > -6; t -= T(0.71)) frames.push_back(t);
  for (int i = 0; i < 100; ++i) frames.push_back(rng.uniform<T>(T(-8), T(45)));
  for (T t = -3; t < 40; t += T(7.3)) frames.push_back(t);  // forward jumps past many segments
  for (const T frame : frames) {
    sample_rig(*clip, frame, ctx, std::span<JointPose<T>>(pose));
    for (std::size_t j = 0; j < pose.size(); ++j) {
      EXPECT_LE(max_abs(pose[j].translation - rig.translations[j].sample(frame)),
                rig_runtime_vec_tolerance<T> * magnitude(rig.translations[j]))
          << "joint " << j << " frame " << frame;
      EXPECT_LE(max_abs(pose[j].scale - rig.scales[j].sample(frame)), rig_runtime_vec_tolerance<T> * magnitude(rig.scales[j]))
          << "joint " << j << " frame " << frame;
      EXPECT_LE(angle_between(pose[j].rotation, rig.rotations[j].sample(frame)), rig_runtime_rotation_tolerance<T>)
          << "joint " << j << " frame " << frame;
    }
  }
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
  EXPECT_EQ(e1.error().code, ErrorCode::unsupported);
  EXPECT_EQ(json_pointer(e1.error().location), "/translations/0");
  const auto e2 = build_rig_clip<double>(ok, squad, ok);
  ASSERT_FALSE(e2);
  EXPECT_EQ(json_pointer(e2.error().location), "/rotations/0/keys/0");
  const auto e3 = build_rig_clip<double>(ok, slerp, std::vector<Track<Vec3d>>{});
  ASSERT_FALSE(e3);
  EXPECT_EQ(e3.error().code, ErrorCode::invalid_argument);
}

}  // namespace
}  // namespace inbetween
