// Root motion (include/inbetween/tracks/runtime/root_motion.hpp) on a real clip: CMU 01_01 (a walk,
// Y up, inches) read by the BVH reader.  The root's local poses go through extract_root_motion;
// then every joint's world transform rebuilt from the motion, the character-space root and the
// unchanged local transforms below it equals the scene's own world transform (Scene::sample,
// Space::world) within 1e-6 of the clip's extent — issue 23's check.  In tests/io because it needs
// the reader; the seeded random clips are in tests/tracks/root_motion_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "inbetween/io/input.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/scene/scene.hpp"
#include "inbetween/tracks/runtime/root_motion.hpp"

namespace inbetween {
namespace {

// Issue 23: character space + root motion reproduces the world transforms within 1e-6 of the extent.
constexpr double kRootMotionTol = 1e-6;

TEST(RootMotionBvh, CmuWalkCharacterSpacePlusMotionIsTheWorld) {
  const std::filesystem::path file = "/usr/share/assimp/models/BVH/01_01.bvh";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " missing (Debian package assimp-testmodels)";
  const auto raw = read_input_file(file);
  ASSERT_TRUE(raw) << raw.error().message;
  const auto scene = build_scene(*raw);
  ASSERT_TRUE(scene) << scene.error().message;
  const auto objects = scene->objects();
  ASSERT_GT(objects.size(), 20u);
  // Each object's translation.x column (then .y .z, rotation.w x y z, scale.x y z).
  std::vector<std::size_t> column(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto cols = scene->columns();
    const auto it = std::find_if(cols.begin(), cols.end(), [&](const SceneColumn& c) { return c.name == objects[i].name + ".translation.x"; });
    ASSERT_NE(it, cols.end()) << objects[i].name;
    column[i] = std::size_t(it - cols.begin());
  }
  const std::size_t root = std::size_t(std::find_if(objects.begin(), objects.end(), [](const auto& o) { return !o.parent; }) - objects.begin());
  ASSERT_LT(root, objects.size());
  const auto pose_at = [&](const std::vector<double>& v, std::size_t i) {
    const double* c = v.data() + column[i];
    return Transform<double>{{c[0], c[1], c[2]}, Quatd::from_wxyz(c[3], c[4], c[5], c[6]), {c[7], c[8], c[9]}};
  };
  std::vector<std::vector<double>> local, world;
  SceneCursor cursor(*scene);
  for (double f = scene->range_start(); f <= scene->range_end(); f += 1) {
    std::vector<double> l(scene->columns().size()), w(scene->columns().size());
    scene->sample(f, l, cursor, Space::local);
    scene->sample(f, w, cursor, Space::world);
    local.push_back(std::move(l));
    world.push_back(std::move(w));
  }
  ASSERT_GT(local.size(), 100u);
  std::vector<JointPose<double>> root_pose;
  double extent = 0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const auto t = pose_at(local[k], root);
    root_pose.push_back({t.translation, t.rotation, t.scale});
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const Vec3d p = pose_at(world[k], i).translation;
      extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    }
  }
  std::vector<RootMotion<double>> motion(root_pose.size());
  std::vector<JointPose<double>> character(root_pose.size());
  extract_root_motion<double>(root_pose, RootMotionOptions{}, motion, character);
  double worst_t = 0, worst_r = 0, travelled = 0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    EXPECT_EQ(motion[k].translation.y, 0.0);
    travelled = std::max(travelled, norm(motion[k].translation));
    // World transforms rebuilt parents first (objects() lists parents before children in a BVH).
    std::vector<Transform<double>> rebuilt(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (i == root) {
        const JointPose<double> w = apply_root_motion(motion[k], character[k]);
        rebuilt[i] = {w.translation, w.rotation, w.scale};
      } else {
        ASSERT_TRUE(objects[i].parent && *objects[i].parent < i);
        rebuilt[i] = compose(rebuilt[*objects[i].parent], pose_at(local[k], i));
      }
      const Transform<double> want = pose_at(world[k], i);
      worst_t = std::max(worst_t, norm(rebuilt[i].translation - want.translation));
      worst_r = std::max(worst_r, angle_between(rebuilt[i].rotation, want.rotation));
    }
  }
  EXPECT_LE(worst_t, kRootMotionTol * extent);
  EXPECT_LE(worst_r, kRootMotionTol);
  EXPECT_GT(travelled, 0.1 * extent);  // the walk does move: the motion track is not trivially zero
  std::printf("CMU 01_01: %zu frames, extent %.3g, worst position %.3g, worst rotation %.3g rad\n", local.size(), extent,
              worst_t, worst_r);
}

}  // namespace
}  // namespace inbetween
