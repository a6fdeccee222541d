// The assimp reader (inbetween/io/assimp.hpp): FBX world transforms against Blender 3.4's FBX
// importer (recorded: tests/data/assimp/, tools/blender/record_assimp_fbx.py), key semantics on a
// hand-written DirectX .x file against closed forms, pre/post states and faults that no file
// format lets through assimp (zero quaternions, NaN times) on scenes built in memory, and the
// refusals of bad files.
#include <gtest/gtest.h>

#include <assimp/anim.h>
#include <assimp/scene.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "inbetween/io/assimp.hpp"
#include "inbetween/io/input.hpp"
#include "inbetween/scene/scene.hpp"
#include "io/assimp_scene.hpp"
#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using namespace inbetween;

const fs::path kModels = "/usr/share/assimp/models";

// Blender's numbers are float32; assimp's too.  The issue's bar: 1e-5 of the clip's extent for
// positions, 1e-5 rad for rotations (measured: 1.9e-7 of the extent, 4.6e-7 rad).
constexpr double kPositionTolOfExtent = 1e-5;
constexpr double kRotationTolRad = 1e-5;
// Closed forms on the hand-written .x file: float32 key values.
constexpr double kFloatTol = 1e-6;

std::map<std::string, std::size_t> column_index(const Scene& scene) {
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < scene.columns().size(); ++i) index[scene.columns()[i].name] = i;
  return index;
}

Vec3d world_position(const std::vector<double>& row, const std::map<std::string, std::size_t>& index, const std::string& name) {
  const std::size_t i = index.at(name + ".translation.x");
  return Vec3d{row[i], row[i + 1], row[i + 2]};
}

Quatd world_rotation(const std::vector<double>& row, const std::map<std::string, std::size_t>& index, const std::string& name) {
  const std::size_t i = index.at(name + ".rotation.w");
  return Quatd::from_wxyz(row[i], row[i + 1], row[i + 2], row[i + 3]);
}

double angle_between_rad(const Quatd& a, const Quatd& b) {
  const double d = std::abs(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z) / (norm(a) * norm(b));
  return 2 * std::acos(std::min(1.0, d));
}

Scene build(const RawScene& raw) {
  auto scene = build_scene(raw);
  if (!scene) ADD_FAILURE() << scene.error().describe();
  return std::move(*scene);
}

// ------------------------------------------------------------------------------ Blender FBX
TEST(AssimpRead, FbxWorldTransformsEqualBlenders) {
  const fs::path fbx = kModels / "FBX/animation_with_skeleton.fbx";
  if (!fs::exists(fbx)) GTEST_SKIP() << "assimp-testmodels is not installed";
  std::ifstream in(fs::path(INBETWEEN_SOURCE_DIR) / "tests/data/assimp/animation_with_skeleton-blender-3.4.1.json");
  ASSERT_TRUE(in);
  const nlohmann::json ref = nlohmann::json::parse(in);
  ASSERT_EQ(ref["unit_scale_factor"].get<double>(), 1.0);  // so assimp's lengths (no unit factor) are Blender's

  auto raw = read_assimp_file(fbx);
  ASSERT_TRUE(raw) << raw.error().describe();
  EXPECT_EQ(raw->fps, ref["fps"].get<double>());
  const Scene scene = build(*raw);
  const auto index = column_index(scene);
  const auto frames = ref["frames"].get<std::vector<double>>();
  EXPECT_EQ(scene.range_start(), frames.front());
  EXPECT_EQ(scene.range_end(), frames.back());

  // Extent of the clip: the largest side of the box around every joint at every frame.
  Vec3d lo{1e300, 1e300, 1e300}, hi = -lo;
  for (const auto& [name, joint] : ref["joints"].items()) {
    for (const auto& p : joint["position"]) {
      lo = Vec3d{std::min(lo.x, p[0].get<double>()), std::min(lo.y, p[1].get<double>()), std::min(lo.z, p[2].get<double>())};
      hi = Vec3d{std::max(hi.x, p[0].get<double>()), std::max(hi.y, p[1].get<double>()), std::max(hi.z, p[2].get<double>())};
    }
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  ASSERT_GT(extent, 0);
  const double tol = kPositionTolOfExtent * extent;

  std::vector<double> row(scene.columns().size());
  double worst_position = 0, worst_rotation = 0, largest_motion = 0;
  std::size_t compared = 0;
  for (const char* group : {"joints", "objects"}) {
    for (const auto& [name, entry] : ref[group].items()) {
      ASSERT_TRUE(index.count(name + ".translation.x")) << "no object " << name;
      const auto positions = entry["position"];
      const Vec3d first{positions[0][0].get<double>(), positions[0][1].get<double>(), positions[0][2].get<double>()};
      for (std::size_t f = 0; f < frames.size(); ++f) {
        scene.sample(frames[f], row);
        const Vec3d want{positions[f][0].get<double>(), positions[f][1].get<double>(), positions[f][2].get<double>()};
        const Vec3d got = world_position(row, index, name);
        const double d = norm(got - want);
        worst_position = std::max(worst_position, d);
        largest_motion = std::max(largest_motion, norm(want - first));
        EXPECT_LE(d, tol) << group << " " << name << " frame " << frames[f];
        if (entry.contains("rotation")) {
          const auto& r = entry["rotation"][f];
          const Quatd q = Quatd::from_wxyz(r[0].get<double>(), r[1].get<double>(), r[2].get<double>(), r[3].get<double>());
          const double a = angle_between_rad(world_rotation(row, index, name), q);
          worst_rotation = std::max(worst_rotation, a);
          EXPECT_LE(a, kRotationTolRad) << name << " frame " << frames[f];
        }
        ++compared;
      }
    }
  }
  // The comparison can fail: the joints move by far more than the tolerance.
  EXPECT_GT(largest_motion, 1000 * tol);
  EXPECT_EQ(ref["joints"].size(), 16u);
  std::printf("FBX vs Blender 3.4: %zu joint-frames, extent %.6g, worst position %.3g (%.3g of the extent), worst rotation %.3g rad\n",
              compared, extent, worst_position, worst_position / extent, worst_rotation);
}

// ------------------------------------------------------------------------------ .x closed forms
// Root at (1, 2, 3) with Child under it; Child keyed: rotation identity → 90° about x → 180° about
// x at ticks 0, 10, 20, position (0,0,0) → (1,2,3) at ticks 0, 20; 24 ticks per second.
const char* kXFile = R"(xof 0303txt 0032
Frame Root {
  FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 1.0,2.0,3.0,1.0;; }
  Frame Child {
    FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;; }
  }
  Frame Twin { FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;; } }
  Frame Twin { FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;; } }
}
AnimTicksPerSecond { 24; }
AnimationSet Walk {
  Animation {
    { Child }
    AnimationKey { 0; 3; 0;4;1.0,0.0,0.0,0.0;;, 10;4;0.70710678,0.70710678,0.0,0.0;;, 20;4;0.0,1.0,0.0,0.0;;; }
    AnimationKey { 2; 2; 0;3;0.0,0.0,0.0;;, 20;3;1.0,2.0,3.0;;; }
  }
}
AnimationSet Second {
  Animation {
    { Root }
    AnimationKey { 2; 2; 0;3;1.0,2.0,3.0;;, 48;3;1.0,2.0,5.0;;; }
  }
}
)";

fs::path x_file(const std::string& name, const std::string& text) { return test::write_test_file(name, text); }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// Issue 26's range rule on assimp's input as on glTF's: Collada writes key times as float text
// (box_nested_animation.dae: 0.04166662 … 1.666667 s, 40 keys on frames 1–40 at 24 fps), which
// gave a range of [0.9999989, 39.9999989] and every baked frame off by 1.1e-6.  A range end within
// its key time's float32 precision of a whole frame is that frame (src/io/key_time.hpp): [1, 40].
// A time between frames stays as it is (a key at 1.65 s: frame 39.6).
TEST(AssimpRead, ColladaRangeEndsOnWholeFramesWithinKeyTimePrecision) {
  const fs::path dae = kModels / "Collada/box_nested_animation.dae";
  if (!fs::exists(dae)) GTEST_SKIP() << dae << " is not installed (Debian assimp-testmodels)";
  auto raw = read_input_file(dae, {.fps = 24});
  ASSERT_TRUE(raw) << raw.error().describe();
  EXPECT_EQ(raw->range[0], 1.0);
  EXPECT_EQ(raw->range[1], 40.0);
  // The text with the last key moved off the frame grid keeps its fraction.
  std::ifstream in(dae);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find(" 1.666667<");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 10, " 1.65<");
  const fs::path moved = inbetween::test::write_test_file("moved.dae", text);
  auto off = read_input_file(moved, {.fps = 24});
  ASSERT_TRUE(off) << off.error().describe();
  EXPECT_EQ(off->range[0], 1.0);
  EXPECT_NEAR(off->range[1], 39.6, 1e-5);
  EXPECT_NE(off->range[1], 40.0);
}

TEST(AssimpRead, DirectXKeysInterpolateLinearlyAndBySlerp) {
  std::vector<std::string> notes;
  AssimpReadOptions options;
  options.notes = &notes;
  auto raw = read_assimp_file(x_file("walk.x", kXFile), options);
  ASSERT_TRUE(raw) << raw.error().describe();
  EXPECT_EQ(raw->fps, 24);  // AnimTicksPerSecond
  EXPECT_EQ(raw->range[0], 0);
  EXPECT_EQ(raw->range[1], 20);
  // Node names: depth first; the second "Twin" made unique with its index.
  std::vector<std::string> names;
  for (const auto& o : raw->objects) names.push_back(o.name);
  ASSERT_EQ(names.size(), 4u) << ::testing::PrintToString(names);
  EXPECT_EQ(names[0], "Root");
  EXPECT_EQ(names[1], "Child");
  EXPECT_EQ(names[2], "Twin");
  EXPECT_EQ(names[3], "Twin#3");
  EXPECT_EQ(raw->objects[1].parent, std::optional<std::string>("Root"));

  const Scene scene = build(*raw);
  const auto index = column_index(scene);
  std::vector<double> row(scene.columns().size());
  // assimp's .x importer turns the left-handed file right-handed (z negated, rotations mirrored
  // accordingly): the closed forms below are in assimp's coordinates.
  for (const double frame : {0.0, 5.0, 10.0, 15.0, 20.0}) {
    scene.sample(frame, row);
    const double u = frame / 20;
    const Vec3d want = Vec3d{1, 2, -3} + Vec3d{1, 2, -3} * u;  // Root's rest + linear key
    const Vec3d got = world_position(row, index, "Child");
    EXPECT_LE(norm(got - want), kFloatTol) << frame;
    // Slerp from identity through 90° to 180° about x at constant speed: the angle is 9° · frame.
    const Quatd q = world_rotation(row, index, "Child");
    EXPECT_NEAR(angle_between_rad(q, Quatd{}), frame * 9 * std::numbers::pi / 180, 1e-6) << frame;
    EXPECT_NEAR(std::abs(q.y) + std::abs(q.z), 0, kFloatTol) << frame;
  }
  // Outside the keys the end keys hold (DEFAULT, the importers' unset state) and a note says so.
  scene.sample(-5, row);
  EXPECT_LE(norm(world_position(row, index, "Child") - Vec3d{1, 2, -3}), kFloatTol);
  EXPECT_FALSE(notes.empty());
}

TEST(AssimpRead, AnimationByNameOrIndexAndFpsScaleAxes) {
  const fs::path file = x_file("walk.x", kXFile);
  AssimpReadOptions options;
  options.animation = "Second";
  auto by_name = read_assimp_file(file, options);
  ASSERT_TRUE(by_name) << by_name.error().describe();
  EXPECT_EQ(by_name->range[1], 48);
  options.animation = "1";
  auto by_index = read_assimp_file(file, options);
  ASSERT_TRUE(by_index);
  EXPECT_EQ(by_index->range[1], 48);
  options.animation = "Run";
  auto missing = read_assimp_file(file, options);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("\"Walk\""), std::string::npos) << missing.error().message;
  EXPECT_NE(missing.error().message.find("\"Second\""), std::string::npos);

  // --fps relabels: frame = seconds · fps.
  options = {};
  options.fps = 48;
  auto fast = read_assimp_file(file, options);
  ASSERT_TRUE(fast);
  EXPECT_EQ(fast->fps, 48);
  EXPECT_EQ(fast->range[1], 40);

  // --scale on every length, --axes as a signed permutation of the world.
  options = {};
  options.scale = 2;
  options.axes = "z-up";  // (x, y, z) → (x, −z, y)
  auto turned = read_assimp_file(file, options);
  ASSERT_TRUE(turned) << turned.error().describe();
  const Scene scene = build(*turned);
  const auto index = column_index(scene);
  std::vector<double> row(scene.columns().size());
  for (const double frame : {0.0, 7.0, 20.0}) {
    scene.sample(frame, row);
    const Vec3d file_world = (Vec3d{1, 2, -3} + Vec3d{1, 2, -3} * (frame / 20)) * 2.0;
    const Vec3d want{file_world.x, -file_world.z, file_world.y};
    EXPECT_LE(norm(world_position(row, index, "Child") - want), 2 * kFloatTol) << frame;
    // A rotation about the file's x stays about x (x is kept).
    const Quatd q = world_rotation(row, index, "Child");
    EXPECT_NEAR(angle_between_rad(q, Quatd{}), frame * 9 * std::numbers::pi / 180, 1e-6) << frame;
  }
  options.axes = "x,x,y";
  EXPECT_FALSE(read_assimp_file(file, options));
  options.axes = "x,-z,y";
  EXPECT_TRUE(read_assimp_file(file, options));
}

// ------------------------------------------------------------------------------ faults in files
TEST(AssimpRead, KeyFaultsNameTheNodeAndKey) {
  struct Case {
    std::string from, to, code_text, expect;
    ErrorCode code;
  };
  const std::vector<Case> cases = {
      {"20;3;1.0,2.0,3.0", "20;3;1.0,nan,3.0", "NaN value", "node \"Child\", position, key 1: value is not finite", ErrorCode::not_finite},
      {"20;3;1.0,2.0,3.0", "20;3;1.0,1e39,3.0", "overflowing float", "node \"Child\", position, key 1: value is not finite",
       ErrorCode::not_finite},
      {"10;4;0.70710678", "0;4;0.70710678", "repeated time", "node \"Child\", rotation, key 1: time 0 is not after",
       ErrorCode::keys_not_increasing},
      {"20;4;0.0,1.0", "5;4;0.0,1.0", "decreasing time", "node \"Child\", rotation, key 2: time 5 is not after",
       ErrorCode::keys_not_increasing},
  };
  for (const Case& c : cases) {
    auto raw = read_assimp_file(x_file("bad.x", replaced(kXFile, c.from, c.to)));
    ASSERT_FALSE(raw) << c.code_text;
    EXPECT_EQ(raw.error().code, c.code) << c.code_text;
    EXPECT_NE(raw.error().message.find(c.expect), std::string::npos) << c.code_text << ": " << raw.error().message;
    EXPECT_NE(raw.error().message.find("animation 0 \"Walk\""), std::string::npos) << raw.error().message;
  }
}

TEST(AssimpRead, UnreadableFilesAreRefused) {
  const fs::path dir = test::test_dir();
  // Missing, not a regular file (a .fbx name on /dev/zero), too large (a sparse file), empty.
  auto missing = read_assimp_file(dir / "missing.fbx");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::io);
  const fs::path zero = dir / "zero.fbx";
  fs::remove(zero);
  fs::create_symlink("/dev/zero", zero);
  auto device = read_assimp_file(zero);
  ASSERT_FALSE(device);
  EXPECT_EQ(device.error().code, ErrorCode::io);
  EXPECT_NE(device.error().message.find("not a regular file"), std::string::npos);
  const fs::path huge = dir / "huge.fbx";
  { std::ofstream(huge) << "x"; }
  fs::resize_file(huge, (std::uintmax_t(1) << 30) + 1);  // sparse: no disk, refused before reading
  auto large = read_assimp_file(huge);
  fs::remove(huge);
  ASSERT_FALSE(large);
  EXPECT_EQ(large.error().code, ErrorCode::unsupported);
  AssimpReadOptions small;
  small.max_file_bytes = 100;
  EXPECT_FALSE(read_assimp_file(x_file("walk.x", kXFile), small));
  // Binary and compressed .x: refused before assimp (its binary parser is not safe on damaged files).
  auto binary = read_assimp_file(x_file("binary.x", std::string("xof 0303bin 0032") + std::string(64, '\0')));
  ASSERT_FALSE(binary);
  EXPECT_EQ(binary.error().code, ErrorCode::unsupported);
  EXPECT_NE(binary.error().message.find("binary and compressed DirectX .x files are not read"), std::string::npos);
  EXPECT_FALSE(read_assimp(std::as_bytes(std::span<const char>("xof 0303bzip0032 ....", 21)), "x"));
  auto empty = read_assimp_file(x_file("empty.dae", ""));
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().code, ErrorCode::parse);

  // What assimp refuses: a truncated FBX and Collada file, garbage, another format under .fbx.
  const auto head_of = [](const fs::path& from, std::size_t n) {
    std::ifstream in(from, std::ios::binary);
    std::string bytes(n, '\0');
    in.read(bytes.data(), std::streamsize(n));
    bytes.resize(std::size_t(in.gcount()));
    return bytes;
  };
  std::vector<fs::path> refused = {x_file("garbage.fbx", std::string(3000, '\x7f') + "\"junk"),
                                   x_file("mesh.fbx", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                                   x_file("cut.x", std::string(kXFile).substr(0, 300))};
  if (fs::exists(kModels)) {
    refused.push_back(x_file("cut.fbx", head_of(kModels / "FBX/animation_with_skeleton.fbx", 5000)));
    refused.push_back(x_file("cut.dae", head_of(kModels / "Collada/box_nested_animation.dae", 5000)));
  }
  // Fuzzed Collada files that made assimp's mesh parser take 14 GB and 40 s: the reader drops the
  // mesh libraries, so they are refused at once (and the message quoting the file stays short).
  // And one that broke an assertion inside assimp (Debian builds it with them on: abort), now an
  // exception (src/io/assimp_read.cpp's Assimp::aiAssertViolation) and an error.
  for (const char* name : {"regression-collada-mesh-14gb.dae", "regression-collada-mesh-timeout.dae", "regression-collada-sampler-assert.dae"})
    refused.push_back(fs::path(INBETWEEN_SOURCE_DIR) / "fuzz/corpus/assimp" / name);
  for (const fs::path& file : refused) {
    const auto start = std::chrono::steady_clock::now();
    auto raw = read_assimp_file(file);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2)) << file;
    ASSERT_FALSE(raw) << file;
    EXPECT_EQ(raw.error().code, ErrorCode::parse) << file;
    EXPECT_EQ(raw.error().place(), file.string());
    EXPECT_EQ(raw.error().message.find('\n'), std::string::npos) << raw.error().message;
    EXPECT_LT(raw.error().message.size(), 300u) << raw.error().message;
  }
  // A fuzzed text .x whose mesh DeclData made assimp crash (SIGSEGV) or ask for 23 GB: the reader
  // drops Mesh objects, and what is left (the frames) reads.
  {
    const auto start = std::chrono::steady_clock::now();
    auto raw = read_assimp_file(fs::path(INBETWEEN_SOURCE_DIR) / "fuzz/corpus/assimp/regression-x-declarray-segv.x");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
    ASSERT_TRUE(raw) << raw.error().describe();
    EXPECT_EQ(raw->objects.at(0).name, "pCube1");
  }
  auto asserted = read_assimp_file(fs::path(INBETWEEN_SOURCE_DIR) / "fuzz/corpus/assimp/regression-collada-sampler-assert.dae");
  ASSERT_FALSE(asserted);
  EXPECT_NE(asserted.error().message.find("assimp's internal check failed: pos < pData.mValues.size()"), std::string::npos)
      << asserted.error().message;
}

TEST(AssimpRead, InputFormatRoutesAssimpExtensions) {
  for (const char* name : {"a.fbx", "A.FBX", "b.dae", "c.x", "d.md5anim", "e.smd", "f.b3d", "g.ms3d", "h.ase", "j.lws", "k.csm"})
    EXPECT_EQ(input_format(name), InputFormat::assimp) << name;
  EXPECT_EQ(input_format("a.bvh"), InputFormat::bvh);
  EXPECT_EQ(input_format("a.glb"), InputFormat::gltf);
  EXPECT_EQ(input_format("a.obj"), InputFormat::scene_json);
  EXPECT_EQ(input_format("a.3ds"), InputFormat::scene_json);  // not enabled (fuzz/known/assimp/)
  InputOptions options;
  options.animation = "1";
  auto raw = read_input_file(x_file("walk.x", kXFile), options);
  ASSERT_TRUE(raw) << raw.error().describe();
  EXPECT_EQ(raw->range[1], 48);
}

// ------------------------------------------------------------------------------ scenes in memory
// Root "hips" with one child "knee" animated by `channel`.
struct MemoryScene {
  aiScene scene;
  aiNodeAnim* channel = nullptr;
  MemoryScene(unsigned positions, unsigned rotations) {
    scene.mRootNode = new aiNode("hips");
    auto* knee = new aiNode("knee");
    knee->mParent = scene.mRootNode;
    knee->mTransformation = aiMatrix4x4(aiVector3D(1, 1, 1), aiQuaternion(), aiVector3D(0, 1, 0));
    scene.mRootNode->addChildren(1, &knee);
    auto* anim = new aiAnimation;
    anim->mName = aiString("bend");
    anim->mTicksPerSecond = 10;
    anim->mDuration = 10;
    channel = new aiNodeAnim;
    channel->mNodeName = aiString("knee");
    channel->mNumPositionKeys = positions;
    channel->mPositionKeys = new aiVectorKey[positions];
    for (unsigned k = 0; k < positions; ++k) channel->mPositionKeys[k] = aiVectorKey(double(k) * 5, aiVector3D(float(k), 1, 0));
    channel->mNumRotationKeys = rotations;
    channel->mRotationKeys = new aiQuatKey[rotations];
    for (unsigned k = 0; k < rotations; ++k) channel->mRotationKeys[k] = aiQuatKey(double(k) * 5, aiQuaternion(aiVector3D(0, 0, 1), float(k)));
    anim->mNumChannels = 1;
    anim->mChannels = new aiNodeAnim*[1]{channel};
    scene.mNumAnimations = 1;
    scene.mAnimations = new aiAnimation*[1]{anim};
  }
};

TEST(AssimpRead, ZeroQuaternionAndNaNTimeNameNodeAndKey) {
  {
    MemoryScene m(2, 3);
    m.channel->mRotationKeys[2].mValue = aiQuaternion(0, 0, 0, 0);
    auto raw = detail::assimp_to_raw_scene(m.scene, {});
    ASSERT_FALSE(raw);
    EXPECT_EQ(raw.error().code, ErrorCode::invalid_argument);
    EXPECT_EQ(raw.error().message, "animation 0 \"bend\", node \"knee\", rotation, key 2: zero quaternion is not a rotation");
  }
  {
    MemoryScene m(3, 1);
    m.channel->mPositionKeys[1].mTime = std::numeric_limits<double>::quiet_NaN();
    auto raw = detail::assimp_to_raw_scene(m.scene, {});
    ASSERT_FALSE(raw);
    EXPECT_EQ(raw.error().code, ErrorCode::not_finite);
    EXPECT_EQ(raw.error().message, "animation 0 \"bend\", node \"knee\", position, key 1: time is not finite");
  }
  {
    MemoryScene m(1, 2);
    m.channel->mRotationKeys[1].mValue.x = std::numeric_limits<float>::infinity();
    auto raw = detail::assimp_to_raw_scene(m.scene, {});
    ASSERT_FALSE(raw);
    EXPECT_EQ(raw.error().message, "animation 0 \"bend\", node \"knee\", rotation, key 1: value is not finite");
  }
  {
    MemoryScene m(2, 2);  // a zero mTicksPerSecond: 25 (assimp's players' default)
    m.scene.mAnimations[0]->mTicksPerSecond = 0;
    std::vector<std::string> notes;
    AssimpReadOptions options;
    options.notes = &notes;
    auto raw = detail::assimp_to_raw_scene(m.scene, options);
    ASSERT_TRUE(raw) << raw.error().describe();
    EXPECT_EQ(raw->fps, 25);
    EXPECT_EQ(raw->range[1], 5);
    ASSERT_FALSE(notes.empty());
    EXPECT_NE(notes[0].find("25 assumed"), std::string::npos);
  }
}

TEST(AssimpRead, RestMatricesThatAreNotTrsAreNotedOrRefused) {
  {
    MemoryScene m(1, 1);  // shear: x' = x + 0.5 y
    m.scene.mRootNode->mTransformation = aiMatrix4x4(1, 0.5f, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    std::vector<std::string> notes;
    AssimpReadOptions options;
    options.notes = &notes;
    auto raw = detail::assimp_to_raw_scene(m.scene, options);
    ASSERT_TRUE(raw) << raw.error().describe();
    ASSERT_FALSE(notes.empty());
    EXPECT_EQ(notes[0].rfind("node \"hips\": rest matrix is not a TRS (", 0), 0u) << notes[0];
    EXPECT_TRUE(build_scene(*raw));
  }
  {
    MemoryScene m(1, 1);  // a bone scaled to nothing (hidden): scale 0, identity rotation
    m.scene.mRootNode->mTransformation = aiMatrix4x4(aiVector3D(0, 0, 0), aiQuaternion(), aiVector3D(4, 5, 6));
    std::vector<std::string> notes;
    AssimpReadOptions options;
    options.notes = &notes;
    auto raw = detail::assimp_to_raw_scene(m.scene, options);
    ASSERT_TRUE(raw) << raw.error().describe();
    const auto& hips = raw->objects.at(0);
    EXPECT_EQ(std::get<Vec3d>(*hips.translation), (Vec3d{4, 5, 6}));
    EXPECT_EQ(std::get<Vec3d>(hips.scale), (Vec3d{0, 0, 0}));
    EXPECT_EQ(std::get<Quatd>(*hips.rotation), Quatd{});
    EXPECT_FALSE(notes.empty());
  }
  {
    MemoryScene m(1, 1);
    m.scene.mRootNode->mChildren[0]->mTransformation.a4 = std::numeric_limits<float>::quiet_NaN();
    auto raw = detail::assimp_to_raw_scene(m.scene, {});
    ASSERT_FALSE(raw);
    EXPECT_EQ(raw.error().message, "node \"knee\": rest matrix is not finite");
  }
}

TEST(AssimpRead, PrePostStatesMapOntoTrackExtends) {
  struct Case {
    aiAnimBehaviour state;
    TrackExtend extend;
    bool rotation_note;
  };
  for (const Case c : {Case{aiAnimBehaviour_DEFAULT, TrackExtend::constant, false}, Case{aiAnimBehaviour_CONSTANT, TrackExtend::constant, false},
                       Case{aiAnimBehaviour_LINEAR, TrackExtend::linear, true}, Case{aiAnimBehaviour_REPEAT, TrackExtend::repeat, true}}) {
    MemoryScene m(3, 3);
    m.channel->mPreState = c.state;
    m.channel->mPostState = c.state;
    std::vector<std::string> notes;
    AssimpReadOptions options;
    options.notes = &notes;
    auto raw = detail::assimp_to_raw_scene(m.scene, options);
    ASSERT_TRUE(raw) << raw.error().describe();
    const auto& knee = raw->objects.at(1);
    const auto& translation = std::get<RawVec3Channel>(*knee.translation);
    EXPECT_EQ(translation.before, c.extend) << int(c.state);
    EXPECT_EQ(translation.after, c.extend) << int(c.state);
    const bool noted = std::any_of(notes.begin(), notes.end(), [](const std::string& n) { return n.find("rotation keys hold") != std::string::npos; });
    EXPECT_EQ(noted, c.rotation_note) << int(c.state);
    // Sampled beyond the keys (frames 0..10 at 10 ticks per second and fps 10): x keys 0, 1, 2.
    const Scene scene = build(*raw);
    const auto index = column_index(scene);
    std::vector<double> row(scene.columns().size());
    scene.sample(15, row);
    const double x = world_position(row, index, "knee").x;
    const double want = c.extend == TrackExtend::linear ? 3.0 : c.extend == TrackExtend::repeat ? 1.0 : 2.0;
    EXPECT_NEAR(x, want, 1e-12) << int(c.state);
  }
}

}  // namespace
