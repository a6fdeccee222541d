// Keyframe reduction against gltfpack's animation resampling (the peer the issue names): the same
// per-frame animation, exported by inbetween with its keys kept, is (a) resampled by `gltfpack -i
// in.glb -o out.glb` (its defaults: 30 Hz, quantised rotations) and (b) reduced by export_gltf with
// `reduce` at a tolerance equal to gltfpack's measured error.  Both outputs are read back with
// tinygltf and played with glTF's formulas on a grid of 4 points per frame against the scene.
// Skips when gltfpack is not installed.  The printed table is copied into docs/gltf.md.
#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "inbetween/io/gltf_write.hpp"
#include "inbetween/scene/scene.hpp"
#include "inbetween/tracks/refit.hpp"
#include "support/cli.hpp"
#include "support/random.hpp"
#include "gltf_read_back.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;

struct Row {
  std::size_t keys = 0;
  double error = 0;
};

// Max error of the file's channel against the scene's local channel on the grid.
Row measure(const Scene& scene, const std::map<std::string, RefitKeys>& channels, const std::string& object,
            const std::string& path) {
  Row r;
  const auto it = channels.find(object + "." + path);
  if (it == channels.end()) return {0, -1};
  r.keys = it->second.size();
  const auto& node = scene.objects()[0];
  for (double f = scene.range_start(); f <= scene.range_end(); f += 0.25) {
    const double t = (f - scene.range_start()) / scene.fps();
    const Transform<double> local = node.local.sample(f);
    if (path == "rotation") {
      r.error = std::max(r.error, rotation_angle_between(evaluate_refit_rotation(it->second, t), local.rotation));
    } else {
      double v[3];
      evaluate_refit(it->second, t, v);
      const Vec3d ref = path == "translation" ? local.translation : local.scale;
      r.error = std::max({r.error, std::abs(v[0] - ref.x), std::abs(v[1] - ref.y), std::abs(v[2] - ref.z)});
    }
  }
  return r;
}

// A per-frame ("baked") animation over `seconds` at `fps`: smooth motion, plus uniform noise of
// amplitude `noise` on the translation (mocap jitter).
RawScene baked(double fps, double seconds, double noise, std::uint64_t seed) {
  test::Random rng(test::seed_for(seed));
  RawScene raw;
  raw.fps = fps;
  raw.range = {0, std::round(fps * seconds)};
  RawObject o;
  o.name = "body";
  RawVec3Channel t;
  RawQuatKeys r;
  for (double f = 0; f <= raw.range[1]; f += 1) {
    const double x = f / fps;
    t.keys.push_back({.frame = f, .value = Vec3d{std::sin(x), 0.5 * std::cos(1.3 * x), 0.4 * x} + rng.vec3(-noise, noise),
                      .tangent = TangentKind::linear});
    r.keys.push_back({.frame = f, .value = Quatd::from_axis_angle(Vec3d{0, 1, 0}, 0.8 * std::sin(x)) *
                                           Quatd::from_axis_angle(Vec3d{1, 0, 0}, 0.3 * x)});
  }
  o.translation = t;
  o.rotation = r;
  raw.objects.push_back(o);
  return raw;
}

TEST(Gltfpack, ReductionAgainstGltfpackResampling) {
  if (std::system("gltfpack -v > /dev/null 2>&1") != 0 && std::system("command -v gltfpack > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "gltfpack not installed (Debian package gltfpack)";
  }
  struct Case {
    const char* name;
    double fps, seconds, noise;
  };
  std::printf("| case | channel | per-frame keys | gltfpack keys | gltfpack max error | inbetween keys at that error | its max error | inbetween keys at 1e-5 | its max error | same, checked at frames only | its max error |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : {Case{"smooth, 30 fps, 10 s", 30, 10, 0}, Case{"smooth, 60 fps, 10 s", 60, 10, 0},
                        Case{"mocap noise 1e-3, 30 fps, 10 s", 30, 10, 1e-3}}) {
    const RawScene raw = baked(c.fps, c.seconds, c.noise, 1401);
    auto scene = build_scene(raw);
    ASSERT_TRUE(scene);
    auto per_frame = export_gltf(raw, *scene);
    ASSERT_TRUE(per_frame) << per_frame.error().describe();
    const fs::path in = test::write_test_file("in.glb", per_frame->bytes);
    const fs::path packed = test::test_dir() / "gltfpack.glb";
    const std::string cmd = "gltfpack -i '" + in.string() + "' -o '" + packed.string() + "' > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const auto pack = test::read_channels(packed);
    for (const char* path : {"translation", "rotation"}) {
      const Row g = measure(*scene, pack, "body", path);
      ASSERT_GE(g.error, 0) << "gltfpack dropped " << path;
      // inbetween at gltfpack's error (absolute: the option is relative to the channel's range).
      double range = 1;
      if (std::string(path) == "translation") {
        double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
        for (const auto& k : std::get<RawVec3Channel>(*raw.objects[0].translation).keys) {
          for (int i = 0; i < 3; ++i) {
            const double v = i == 0 ? k.value.x : i == 1 ? k.value.y : k.value.z;
            lo[i] = std::min(lo[i], v);
            hi[i] = std::max(hi[i], v);
          }
        }
        range = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
      }
      // Refit at 95% of gltfpack's error so that float storage stays within it.
      auto ours = export_gltf(raw, *scene, {.tolerance = 0.95 * g.error / range, .reduce = true});
      ASSERT_TRUE(ours) << ours.error().describe();
      const fs::path mine = test::write_test_file("inbetween.glb", ours->bytes);
      const Row o = measure(*scene, test::read_channels(mine), "body", path);
      // And at the default tolerance (1e-5 of the range; 1e-5 rad).
      auto def = export_gltf(raw, *scene, {.reduce = true});
      ASSERT_TRUE(def);
      const Row d = measure(*scene, test::read_channels(test::write_test_file("default.glb", def->bytes)), "body", path);
      // Per-frame data is known at its frames only: the same reduction checked at frames
      // (substeps 1), its error still measured at 4 points per frame.
      auto at_frames = export_gltf(raw, *scene, {.substeps = 1, .reduce = true});
      ASSERT_TRUE(at_frames);
      const Row a = measure(*scene, test::read_channels(test::write_test_file("frames.glb", at_frames->bytes)), "body", path);
      std::printf("| %s | %s | %zu | %zu | %.3g | %zu | %.3g | %zu | %.3g | %zu | %.3g |\n", c.name, path,
                  std::get<RawVec3Channel>(*raw.objects[0].translation).keys.size(), g.keys, g.error, o.keys, o.error, d.keys,
                  d.error, a.keys, a.error);
      EXPECT_LE(o.error, g.error) << c.name << " " << path;
      // Never more keys at gltfpack's error; strictly fewer wherever gltfpack is lossy beyond float
      // storage (where it only re-stores the per-frame keys, a lossless reduction of per-frame
      // linear keys needs them all: each frame is a kink).
      EXPECT_LE(o.keys, g.keys) << c.name << " " << path;
      if (g.error > 1e-5) EXPECT_LT(o.keys, g.keys) << c.name << " " << path;
    }
  }
}

}  // namespace
}  // namespace inbetween
