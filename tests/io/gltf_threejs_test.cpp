// Independent reference for glTF import as a whole: three.js's GLTFLoader + AnimationMixer
// (tools/threejs/sample_gltf_file.mjs, headless in Node) play random .glb files with every sampler
// kind on every path (translation, rotation, scale, weights), normalised-integer (weights) and
// sparse output accessors and a three-level hierarchy; the scene read by inbetween must give the same world
// transforms and weights.  Skips when `node` or the three package (`npm ci --prefix tools/threejs`,
// run by `make deps` when npm is available) is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inbetween/io/bvh.hpp"
#include "inbetween/io/gltf.hpp"
#include "inbetween/io/gltf_write.hpp"
#include "inbetween/scene/scene.hpp"
#include "support/cli.hpp"
#include "support/gltf_builder.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;

// Issue 10's figure.  three.js keeps key values and each interpolant's result in Float32Arrays
// (6e-8 relative per rounding); the inputs here are float-exact and of magnitude ≤ ~3, so the
// difference from inbetween's double evaluation is a few float roundings, well under 2e-6.
constexpr double kThreeJsTol = 2e-6;
constexpr double kFps = 24;

const char* const kSamplers[] = {"STEP", "LINEAR", "CUBICSPLINE"};

struct RandomFile {
  test::GltfBuilder g;
  double end_s = 0;
};

// Node 0 (root) → node 1 → node 2 (leaf), node 3 (root, a mesh with two morph targets).  Parents
// get uniform scale keys so that world transforms are TRS in both libraries (a non-uniform parent
// scale under a rotated child is a shear, which three.js's decompose and inbetween's compose()
// resolve differently by design).  Interpolations rotate with the round so every sampler meets
// every path.
RandomFile random_file(test::Random& rng, int round) {
  RandomFile f;
  auto& g = f.g;
  g.add_node({{"name", "root"}, {"children", {1}}});
  g.add_node({{"name", "mid"}, {"children", {2}}, {"translation", {0.5, 0, 0}}}, false);
  g.add_node({{"name", "leaf"}, {"rotation", {0, 0.6, 0, 0.8}}}, false);
  g.add_node({{"name", "morph"}, {"mesh", g.add_morph_mesh(2)}});
  auto flt = [&](double lo, double hi) { return float(rng.uniform(lo, hi)); };
  int path_index = 0;
  auto channel = [&](int node, const std::string& path) {
    const std::string interp = kSamplers[(round + node + path_index++) % 3];
    const bool cubic = interp == std::string("CUBICSPLINE");
    const int n = rng.integer(2, 6);
    std::vector<float> times;
    float t = flt(0.0, 0.3);
    for (int k = 0; k < n; ++k) {
      times.push_back(t);
      t += flt(0.1, 0.6);
    }
    f.end_s = std::max(f.end_s, double(times.back()));
    const int in = g.add_times(times);
    const int width = path == "weights" ? 2 : path == "rotation" ? 4 : 3;
    const bool uniform = path == "scale" && node < 2;
    std::vector<float> out;
    for (int k = 0; k < n; ++k) {
      for (int part = 0; part < (cubic ? 3 : 1); ++part) {
        const bool value = !cubic || part == 1;
        if (path == "rotation" && value) {
          const Quatd q = rng.rotation<double>();
          for (double c : {q.x, q.y, q.z, q.w}) out.push_back(float(c));
        } else if (uniform) {
          const float s = value ? flt(0.6, 1.4) : flt(-0.8, 0.8);
          out.insert(out.end(), {s, s, s});
        } else {
          for (int c = 0; c < width; ++c)
            out.push_back(value ? (path == "scale" ? flt(0.5, 1.5) : path == "weights" ? flt(0, 1) : flt(-1, 1)) : flt(-1, 1));
        }
      }
    }
    int acc = -1;
    // Normalised integers on weights (unsigned bytes).  Not on rotations here: a quantised
    // quaternion is not unit, and three.js composes its matrix without normalising (a scale error
    // of ~1e-5); the reader's decoding of them is checked against the specification in
    // gltf_read_test.cpp.
    if (path == "weights" && !cubic && round % 2 == 1) {
      std::vector<std::uint8_t> b;
      for (float v : out) b.push_back(std::uint8_t(std::lround(v * 255)));
      acc = g.add_accessor(b, test::kUByte, "SCALAR", true);
    } else {
      acc = g.add_accessor(out, test::kFloat, path == "weights" ? "SCALAR" : path == "rotation" ? "VEC4" : "VEC3");
      if (path == "translation" && node == 2) {
        // Sparse: the first element replaced.
        std::vector<float> sub(out.begin(), out.begin() + 3);
        for (float& v : sub) v = flt(-1, 1);
        const int idx = g.add_view(std::vector<std::uint32_t>{0}.data(), 4);
        const int val = g.add_view(sub.data(), 12);
        g.doc["accessors"][std::size_t(acc)]["sparse"] = {
            {"count", 1}, {"indices", {{"bufferView", idx}, {"componentType", test::kUInt}}}, {"values", {{"bufferView", val}}}};
      }
    }
    g.add_channel(0, node, path, in, acc, interp);
  };
  for (int node = 0; node < 4; ++node)
    for (const char* path : {"translation", "rotation", "scale"}) channel(node, path);
  channel(3, "weights");
  return f;
}

TEST(ThreeJsGltfImport, BakeMatchesThreeJsOnRandomFiles) {
  const fs::path tools = fs::path(INBETWEEN_SOURCE_DIR) / "tools/threejs";
  if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "node not installed";
  if (!fs::exists(tools / "node_modules/three/package.json")) {
    GTEST_SKIP() << "three.js not installed (npm ci --prefix tools/threejs)";
  }
  test::Random rng(test::seed_for(2026));
  SCOPED_TRACE(rng.trace());
  double worst_all = 0;
  for (int round = 0; round < 6; ++round) {
    RandomFile file = random_file(rng, round);
    const fs::path dir = test::test_dir();
    const fs::path glb = test::write_test_file("random" + std::to_string(round) + ".glb", file.g.glb());
    std::vector<double> times;
    for (int i = 0; i <= 240; ++i) times.push_back((file.end_s + 0.1) * i / 240.0);
    const fs::path req = dir / "request.json", out = dir / "three.json";
    std::ofstream(req) << nlohmann::json{{"animation", 0}, {"times", times}}.dump();
    const std::string cmd = "node '" + (tools / "sample_gltf_file.mjs").string() + "' '" + glb.string() + "' < '" +
                            req.string() + "' > '" + out.string() + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const auto three = nlohmann::json::parse(test::slurp(out));

    auto raw = read_gltf_file(glb, {.fps = kFps});
    ASSERT_TRUE(raw.has_value()) << raw.error().describe();
    auto scene = build_scene(*raw);
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    const auto cols = scene->columns();
    auto column = [&](const std::string& name) {
      for (std::size_t i = 0; i < cols.size(); ++i)
        if (cols[i].name == name) return i;
      ADD_FAILURE() << name;
      return std::size_t(0);
    };
    const char* names[] = {"root", "mid", "leaf", "morph"};
    std::vector<double> row(cols.size());
    double worst = 0;
    for (std::size_t k = 0; k < times.size(); ++k) {
      scene->sample(times[k] * kFps, row);
      for (int node = 0; node < 4; ++node) {
        const auto& theirs = three["nodes"][std::to_string(node)][k];
        const std::size_t c = column(std::string(names[node]) + ".translation.x");
        double d = 0;
        for (int i : {0, 1, 2, 7, 8, 9}) d = std::max(d, std::abs(row[c + std::size_t(i)] - theirs[std::size_t(i)].get<double>()));
        double plus = 0, minus = 0;  // a rotation is ±q
        for (int i = 3; i < 7; ++i) {
          plus = std::max(plus, std::abs(row[c + std::size_t(i)] - theirs[std::size_t(i)].get<double>()));
          minus = std::max(minus, std::abs(row[c + std::size_t(i)] + theirs[std::size_t(i)].get<double>()));
        }
        d = std::max(d, std::min(plus, minus));
        EXPECT_LT(d, kThreeJsTol) << names[node] << " round " << round << " t = " << times[k];
        worst = std::max(worst, d);
      }
      for (int w = 0; w < 2; ++w) {
        const double d = std::abs(row[column("morph.weights." + std::to_string(w))] - three["weights"]["3"][k][std::size_t(w)].get<double>());
        EXPECT_LT(d, kThreeJsTol) << "weight " << w << " round " << round << " t = " << times[k];
        worst = std::max(worst, d);
      }
    }
    std::printf("three.js glTF import round %d: worst difference %.3g over %zu times\n", round, worst, times.size());
    worst_all = std::max(worst_all, worst);
  }
  std::printf("three.js glTF import: worst difference over all rounds %.3g (tolerance %.1g)\n", worst_all, kThreeJsTol);
}

// Issue 20: `convert CLIP.bvh OUT.glb` writes the skeleton as nodes with a skin, and three.js plays
// the file as `bake` plays the clip.  A real CMU clip (Debian's assimp-testmodels) read by
// inbetween's BVH reader, exported with the default options (BVH keys are per-frame slerp and
// linear keys, which glTF LINEAR holds exactly, so no channel is refitted), loaded by GLTFLoader
// and played by AnimationMixer at every 7th frame and between frames; every joint's world transform
// equals the BVH scene's.  The only difference is float32 storage of times, offsets and keys:
// positions within 1e-5 of the clip's extent (the figure), rotations within 1e-5 rad.
TEST(ThreeJsGltfImport, CmuClipConvertedToGlbPlaysAsBakeDoes) {
  const fs::path tools = fs::path(INBETWEEN_SOURCE_DIR) / "tools/threejs";
  const fs::path clip = "/usr/share/assimp/models/BVH/01_01.bvh";
  if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "node not installed";
  if (!fs::exists(tools / "node_modules/three/package.json")) {
    GTEST_SKIP() << "three.js not installed (npm ci --prefix tools/threejs)";
  }
  if (!fs::exists(clip)) GTEST_SKIP() << clip << " missing (Debian package assimp-testmodels)";
  auto raw = read_bvh_file(clip);
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  auto scene = build_scene(*raw);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  auto out = export_gltf(*raw, *scene, {});
  ASSERT_TRUE(out.has_value()) << out.error().describe();
  for (const auto& c : out->channels) EXPECT_FALSE(c.refitted) << c.object << "." << c.path << ": " << c.reason;
  const fs::path dir = test::test_dir();
  const fs::path glb = test::write_test_file("01_01.glb", out->bytes);

  // glTF key times are float32: key i of the file is at k_i = float(i / fps), not at i / fps.  The
  // times asked of three.js are such key times (where every sampler returns its key exactly) and
  // midpoints between two of them; the BVH scene is sampled at the frame those times stand for,
  // i + (t − k_i) / (k_{i+1} − k_i), so the comparison sees the stored values, not the time rounding
  // (which alone moves a fast joint by ~1e-5 rad between frames at 120 fps).
  const double fps = scene->fps();
  auto key_time = [&](double i) { return double(float(i / fps)); };
  std::vector<double> frames, times;
  for (double f = scene->range_start(); f <= scene->range_end(); f += 7) {
    frames.push_back(f);
    times.push_back(key_time(f));
  }
  for (double f = scene->range_start(); f + 1 <= scene->range_end(); f += 61) {
    const double k0 = key_time(f), k1 = key_time(f + 1), t = 0.5 * (k0 + k1);
    frames.push_back(f + (t - k0) / (k1 - k0));
    times.push_back(t);
  }
  const fs::path req = dir / "request.json", three_out = dir / "three.json";
  std::ofstream(req) << nlohmann::json{{"animation", 0}, {"times", times}}.dump();
  const std::string cmd = "node '" + (tools / "sample_gltf_file.mjs").string() + "' '" + glb.string() + "' < '" +
                          req.string() + "' > '" + three_out.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto three = nlohmann::json::parse(test::slurp(three_out));

  // Node i of the file is object i of the scene (the writer keeps the order).
  const auto objects = scene->objects();
  ASSERT_EQ(three["nodes"].size(), objects.size());
  const auto cols = scene->columns();
  std::vector<double> row(cols.size());
  std::vector<std::array<double, 10>> world;  // every object, every frame
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (double f : frames) {
    scene->sample(f, row);
    for (std::size_t i = 0; i < objects.size(); ++i) {
      std::array<double, 10> trs{};
      for (std::size_t c = 0; c < 10; ++c) trs[c] = row[10 * i + c];  // objects' columns: 10 each, in order
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], trs[std::size_t(a)]), hi[a] = std::max(hi[a], trs[std::size_t(a)]);
      world.push_back(trs);
    }
  }
  ASSERT_EQ(cols.size(), 10 * objects.size());  // a BVH scene has only objects
  for (std::size_t i = 0; i < objects.size(); ++i) ASSERT_EQ(cols[10 * i].name, raw->objects[i].name + ".translation.x");
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  double worst_position = 0, worst_angle = 0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const auto& mine = world[k * objects.size() + i];
      const auto& theirs = three["nodes"][std::to_string(i)][k];
      double d = 0;
      for (std::size_t c = 0; c < 3; ++c) d = std::max(d, std::abs(mine[c] - theirs[c].get<double>()));
      double plus = 0, minus = 0;
      for (std::size_t c = 3; c < 7; ++c) {
        plus += (mine[c] - theirs[c].get<double>()) * (mine[c] - theirs[c].get<double>());
        minus += (mine[c] + theirs[c].get<double>()) * (mine[c] + theirs[c].get<double>());
      }
      const double angle = 4 * std::asin(std::min(1.0, std::sqrt(std::min(plus, minus)) / 2));  // |q1 − q2| = 2 sin(θ/4)
      EXPECT_LT(d, 1e-5 * extent) << "object " << i << " frame " << frames[k];
      EXPECT_LT(angle, 1e-5) << "object " << i << " frame " << frames[k];
      worst_position = std::max(worst_position, d);
      worst_angle = std::max(worst_angle, angle);
    }
  }
  std::printf("01_01.bvh → .glb in three.js: %zu frames × %zu joints, positions %.3g of the extent %.4g, rotations %.3g rad\n",
              frames.size(), objects.size(), worst_position / extent, extent, worst_angle);
}

}  // namespace
}  // namespace inbetween
