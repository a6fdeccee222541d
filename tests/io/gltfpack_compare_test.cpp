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

#include "inbetween/io/gltf.hpp"
#include "inbetween/io/gltf_write.hpp"
#include "inbetween/io/scene.hpp"
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


// The per-frame ("baked") world motion of frame22.json's ball (path with speed control, two legs,
// banking on the second): one LINEAR translation and slerp rotation key per frame of the range
// 16 … 86, from Scene::sample (what bake prints); the ball has no parent, so world = local.
RawScene baked_frame22() {
  auto raw = read_scene_json(test::slurp(fs::path(INBETWEEN_SOURCE_DIR) / "examples/scenes/frame22.json"));
  EXPECT_TRUE(raw);
  auto scene = build_scene(*raw);
  EXPECT_TRUE(scene);
  RawScene out;
  out.fps = scene->fps();
  out.range = {scene->range_start(), scene->range_end()};
  RawObject o;
  o.name = "ball";
  RawVec3Channel t;
  RawQuatKeys r;
  std::vector<double> row(scene->columns().size());
  SceneCursor cursor(*scene);
  for (double f = scene->range_start(); f <= scene->range_end(); f += 1) {
    scene->sample(f, row, cursor);  // ball is the first object: its columns come first
    t.keys.push_back({.frame = f, .value = Vec3d{row[0], row[1], row[2]}, .tangent = TangentKind::linear});
    r.keys.push_back({.frame = f, .value = Quatd::from_wxyz(row[3], row[4], row[5], row[6])});
  }
  EXPECT_EQ(scene->columns()[0].name, "ball.translation.x");
  o.translation = t;
  o.rotation = r;
  out.objects.push_back(o);
  return out;
}

// Issue 10's `convert IN.glb OUT.glb --reduce TOL` on glTF input: a per-frame glTF file (written by
// the exporter with its keys kept) is read by the glTF reader, built and exported with `reduce` —
// the path the CLI takes (apps/inbetween/cmd_convert.cpp; the CLI itself is run by
// GltfCli.ReduceGlbInput).  Measured against the input file as read (its scene's local channels,
// 4 points per frame), next to gltfpack on the same file.
TEST(Gltfpack, ReduceOnGltfInputAgainstGltfpack) {
  const bool have_gltfpack = std::system("command -v gltfpack > /dev/null 2>&1") == 0;
  struct Case {
    const char* name;
    RawScene raw;
  };
  std::printf("| per-frame glTF input | channel | keys in the file | --reduce 1e-5: keys | its max error (report) | its max error (read back) | "
              "gltfpack keys | gltfpack max error | --reduce at gltfpack's error: keys | its max error | --reduce 1e-5 --substeps 1: keys | its max error |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : {Case{"frame22 ball, 24 fps, 71 frames", baked_frame22()}, Case{"smooth, 60 fps, 10 s", baked(60, 10, 0, 1401)}}) {
    auto source = build_scene(c.raw);
    ASSERT_TRUE(source);
    auto per_frame = export_gltf(c.raw, *source);
    ASSERT_TRUE(per_frame) << per_frame.error().describe();
    for (const auto& ch : per_frame->channels) ASSERT_FALSE(ch.refitted) << ch.path;  // one key per frame, kept
    const fs::path in = test::write_test_file("per_frame.glb", per_frame->bytes);
    // What convert does with glTF input.
    auto raw = read_gltf_file(in, {.fps = c.raw.fps});
    ASSERT_TRUE(raw) << raw.error().describe();
    auto scene = build_scene(*raw);
    ASSERT_TRUE(scene) << scene.error().describe();
    const std::string object = scene->objects()[0].name;
    auto reduced = export_gltf(*raw, *scene, {.tolerance = 1e-5, .reduce = true});
    ASSERT_TRUE(reduced) << reduced.error().describe();
    const auto mine = test::read_channels(test::write_test_file("reduced.glb", reduced->bytes));
    // Checked at the frames only (the per-frame data's own points), measured at 4 points per frame.
    auto at_frames = export_gltf(*raw, *scene, {.tolerance = 1e-5, .substeps = 1, .reduce = true});
    ASSERT_TRUE(at_frames) << at_frames.error().describe();
    const auto frames_only = test::read_channels(test::write_test_file("frames.glb", at_frames->bytes));
    std::map<std::string, RefitKeys> packed;
    if (have_gltfpack) {
      const fs::path out = test::test_dir() / "gltfpack.glb";
      const std::string cmd = "gltfpack -i '" + in.string() + "' -o '" + out.string() + "' > /dev/null 2>&1";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
      packed = test::read_channels(out);
    }
    for (const GltfChannelReport& r : reduced->channels) {
      ASSERT_TRUE(r.refitted);
      EXPECT_EQ(r.reason, "reduce");
      EXPECT_EQ(r.keys_before, c.raw.objects[0].translation ? std::get<RawVec3Channel>(*c.raw.objects[0].translation).keys.size() : 0u);
      EXPECT_LT(r.keys_after, r.keys_before) << c.name << " " << r.path;
      const Row m = measure(*scene, mine, object, r.path);
      // The report's error is the one of the file read back (both: float keys, glTF's formulas,
      // the same grid); within the tolerance up to float storage (values ≤ ~10: 1e-6).
      EXPECT_NEAR(m.error, r.max_error, 1e-9) << r.path;
      EXPECT_LE(m.error, r.tolerance + 1e-6) << r.path;
      std::string gk = "-", ge = "-", ok = "-", oe = "-";
      if (have_gltfpack) {
        const Row g = measure(*scene, packed, object, r.path);
        ASSERT_GE(g.error, 0) << "gltfpack dropped " << r.path;
        gk = std::to_string(g.keys);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3g", g.error);
        ge = buf;
        // At gltfpack's own error (95 %, so float storage stays within it): relative for translation.
        double range = 1;
        if (r.path == "translation") range = r.tolerance / 1e-5;
        auto at = export_gltf(*raw, *scene, {.tolerance = 0.95 * g.error / range, .reduce = true});
        ASSERT_TRUE(at) << at.error().describe();
        const Row o = measure(*scene, test::read_channels(test::write_test_file("at_gltfpack.glb", at->bytes)), object, r.path);
        ok = std::to_string(o.keys);
        std::snprintf(buf, sizeof buf, "%.3g", o.error);
        oe = buf;
        EXPECT_LE(o.error, g.error) << c.name << " " << r.path;
        EXPECT_LE(o.keys, g.keys) << c.name << " " << r.path;
      }
      const Row f = measure(*scene, frames_only, object, r.path);
      std::printf("| %s | %s | %zu | %zu | %.3g | %.3g | %s | %s | %s | %s | %zu | %.3g |\n", c.name, r.path.c_str(), r.keys_before,
                  r.keys_after, r.max_error, m.error, gk.c_str(), ge.c_str(), ok.c_str(), oe.c_str(), f.keys, f.error);
    }
  }
}

}  // namespace
}  // namespace inbetween
