// The BVH writer (write_bvh, inbetween/io/bvh.hpp, docs/bvh.md): CMU clip → BVH → read back
// gives the same world transforms; a keyed scene with a hierarchy → BVH → read back equals the
// scene at every written frame; Euler angles continuous across frames (a 720° spin, a pass through
// gimbal lock); what BVH cannot hold is refused or noted.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "inbetween/io/bvh.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/scene/scene.hpp"
#include "support/random.hpp"

namespace {

using namespace inbetween;

constexpr double kPi = 3.14159265358979323846;
const std::filesystem::path kCmu = "/usr/share/assimp/models/BVH";

// Quaternion → intrinsic ZXY angles (Bernardes–Viollet, a few ulp) → degrees as shortest text,
// read back → radians → three axis quaternions multiplied (a few ulp each), then down a chain of
// up to 8 joints: 1e-12 rad holds it with room, and a wrong order or sign is off by ≥ 1e-3.
constexpr double kRoundTripRotationTol = 1e-12;
// World positions: that rotation error times the lengths of the chain (CMU clips: extent ≈ 100).
constexpr double kRoundTripPositionTolPerUnit = 1e-12;

Scene built(const RawScene& raw) {
  auto scene = build_scene(raw);
  EXPECT_TRUE(scene.has_value()) << (scene ? "" : scene.error().describe());
  return std::move(*scene);
}

// Largest world rotation angle and position difference over the objects of a and b (same columns)
// at frames a_first + i and i of b, for i in [0, count).
void expect_same_world(const Scene& a, double a_first, const Scene& b, std::size_t count, double extent) {
  ASSERT_EQ(a.columns().size(), b.columns().size());
  for (std::size_t i = 0; i < a.columns().size(); ++i) ASSERT_EQ(a.columns()[i].name, b.columns()[i].name);
  std::vector<double> va(a.columns().size()), vb(b.columns().size());
  double worst_rotation = 0, worst_position = 0;
  for (std::size_t f = 0; f < count; ++f) {
    a.sample(a_first + double(f), va);
    b.sample(double(f), vb);
    for (std::size_t c = 0; c + 10 <= va.size(); c += 10) {
      const Quatd qa = Quatd::from_wxyz(va[c + 3], va[c + 4], va[c + 5], va[c + 6]);
      const Quatd qb = Quatd::from_wxyz(vb[c + 3], vb[c + 4], vb[c + 5], vb[c + 6]);
      worst_rotation = std::max(worst_rotation, angle_between(qa, qb));
      for (int k = 0; k < 3; ++k) worst_position = std::max(worst_position, std::abs(va[c + k] - vb[c + k]));
    }
  }
  EXPECT_LT(worst_rotation, kRoundTripRotationTol);
  EXPECT_LT(worst_position, kRoundTripPositionTolPerUnit * extent);
  std::printf("  worst world rotation %.3g rad, position %.3g (extent %.3g)\n", worst_rotation, worst_position, extent);
}

TEST(BvhWrite, CmuClipRoundTrip) {
  if (!std::filesystem::exists(kCmu / "01_01.bvh")) GTEST_SKIP() << "assimp-testmodels not installed";
  auto raw = read_bvh_file(kCmu / "01_01.bvh");
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  const Scene scene = built(*raw);
  auto written = write_bvh(scene);
  ASSERT_TRUE(written.has_value()) << written.error().describe();
  EXPECT_TRUE(written->notes.empty());
  // The header the documentation promises.
  EXPECT_NE(written->text.find("ROOT Hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"),
            std::string::npos);
  EXPECT_NE(written->text.find("\tJOINT LHipJoint\n\t{\n"), std::string::npos);
  EXPECT_NE(written->text.find("\t\tCHANNELS 3 Zrotation Xrotation Yrotation\n"), std::string::npos);
  EXPECT_NE(written->text.find("Frames: 2752\n"), std::string::npos);
  auto back = read_bvh(written->text);
  ASSERT_TRUE(back.has_value()) << back.error().describe();
  EXPECT_NEAR(back->fps, raw->fps, raw->fps * 1e-15);
  const Scene again = built(*back);
  expect_same_world(scene, 0, again, 2752, 200);
}

// Three objects: a translated, turning root; a child whose translation is keyed; a grandchild
// with Bézier rotation keys that pass through X = 90° (the middle angle of ZXY: gimbal lock) and a
// blank in its name; the range starts at frame 1.
RawScene hierarchy_scene() {
  RawScene raw;
  raw.fps = 30;
  raw.range = {1, 25};
  RawObject root;
  root.name = "root";
  RawVec3Channel t;
  for (int k = 0; k < 3; ++k) t.keys.push_back({double(1 + 12 * k), Vec3d{double(k), 2.0 * k * k, -1.0 * k}});
  root.translation = t;
  RawQuatKeys spin;  // 720° about z in 24 frames: written Zrotation must run on continuously
  for (int k = 0; k <= 8; ++k) spin.keys.push_back({double(1 + 3 * k), Quatd::from_axis_angle(Vec3d{0, 0, 1}, k * kPi / 2)});
  root.rotation = spin;
  RawObject arm;
  arm.name = "arm";
  arm.parent = "root";
  RawVec3Channel at;
  at.keys.push_back({1, Vec3d{1, 0, 0}});
  at.keys.push_back({25, Vec3d{3, 1, 0}});
  arm.translation = at;
  arm.rotation = Quatd::from_axis_angle(Vec3d{0, 1, 0}, 0.3);
  RawObject hand;
  hand.name = "left hand";
  hand.parent = "arm";
  hand.translation = Vec3d{0, 2, 0};
  RawQuatKeys tilt;
  for (int k = 0; k < 5; ++k) {
    QuatKey<double> key;
    key.frame = 1 + 6 * k;
    key.value = Quatd::from_axis_angle(Vec3d{1, 0, 0}, (k - 2) * kPi / 4) * Quatd::from_axis_angle(Vec3d{0, 1, 0}, 0.2 * k);
    key.interpolation = QuatInterpolation::bezier;
    tilt.keys.push_back(key);
  }
  hand.rotation = tilt;
  raw.objects = {root, arm, hand};
  return raw;
}

TEST(BvhWrite, KeyedHierarchyRoundTrip) {
  const Scene scene = built(hierarchy_scene());
  auto written = write_bvh(scene);
  ASSERT_TRUE(written.has_value()) << written.error().describe();
  ASSERT_EQ(written->notes.size(), 1u);
  EXPECT_NE(written->notes[0].find("'left hand' written as joint 'left_hand'"), std::string::npos);
  // arm's translation is keyed: position channels and OFFSET 0; the hand's is not: its OFFSET.
  EXPECT_NE(written->text.find("JOINT arm\n\t{\n\t\tOFFSET 0 0 0\n\t\tCHANNELS 6 Xposition"), std::string::npos) << written->text;
  EXPECT_NE(written->text.find("JOINT left_hand\n\t\t{\n\t\t\tOFFSET 0 2 0\n\t\t\tCHANNELS 3 Zrotation"), std::string::npos);
  EXPECT_NE(written->text.find("Frames: 25\nFrame Time: 0.03333333333333333\n"), std::string::npos);
  auto back = read_bvh(written->text);
  ASSERT_TRUE(back.has_value()) << back.error().describe();
  RawScene renamed = hierarchy_scene();
  renamed.objects[2].name = "left_hand";
  expect_same_world(built(renamed), 1, built(*back), 25, 10);
  // The root's Zrotation (6th number of a line) turns on past ±180°: consecutive values differ by
  // 30° (720° / 24), never by a jump of 360°.
  std::istringstream lines(written->text.substr(written->text.find("Frame Time:")));
  std::string line;
  std::getline(lines, line);
  double previous = std::nan("");
  double total = 0;
  while (std::getline(lines, line)) {
    std::istringstream numbers(line);
    double v[4];
    for (double& x : v) numbers >> x;
    if (!std::isnan(previous)) {
      EXPECT_NEAR(std::abs(v[3] - previous), 30.0, 1e-9);
      total += v[3] - previous;
    }
    previous = v[3];
  }
  EXPECT_NEAR(std::abs(total), 720.0, 1e-9);
}

TEST(BvhWrite, RefusesWhatBvhCannotHold) {
  RawScene raw = hierarchy_scene();
  RawVec3Channel grow;
  grow.keys.push_back({1, Vec3d{1, 1, 1}});
  grow.keys.push_back({25, Vec3d{2, 2, 2}});
  raw.objects[1].scale = grow;
  auto scaled = write_bvh(built(raw));
  ASSERT_FALSE(scaled.has_value());
  EXPECT_EQ(scaled.error().code, ErrorCode::unsupported);
  EXPECT_NE(scaled.error().message.find("object 'arm' has scale"), std::string::npos) << scaled.error().message;
  EXPECT_NE(scaled.error().message.find("BVH holds no scale"), std::string::npos);
  // A constant scale of 1 is fine; a scene with no objects is refused.
  RawScene tracks_only;
  RawVectorTrack v;
  v.name = "v";
  v.keys.push_back({0, Vec4d{1, 2, 3, 0}});
  tracks_only.tracks.push_back(v);
  auto none = write_bvh(built(tracks_only));
  ASSERT_FALSE(none.has_value());
  EXPECT_NE(none.error().message.find("no objects"), std::string::npos);
  // Two roots: both written, with a note; a track beside objects: a note.
  RawScene two = hierarchy_scene();
  two.objects[1].parent.reset();
  two.tracks.push_back(v);
  auto both = write_bvh(built(two));
  ASSERT_TRUE(both.has_value()) << both.error().describe();
  EXPECT_EQ(both->notes.size(), 3u);
  auto back = read_bvh(both->text);
  ASSERT_TRUE(back.has_value()) << back.error().describe();
  ASSERT_EQ(back->objects.size(), 3u);
  EXPECT_EQ(back->objects[1].name, "arm");  // depth first: root, then arm's tree
  EXPECT_FALSE(back->objects[1].parent.has_value());
  EXPECT_EQ(back->objects[2].parent, "arm");
  ASSERT_EQ(back->skins.size(), 2u);  // one skin per ROOT
  EXPECT_EQ(back->skins[1].joints, (std::vector<std::string>{"arm", "left_hand"}));
  // A name that collides once blanks become '_'.
  RawScene clash = hierarchy_scene();
  clash.objects[1].name = "left_hand";
  clash.objects[2].parent = "left_hand";
  auto clashed = write_bvh(built(clash));
  ASSERT_FALSE(clashed.has_value());
  EXPECT_NE(clashed.error().message.find("two objects are written as joint 'left_hand'"), std::string::npos);
}

TEST(BvhWrite, FrameRangeOption) {
  const Scene scene = built(hierarchy_scene());
  auto part = write_bvh(scene, {.first = 5, .last = 9.5});
  ASSERT_TRUE(part.has_value());
  EXPECT_NE(part->text.find("Frames: 5\n"), std::string::npos);  // 5, 6, 7, 8, 9
  EXPECT_FALSE(write_bvh(scene, {.first = 9, .last = 5}).has_value());
  EXPECT_FALSE(write_bvh(scene, {.first = 0, .last = 1e300}).has_value());
  // 3 joints + 2 position sets = 5 keys a frame: the reader's limit allows kMaxBvhKeys / 5 frames.
  const double most = double(kMaxBvhKeys / 5);
  EXPECT_FALSE(write_bvh(scene, {.first = 0, .last = most}).has_value());  // most + 1 frames
  EXPECT_NE(write_bvh(scene, {.first = 0, .last = most}).error().message.find("keys the BVH reader accepts"), std::string::npos);
}

}  // namespace
