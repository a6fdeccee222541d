// Real motion capture against two recorded outside tools (issue 20, "Real data, in the tests"): the
// CMU clips of Debian's assimp-testmodels (01_01.bvh, 01_03.bvh, Boxing_Toes.bvh) read by inbetween
// (read_input_file + build_scene + Scene::sample, world TRS columns) give, for every joint and
// every frame, the world positions Blender 3.4's BVH importer gives and the world positions and
// rotations three.js's BVHLoader + AnimationMixer give.  The references are recorded in
// tests/data/bvh/ (tools/blender/record_bvh.py, tools/threejs/record_bvh.mjs; the folder's README
// says how to regenerate them and what they hold), so this runs without Blender or Node.
//
// Skips: when the clip is not installed (assimp-testmodels), and — for the inbetween side only —
// while read_input_file answers ErrorCode::unsupported for .bvh (no BVH reader yet).  Any other
// error, or a disagreement, fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inbetween/io/input.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;

// Issue 20's figures.  Positions: 1e-5 of the clip's extent (the largest side of the bounding box
// of every joint position over the clip).  Both references compute in float32 (three.js stores key
// values in Float32Arrays; Blender's mathutils and F-curves are float), and the recordings are
// float32 (rounding ≤ 6e-8 of |p| ≤ extent for these clips): the two references agree to 2.7e-7 of
// the extent, 37× inside.  Rotations: 1e-5 rad against three.js (float32 quaternion keys, ~1e-7 rad
// each, composed down chains of ≤ 9 joints).
constexpr double kPositionTolOfExtent = 1e-5;
constexpr double kRotationTolRad = 1e-5;
// inbetween composes world scale as a product of the joints' scales, all exactly 1 for BVH.
constexpr double kScaleTol = 1e-12;

const fs::path kClipDir = "/usr/share/assimp/models/BVH";
const fs::path kDataDir = fs::path(INBETWEEN_SOURCE_DIR) / "tests/data/bvh";

// A recording: its JSON header and float32 values [frame][joint][value].
struct Recording {
  nlohmann::json header;
  std::vector<std::string> joints;
  std::size_t frames = 0;
  std::size_t width = 0;  // values per joint: 3 (tx ty tz) or 7 (tx ty tz qw qx qy qz)
  std::vector<float> values;

  [[nodiscard]] const float* at(std::size_t frame, std::size_t joint) const {
    return &values[(frame * joints.size() + joint) * width];
  }
  [[nodiscard]] std::size_t joint_index(const std::string& name) const {
    return std::size_t(std::find(joints.begin(), joints.end(), name) - joints.begin());
  }
};

// Reads a recording (tests/data/bvh/README.md): one JSON line, then little-endian float32 values.
Recording read_recording(const fs::path& file) {
  static_assert(std::endian::native == std::endian::little, "the recordings are little-endian float32");
  Recording r;
  std::ifstream in(file, std::ios::binary);
  EXPECT_TRUE(in) << "cannot open " << file;
  std::string line;
  std::getline(in, line);
  r.header = nlohmann::json::parse(line);
  EXPECT_EQ(r.header.at("format"), "inbetween-bvh-reference-1") << file;
  EXPECT_EQ(r.header.at("dtype"), "float32 little-endian") << file;
  r.joints = r.header.at("joints").get<std::vector<std::string>>();
  r.frames = r.header.at("frames").get<std::size_t>();
  r.width = r.header.at("values").size();
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.size(), r.frames * r.joints.size() * r.width * sizeof(float)) << file;
  r.values.resize(bytes.size() / sizeof(float));
  std::memcpy(r.values.data(), bytes.data(), r.values.size() * sizeof(float));
  return r;
}

// Number of MOTION lines of a BVH file: the non-blank lines after "Frame Time:".
std::size_t motion_lines(const fs::path& clip) {
  std::ifstream in(clip);
  std::string line;
  while (std::getline(in, line) && line.find("Frame Time:") == std::string::npos) {
  }
  std::size_t n = 0;
  while (std::getline(in, line)) n += line.find_first_not_of(" \t\r") != std::string::npos;
  return n;
}

struct Clip {
  const char* name;
};

void PrintTo(const Clip& clip, std::ostream* os) { *os << clip.name; }

class BvhReference : public ::testing::TestWithParam<Clip> {
 protected:
  void SetUp() override {
    clip_ = kClipDir / (std::string(GetParam().name) + ".bvh");
    if (!fs::exists(clip_)) GTEST_SKIP() << clip_ << " is not installed (Debian package assimp-testmodels)";
    blender_ = read_recording(kDataDir / (std::string(GetParam().name) + ".blender.bin"));
    three_ = read_recording(kDataDir / (std::string(GetParam().name) + ".threejs.bin"));
    ASSERT_EQ(blender_.width, 3u);
    ASSERT_EQ(three_.width, 7u);
    for (const Recording* r : {&blender_, &three_}) {
      // The installed clip is the one recorded (another Debian version of the data would be).
      ASSERT_EQ(r->header.at("source_bytes").get<std::uintmax_t>(), fs::file_size(clip_))
          << r->header.at("tool") << " recorded another " << clip_.filename();
      ASSERT_EQ(r->joints.size(), three_.joints.size());
      for (const std::string& j : three_.joints) ASSERT_LT(r->joint_index(j), r->joints.size()) << j;
    }
    // The frames both references have: three.js reads the declared `Frames:` count, Blender every
    // MOTION line (Boxing_Toes.bvh declares 3 069 and has 3 070).
    declared_ = three_.header.at("declared_frames").get<std::size_t>();
    EXPECT_EQ(three_.frames, declared_);
    EXPECT_EQ(blender_.frames, motion_lines(clip_));
    frames_ = std::min(blender_.frames, three_.frames);
    // Extent: the largest bounding-box side of every joint position over the compared frames
    // (Blender's positions; three.js's give the same box within 1e-7 of it).
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (std::size_t f = 0; f < frames_; ++f) {
      for (std::size_t j = 0; j < blender_.joints.size(); ++j) {
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], double(blender_.at(f, j)[k]));
          hi[k] = std::max(hi[k], double(blender_.at(f, j)[k]));
        }
      }
    }
    extent_ = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    ASSERT_GT(extent_, 0);
  }

  fs::path clip_;
  Recording blender_, three_;
  std::size_t declared_ = 0, frames_ = 0;
  double extent_ = 0;
};

// The worst difference seen and where.
struct Worst {
  double value = 0;
  std::size_t frame = 0;
  std::string joint;
  void see(double v, std::size_t f, const std::string& j) {
    if (v > value || std::isnan(v)) *this = {v, f, j};
  }
};

std::ostream& operator<<(std::ostream& os, const Worst& w) {
  return os << w.value << " (frame " << w.frame << ", " << w.joint << ")";
}

double distance(const float* a, const double* b) {
  return std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]);
}

// Two independent references agree with each other: Blender's and three.js's world positions.
TEST_P(BvhReference, BlenderAndThreeJsPositionsAgree) {
  Worst worst;
  for (std::size_t f = 0; f < frames_; ++f) {
    for (std::size_t j = 0; j < three_.joints.size(); ++j) {
      const float* t = three_.at(f, j);
      const double p[3] = {t[0], t[1], t[2]};
      worst.see(distance(blender_.at(f, blender_.joint_index(three_.joints[j])), p) / extent_, f, three_.joints[j]);
    }
  }
  std::printf("%s: %zu frames x %zu joints, extent %.6g; Blender vs three.js positions: %.3g of the extent\n",
              GetParam().name, frames_, three_.joints.size(), extent_, worst.value);
  EXPECT_LE(worst.value, kPositionTolOfExtent) << "worst at " << worst;
}

TEST_P(BvhReference, InbetweenAgreesWithBlenderAndThreeJs) {
  Expected<RawScene> raw = read_input_file(clip_);
  if (!raw && raw.error().code == ErrorCode::unsupported) GTEST_SKIP() << "no BVH reader yet: " << raw.error().message;
  ASSERT_TRUE(raw) << raw.error().message << " at " << raw.error().place();
  Expected<Scene> scene = build_scene(*raw);
  ASSERT_TRUE(scene) << scene.error().message;

  // Frame i is MOTION line i, frames 0 … declared − 1 (extra lines ignored), fps 1 / Frame Time.
  EXPECT_EQ(scene->range_start(), 0.0);
  EXPECT_EQ(scene->range_end(), double(declared_ - 1));
  EXPECT_DOUBLE_EQ(scene->fps(), 1.0 / three_.header.at("frame_time").get<double>());
  // One object per joint (End Sites are not joints).
  EXPECT_EQ(scene->objects().size(), three_.joints.size());

  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; c < scene->columns().size(); ++c) column[scene->columns()[c].name] = c;
  std::vector<std::size_t> first;  // per three.js joint: its <joint>.translation.x column
  for (const std::string& j : three_.joints) {
    const auto it = column.find(j + ".translation.x");
    ASSERT_NE(it, column.end()) << "no column " << j << ".translation.x";
    ASSERT_EQ(column.at(j + ".rotation.w"), it->second + 3) << j;
    ASSERT_EQ(column.at(j + ".scale.x"), it->second + 7) << j;
    first.push_back(it->second);
  }

  std::vector<double> row(scene->columns().size());
  Worst pos_blender, pos_three, rot_three, scale;
  for (std::size_t f = 0; f < frames_; ++f) {
    scene->sample(double(f), row);
    for (std::size_t j = 0; j < three_.joints.size(); ++j) {
      const std::string& name = three_.joints[j];
      const double* ours = &row[first[j]];
      pos_blender.see(distance(blender_.at(f, blender_.joint_index(name)), ours) / extent_, f, name);
      pos_three.see(distance(three_.at(f, j), ours) / extent_, f, name);
      const float* t = three_.at(f, j);
      const Quatd theirs = normalized(Quatd::from_wxyz(t[3], t[4], t[5], t[6]));
      rot_three.see(angle_between(Quatd::from_wxyz(ours[3], ours[4], ours[5], ours[6]), theirs), f, name);
      for (int k = 7; k < 10; ++k) scale.see(std::abs(ours[k] - 1), f, name);
    }
  }
  std::printf("%s: inbetween vs Blender positions %.3g of the extent, vs three.js positions %.3g of the extent, "
              "vs three.js rotations %.3g rad (%zu frames x %zu joints)\n",
              GetParam().name, pos_blender.value, pos_three.value, rot_three.value, frames_, three_.joints.size());
  EXPECT_LE(pos_blender.value, kPositionTolOfExtent) << "worst at " << pos_blender;
  EXPECT_LE(pos_three.value, kPositionTolOfExtent) << "worst at " << pos_three;
  EXPECT_LE(rot_three.value, kRotationTolRad) << "worst at " << rot_three;
  EXPECT_LE(scale.value, kScaleTol) << "worst at " << scale;
}

INSTANTIATE_TEST_SUITE_P(CmuClips, BvhReference,
                         ::testing::Values(Clip{"01_01"}, Clip{"01_03"}, Clip{"Boxing_Toes"}),
                         [](const ::testing::TestParamInfo<Clip>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace inbetween
