// A Scene compiled into the tracks runtime (scene/scene_rig_clip.hpp): every object's local TRS
// from sample_rig equals the scene's own per-object sampling (TransformTrack::sample, the
// reference) to the runtime's named tolerances; objects on a path are refused with their place.
#include "inbetween/scene/scene_rig_clip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "inbetween/curves/catmull_rom.hpp"

namespace inbetween {
namespace {

TEST(SceneRigClip, ObjectsLocalTransformsAgreeWithTheScene) {
  RawScene raw;
  raw.range = {0, 20};
  RawObject a;
  a.name = "a";
  RawVec3Channel t;
  t.keys.resize(3);
  t.keys[0].frame = 0, t.keys[0].value = {0, 0, 0};
  t.keys[1].frame = 5, t.keys[1].value = {1, 2, 3};
  t.keys[2].frame = 12, t.keys[2].value = {-4, 0, 1};
  a.translation = t;
  RawQuatKeys r;
  r.keys.resize(2);
  r.keys[0].frame = 0;
  r.keys[1].frame = 10, r.keys[1].value = Quatd::from_axis_angle(Vec3d{0, 0, 1}, 1.2);
  a.rotation = r;
  raw.objects.push_back(a);
  RawObject b;  // constants only, child of a
  b.name = "b";
  b.parent = "a";
  b.translation = Vec3d{1, 0, 0};
  b.scale = Vec3d{2, 2, 2};
  raw.objects.push_back(b);
  const auto scene = build_scene(raw);
  ASSERT_TRUE(scene) << scene.error().describe();
  const auto clip = build_scene_rig_clip(*scene);
  ASSERT_TRUE(clip) << clip.error().describe();
  ASSERT_EQ(clip->joints(), 2u);
  RigClipCursor ctx = make_rig_clip_cursor(*clip);
  std::vector<JointPose<double>> pose(2);
  for (double f = -3; f < 16; f += 0.37) {
    sample_rig(*clip, f, ctx, std::span<JointPose<double>>(pose));
    for (std::size_t i = 0; i < 2; ++i) {
      const Transform<double> ref = scene->objects()[i].local.sample(f);
      const Vec3d dt = pose[i].translation - ref.translation, ds = pose[i].scale - ref.scale;
      // |value| + |slope|·(segment length) ≤ 4 + 5 here (keys above): the tolerance relative to 16
      EXPECT_LE(std::max({std::abs(dt.x), std::abs(dt.y), std::abs(dt.z)}), 16 * rig_runtime_vec_tolerance<double>);
      EXPECT_LE(std::max({std::abs(ds.x), std::abs(ds.y), std::abs(ds.z)}), 16 * rig_runtime_vec_tolerance<double>);
      EXPECT_LE(angle_between(pose[i].rotation, ref.rotation), rig_runtime_rotation_tolerance<double>) << f;
    }
  }
}

TEST(SceneRigClip, RefusesAnObjectOnAPathWithThePlace) {
  RawScene raw;
  raw.range = {0, 10};
  raw.paths.push_back({"p", AnyCurve{CurveKind::catmull_rom, 3,
                                     AnyCurveVariant{build_catmull_rom(std::vector<Vec3d>{{0, 0, 0}, {1, 2, 0}, {3, 0, 1}}).value()}}});
  RawObject still;
  still.name = "still";
  raw.objects.push_back(still);
  RawObject mover;
  mover.name = "mover";
  RawPathLeg leg;
  leg.curve = std::string("p");
  leg.speed = RawSpeed{.kind = SpeedKind::ease, .start_frame = 0, .end_frame = 5};
  mover.path = {leg};
  raw.objects.push_back(mover);
  const auto scene = build_scene(raw);
  ASSERT_TRUE(scene) << scene.error().describe();
  const auto clip = build_scene_rig_clip(*scene);
  ASSERT_FALSE(clip);
  EXPECT_EQ(clip.error().code, ErrorCode::Unsupported);
  EXPECT_EQ(json_pointer(clip.error().location), "/objects/1");
}

}  // namespace
}  // namespace inbetween
