// `inbetween curve info|sample|plot`: output shape, measured continuity in `info`, and exit code 2
// with the file and JSON pointer for bad input.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct CliRun {
  int code = 0;
  std::string out;
};

CliRun run_cli(const std::string& args) {
  const std::string cmd = std::string(INBETWEEN_CLI) + " " + args + " 2>&1";
  CliRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, ""};
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string example(const std::string& name) {
  return std::string(INBETWEEN_SOURCE_DIR) + "/examples/curves/" + name;
}

std::string temp_file(const std::string& name, const std::string& content) {
  const auto path = std::filesystem::path(INBETWEEN_BINARY_DIR) / ("curve_cli_" + name);
  std::ofstream(path) << content;
  return path.string();
}

TEST(CurveCli, InfoReportsKindSegmentsAndContinuityPerJoint) {
  const CliRun r = run_cli("curve info " + example("kochanek-bartels.json"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("kind: kochanek-bartels"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("segments: 4"), std::string::npos);
  EXPECT_NE(r.out.find("joints: 3"), std::string::npos);
  // Key 2 has continuity 0.8: a corner (C0, not G1); keys 1 and 3 are C1 (theory: S_i = E_i for c = 0).
  EXPECT_NE(r.out.find(" C0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" C1\n"), std::string::npos) << r.out;
}

TEST(CurveCli, InfoShowsC2ForNaturalAndBSpline) {
  for (const char* f : {"natural.json", "bspline-cubic.json"}) {
    const CliRun r = run_cli(std::string("curve info ") + example(f));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(" C2\n"), std::string::npos) << f << "\n" << r.out;
    EXPECT_EQ(r.out.find(" C1\n"), std::string::npos) << f << "\n" << r.out;
  }
}

TEST(CurveCli, SampleWritesHeaderAndEquallySpacedParameters) {
  const CliRun r = run_cli("curve sample " + example("bezier-path.json") + " --count 5");
  ASSERT_EQ(r.code, 0) << r.out;
  // Domain [0, 2] (two segments); the anchors are exact: P(0) = (0,0), P(1) = (4,0), P(2) = (8,0).
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "u,x,y");
  std::getline(in, line);
  EXPECT_EQ(line, "0,0,0");
  std::getline(in, line);
  EXPECT_EQ(line.substr(0, 4), "0.5,");
  int rows = 2;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 5);
}

TEST(CurveCli, SampleOneDimensionalHasOnlyX) {
  const CliRun r = run_cli("curve sample " + example("lagrange-runge.json") + " -n 3");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.substr(0, 4), "u,x\n");
}

TEST(CurveCli, PlotWritesSvg) {
  const auto out = (std::filesystem::path(INBETWEEN_BINARY_DIR) / "curve_cli_plot.svg").string();
  std::filesystem::remove(out);
  const CliRun r = run_cli("curve plot " + example("catmull-rom-centripetal.json") + " -o " + out);
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("<svg"), std::string::npos);
  EXPECT_NE(ss.str().find("<polyline"), std::string::npos);
  EXPECT_NE(ss.str().find("</svg>"), std::string::npos);
}

TEST(CurveCli, BadInputExitsTwoNamingFileAndPointer) {
  const auto f = temp_file("bad_dim.json", R"({"type": "bezier", "points": [[0, 0, 0], [1, 2, 3], [1, 2]]})");
  CliRun r = run_cli("curve info " + f);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find(f + ":/points/2: expected 3 numbers"), std::string::npos) << r.out;

  const auto g = temp_file("bad_knots.json", R"({"type": "bspline", "degree": 1, "points": [0, 1, 2], "knots": [0, 0, 2, 1, 3]})");
  r = run_cli("curve sample " + g);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find(":/knots/3"), std::string::npos) << r.out;

  r = run_cli("curve info /nonexistent/curve.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("/nonexistent/curve.json"), std::string::npos);

  r = run_cli("curve sample " + example("natural.json") + " --count 1");
  EXPECT_EQ(r.code, 2);
}

}  // namespace
