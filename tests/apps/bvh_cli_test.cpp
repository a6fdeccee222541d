// `inbetween bake|convert CLIP.bvh` and `convert SCENE OUT.bvh` (docs/bvh.md): the CMU clips of
// assimp-testmodels bake with glTF's column names, the Frames: note, --scale/--axes/--fps, a
// round trip through OUT.bvh, and every malformed file: exit 2, ONE line naming the file and its
// line, no output file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::run_cli;
using inbetween::test::write_test_file;

const fs::path kCmu = "/usr/share/assimp/models/BVH";

// Values written with shortest round-trip text and read back, then composed again: a few ulp of the
// clip's extent (about 100 units) per joint of a chain.
constexpr double kCsvRoundTripTol = 1e-10;

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

std::size_t lines_of(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

std::vector<std::vector<double>> csv_rows(const std::string& csv) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::strtod(cell.c_str(), nullptr));
    rows.push_back(row);
  }
  return rows;
}

std::string header(const std::string& csv) { return csv.substr(0, csv.find('\n')); }

bool has_cmu() { return fs::exists(kCmu / "01_01.bvh"); }

TEST(BvhCli, BakeCmuClips) {
  if (!has_cmu()) GTEST_SKIP() << "assimp-testmodels not installed";
  const auto r = run_cli("bake " + q(kCmu / "01_01.bvh"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::string start =
      "frame,time,Hips.translation.x,Hips.translation.y,Hips.translation.z,Hips.rotation.w,Hips.rotation.x,"
      "Hips.rotation.y,Hips.rotation.z,Hips.scale.x,Hips.scale.y,Hips.scale.z,LHipJoint.translation.x,";
  EXPECT_EQ(header(r.out).substr(0, start.size()), start);
  EXPECT_EQ(lines_of(r.out), 1u + 2752u);  // Frames: 2752
  // Boxing_Toes.bvh: Frames: 3069 and 3070 lines: a note, 3069 rows.
  const auto b = run_cli("bake " + q(kCmu / "Boxing_Toes.bvh") + " --frames 0:5000");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(b.err, "note: " + (kCmu / "Boxing_Toes.bvh").string() +
                       ": 1 MOTION line after the 3069 frames of 'Frames:' ignored (line 3199)\n");
  const auto rows = csv_rows(b.out);
  ASSERT_EQ(rows.size(), 5001u);
  // Past the last frame (3068) values hold: the last row equals frame 3068's.
  EXPECT_EQ(std::vector<double>(rows[3068].begin() + 2, rows[3068].end()), std::vector<double>(rows[5000].begin() + 2, rows[5000].end()));
}

TEST(BvhCli, ScaleAxesAndFps) {
  if (!has_cmu()) GTEST_SKIP() << "assimp-testmodels not installed";
  const std::string clip = q(kCmu / "01_01.bvh");
  const auto plain = csv_rows(run_cli("bake " + clip + " --frames 0:2").out);
  const auto scaled = run_cli("bake " + clip + " --frames 0:2 --scale 0.01 --axes z-up");
  ASSERT_EQ(scaled.exit_code, 0) << scaled.err;
  const auto rows = csv_rows(scaled.out);
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t f = 0; f < 3; ++f) {
    // Hips.translation: (x, y, z) → 0.01 · (x, −z, y); rotation w unchanged, (x, y, z) → (x, −z, y).
    EXPECT_DOUBLE_EQ(rows[f][2], 0.01 * plain[f][2]);
    EXPECT_DOUBLE_EQ(rows[f][3], -0.01 * plain[f][4]);
    EXPECT_DOUBLE_EQ(rows[f][4], 0.01 * plain[f][3]);
    EXPECT_EQ(rows[f][5], plain[f][5]);
    EXPECT_EQ(rows[f][6], plain[f][6]);
    EXPECT_EQ(rows[f][7], -plain[f][8]);
    EXPECT_EQ(rows[f][8], plain[f][7]);
  }
  // --fps 60 halves the frame numbers of a 120 fps clip: frame 1 at 60 fps is the clip's frame 2.
  const auto at60 = csv_rows(run_cli("bake " + clip + " --frames 1:1 --fps 60").out);
  ASSERT_EQ(at60.size(), 1u);
  for (std::size_t c = 2; c < at60[0].size(); ++c) EXPECT_NEAR(at60[0][c], plain[2][c], 1e-3) << c;
  for (const char* bad : {"--axes up", "--axes x,x,z", "--animation 1"}) {
    const auto r = run_cli("bake " + clip + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(lines_of(r.err), 1u) << r.err;
  }
}

struct BadFile {
  const char* name;
  std::string text;
  const char* expected;  // the message after "inbetween: FILE: "
};

TEST(BvhCli, BadFilesExitTwoWithOneLineAndWriteNothing) {
  const std::string head = "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n}\nMOTION\n";
  std::string many = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
  for (int i = 0; i < 1000000; ++i) many += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 0 0\n}\n";
  const std::vector<BadFile> files = {
      {"truncated.bvh", head + "Frames: 3\nFrame Time: 0.1\n0 0 0\n1 1 1\n",
       "line 8: Frames: 3, but the MOTION section ends after 2 frame lines (line 11)"},
      {"few.bvh", head + "Frames: 2\nFrame Time: 0.1\n0 0 0\n1 1\n", "line 11: frame 1 has 2 numbers, the CHANNELS lines declare 3"},
      {"many.bvh", head + "Frames: 1\nFrame Time: 0.1\n0 0 0 0\n", "line 10: frame 0 has 4 numbers, the CHANNELS lines declare 3"},
      {"channel.bvh", "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Wrotation\n}\n",
       "line 5: unknown channel 'Wrotation' (Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation)"},
      {"duplicate.bvh", "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nJOINT a\n",
       "line 5: joint name 'a' is already used by the joint of line 2"},
      {"time0.bvh", head + "Frames: 1\nFrame Time: 0\n0 0 0\n", "line 9: Frame Time 0 is not a positive number of seconds"},
      {"timenan.bvh", head + "Frames: 1\nFrame Time: nan\n0 0 0\n", "line 9: Frame Time: 'nan' is not a finite number"},
      {"nan.bvh", head + "Frames: 1\nFrame Time: 0.1\n0 inf 0\n", "line 10: frame 0, value 2: 'inf' is not a finite number"},
      {"brace.bvh", "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 0\nMOTION\n", "line 6: MOTION before the '}' of the joint 'a' opened at line 2"},
      {"empty.bvh", "", "line 1: empty file: no HIERARCHY"},
      // The ROOT and 4095 JOINTs are the limit; the next JOINT (line 6 + 4 × 4095) is refused.
      {"joints.bvh", many, "line 16386: more than 4096 joints (the reader's limit)"},
  };
  for (const BadFile& f : files) {
    SCOPED_TRACE(f.name);
    const fs::path in = write_test_file(f.name, f.text);
    const fs::path out = inbetween::test::test_dir() / (std::string(f.name) + ".csv");
    const auto r = run_cli("bake " + q(in) + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "inbetween: " + in.string() + ": " + f.expected + "\n");
    EXPECT_FALSE(fs::exists(out));
    const fs::path bvh_out = inbetween::test::test_dir() / (std::string(f.name) + ".out.bvh");
    const auto c = run_cli("convert " + q(in) + " " + q(bvh_out));
    EXPECT_EQ(c.exit_code, 2);
    EXPECT_EQ(lines_of(c.err), 1u) << c.err;
    EXPECT_FALSE(fs::exists(bvh_out));
  }
}

TEST(BvhCli, ConvertClipToBvhAndBack) {
  if (!has_cmu()) GTEST_SKIP() << "assimp-testmodels not installed";
  const fs::path out = inbetween::test::test_dir() / "01_01.out.bvh";
  const auto c = run_cli("convert " + q(kCmu / "01_01.bvh") + " " + q(out));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(c.err, "");
  const auto a = run_cli("bake " + q(kCmu / "01_01.bvh"));
  const auto b = run_cli("bake " + q(out));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(header(a.out), header(b.out));
  const auto ra = csv_rows(a.out), rb = csv_rows(b.out);
  ASSERT_EQ(ra.size(), rb.size());
  double worst = 0;
  for (std::size_t f = 0; f < ra.size(); ++f) {
    ASSERT_EQ(ra[f].size(), rb[f].size());
    for (std::size_t k = 2; k < ra[f].size(); ++k) worst = std::max(worst, std::abs(ra[f][k] - rb[f][k]));
  }
  EXPECT_LT(worst, kCsvRoundTripTol);
}

TEST(BvhCli, ConvertSceneToBvh) {
  // Two keyed objects in a hierarchy: written, and baked back the same at frames 0 … 2 of the BVH
  // (the scene's frames 1 … 3).
  const fs::path scene = write_test_file("arm.json", R"({"inbetween": 1, "fps": 24, "range": [1, 3], "objects": [
    {"name": "upper arm", "translation": [0, 1, 0],
     "rotation": {"keys": [{"frame": 1, "value": [1, 0, 0, 0]}, {"frame": 3, "value": [0, 0, 0, 1]}]}},
    {"name": "fore", "parent": "upper arm", "translation": [0, 2, 0],
     "rotation": {"keys": [{"frame": 1, "value": [1, 0, 0, 0]}, {"frame": 3, "value": [0.8, 0.6, 0, 0]}]}}]})");
  const fs::path out = inbetween::test::test_dir() / "arm.bvh";
  const auto c = run_cli("convert " + q(scene) + " " + q(out));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(c.err, "note: object 'upper arm' written as joint 'upper_arm'\n");
  const auto a = csv_rows(run_cli("bake " + q(scene)).out);
  const auto b = csv_rows(run_cli("bake " + q(out)).out);
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  for (std::size_t f = 0; f < 3; ++f)
    for (std::size_t k = 2; k < a[f].size(); ++k) {
      // Quaternion columns may differ in sign only where the scene's are not sign-continuous; these are.
      EXPECT_NEAR(a[f][k], b[f][k], kCsvRoundTripTol) << "frame " << f << " column " << k;
    }
  // A scale BVH cannot hold: exit 2, one line, nothing written.
  const fs::path cube_out = inbetween::test::test_dir() / "cube.bvh";
  const auto s = run_cli("convert " + q(fs::path(INBETWEEN_SOURCE_DIR) / "examples/scenes/bouncing_cube.json") + " " + q(cube_out));
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_EQ(lines_of(s.err), 1u) << s.err;
  EXPECT_NE(s.err.find("object 'cube' has scale (0.5, 0.5, 0.5) at frame 1: BVH holds no scale"), std::string::npos) << s.err;
  EXPECT_FALSE(fs::exists(cube_out));
}

}  // namespace
