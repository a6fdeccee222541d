// The BVH reader (inbetween/io/bvh.hpp, docs/bvh.md): hand-made files with known answers (rotation
// order, position channels replacing OFFSET, Frames: rule, fps, --scale/--axes), every refused
// input with its line, the CMU clips of Debian's assimp-testmodels, and a seeded property test:
// random BVH files (every rotation order, position channels anywhere, angles past ±180°, near
// gimbal lock, numbers printed as float, double and fixed) whose world transforms from
// build_scene() + Scene::sample() equal an independent Eigen composition of the raw numbers.
#include <gtest/gtest.h>

#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <functional>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "inbetween/io/bvh.hpp"
#include "inbetween/io/input.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/scene/scene.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace {

using namespace inbetween;
using inbetween::test::Random;

constexpr double kPi = 3.14159265358979323846;
const std::filesystem::path kCmu = "/usr/share/assimp/models/BVH";

// A chain of up to 8 joints, each 3 axis rotations (degrees → radians: one rounding each) and a
// product: a few ulp per step; 1e-12 rad leaves room for angles up to 400° (7 rad, whose sine is
// known to 7 eps absolute) without hiding an error of a wrong order or sign (≥ 1e-3 rad).
constexpr double kChainRotationTol = 1e-12;
// Positions: the same relative error times the chain's lengths (offsets up to 100 units).
constexpr double kChainPositionTolPerUnit = 1e-12;

std::string text_of(std::vector<std::string> lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

// One joint with the given channels, and frame lines.
std::string one_joint(const std::string& channels, const std::vector<std::string>& frames, const std::string& frame_time = "0.04") {
  std::string s = "HIERARCHY\nROOT hip\n{\n  OFFSET 1 2 3\n  CHANNELS " + channels + "\n  End Site\n  {\n    OFFSET 0 1 0\n  }\n}\nMOTION\n";
  s += "Frames: " + std::to_string(frames.size()) + "\nFrame Time: " + frame_time + "\n";
  for (const auto& f : frames) s += f + "\n";
  return s;
}

Eigen::Matrix3d axis_matrix(char axis, double deg) {
  const Eigen::Vector3d a = axis == 'X' ? Eigen::Vector3d::UnitX() : axis == 'Y' ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
  return Eigen::AngleAxisd(deg * kPi / 180, a).toRotationMatrix();
}

Eigen::Matrix3d matrix_of(const Quatd& q) { return Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix(); }

std::size_t column(const Scene& scene, const std::string& name) {
  const auto cols = scene.columns();
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (cols[i].name == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

Scene built(const RawScene& raw) {
  auto scene = build_scene(raw);
  EXPECT_TRUE(scene.has_value()) << (scene ? "" : scene.error().describe());
  return std::move(*scene);
}

TEST(BvhRead, RotationChannelsComposeInTheListedOrder) {
  // Zrotation Xrotation Yrotation (30, 50, -70) is Rz(30)·Rx(50)·Ry(-70) on column vectors.
  auto raw = read_bvh(one_joint("3 Zrotation Xrotation Yrotation", {"30 50 -70"}));
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  ASSERT_EQ(raw->objects.size(), 1u);  // the End Site is no joint
  const RawObject& o = raw->objects[0];
  EXPECT_EQ(o.name, "hip");
  EXPECT_FALSE(o.parent);
  ASSERT_TRUE(o.rotation && std::holds_alternative<RawQuatKeys>(*o.rotation));
  const auto& keys = std::get<RawQuatKeys>(*o.rotation).keys;
  ASSERT_EQ(keys.size(), 1u);
  const Eigen::Matrix3d expected = axis_matrix('Z', 30) * axis_matrix('X', 50) * axis_matrix('Y', -70);
  EXPECT_LT((matrix_of(keys[0].value) - expected).cwiseAbs().maxCoeff(), kChainRotationTol);
  // The reversed product is a different rotation: the test would see a wrong order.
  const Eigen::Matrix3d reversed = axis_matrix('Y', -70) * axis_matrix('X', 50) * axis_matrix('Z', 30);
  EXPECT_GT((matrix_of(keys[0].value) - reversed).cwiseAbs().maxCoeff(), 0.1);
  // No position channels: the translation is the OFFSET, constant.
  ASSERT_TRUE(o.translation && std::holds_alternative<Vec3d>(*o.translation));
  EXPECT_EQ(std::get<Vec3d>(*o.translation), (Vec3d{1, 2, 3}));
}

TEST(BvhRead, PositionChannelsReplaceTheOffsetAndMissingComponentsAreZero) {
  // Blender 3.4's importer: location = channels (a missing one 0); three.js would add OFFSET (1 2 3).
  auto raw = read_bvh(one_joint("2 Yposition Xposition", {"5 7", "6 8"}));
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  const RawObject& o = raw->objects[0];
  ASSERT_TRUE(std::holds_alternative<RawVec3Channel>(*o.translation));
  const auto& keys = std::get<RawVec3Channel>(*o.translation).keys;
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].value, (Vec3d{7, 5, 0}));
  EXPECT_EQ(keys[1].value, (Vec3d{8, 6, 0}));
  EXPECT_EQ(keys[1].frame, 1.0);
  EXPECT_EQ(keys[0].tangent, TangentKind::linear);
  EXPECT_FALSE(o.rotation);  // no rotation channel: identity
}

TEST(BvhRead, FramesTimesAndFps) {
  const std::string text = one_joint("1 Xrotation", {"0", "10", "20", "30", "40"}, "0.04");
  auto raw = read_bvh(text);
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  EXPECT_DOUBLE_EQ(raw->fps, 25.0);  // 1 / Frame Time
  EXPECT_EQ(raw->range, (std::array<double, 2>{0, 4}));
  // --fps 100: frame = i × 0.04 s × 100.
  auto at100 = read_bvh(text, {.fps = 100});
  ASSERT_TRUE(at100.has_value());
  EXPECT_EQ(at100->fps, 100.0);
  EXPECT_DOUBLE_EQ(at100->range[1], 16.0);
  EXPECT_DOUBLE_EQ(std::get<RawQuatKeys>(*at100->objects[0].rotation).keys[2].frame, 8.0);
  // Between frames: slerp of the neighbours (5° at frame 0.5 about x).
  const Scene scene = built(*raw);
  std::vector<double> out(scene.columns().size());
  scene.sample(0.5, out);
  EXPECT_NEAR(out[column(scene, "hip.rotation.x")], std::sin(5 * kPi / 180 / 2), test::few_ulp<double>);
}

TEST(BvhRead, ExtraMotionLinesAreANoteAndIgnored) {
  std::string text = one_joint("1 Xrotation", {"0", "10"});
  text += "20\n\n30\n";  // two more frame lines than Frames: 2 (and a blank line, skipped)
  std::vector<std::string> notes;
  auto raw = read_bvh(text, {.notes = &notes});
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  EXPECT_EQ(std::get<RawQuatKeys>(*raw->objects[0].rotation).keys.size(), 2u);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("2 MOTION lines after the 2 frames"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("line 16–18"), std::string::npos) << notes[0];
}

TEST(BvhRead, HierarchyParentsAndNamesInFileOrder) {
  const std::string text = text_of({"HIERARCHY", "ROOT Hips {", "OFFSET 0 0 0", "CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation",
                                    "JOINT Left Up Leg", "{", "OFFSET 1 0 0", "CHANNELS 3 Xrotation Yrotation Zrotation",
                                    "End Site", "{", "OFFSET 0 -1 0", "}", "}", "JOINT Spine", "{", "OFFSET 0 1 0",
                                    "CHANNELS 0", "JOINT Head", "{", "OFFSET 0 1 0", "CHANNELS 1 Yrotation", "}", "}", "}",
                                    "MOTION", "Frames: 1", "Frame Time: 0.5", "1 2 3 4 5 6 7 8 9 10"});
  auto raw = read_bvh(text);
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  ASSERT_EQ(raw->objects.size(), 4u);
  EXPECT_EQ(raw->objects[1].name, "Left_Up_Leg");  // words joined with '_' (Blender)
  EXPECT_EQ(raw->objects[1].parent, "Hips");
  EXPECT_EQ(raw->objects[2].name, "Spine");
  EXPECT_EQ(raw->objects[2].parent, "Hips");
  EXPECT_EQ(raw->objects[3].parent, "Spine");
  EXPECT_FALSE(raw->objects[2].rotation);  // CHANNELS 0
  // One skin per ROOT, naming its joints in file order.
  ASSERT_EQ(raw->skins.size(), 1u);
  EXPECT_EQ(raw->skins[0].name, "Hips");
  EXPECT_EQ(raw->skins[0].joints, (std::vector<std::string>{"Hips", "Left_Up_Leg", "Spine", "Head"}));
  const Scene scene = built(*raw);
  // Columns as for glTF nodes: translation, rotation, scale per joint, in file order.
  EXPECT_EQ(scene.columns()[0].name, "Hips.translation.x");
  EXPECT_EQ(scene.columns()[3].name, "Hips.rotation.w");
  EXPECT_EQ(scene.columns()[7].name, "Hips.scale.x");
  EXPECT_EQ(scene.columns()[10].name, "Left_Up_Leg.translation.x");
  // Head's value is the 10th number: Yrotation 10°.
  const auto& head = std::get<RawQuatKeys>(*raw->objects[3].rotation).keys[0].value;
  EXPECT_NEAR(head.y, std::sin(10 * kPi / 180 / 2), test::few_ulp<double>);
}

TEST(BvhRead, ScaleAndAxes) {
  const std::string text = one_joint("6 Xposition Yposition Zposition Xrotation Yrotation Zrotation", {"1 2 3 0 90 0"});
  auto z_up = read_bvh(text, {.scale = 2, .axes = "z-up"});
  ASSERT_TRUE(z_up.has_value()) << z_up.error().describe();
  // (x, y, z) → (x, −z, y), times 2.
  EXPECT_EQ(std::get<RawVec3Channel>(*z_up->objects[0].translation).keys[0].value, (Vec3d{2, -6, 4}));
  // A quarter turn about file y is a quarter turn about new z: R' = M R Mᵀ.
  const Quatd q = std::get<RawQuatKeys>(*z_up->objects[0].rotation).keys[0].value;
  const Eigen::Matrix3d m = (Eigen::Matrix3d() << 1, 0, 0, 0, 0, -1, 0, 1, 0).finished();
  EXPECT_LT((matrix_of(q) - m * axis_matrix('Y', 90) * m.transpose()).cwiseAbs().maxCoeff(), test::few_ulp<double>);
  // A mirror keeps rotations proper.
  auto mirror = read_bvh(text, {.axes = "-x,y,z"});
  ASSERT_TRUE(mirror.has_value());
  const Eigen::Matrix3d mm = Eigen::Vector3d(-1, 1, 1).asDiagonal();
  const Quatd qm = std::get<RawQuatKeys>(*mirror->objects[0].rotation).keys[0].value;
  EXPECT_LT((matrix_of(qm) - mm * axis_matrix('Y', 90) * mm.transpose()).cwiseAbs().maxCoeff(), test::few_ulp<double>);
  auto scaled = read_bvh(one_joint("1 Xrotation", {"0"}), {.scale = 10});
  ASSERT_TRUE(scaled.has_value());
  EXPECT_EQ(std::get<Vec3d>(*scaled->objects[0].translation), (Vec3d{10, 20, 30}));  // OFFSET × 10
  for (const char* bad : {"up", "x,y", "x,x,y", "x,y,z,", "a,b,c"}) {
    auto r = read_bvh(text, {.axes = bad});
    ASSERT_FALSE(r.has_value()) << bad;
    EXPECT_EQ(r.error().place(), "--axes");
  }
  EXPECT_EQ(read_bvh(text, {.scale = 0}).error().place(), "--scale");
  EXPECT_EQ(read_bvh(text, {.scale = std::nan("")}).error().place(), "--scale");
}

struct BadCase {
  const char* what;
  std::string text;
  int line;
  const char* message;  // a part of the message
};

TEST(BvhRead, BadInputNamesTheLine) {
  const std::string head = "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n";
  const std::string close = "}\nMOTION\n";
  const std::vector<BadCase> cases = {
      {"empty file", "", 1, "empty file"},
      {"blank file", "\n  \n", 2, "empty file"},
      {"not BVH", "hello\n", 1, "starts with HIERARCHY"},
      {"unknown channel", "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Wrotation\n}\n", 5, "unknown channel 'Wrotation'"},
      {"channel twice", "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 2 Zrotation zrotation\n}\n", 5, "listed twice"},
      {"count disagrees", "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation\n}\n", 5, "names 2 channels"},
      {"duplicate joint", head + "JOINT b\n{\nOFFSET 0 0 0\n}\nJOINT b\n{\nOFFSET 0 0 0\n}\n" + close, 10, "already used by the joint of line 6"},
      {"missing brace", head + "JOINT b\n{\nOFFSET 0 0 0\n" + close + "Frames: 0\nFrame Time: 1\n", 10, "MOTION before the '}' of the joint 'a'"},
      {"missing open brace", "HIERARCHY\nROOT a\nOFFSET 0 0 0\n", 3, "expected '{'"},
      {"extra brace", head + "}\n" + close, 7, "without an open joint"},
      {"end of file in joint", head, 5, "missing '}'"},
      {"no OFFSET", "HIERARCHY\nROOT a\n{\nCHANNELS 0\n}\n", 5, "has no OFFSET"},
      {"OFFSET of 2", "HIERARCHY\nROOT a\n{\nOFFSET 0 0\n", 4, "OFFSET needs 3 numbers"},
      {"OFFSET nan", "HIERARCHY\nROOT a\n{\nOFFSET 0 nan 0\n", 4, "not a finite number"},
      {"no MOTION", head + "}\n", 6, "ends before MOTION"},
      {"no Frames", head + close, 7, "no 'Frames:' line"},
      {"Frames negative", head + close + "Frames: -1\nFrame Time: 1\n", 8, "not a whole number"},
      {"Frame Time 0", head + close + "Frames: 1\nFrame Time: 0\n0 0 0\n", 9, "Frame Time 0 is not a positive"},
      {"Frame Time negative", head + close + "Frames: 1\nFrame Time: -0.01\n0 0 0\n", 9, "is not a positive"},
      {"Frame Time NaN", head + close + "Frames: 1\nFrame Time: NaN\n0 0 0\n", 9, "not a finite number"},
      {"Frame Time subnormal", head + close + "Frames: 1\nFrame Time: 1e-320\n0 0 0\n", 9, "is not a positive"},
      {"truncated MOTION", head + close + "Frames: 3\nFrame Time: 0.1\n0 0 0\n1 1 1\n", 8, "ends after 2 frame lines"},
      {"too few numbers", head + close + "Frames: 2\nFrame Time: 0.1\n0 0 0\n1 1\n", 11, "frame 1 has 2 numbers"},
      {"too many numbers", head + close + "Frames: 2\nFrame Time: 0.1\n0 0 0 0\n1 1 1\n", 10, "frame 0 has 4 numbers"},
      {"NaN value", head + close + "Frames: 1\nFrame Time: 0.1\n0 nan 0\n", 10, "value 2: 'nan' is not a finite"},
      {"infinite value", head + close + "Frames: 1\nFrame Time: 0.1\n0 0 1e400\n", 10, "is not a finite number"},
      {"not a number", head + close + "Frames: 1\nFrame Time: 0.1\n0 0x1 0\n", 10, "is not a number"},
      {"too many keys", head + close + "Frames: 100000000\nFrame Time: 0.1\n", 8, "reader's limit"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.what);
    auto r = read_bvh(c.text);
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().place(), "line " + std::to_string(c.line)) << r.error().message;
    EXPECT_NE(r.error().message.find(c.message), std::string::npos) << r.error().message;
  }
}

TEST(BvhRead, AMillionJointsAreRefusedQuickly) {
  // Flat and nested: both stop at joint kMaxBvhJoints + 1, at its line, without reading the rest.
  for (const bool nested : {false, true}) {
    SCOPED_TRACE(nested ? "nested" : "flat");
    std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
    constexpr std::size_t kJoints = 1000000;
    text.reserve(kJoints * 40);
    for (std::size_t i = 0; i < kJoints; ++i) {
      text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
      if (!nested) text += "}\n";
    }
    const auto start = std::chrono::steady_clock::now();
    auto r = read_bvh(text);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().code, ErrorCode::unsupported);
    const std::size_t line = 6 + (kMaxBvhJoints - 1) * (nested ? 4 : 5);  // the (limit + 1)-th joint's JOINT line
    EXPECT_EQ(r.error().place(), "line " + std::to_string(line)) << r.error().message;
    EXPECT_LT(seconds, 1.0);  // the limit is checked as joints come, not after reading 40 MB
  }
}

TEST(BvhRead, FilesAboveTheSizeLimitAreNotRead) {
  // A sparse file one byte over the limit: refused by its size, before a byte is read.
  const auto path = std::filesystem::temp_directory_path() / ("inbetween-bvh-size-" + std::to_string(::getpid()) + ".bvh");
  { std::ofstream(path) << "HIERARCHY\n"; }
  std::filesystem::resize_file(path, kMaxBvhFileBytes + 1);
  auto r = read_bvh_file(path);
  std::filesystem::remove(path);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::unsupported);
  EXPECT_EQ(r.error().place(), path.string());
  EXPECT_FALSE(read_bvh_file(path).has_value());  // gone: cannot open
}

TEST(BvhRead, CmuClipsOfAssimpTestmodels) {
  if (!std::filesystem::exists(kCmu / "01_01.bvh")) GTEST_SKIP() << "assimp-testmodels not installed";
  struct Clip {
    const char* file;
    std::size_t frames;
    std::size_t joints;
    std::size_t notes;
  };
  // Frames and joints counted in the files (grep -c JOINT + ROOT; Frames:); Boxing_Toes.bvh has
  // one more line than its Frames: 3069.
  for (const Clip& c : {Clip{"01_01.bvh", 2752, 31, 0}, Clip{"01_03.bvh", 4511, 31, 0}, Clip{"Boxing_Toes.bvh", 3069, 21, 1}}) {
    SCOPED_TRACE(c.file);
    std::vector<std::string> notes;
    auto raw = read_input_file(kCmu / c.file, {.notes = &notes});
    ASSERT_TRUE(raw.has_value()) << raw.error().describe();
    EXPECT_EQ(raw->objects.size(), c.joints);
    EXPECT_EQ(notes.size(), c.notes);
    EXPECT_EQ(raw->range[1], double(c.frames - 1));
    const Scene scene = built(*raw);
    EXPECT_EQ(scene.columns().size(), 10 * c.joints);
  }
}

// ------------------------------------------------------------------------------ property test
struct TestJoint {
  std::string name;
  int parent = -1;
  std::array<std::string, 3> offset;   // as printed
  std::vector<std::string> channels;   // e.g. "Zrotation"
};

// A number as a BVH writer prints it: style 0 shortest double, 1 shortest float, 2 fixed 6
// decimals (CMU's), 3 exponent form.
std::string print(double v, int style) {
  char buf[64];
  switch (style) {
    case 0: return shortest_text(v);
    case 1: return shortest_text(float(v));
    case 2: std::snprintf(buf, sizeof buf, "%.6f", v); return buf;
    default: std::snprintf(buf, sizeof buf, "%.9e", v); return buf;
  }
}

TEST(BvhRead, RandomFilesMatchAnIndependentComposition) {
  Random rng(test::seed_for(20261127));
  SCOPED_TRACE(rng.trace());
  std::printf("BvhRead.RandomFilesMatchAnIndependentComposition %s\n", rng.trace().c_str());
  const std::array<std::string, 6> orders = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"};
  std::array<int, 6> order_count{};
  int position_on_non_root = 0, gimbal_frames = 0, halfway_total = 0, halfway_skipped = 0;
  double worst_rotation = 0, worst_position = 0;
  for (int file = 0; file < 60; ++file) {
    SCOPED_TRACE("file " + std::to_string(file));
    const int joint_count = rng.integer(1, 8);
    const int style = rng.integer(0, 3);
    std::vector<TestJoint> joints(static_cast<std::size_t>(joint_count));
    for (int k = 0; k < joint_count; ++k) {
      TestJoint& j = joints[std::size_t(k)];
      j.name = "j" + std::to_string(k);
      j.parent = k == 0 ? -1 : rng.integer(0, k - 1);  // file order = depth first, fixed below
      for (auto& c : j.offset) c = print(rng.uniform(-100.0, 100.0), style);  // the root's too: non-zero
      const int order = (file + k) % 6;
      for (char a : orders[std::size_t(order)]) j.channels.push_back(std::string(1, a) + "rotation");
      ++order_count[std::size_t(order)];
      if (k == 0) {
        j.channels.insert(j.channels.begin(), {"Xposition", "Yposition", "Zposition"});
      } else if (rng.integer(0, 2) == 0) {
        ++position_on_non_root;
        for (const char* p : {"Xposition", "Yposition", "Zposition"})
          if (rng.integer(0, 3) > 0) j.channels.push_back(p);
        std::shuffle(j.channels.begin(), j.channels.end(), rng.engine());  // positions anywhere in the list
      } else if (rng.integer(0, 9) == 0) {
        j.channels.clear();  // CHANNELS 0
      }
    }
    // Depth-first file order: write children inside parents; remember the order written.
    std::vector<std::vector<int>> kids(joints.size());
    for (int k = 1; k < joint_count; ++k) kids[std::size_t(joints[std::size_t(k)].parent)].push_back(k);
    std::vector<int> order;
    std::string text = "HIERARCHY\n";
    std::function<void(int, int)> emit = [&](int k, int depth) {
      const std::string in(std::size_t(depth), ' ');
      const TestJoint& j = joints[std::size_t(k)];
      order.push_back(k);
      text += in + (k == 0 ? "ROOT " : "JOINT ") + j.name + "\n" + in + "{\n" + in + " OFFSET " + j.offset[0] + " " + j.offset[1] +
              " " + j.offset[2] + "\n" + in + " CHANNELS " + std::to_string(j.channels.size());
      for (const auto& c : j.channels) text += " " + c;
      text += "\n";
      for (int c : kids[std::size_t(k)]) emit(c, depth + 1);
      if (kids[std::size_t(k)].empty()) text += in + " End Site\n" + in + " {\n" + in + "  OFFSET 0 0 1\n" + in + " }\n";
      text += in + "}\n";
    };
    emit(0, 0);
    const int frames = rng.integer(2, 6);
    text += "MOTION\nFrames: " + std::to_string(frames) + "\nFrame Time: 0.0333333\n";
    // values[f][k][c] as printed and as read by strtod (the reference's input).
    std::vector<std::vector<std::vector<double>>> values(std::size_t(frames), std::vector<std::vector<double>>(joints.size()));
    for (int f = 0; f < frames; ++f) {
      std::string line;
      for (int k : order) {
        const TestJoint& j = joints[std::size_t(k)];
        int rotation_index = 0;
        const bool near_lock = rng.integer(0, 3) == 0;
        for (const auto& c : j.channels) {
          double v;
          if (c[1] == 'p') {
            v = rng.uniform(-50.0, 50.0);
          } else {
            v = rng.uniform(-400.0, 400.0);  // past ±180° and ±360°
            if (near_lock && rotation_index == 1) {
              // Middle angle at ±90° (Tait–Bryan gimbal lock), exactly or 1e-7° off, plus turns.
              v = (rng.integer(0, 1) ? 90.0 : -90.0) + 360.0 * rng.integer(-1, 1) + (rng.integer(0, 1) ? 0.0 : 1e-7);
              ++gimbal_frames;
            }
            ++rotation_index;
          }
          const std::string s = print(v, style);
          line += s + " ";
          values[std::size_t(f)][std::size_t(k)].push_back(std::strtod(s.c_str(), nullptr));
        }
      }
      text += line + "\n";
    }
    auto raw = read_bvh(text);
    ASSERT_TRUE(raw.has_value()) << raw.error().describe() << "\n" << text;
    const Scene scene = built(*raw);
    std::vector<double> out(scene.columns().size());
    // The reference: world = parent_world · T(position or OFFSET) · R(channels in order), Eigen 4×4.
    const auto local_at = [&](int f, int k) {
      const TestJoint& j = joints[std::size_t(k)];
      Eigen::Vector3d t(std::strtod(j.offset[0].c_str(), nullptr), std::strtod(j.offset[1].c_str(), nullptr),
                        std::strtod(j.offset[2].c_str(), nullptr));
      bool has_position = false;
      for (const auto& c : j.channels) has_position |= c[1] == 'p';
      if (has_position) t.setZero();
      Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
      for (std::size_t c = 0; c < j.channels.size(); ++c) {
        const double v = values[std::size_t(f)][std::size_t(k)][c];
        const char axis = j.channels[c][0];
        if (j.channels[c][1] == 'p') t[axis - 'X'] = v;
        else r = r * axis_matrix(axis, v);
      }
      Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
      m.topLeftCorner<3, 3>() = r;
      m.topRightCorner<3, 1>() = t;
      return m;
    };
    double extent = 1;
    for (const auto& j : joints)
      for (const auto& c : j.offset) extent += std::abs(std::strtod(c.c_str(), nullptr));
    extent += 150.0 * joint_count;  // positions up to 50 per component
    for (int f = 0; f < frames; ++f) {
      scene.sample(double(f), out);
      std::vector<Eigen::Matrix4d> world(joints.size());
      for (int k : order) {
        const int p = joints[std::size_t(k)].parent;
        world[std::size_t(k)] = (p < 0 ? Eigen::Matrix4d::Identity() : world[std::size_t(p)]) * local_at(f, k);
        const std::string& name = joints[std::size_t(k)].name;
        const std::size_t c = column(scene, name + ".translation.x");
        const Eigen::Vector3d t(out[c], out[c + 1], out[c + 2]);
        const Quatd q = Quatd::from_wxyz(out[c + 3], out[c + 4], out[c + 5], out[c + 6]);
        const double rotation_error = (matrix_of(q) - world[std::size_t(k)].topLeftCorner<3, 3>()).cwiseAbs().maxCoeff();
        const double position_error = (t - world[std::size_t(k)].topRightCorner<3, 1>()).cwiseAbs().maxCoeff();
        worst_rotation = std::max(worst_rotation, rotation_error);
        worst_position = std::max(worst_position, position_error / extent);
        ASSERT_LT(rotation_error, kChainRotationTol) << name << " frame " << f << "\n" << text;
        ASSERT_LT(position_error, kChainPositionTolPerUnit * extent) << name << " frame " << f << "\n" << text;
        EXPECT_EQ(out[c + 7], 1.0);
      }
    }
    // Halfway between frames: each joint's rotation is the slerp of its neighbours (Eigen's
    // slerp, shortest arc), its position the average.
    for (int f = 0; f + 1 < frames; ++f) {
      scene.sample(f + 0.5, out);
      for (int k : order) {
        if (joints[std::size_t(k)].parent >= 0) continue;  // the root: world = local
        const Eigen::Matrix4d a = local_at(f, k), b = local_at(f + 1, k);
        const Eigen::Quaterniond qa(Eigen::Matrix3d(a.topLeftCorner<3, 3>())), qb(Eigen::Matrix3d(b.topLeftCorner<3, 3>()));
        const Eigen::Matrix3d r = qa.slerp(0.5, qb).toRotationMatrix();
        const std::size_t c = column(scene, joints[std::size_t(k)].name + ".translation.x");
        const Quatd q = Quatd::from_wxyz(out[c + 3], out[c + 4], out[c + 5], out[c + 6]);
        // Two keys 180° apart (|qa·qb| ≈ 0, which random angles past ±180° hit) have no shortest
        // arc: every half-turn path is a slerp, and the last bit of the keys picks one, differently
        // in each implementation.  Compare the rotation where the arc is unique (|qa·qb| > 1e-6).
        ++halfway_total;
        if (std::abs(qa.dot(qb)) < 1e-6) {
          ++halfway_skipped;
          continue;
        }
        ASSERT_LT((matrix_of(q) - r).cwiseAbs().maxCoeff(), kChainRotationTol) << "frame " << f + 0.5;
        const Eigen::Vector3d t = 0.5 * (a.topRightCorner<3, 1>() + b.topRightCorner<3, 1>());
        ASSERT_LT((Eigen::Vector3d(out[c], out[c + 1], out[c + 2]) - t).cwiseAbs().maxCoeff(), kChainPositionTolPerUnit * extent);
      }
    }
  }
  for (int n : order_count) EXPECT_GT(n, 0);  // every rotation order was exercised
  // The halfway check must compare nearly every pair (measured: 162 of 171, the generator's angles
  // past ±180° and at ±90° make some half turns).
  std::printf("  halfway rotations compared: %d of %d (%d half-turn pairs skipped)\n", halfway_total - halfway_skipped,
              halfway_total, halfway_skipped);
  EXPECT_GT(halfway_total, 0);
  EXPECT_LE(halfway_skipped * 10, halfway_total) << "more than 10 % of the halfway pairs skipped as half turns";
  EXPECT_GT(position_on_non_root, 0);
  EXPECT_GT(gimbal_frames, 0);
  std::printf("  worst rotation error %.3g, worst position error %.3g of the extent\n", worst_rotation, worst_position);
}

}  // namespace
