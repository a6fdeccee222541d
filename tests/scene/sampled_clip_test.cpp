// The sampled clip and ACL's virtual-vertex error (scene/sampled_clip.hpp), against closed forms:
// a rotation error θ moves a point at distance r from the axis by the chord 2·r·sin(θ/2); a
// translation error d moves every point by d; a parent's error carries its children.
#include "inbetween/scene/sampled_clip.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace inbetween {
namespace {

// Rounding of a few compositions in double at magnitudes ≤ 10.
constexpr double metric_tolerance = 1e-12;

SampledClip chain(std::size_t joints, std::size_t frames) {
  SampledClip clip;
  for (std::size_t j = 0; j < joints; ++j) {
    clip.parents.push_back(std::int32_t(j) - 1);
    clip.names.push_back("j" + std::to_string(j));
  }
  clip.frame_rate = 30;
  clip.frames = frames;
  clip.poses.resize(joints * frames);
  return clip;
}

TEST(ClipError, RootRotationErrorIsTheChordAtTheAxisPoints) {
  const double shell = 3, theta = 0.05;
  const SampledClip reference = chain(1, 2);
  SampledClip candidate = reference;
  candidate.poses[1].rotation = Quatd::from_axis_angle(Vec3d{0, 0, 1}, theta);
  const ClipError e = clip_error(reference, candidate, shell);
  EXPECT_NEAR(e.max, 2 * shell * std::sin(theta / 2), metric_tolerance);
  EXPECT_EQ(e.frame, 1u);
  EXPECT_EQ(e.joint, 0u);
  EXPECT_EQ(clip_error(reference, reference, shell).max, 0.0);
}

TEST(ClipError, ParentRotationErrorCarriesTheChild) {
  // Child at L along the parent's x: its x axis point is at L + D from the parent's z axis.
  const double shell = 3, theta = 0.02, length = 5;
  SampledClip reference = chain(2, 1);
  reference.poses[1].translation = {length, 0, 0};
  SampledClip candidate = reference;
  candidate.poses[0].rotation = Quatd::from_axis_angle(Vec3d{0, 0, 1}, theta);
  const ClipError e = clip_error(reference, candidate, shell);
  EXPECT_NEAR(e.max, 2 * (length + shell) * std::sin(theta / 2), metric_tolerance);
  EXPECT_EQ(e.joint, 1u);
}

TEST(ClipError, TranslationErrorMovesEveryPointAndScaleStretchesTheShell) {
  const double shell = 2;
  SampledClip reference = chain(2, 1);
  SampledClip candidate = reference;
  candidate.poses[1].translation = {0, 0.25, 0};  // the child only
  EXPECT_NEAR(clip_error(reference, candidate, shell).max, 0.25, metric_tolerance);
  candidate = reference;
  candidate.poses[0].scale = {1.5, 1, 1};  // the root's x point moves by 0.5·D; the child's too
  const ClipError e = clip_error(reference, candidate, shell);
  EXPECT_NEAR(e.max, 0.5 * shell, metric_tolerance);
}

TEST(ClipError, NanCountsAsInfinite) {
  SampledClip reference = chain(1, 1);
  SampledClip candidate = reference;
  candidate.poses[0].translation.x = std::nan("");
  EXPECT_TRUE(std::isinf(clip_error(reference, candidate, 1).max));
}

TEST(SampleClip, ParentsComeFirstAndPosesAreLocal) {
  RawScene raw;
  raw.range = {2, 6};
  RawObject child;
  child.name = "child";
  child.parent = "root";
  child.translation = Vec3d{1, 0, 0};
  RawObject root;
  root.name = "root";
  RawVec3Channel t;
  t.keys.resize(2);
  t.keys[0].frame = 2, t.keys[0].value = {0, 0, 0};
  t.keys[1].frame = 6, t.keys[1].value = {4, 0, 0};
  root.translation = t;
  raw.objects = {child, root};  // the child first in the file
  const auto scene = build_scene(raw);
  ASSERT_TRUE(scene) << scene.error().describe();
  const auto clip = sample_clip(*scene);
  ASSERT_TRUE(clip) << clip.error().describe();
  ASSERT_EQ(clip->joints(), 2u);
  EXPECT_EQ(clip->frames, 5u);
  EXPECT_EQ(clip->first_frame, 2.0);
  EXPECT_EQ(clip->names[0], "root");
  EXPECT_EQ(clip->parents[0], -1);
  EXPECT_EQ(clip->parents[1], 0);
  for (std::size_t f = 0; f < clip->frames; ++f) {
    EXPECT_EQ(clip->frame(f)[1].translation.x, 1.0);  // local, not world
  }
  EXPECT_EQ(clip->frame(0)[0].translation.x, 0.0);
  EXPECT_EQ(clip->frame(4)[0].translation.x, 4.0);
  std::vector<Transform<double>> world(2);
  world_poses(*clip, 4, world);
  EXPECT_EQ(world[1].translation.x, 5.0);
}

}  // namespace
}  // namespace inbetween
