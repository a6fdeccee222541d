// Skins through glTF and the scene file: export_gltf writes a skin (joints in order, inverse bind
// matrices) that tinygltf reads back, whose matrices invert the joints' bind-pose world matrices
// (composed here independently, with Eigen, from the nodes' TRS as the file holds them), that the
// Khronos validator accepts (optional) and that three.js loads as bones (optional); the glTF
// reader and the scene file keep the skin (BVH → JSON → glb keeps it).
#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "inbetween/io/gltf.hpp"
#include "inbetween/io/gltf_write.hpp"
#include "inbetween/io/scene.hpp"
#include "inbetween/io/scene_write.hpp"
#include "support/cli.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = fs::path(INBETWEEN_SOURCE_DIR);

// A small character: hips (keyed, away from the origin, turned), spine, a scaled arm, a hand with
// a non-uniform scale, and a prop that is no joint.  The skin lists the joints out of file order.
constexpr const char* kCharacter = R"({"inbetween": 2, "fps": 30, "range": [0, 10],
  "objects": [
    {"name": "hips", "translation": {"keys": [{"frame": 0, "value": [1, 0.9, -2]}, {"frame": 10, "value": [1.5, 0.95, -1]}]},
     "rotation": {"keys": [{"frame": 0, "value": [0.9238795, 0, 0.3826834, 0]}, {"frame": 10, "value": [1, 0, 0, 0]}]}},
    {"name": "spine", "parent": "hips", "translation": [0, 0.3, 0], "rotation": [0.9659258, 0.2588190, 0, 0]},
    {"name": "arm", "parent": "spine", "translation": [0.2, 0.25, 0.05], "rotation": [0.7071068, 0, 0, -0.7071068],
     "scale": [1.5, 1.5, 1.5]},
    {"name": "hand", "parent": "arm", "translation": [0.3, 0, 0], "rotation": [0.8660254, 0, 0.5, 0], "scale": [1, 0.5, 2]},
    {"name": "prop", "parent": "hand", "translation": [0.1, 0, 0]}],
  "skins": [{"name": "body", "joints": ["spine", "hips", "arm", "hand"]}]})";

struct Loaded {
  RawScene raw;
  Scene scene;
};

Loaded load_character() {
  auto raw = read_scene_json(kCharacter, "");
  EXPECT_TRUE(raw) << raw.error().describe();
  auto scene = build_scene(*raw);
  EXPECT_TRUE(scene) << scene.error().describe();
  return {*raw, *scene};
}

tinygltf::Model read_glb(const std::string& bytes) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                          static_cast<unsigned int>(bytes.size())))
      << err;
  return model;
}

// A node's world matrix from the file's TRS, parent chain by matrix products (Eigen, double).
Eigen::Matrix4d world_of(const tinygltf::Model& m, int node) {
  std::vector<int> parent(m.nodes.size(), -1);
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (int c : m.nodes[i].children) parent[std::size_t(c)] = int(i);
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
  for (int n = node; n >= 0; n = parent[std::size_t(n)]) {
    const tinygltf::Node& g = m.nodes[std::size_t(n)];
    Eigen::Affine3d local = Eigen::Affine3d::Identity();
    if (g.translation.size() == 3) local.translate(Eigen::Vector3d(g.translation[0], g.translation[1], g.translation[2]));
    if (g.rotation.size() == 4) local.rotate(Eigen::Quaterniond(g.rotation[3], g.rotation[0], g.rotation[1], g.rotation[2]).normalized());
    if (g.scale.size() == 3) local.scale(Eigen::Vector3d(g.scale[0], g.scale[1], g.scale[2]));
    world = local.matrix() * world;
  }
  return world;
}

bool have_node_package(const fs::path& dir, const char* package) {
  return std::system("node --version > /dev/null 2>&1") == 0 && fs::exists(dir / "node_modules" / package / "package.json");
}

TEST(GltfSkin, ExportWritesJointsAndInverseBindMatrices) {
  // The inverse bind matrices are float: IBM · world is the identity to float rounding of entries
  // of size up to |world| · |IBM| (about 3 and 2 here) — 8 float ulp of that product.
  constexpr double kIdentityTol = 8 * 6 * double(std::numeric_limits<float>::epsilon());
  const Loaded s = load_character();
  auto out = export_gltf(s.raw, s.scene);
  ASSERT_TRUE(out) << out.error().describe();
  const tinygltf::Model m = read_glb(out->bytes);
  ASSERT_EQ(m.skins.size(), 1u);
  const tinygltf::Skin& skin = m.skins[0];
  EXPECT_EQ(skin.name, "body");
  std::vector<std::string> joint_names;
  for (int j : skin.joints) joint_names.push_back(m.nodes[std::size_t(j)].name);
  EXPECT_EQ(joint_names, (std::vector<std::string>{"spine", "hips", "arm", "hand"}));
  ASSERT_GE(skin.inverseBindMatrices, 0);
  const tinygltf::Accessor& a = m.accessors[std::size_t(skin.inverseBindMatrices)];
  EXPECT_EQ(a.type, TINYGLTF_TYPE_MAT4);
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  ASSERT_EQ(a.count, skin.joints.size());
  const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
  const auto* data = reinterpret_cast<const float*>(m.buffers[0].data.data() + v.byteOffset + a.byteOffset);
  double worst = 0;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    Eigen::Matrix4d ibm;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) ibm(r, c) = data[16 * j + std::size_t(4 * c + r)];  // column-major
    EXPECT_EQ(ibm.row(3), Eigen::RowVector4d(0, 0, 0, 1)) << joint_names[j];  // exact, as glTF requires
    const Eigen::Matrix4d product = ibm * world_of(m, skin.joints[j]);
    const double error = (product - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff();
    worst = std::max(worst, error);
    EXPECT_LE(error, kIdentityTol) << joint_names[j];
  }
  std::printf("[ skin ] IBM · bind world vs identity: %.3g (tolerance %.3g)\n", worst, kIdentityTol);
  // The bind pose is the nodes' TRS: the hips' keys at the first frame of the range.
  const tinygltf::Node& hips = m.nodes[std::size_t(skin.joints[1])];
  EXPECT_EQ(hips.translation, (std::vector<double>{1, 0.9, -2}));
}

TEST(GltfSkin, ReaderAndSceneFileKeepTheSkin) {
  const Loaded s = load_character();
  auto out = export_gltf(s.raw, s.scene);
  ASSERT_TRUE(out) << out.error().describe();
  auto back = read_gltf(std::as_bytes(std::span<const char>(out->bytes.data(), out->bytes.size())), "");
  ASSERT_TRUE(back) << back.error().describe();
  ASSERT_EQ(back->skins.size(), 1u);
  EXPECT_EQ(back->skins[0].name, "body");
  EXPECT_EQ(back->skins[0].joints, (std::vector<std::string>{"spine", "hips", "arm", "hand"}));
  // glTF → scene file → RawScene: the same skin.
  auto text = write_scene_json(*back);
  ASSERT_TRUE(text) << text.error().describe();
  EXPECT_NE(text->find("\"skins\""), std::string::npos);
  auto again = read_scene_json(*text, "");
  ASSERT_TRUE(again) << again.error().describe();
  ASSERT_EQ(again->skins.size(), 1u);
  EXPECT_EQ(again->skins[0].joints, back->skins[0].joints);
  EXPECT_TRUE(build_scene(*again).has_value());
}

TEST(GltfSkin, BadSkinsNameTheirPlace) {
  // Scene file: shape errors from the reader, joint errors from build_scene, at the JSON pointer.
  auto place = [](const std::string& text) {
    auto scene = parse_scene(text, "");
    EXPECT_FALSE(scene.has_value());
    return scene ? std::string("(built)") : scene.error().place() + ": " + scene.error().message;
  };
  const std::string objects = R"("objects": [{"name": "a"}, {"name": "b", "parent": "a"}])";
  EXPECT_EQ(place(R"({"inbetween": 1, )" + objects + R"(, "skins": [{"joints": ["a"]}]})").substr(0, 7), "/skins:");
  EXPECT_EQ(place(R"({"inbetween": 2, )" + objects + R"(, "skins": [{"joints": ["a", 3]}]})"),
            "/skins/0/joints/1: a joint is an object name (a string), found number");
  EXPECT_EQ(place(R"({"inbetween": 2, )" + objects + R"(, "skins": [{"joints": ["a", "c"]}]})"),
            "/skins/0/joints/1: no object named \"c\" in \"objects\"");
  EXPECT_EQ(place(R"({"inbetween": 2, )" + objects + R"(, "skins": [{"joints": ["b", "a", "b"]}]})"),
            "/skins/0/joints/2: joint \"b\" appears twice in this skin");
  EXPECT_EQ(place(R"({"inbetween": 2, )" + objects + R"(, "skins": [{"joints": ["a"], "bones": 1}]})").substr(0, 15),
            "/skins/0/bones:");
  // A joint whose bind pose has a zero scale has no inverse bind matrix: an export error at the joint.
  auto raw = read_scene_json(R"({"inbetween": 2, "objects": [{"name": "a", "scale": [1, 0, 1]}], "skins": [{"joints": ["a"]}]})", "");
  ASSERT_TRUE(raw) << raw.error().describe();
  auto scene = build_scene(*raw);
  ASSERT_TRUE(scene) << scene.error().describe();
  auto out = export_gltf(*raw, *scene);
  ASSERT_FALSE(out);
  EXPECT_EQ(json_pointer(out.error().location), "/skins/0/joints/0");
}

TEST(GltfSkin, GltfSkinErrorsNameTheSkinsJoint) {
  auto read = [](const std::string& text) { return read_gltf(std::as_bytes(std::span<const char>(text.data(), text.size())), ""); };
  const std::string head = R"({"asset": {"version": "2.0"}, "nodes": [{"name": "a", "children": [1]}, {"name": "b"}], )";
  auto outside = read(head + R"("skins": [{"name": "s", "joints": [0, 5]}]})");
  ASSERT_FALSE(outside);
  EXPECT_EQ(json_pointer(outside.error().location), "/skins/0/joints/1");
  EXPECT_NE(outside.error().message.find("joint 5 is not a node"), std::string::npos) << outside.error().message;
  // A repeated joint reads, and build_scene names the same place in the glTF file.
  auto twice = read(head + R"("skins": [{"joints": [1, 0, 1]}]})");
  ASSERT_TRUE(twice) << twice.error().describe();
  EXPECT_EQ(twice->skins[0].joints, (std::vector<std::string>{"b", "a", "b"}));
  auto built = build_scene(*twice);
  ASSERT_FALSE(built);
  EXPECT_EQ(json_pointer(built.error().location), "/skins/0/joints/2");
}

TEST(GltfSkin, PassesTheKhronosValidator) {
  const fs::path tool = kSource / "tools/gltf-validator";
  if (!have_node_package(tool, "gltf-validator")) GTEST_SKIP() << "node or gltf-validator missing (npm ci --prefix tools/gltf-validator)";
  const Loaded s = load_character();
  for (bool binary : {true, false}) {
    auto out = export_gltf(s.raw, s.scene, {.binary = binary});
    ASSERT_TRUE(out) << out.error().describe();
    const fs::path file = test::write_test_file(binary ? "character.glb" : "character.gltf", out->bytes);
    const fs::path report = test::test_dir() / "report.json";
    const std::string cmd = "node '" + (tool / "validate.mjs").string() + "' '" + file.string() + "' > '" + report.string() + "'";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << test::slurp(report);
    const auto j = nlohmann::json::parse(test::slurp(report));
    EXPECT_EQ(j["issues"]["numErrors"], 0) << j.dump(1);
    EXPECT_EQ(j["issues"]["numWarnings"], 0) << j.dump(1);
    std::printf("[ validator ] skinned character (%s): %d errors, %d warnings, %d infos\n", binary ? "glb" : "gltf",
                int(j["issues"]["numErrors"]), int(j["issues"]["numWarnings"]), int(j["issues"]["numInfos"]));
  }
}

TEST(GltfSkin, ThreeJsLoadsTheJointsAsBones) {
  // three.js's GLTFLoader makes a THREE.Bone of every node a skin names as a joint (a SkeletonHelper
  // then draws them) and an Object3D of the others.
  const fs::path tools = kSource / "tools/threejs";
  if (!have_node_package(tools, "three")) GTEST_SKIP() << "node or three.js missing (npm ci --prefix tools/threejs)";
  const Loaded s = load_character();
  auto out = export_gltf(s.raw, s.scene);
  ASSERT_TRUE(out) << out.error().describe();
  const fs::path file = test::write_test_file("character.glb", out->bytes);
  const fs::path script = test::write_test_file("bones.mjs", R"(
import { GLTFLoader } from ')" + (tools / "node_modules/three/examples/jsm/loaders/GLTFLoader.js").string() + R"(';
import { readFileSync } from 'node:fs';
globalThis.ProgressEvent ??= class extends Event { constructor(type, init = {}) { super(type); Object.assign(this, init); } };
const bytes = readFileSync(process.argv[2]);
new GLTFLoader().parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '', (gltf) => {
  const out = {};
  gltf.scene.traverse((o) => { if (o.name) out[o.name] = o.isBone === true; });
  process.stdout.write(JSON.stringify(out));
}, (e) => { console.error(String(e)); process.exit(1); });
)");
  const fs::path res = test::test_dir() / "bones.json";
  const std::string cmd = "node '" + script.string() + "' '" + file.string() + "' > '" + res.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto bones = nlohmann::json::parse(test::slurp(res));
  for (const char* joint : {"hips", "spine", "arm", "hand"}) EXPECT_EQ(bones[joint], true) << joint;
  EXPECT_EQ(bones["prop"], false);
}

}  // namespace
}  // namespace inbetween
