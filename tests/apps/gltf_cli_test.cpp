// `inbetween bake MODEL.gltf|MODEL.glb` and `inbetween convert MODEL.glb OUT.json`: the output
// shape, convert's scene baking exactly as the glTF file, and exit code 2 with a message naming
// the index and no output file for malformed glTF.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

// A perspective camera node is a scene camera (docs/gltf.md, "Cameras"): bake has its target
// columns, convert writes it as an own_rotation camera that bakes the same, and what the scene
// camera cannot keep (an orthographic camera, znear/aspectRatio) is a note on standard error.
TEST(GltfCli, CameraNodesBecomeSceneCamerasWithNotes) {
  const fs::path gltf = fs::path(INBETWEEN_SOURCE_DIR) / "fuzz/corpus/gltf/cameras-perspective-orthographic.gltf";
  const auto b = run_cli("bake '" + gltf.string() + "' --frames 0:24:0.5");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string header = first_line(b.out);
  EXPECT_NE(header.find("lens.scale.z,lens.target.x,lens.target.y,lens.target.z"), std::string::npos) << header;
  EXPECT_NE(header.find("wide.target.x"), std::string::npos) << header;
  EXPECT_EQ(header.find("flat.target.x"), std::string::npos) << "an orthographic camera is a plain object: " << header;
  EXPECT_NE(b.err.find("note: "), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("\"flat\": camera 1 \"ortho\" is orthographic"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("znear 0.01, zfar infinite, aspectRatio 1.5 not kept"), std::string::npos) << b.err;
  const fs::path json = inbetween::test::test_dir() / "cameras.json";
  const auto c = run_cli("convert '" + gltf.string() + "' '" + json.string() + "'");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const std::string text = inbetween::test::slurp(json);
  EXPECT_NE(text.find("\"camera\": {\"yfov_deg\": "), std::string::npos) << text;
  EXPECT_NE(text.find("\"own_rotation\": {}"), std::string::npos) << text;
  const auto from_json = run_cli("bake '" + json.string() + "' --frames 0:24:0.5");
  ASSERT_EQ(from_json.exit_code, 0) << from_json.err;
  EXPECT_EQ(from_json.out, b.out);
  EXPECT_TRUE(from_json.err.empty()) << from_json.err;
  // Back to glTF: the camera's rotation is its node's keys, written back as they are (not
  // resampled from the view), and the file bakes the same.
  const fs::path glb = inbetween::test::test_dir() / "cameras.glb";
  const auto g = run_cli("convert '" + gltf.string() + "' '" + glb.string() + "'");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  EXPECT_NE(g.err.find("lens.rotation: LINEAR, 3 keys -> 3"), std::string::npos) << g.err;
  EXPECT_NE(g.err.find("(keys kept)"), std::string::npos) << g.err;
  EXPECT_EQ(g.err.find("camera view"), std::string::npos) << g.err;
  const auto from_glb = run_cli("bake '" + glb.string() + "' --frames 0:24:0.5");
  ASSERT_EQ(from_glb.exit_code, 0) << from_glb.err;
  EXPECT_EQ(from_glb.out, b.out);
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
    // glTF → glTF (keyframe reduction) reads the same way: exit 2, the place, no file.
    const fs::path glb_out = dir / (c.name + ".out.glb");
    const auto g = run_cli("convert '" + in.string() + "' '" + glb_out.string() + "' --reduce 1e-4");
    EXPECT_EQ(g.exit_code, 2) << c.name << ": " << g.err;
    EXPECT_NE(g.err.find(c.words), std::string::npos) << c.name << ": " << g.err;
    EXPECT_FALSE(fs::exists(glb_out)) << c.name;
  }
}

// `convert IN.glb OUT.glb --reduce TOL` on a per-frame glTF file: the file is made by the tool
// itself (a scene with a linear key on every frame of a smooth motion, exported with its keys
// kept), then reduced.  The report names every channel with keys before → after and the measured
// error; bake of the reduced file agrees with bake of the per-frame file within the tolerance
// (absolute 1e-4 × the channel's range ≤ 2: 2e-4 for translations, 1e-4 rad for rotations → a
// unit quaternion component moves by at most half the angle), checked at every frame.
TEST(GltfCli, ReduceGlbInput) {
  std::string keys_t, keys_r;
  for (int f = 0; f <= 96; ++f) {
    const double x = f / 24.0;
    const double half = 0.5 * 0.8 * std::sin(x);  // rotation about y by 0.8 sin(x)
    keys_t += std::string(f ? ", " : "") + "{\"frame\": " + std::to_string(f) + ", \"value\": [" + std::to_string(std::sin(x)) +
              ", " + std::to_string(0.5 * std::cos(1.3 * x)) + ", " + std::to_string(0.2 * x) + "], \"tangent\": \"linear\"}";
    keys_r += std::string(f ? ", " : "") + "{\"frame\": " + std::to_string(f) + ", \"value\": [" + std::to_string(std::cos(half)) +
              ", 0, " + std::to_string(std::sin(half)) + ", 0]}";
  }
  const std::string scene = R"({"inbetween": 1, "fps": 24, "range": [0, 96], "objects": [{"name": "body", "translation": {"keys": [)" +
                            keys_t + R"(]}, "rotation": {"keys": [)" + keys_r + "]}}]}";
  const fs::path dir = inbetween::test::test_dir();
  const fs::path json = inbetween::test::write_test_file("per_frame.json", scene);
  const fs::path per_frame = dir / "per_frame.glb", reduced = dir / "reduced.glb";
  const auto a = run_cli("convert '" + json.string() + "' '" + per_frame.string() + "'");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_NE(a.err.find("body.translation: LINEAR, 97 keys -> 97"), std::string::npos) << a.err;
  const auto r = run_cli("convert '" + per_frame.string() + "' '" + reduced.string() + "' --reduce 1e-4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::printf("%s", r.err.c_str());
  for (const char* channel : {"body.translation: ", "body.rotation: "}) {
    const auto at = r.err.find(channel);
    ASSERT_NE(at, std::string::npos) << r.err;
    const std::string line = r.err.substr(at, r.err.find('\n', at) - at);
    EXPECT_NE(line.find("97 keys -> "), std::string::npos) << line;
    EXPECT_NE(line.find("refitted: reduce"), std::string::npos) << line;
    const std::size_t after = std::stoul(line.substr(line.find("-> ") + 3));
    EXPECT_LT(after, 97u / 2) << line;
  }
  const auto b1 = run_cli("bake '" + per_frame.string() + "'"), b2 = run_cli("bake '" + reduced.string() + "'");
  ASSERT_EQ(b1.exit_code, 0) << b1.err;
  ASSERT_EQ(b2.exit_code, 0) << b2.err;
  auto rows = [](const std::string& csv) {
    std::vector<std::vector<double>> out;
    std::size_t pos = csv.find('\n') + 1;
    while (pos < csv.size()) {
      const std::size_t end = csv.find('\n', pos);
      std::vector<double> row;
      std::size_t p = pos;
      while (p < end) {
        const std::size_t comma = std::min(csv.find(',', p), end);
        row.push_back(std::stod(csv.substr(p, comma - p)));
        p = comma + 1;
      }
      out.push_back(row);
      pos = end + 1;
    }
    return out;
  };
  const auto x = rows(b1.out), y = rows(b2.out);
  ASSERT_EQ(x.size(), 97u);
  ASSERT_EQ(y.size(), x.size());
  double worst_t = 0, worst_r = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t c = 2; c < 5; ++c) worst_t = std::max(worst_t, std::abs(x[i][c] - y[i][c]));
    double plus = 0, minus = 0;
    for (std::size_t c = 5; c < 9; ++c) {
      plus = std::max(plus, std::abs(x[i][c] - y[i][c]));
      minus = std::max(minus, std::abs(x[i][c] + y[i][c]));
    }
    worst_r = std::max(worst_r, std::min(plus, minus));
  }
  std::printf("reduced glTF input, bake against the per-frame file at every frame: translation %.3g, rotation components %.3g\n",
              worst_t, worst_r);
  EXPECT_LE(worst_t, 2e-4 + 1e-6);
  EXPECT_LE(worst_r, 0.5e-4 + 1e-6);
}


// Morph-target weights read from glTF are not exported (no meshes are kept): convert glb → glb says
// so on a note line naming the node, once, instead of dropping them silently.
TEST(GltfCli, WeightsAreNotedWhenExportingGltf) {
  const fs::path glb = inbetween::test::write_test_file("model.glb", model().glb());
  const fs::path out = inbetween::test::test_dir() / "out.glb";
  const auto r = run_cli("convert '" + glb.string() + "' '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
  const std::string note = "note: morph-target weights of node 'face' (tracks face.weights.*): not exported";
  const auto at = r.err.find(note);
  EXPECT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(note, at + 1), std::string::npos) << "one note per node:\n" << r.err;
}

}  // namespace

namespace {

// Issue 21, messages: every refusal is one line naming the place, quoting the input only as a short
// escaped excerpt.  Before: tinygltf's two lines without a place for a missing sampler input, a
// 100 KB data URI quoted whole, names with a newline splitting the line.
TEST(GltfCli, ErrorsAreOneLineWithThePlaceAndShortEscapedQuotes) {
  struct Case {
    std::string name, text, words;
  };
  const std::vector<Case> cases = {
      {"missing-input.gltf",
       R"({"asset": {"version": "2.0"}, "nodes": [{"name": "a"}], "animations": [{"channels": [{"sampler": 0,
          "target": {"node": 0, "path": "translation"}}], "samplers": [{"output": 0}]}]})",
       "missing-input.gltf: /animations/0/samplers/0/input: required member \"input\" is missing"},
      {"uri.gltf",
       R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 10, "uri": "data:application/octet-stream;base64,)" +
           std::string(100000, '!') + R"("}]})",
       "uri.gltf: "},
      {"newline.gltf",
       R"({"asset": {"version": "2.0"}, "nodes": [{"name": "a\nb"}], "animations": [{"name": "walk\nrun", "channels": [{"sampler": 0,
          "target": {"node": 0, "path": "translation"}}], "samplers": [{"input": 5, "output": 0}]}]})",
       R"(animation 0 "walk\nrun", channel 0 (node 0 "a\nb" translation))"},
  };
  for (const Case& c : cases) {
    const fs::path in = inbetween::test::write_test_file(c.name, c.text);
    const auto r = run_cli("bake '" + in.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.words), std::string::npos) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << c.name << ": not one line: " << r.err;
    EXPECT_LT(r.err.size(), 600u) << c.name << ": " << r.err.substr(0, 600);
  }
  // A name asked for with a newline is quoted escaped too.
  const fs::path nl = inbetween::test::test_dir() / "newline.gltf";
  const auto r = run_cli("bake '" + nl.string() + "' --animation \"$(printf 'no\\nsuch')\"");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(R"("no\nsuch" (the file has 1: 0 "walk\nrun"))"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

}  // namespace
