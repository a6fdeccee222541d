// `inbetween bake MODEL.gltf|MODEL.glb` and `inbetween convert MODEL.glb OUT.json`: the output
// shape, convert's scene baking exactly as the glTF file, and exit code 2 with a message naming
// the index and no output file for malformed glTF.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "support/cli.hpp"
#include "support/gltf_builder.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::GltfBuilder;
using inbetween::test::run_cli;

// Two animations; node 0 (named) parent of node 1 (unnamed), node 2 a morph mesh.
GltfBuilder model() {
  GltfBuilder g;
  g.add_node({{"name", "arm"}, {"children", {1}}});
  g.add_node({{"translation", {0, 1, 0}}}, false);
  g.add_node({{"name", "face"}, {"mesh", g.add_morph_mesh(2)}});
  const int in = g.add_times({0.0f, 0.5f, 1.0f});
  g.add_channel(0, 0, "rotation", in,
                g.add_accessor(std::vector<float>{0, 0, 0, 1, 0, 0, 0.6f, 0.8f, 0, 0, 1, 0}, inbetween::test::kFloat, "VEC4"),
                "LINEAR");
  g.add_channel(0, 1, "translation", in,
                g.add_accessor(std::vector<float>{0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 2, 0,
                                                  0, 0, 0},
                               inbetween::test::kFloat, "VEC3"),
                "CUBICSPLINE");
  g.add_channel(0, 2, "weights", in, g.add_accessor(std::vector<float>{0, 1, 0.5f, 0.5f, 1, 0}, inbetween::test::kFloat, "SCALAR"),
                "STEP");
  g.doc["animations"][0]["name"] = "wave";
  g.add_channel(1, 2, "scale", in, g.add_accessor(std::vector<float>{1, 1, 1, 2, 2, 2, 3, 3, 3}, inbetween::test::kFloat, "VEC3"),
                "LINEAR");
  g.doc["animations"][1]["name"] = "grow";
  return g;
}

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

TEST(GltfCli, BakeWritesTheSceneShape) {
  const fs::path glb = inbetween::test::write_test_file("model.glb", model().glb());
  const auto r = run_cli("bake '" + glb.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(first_line(r.out),
            "frame,time,face.weights.0,face.weights.1,"
            "arm.translation.x,arm.translation.y,arm.translation.z,arm.rotation.w,arm.rotation.x,arm.rotation.y,arm.rotation.z,"
            "arm.scale.x,arm.scale.y,arm.scale.z,"
            "node1.translation.x,node1.translation.y,node1.translation.z,node1.rotation.w,node1.rotation.x,node1.rotation.y,"
            "node1.rotation.z,node1.scale.x,node1.scale.y,node1.scale.z,"
            "face.translation.x,face.translation.y,face.translation.z,face.rotation.w,face.rotation.x,face.rotation.y,"
            "face.rotation.z,face.scale.x,face.scale.y,face.scale.z");
  // Default range: the animation's 0 … 1 s at 24 fps → frames 0 … 24, time = frame / 24.
  std::size_t rows = 0;
  for (char c : r.out) rows += c == '\n';
  EXPECT_EQ(rows, 1u + 25u);
  EXPECT_NE(r.out.find("\n12,0.5,"), std::string::npos);
  // --fps and --frames, by index and by name.
  const auto a = run_cli("bake '" + glb.string() + "' --animation 1 --fps 10 --frames 0:10:5");
  const auto b = run_cli("bake '" + glb.string() + "' --animation grow --fps 10 --frames 0:10:5");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_NE(a.out.find("\n5,0.5,"), std::string::npos) << a.out;
  // JSON output has the same columns.
  const auto j = run_cli("bake '" + glb.string() + "' --format json --frames 0:0");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_NE(j.out.find("\"face.weights.1\""), std::string::npos);
}

TEST(GltfCli, ConvertedSceneBakesTheSame) {
  const fs::path dir = inbetween::test::test_dir();
  const fs::path glb = inbetween::test::write_test_file("model.glb", model().glb());
  for (const std::string extra : {"", " --fps 30", " --animation grow"}) {
    const fs::path json = dir / "scene.json";
    const auto c = run_cli("convert '" + glb.string() + "' '" + json.string() + "'" + extra);
    ASSERT_EQ(c.exit_code, 0) << c.err;
    const std::string fps = extra == " --fps 30" ? extra : "";
    const std::string anim = extra == " --animation grow" ? extra : "";
    const auto from_glb = run_cli("bake '" + glb.string() + "'" + fps + anim + " --frames -5:40:0.5");
    const auto from_json = run_cli("bake '" + json.string() + "' --frames -5:40:0.5");
    ASSERT_EQ(from_glb.exit_code, 0) << from_glb.err;
    ASSERT_EQ(from_json.exit_code, 0) << from_json.err;
    EXPECT_EQ(from_glb.out, from_json.out) << extra;
  }
}

TEST(GltfCli, MalformedGltfExitsTwoWithTheIndexAndNoOutput) {
  const fs::path dir = inbetween::test::test_dir();
  struct Case {
    std::string name, bytes, words;
  };
  std::vector<Case> cases;
  const std::string glb = model().glb();
  cases.push_back({"truncated.glb", glb.substr(0, glb.size() - 7), "not a readable glTF"});
  GltfBuilder shorter = model();
  shorter.doc["bufferViews"][5]["byteLength"] = 16;
  cases.push_back({"short.gltf", shorter.gltf_embedded(), "accessor 5"});
  GltfBuilder count = model();
  count.doc["accessors"][5]["count"] = 4;
  cases.push_back({"count.gltf", count.gltf_embedded(), "output accessor 5 has 4 elements"});
  GltfBuilder nan = model();
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.bin.data() + std::size_t(nan.doc["bufferViews"][5]["byteOffset"].get<int>()) + 8, &q, 4);
  cases.push_back({"nan.gltf", nan.gltf_embedded(), "output accessor 5, element 0 is not finite"});
  GltfBuilder times = model();
  const float back = 0.25f;
  std::memcpy(times.bin.data() + std::size_t(times.doc["bufferViews"][3]["byteOffset"].get<int>()) + 8, &back, 4);
  cases.push_back({"times.gltf", times.gltf_embedded(), "input accessor 3, key 2"});
  GltfBuilder interp = model();
  interp.doc["animations"][0]["samplers"][1]["interpolation"] = "SMOOTH";
  cases.push_back({"interp.gltf", interp.gltf_embedded(), "animation 0 \"wave\", channel 1"});
  cases.push_back({"lost.gltf", model().with_buffer("lost.bin").dump(), "lost.bin"});
  for (const Case& c : cases) {
    const fs::path in = inbetween::test::write_test_file(c.name, c.bytes);
    const fs::path out = dir / (c.name + ".csv");
    const auto r = run_cli("bake '" + in.string() + "' -o '" + out.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.words), std::string::npos) << c.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.name;
    const fs::path json = dir / (c.name + ".json");
    const auto v = run_cli("convert '" + in.string() + "' '" + json.string() + "'");
    EXPECT_EQ(v.exit_code, 2) << c.name << ": " << v.err;
    EXPECT_FALSE(fs::exists(json)) << c.name;
  }
}

}  // namespace
