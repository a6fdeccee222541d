// The runtime contract of built tracks (docs/tracks.md, house rule 10): evaluation is noexcept
// and sampling with a cursor or into a caller's span never allocates.  This file replaces the
// global operator new of the tracks test program with a counting one; the count is switched on
// only around the calls under test.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>
#include <span>
#include <utility>
#include <vector>

#include "inbetween/arclength/arc_length_inverse.hpp"
#include "inbetween/curves/bezier.hpp"
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"
#include "inbetween/tracks/runtime/fcurve_clip.hpp"
#include "inbetween/tracks/runtime/blend.hpp"
#include "inbetween/tracks/runtime/inertialize.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"
#include "inbetween/tracks/runtime/root_motion.hpp"
#include "inbetween/tracks/transform_track.hpp"
#include "support/museum_tracks.hpp"

#include "support/counting_new.hpp"  // this program's counting operator new (one per test program)

namespace inbetween {
namespace {

using test::allocations_in;

TEST(HotPath, CounterSeesAnAllocation) {
  // The counter itself can fail: a vector of one element allocates once.
  EXPECT_EQ(allocations_in([] { std::vector<int> v(1); (void)v; }), 1);
}

TEST(HotPath, ArcLengthInverseQueriesNeverAllocate) {
  // Issue 12: u(s) from the piecewise inverse, one at a time and in batch, into caller-owned spans.
  const auto bez = build_bezier(std::vector<Vec3d>{{0, 0, 0}, {1, 2, 0}, {2, -1, 1}, {3, 0, 0}});
  ASSERT_TRUE(bez);
  const auto inv = make_arc_length_inverse(*make_arc_length(*bez));
  ASSERT_TRUE(inv);
  std::vector<double> s(64), u(64);
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = inv->length() * double(k) / 63.0;
  double sink = 0;
  EXPECT_EQ(allocations_in([&] {
              for (const double sk : s) sink += inv->u_at(sk);
              inv->u_at(std::span<const double>(s), std::span<double>(u));
            }),
            0);
  EXPECT_GT(sink + u.back(), 0.0);
}

TEST(HotPath, RigClipSamplingNeverAllocates) {
  // Issue 12: one sample_rig call fills every joint's pose into a caller-owned span.
  std::vector<TrackKey<Vec3d>> tk;
  std::vector<QuatKey<double>> rk;
  for (int i = 0; i < 8; ++i) {
    TrackKey<Vec3d> t;
    t.frame = double(i);
    t.value = Vec3d{double(i % 3), 1.0, double(i)};
    tk.push_back(t);
    QuatKey<double> r;
    r.frame = double(i);
    r.value = Quatd::from_axis_angle(Vec3d{0, 0, 1}, 0.4 * i);
    rk.push_back(r);
  }
  const std::vector<Track<Vec3d>> tv(30, *build_track(tk));
  const std::vector<QuatTrack<double>> rv(30, *build_quat_track(rk));
  const auto clip = build_rig_clip<double>(tv, rv, tv);
  ASSERT_TRUE(clip);
  RigClipCursor ctx = make_rig_clip_cursor(*clip);
  std::vector<JointPose<double>> pose(clip->joints());
  EXPECT_EQ(allocations_in([&] {
              for (double f = -1; f < 9; f += 0.25) sample_rig(*clip, f, ctx, std::span<JointPose<double>>(pose));
            }),
            0);
  EXPECT_NEAR(pose[0].translation.z, 7.0, 1e-12);  // held after the last key (closed form)
}

TEST(HotPath, FCurveClipSamplingNeverAllocates) {
  // Issue 12: the F-curve runtime fills every channel (and every joint's pose) into caller-owned
  // spans; forwards, backwards and jumps all run on the context's storage.
  RawFCurve raw;
  for (int i = 0; i < 6; ++i) {
    FCurveKey k;
    k.frame = 4.0 * i;
    k.value = double((i * 7) % 5);
    raw.keys.push_back(k);
  }
  const std::vector<FCurve> curves(20, *build_fcurve(raw));  // two joints of 10 curves
  const auto clip = build_fcurve_rig(curves);
  ASSERT_TRUE(clip);
  auto ctx = make_fcurve_clip_cursor(*clip);
  std::vector<float> values(clip->channels());
  std::vector<JointPose<float>> pose(clip->joints());
  EXPECT_EQ(allocations_in([&] {
              for (float f = -2; f < 24; f += 0.3f) sample_fcurves(*clip, f, ctx, std::span<float>(values));
              for (float f = 24; f > -2; f -= 1.7f) sample_fcurve_rig(*clip, f, ctx, std::span<JointPose<float>>(pose));
            }),
            0);
  sample_fcurves(*clip, 30.0f, ctx, std::span<float>(values));
  EXPECT_EQ(values[0], 0.0f);  // held after the last key, whose value is (5·7) mod 5 = 0
  EXPECT_EQ(values[10], 0.0f);
}

TEST(HotPath, CyclingFCurveClipSamplingNeverAllocates) {
  // The Cycles fold (windows, pieces refreshed on the scalar path, one-frame folds at cycle
  // boundaries and far frames) runs on the context's storage too.
  RawFCurve raw;
  for (int i = 0; i < 6; ++i) {
    FCurveKey k;
    k.frame = 4.0 * i;
    k.value = double((i * 7) % 5);
    raw.keys.push_back(k);
  }
  raw.modifiers = {FCurveModifier{.kind = FCurveCycles{.before = CycleMode::mirror, .after = CycleMode::repeat_offset}}};
  std::vector<FCurve> curves(20, *build_fcurve(raw));
  raw.modifiers = {FCurveModifier{.kind = FCurveCycles{.before = CycleMode::repeat, .after = CycleMode::mirror, .count_before = 2}}};
  curves[3] = *build_fcurve(raw);
  const auto clip = build_fcurve_rig(curves);
  ASSERT_TRUE(clip);
  auto ctx = make_fcurve_clip_cursor(*clip);
  std::vector<float> values(clip->channels());
  std::vector<JointPose<float>> pose(clip->joints());
  EXPECT_EQ(allocations_in([&] {
              for (float f = -90; f < 140; f += 0.3f) sample_fcurves(*clip, f, ctx, std::span<float>(values));
              for (float f = 140; f > -90; f -= 1.7f) sample_fcurve_rig(*clip, f, ctx, std::span<JointPose<float>>(pose));
              for (const float f : {40.0f, -60.0f, 1e7f, -3e38f, 20.0f}) sample_fcurves(*clip, f, ctx, std::span<float>(values));
            }),
            0);
  sample_fcurves(*clip, 40.0f, ctx, std::span<float>(values));
  // Frame 40 = last key + 2 periods of 20: the last key's value 0 plus 2 offsets of (0 − 0) = 0.
  EXPECT_EQ(values[0], 0.0f);
}

template <class T>
class HotPathTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(HotPathTyped, Scalars);

TYPED_TEST(HotPathTyped, TrackQuatAndEulerSamplingNeverAllocate) {
  using T = TypeParam;
  std::vector<TrackKey<Vec3<T>>> vkeys;
  std::vector<QuatKey<T>> qkeys;
  std::vector<EulerKey<T>> ekeys;
  for (int i = 0; i < 12; ++i) {
    TrackKey<Vec3<T>> k;
    k.frame = T(i);
    k.value = Vec3<T>{T(i % 3), T(i * i % 5), T(1)};
    k.tangent = TangentKind(i % 8);
    vkeys.push_back(k);
    QuatKey<T> q;
    q.frame = T(i);
    q.value = Quat<T>::from_axis_angle(Vec3<T>{0, 0, 1}, T(0.7) * T(i));
    q.interpolation = QuatInterpolation(i % 5);
    qkeys.push_back(q);
    EulerKey<T> e;
    e.frame = T(i);
    e.angles_rad = {T(0.3) * T(i), T(0.1), T(-0.2) * T(i)};
    ekeys.push_back(e);
  }
  auto tr = build_track(vkeys, TrackExtend::mirror, TrackExtend::repeat_offset);
  auto qt = build_quat_track(qkeys);
  auto et = build_euler_track(ekeys);
  ASSERT_TRUE(tr && qt && et);
  TrackCursor c0;
  static_assert(noexcept(std::declval<const Track<Vec3<T>>&>().sample(T(1), c0)));
  static_assert(noexcept(std::declval<const QuatTrack<T>&>().sample(T(1), c0)));
  static_assert(noexcept(std::declval<const EulerTrack<T>&>().sample(T(1))));
  std::vector<T> frames;
  for (int i = -100; i < 1300; ++i) frames.push_back(T(i) / T(50));
  std::vector<Vec3<T>> vout(frames.size());
  std::vector<Quat<T>> qout(frames.size());
  TrackCursor cursor;
  EXPECT_EQ(allocations_in([&] {
              for (T f : frames) {
                (void)tr->sample(f, cursor);
                (void)tr->sample(f);
              }
              tr->sample(std::span<const T>(frames), std::span<Vec3<T>>(vout), cursor);
            }),
            0);
  EXPECT_EQ(allocations_in([&] {
              for (T f : frames) {
                (void)qt->sample(f, cursor);
                (void)et->sample(f);
                (void)et->sample_angles(f);
              }
              qt->sample(std::span<const T>(frames), std::span<Quat<T>>(qout), cursor);
            }),
            0);
}

TEST(HotPath, FCurveAndHierarchySamplingNeverAllocate) {
  std::vector<FCurve> curves;
  for (const auto& ex : test::museum_fcurves()) curves.push_back(*build_fcurve(ex.curve));
  std::vector<float> frames;
  for (int i = -500; i < 3000; ++i) frames.push_back(float(i) * 0.01f);
  std::vector<float> out(frames.size());
  TrackCursor c0;
  static_assert(noexcept(std::declval<const FCurve&>().sample(1.0f, c0)));
  EXPECT_EQ(allocations_in([&] {
              for (const FCurve& c : curves) {
                TrackCursor cursor;
                for (float f : frames) (void)c.sample(f, cursor);
                c.sample(std::span<const float>(frames), std::span<float>(out), cursor);
              }
            }),
            0);

  std::vector<HierarchyNode<double>> nodes(3);
  nodes[1].parent = 0;
  nodes[2].parent = 1;
  std::vector<TrackKey<Vec3d>> keys(2);
  keys[1].frame = 10;
  keys[1].value = Vec3d{1, 2, 3};
  nodes[1].local.translation = *build_track(keys);
  auto h = build_transform_hierarchy(std::move(nodes));
  ASSERT_TRUE(h);
  std::vector<Transform<double>> world(3);
  std::vector<Mat4d> matrices(3);
  EXPECT_EQ(allocations_in([&] {
              for (double f = -5; f < 15; f += 0.25) {
                h->sample_world(f, std::span<Transform<double>>(world));
                h->sample_world(f, std::span<Mat4d>(matrices));
              }
            }),
            0);
}

TEST(HotPath, BlendInertializeAndRootMotionNeverAllocate) {
  // Issue 23: one call per character into caller-owned spans.
  const std::size_t n = 37;
  std::vector<JointPose<float>> a(n), b(n), rest(n), out(n), delta(n);
  for (std::size_t j = 0; j < n; ++j) {
    a[j].translation = {float(j), 1, 2};
    b[j].rotation = Quatf::from_axis_angle(Vec3f{0, 1, 0}, 0.1f * float(j));
  }
  std::vector<float> mask(n, 0.5f);
  const std::vector<BlendLayer<float>> layers{{a, 0.7f}, {b, 0.3f, mask}};
  const std::vector<AdditiveLayer<float>> additive{{delta, 0.5f, mask}};
  std::vector<JointOffset<float>> offsets(n);
  std::vector<RootMotion<float>> motion(n);
  std::vector<JointPose<float>> character(n);
  EXPECT_EQ(allocations_in([&] {
              additive_delta<float>(b, a, delta);
              blend_poses<float>(layers, additive, rest, out);
              inertialize_begin<float>(a, b, b, a, 1.0f / 30, offsets);
              inertialize<float>(offsets, 0.1f, 0.3f, a, out);
              extract_root_motion<float>(a, RootMotionOptions{.loop = true}, motion, character);
            }),
            0);
  // The PoseBlock (SoA) overload and its conversions.
  std::vector<PoseBlock> sa(pose_blocks(n)), sb(sa.size()), sr(sa.size()), so(sa.size()), sd(sa.size());
  std::vector<float> smask(sa.size() * pose_block_joints);
  const std::vector<BlendLayerSoA> layers_soa{{sa, 0.7f}, {sb, 0.3f, smask}};
  const std::vector<AdditiveLayerSoA> additive_soa{{sd, 0.5f, smask}};
  EXPECT_EQ(allocations_in([&] {
              to_pose_blocks(a, sa), to_pose_blocks(b, sb), to_pose_blocks(rest, sr), to_pose_blocks(delta, sd);
              to_mask_blocks(mask, smask);
              blend_poses(layers_soa, additive_soa, sr, so);
              from_pose_blocks(so, out);
            }),
            0);
  EXPECT_TRUE(std::isfinite(out[5].translation.x + motion.back().translation.x));
}

}  // namespace
}  // namespace inbetween
