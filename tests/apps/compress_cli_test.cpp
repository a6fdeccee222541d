// `inbetween compress CLIP -o OUT.ibc`, `inbetween info OUT.ibc` and `inbetween bake OUT.ibc`
// (docs/compression.md): a small BVH compressed within --error (the measured error printed and
// stored, ≤ E), info's fields, bake of the .ibc against bake of the BVH (world space, the same
// columns, positions within E), and bad input: exit 2 with one line naming the place, no output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::run_cli;
using inbetween::test::slurp;
using inbetween::test::test_dir;
using inbetween::test::write_test_file;

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// A three-joint BVH, 24 frames of a wave.
std::string small_bvh() {
  std::ostringstream s;
  s << "HIERARCHY\nROOT hip\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
       " JOINT arm\n {\n  OFFSET 0 5 0\n  CHANNELS 3 Zrotation Yrotation Xrotation\n  JOINT hand\n  {\n   OFFSET 0 4 0\n"
       "   CHANNELS 3 Zrotation Yrotation Xrotation\n   End Site\n   {\n    OFFSET 0 1 0\n   }\n  }\n }\n}\nMOTION\nFrames: 24\n"
       "Frame Time: 0.0333333\n";
  for (int f = 0; f < 24; ++f) {
    const double t = f / 24.0;
    s << 0.5 * t << " 10 " << std::sin(3 * t) << " " << 20 * std::sin(2 * t) << " 5 0 " << 40 * std::sin(4 * t) << " 0 "
      << 10 * t << " " << -30 * t << " " << 15 * std::cos(5 * t) << " 0\n";
  }
  return s.str();
}

double field(const std::string& text, const std::string& name) {
  const auto at = text.find(name + ": ");
  if (at == std::string::npos) return NAN;
  return std::stod(text.substr(at + name.size() + 2));
}

TEST(CompressCli, CompressInfoAndBake) {
  const fs::path bvh = write_test_file("wave.bvh", small_bvh());
  const fs::path ibc = test_dir() / "wave.ibc";
  const auto run = run_cli("compress " + q(bvh) + " -o " + q(ibc) + " --error 0.002 --shell 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(field(run.out, "bytes"), double(fs::file_size(ibc)));
  EXPECT_LE(field(run.out, "measured error"), 0.002);
  const auto info = run_cli("info " + q(ibc));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(field(info.out, "bytes"), double(fs::file_size(ibc)));
  EXPECT_EQ(field(info.out, "raw float32 bytes"), 3 * 24 * 40.0);  // joints · frames · 10 floats
  EXPECT_LE(field(info.out, "measured error"), 0.002);
  EXPECT_EQ(field(info.out, "shell"), 2.0);
  EXPECT_EQ(field(info.out, "frames"), 24.0);
  EXPECT_GT(field(info.out, "bits per channel sample"), 0.0);
  // Bake both in world space: same header; every translation within E of the original (the
  // origin is one of the metric's virtual vertices).
  const auto a = run_cli("bake " + q(bvh) + " --space world");
  const auto b = run_cli("bake " + q(ibc) + " --space world");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  std::istringstream sa(a.out), sb(b.out);
  std::string la, lb;
  std::getline(sa, la), std::getline(sb, lb);
  ASSERT_EQ(la, lb);
  std::vector<std::string> names;
  {
    std::istringstream h(la);
    std::string n;
    while (std::getline(h, n, ',')) names.push_back(n);
  }
  int rows = 0;
  while (std::getline(sa, la) && std::getline(sb, lb)) {
    std::istringstream ra(la), rb(lb);
    std::string va, vb;
    for (std::size_t c = 0; std::getline(ra, va, ',') && std::getline(rb, vb, ','); ++c) {
      if (names[c].find(".translation.") != std::string::npos) EXPECT_NEAR(std::stod(va), std::stod(vb), 0.002) << names[c];
    }
    ++rows;
  }
  EXPECT_EQ(rows, 24);
}

TEST(CompressCli, BadInputExitsTwoNamingThePlace) {
  const fs::path bvh = write_test_file("wave.bvh", small_bvh());
  const fs::path ibc = test_dir() / "never.ibc";
  auto run = run_cli("compress " + q(bvh) + " -o " + q(ibc) + " --error 0");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_FALSE(fs::exists(ibc));
  const fs::path good = test_dir() / "good.ibc";
  ASSERT_EQ(run_cli("compress " + q(bvh) + " -o " + q(good)).exit_code, 0);
  std::string bytes = slurp(good);
  const fs::path cut = write_test_file("cut.ibc", bytes.substr(0, bytes.size() / 2));
  for (const std::string command : {"info ", "bake "}) {
    run = run_cli(command + q(cut));
    EXPECT_EQ(run.exit_code, 2) << command;
    EXPECT_NE(run.err.find("byte 8: file size"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("cut.ibc"), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
  bytes[0] = 'X';
  const fs::path magic = write_test_file("magic.ibc", bytes);
  run = run_cli("info " + q(magic));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("byte 0: magic"), std::string::npos) << run.err;
}

}  // namespace
