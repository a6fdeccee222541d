// `inbetween curve info|sample|plot`: output shape, measured continuity in `info`, and exit code 2
// with the file and JSON pointer for bad input.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/cli.hpp"

namespace {

using inbetween::test::CliRun;
using inbetween::test::run_cli;
namespace fs = std::filesystem;

std::string example(const std::string& name) {
  return std::string(INBETWEEN_SOURCE_DIR) + "/examples/curves/" + name;
}

std::string temp_file(const std::string& name, const std::string& content) {
  return inbetween::test::write_test_file(name, content).string();
}

TEST(CurveCli, InfoReportsKindSegmentsAndContinuityPerJoint) {
  const CliRun r = run_cli("curve info " + example("kochanek-bartels.json"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
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
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find(" C2\n"), std::string::npos) << f << "\n" << r.out;
    EXPECT_EQ(r.out.find(" C1\n"), std::string::npos) << f << "\n" << r.out;
  }
}

// The params and closed members reach the CLI: a closed natural spline at uneven params reports its
// seam as a joint and C² everywhere (periodic C² by construction), and samples over [t_0, t_n] start
// and end at the first point.
TEST(CurveCli, ClosedNaturalWithParamsIsC2WithTheSeam) {
  const std::string f = temp_file("closed_params.json",
                                  R"({"type": "natural", "points": [[1,0],[0,1],[-1,0],[0,-1]], "closed": true,
                                      "params": [0, 1, 2.5, 3, 4]})");
  const CliRun info = run_cli("curve info " + f);
  ASSERT_EQ(info.exit_code, 0) << info.out << info.err;
  EXPECT_NE(info.out.find("segments: 4"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("joints: 4"), std::string::npos) << info.out;
  EXPECT_EQ(info.out.find(" C1\n"), std::string::npos) << info.out;
  EXPECT_EQ(info.out.find(" C0\n"), std::string::npos) << info.out;
  const CliRun s = run_cli("curve sample " + f + " --count 3");
  ASSERT_EQ(s.exit_code, 0) << s.out << s.err;
  std::istringstream in(s.out);
  std::string line, first, last;
  std::getline(in, line);
  EXPECT_EQ(line, "u,x,y");
  std::getline(in, first);
  while (std::getline(in, line)) last = line;
  EXPECT_EQ(first, "0,1,0");
  // The curve closes at t_4 = 4 on the first point (1, 0): the Horner sum of the closing segment at
  // v = 1 rounds, by at most a few ulp of its O(1) coefficients.
  double u = 0, x = 0, y = 0;
  ASSERT_EQ(std::sscanf(last.c_str(), "%lf,%lf,%lf", &u, &x, &y), 3) << last;
  EXPECT_EQ(u, 4.0);
  EXPECT_NEAR(x, 1.0, 1e-14);
  EXPECT_NEAR(y, 0.0, 1e-14);
  const CliRun bad = run_cli("curve info " + temp_file("bad_params.json", R"({"type": "hermite", "points": [0, 1], "tangents": [1, 1], "params": [1, 0]})"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("/params/1"), std::string::npos) << bad.err;
}

TEST(CurveCli, SampleWritesHeaderAndEquallySpacedParameters) {
  const CliRun r = run_cli("curve sample " + example("bezier-path.json") + " --count 5");
  ASSERT_EQ(r.exit_code, 0) << r.out;
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
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.substr(0, 4), "u,x\n");
}

TEST(CurveCli, PlotWritesSvg) {
  const auto out = (inbetween::test::test_dir() / "plot.svg").string();
  std::filesystem::remove(out);
  const CliRun r = run_cli("curve plot " + example("catmull-rom-centripetal.json") + " -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("<svg"), std::string::npos);
  EXPECT_NE(ss.str().find("<polyline class=\"curve\""), std::string::npos);
  EXPECT_NE(ss.str().find("</svg>"), std::string::npos);
  // Axes with ticks and labels, as `inbetween plot` draws them (read back in curve_plot_cli_test.cpp).
  EXPECT_NE(ss.str().find("<g class=\"tick-x\">"), std::string::npos);
  EXPECT_NE(ss.str().find("<g class=\"tick-y\">"), std::string::npos);
  EXPECT_NE(ss.str().find("class=\"axis-label\""), std::string::npos);
}

TEST(CurveCli, BadInputExitsTwoNamingFileAndPointer) {
  const auto f = temp_file("bad_dim.json", R"({"type": "bezier", "points": [[0, 0, 0], [1, 2, 3], [1, 2]]})");
  CliRun r = run_cli("curve info " + f);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(f + ":/points/2: expected 3 numbers"), std::string::npos) << r.err;

  const auto g = temp_file("bad_knots.json", R"({"type": "bspline", "degree": 1, "points": [0, 1, 2], "knots": [0, 0, 2, 1, 3]})");
  r = run_cli("curve sample " + g);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(":/knots/3"), std::string::npos) << r.err;

  r = run_cli("curve info " + inbetween::test::test_dir().string());  // a folder, not a file
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;

  const auto array = temp_file("array.json", "[1, 2]");  // the root is not an object
  r = run_cli("curve info " + array);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(array + ": expected a JSON object"), std::string::npos) << r.err;

  r = run_cli("curve info /nonexistent/curve.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/curve.json"), std::string::npos);

  r = run_cli("curve sample " + example("natural.json") + " --count 1");
  EXPECT_EQ(r.exit_code, 2);
}

// Values in messages are printed exactly: close parameters used to read "(0.000000) ... (0.000000)".
TEST(CurveCli, MessagesPrintValuesExactly) {
  const auto f = temp_file("lagrange_close.json",
                           R"({"type": "lagrange", "points": [[0, 0], [1, 1], [2, 0]], "params": [0, 2e-9, 1e-9]})");
  const CliRun r = run_cli("curve info " + f);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(":/params/2: param 2 (1e-09) is not greater than param 1 (2e-09)"), std::string::npos) << r.err;
}

// Finite but overflowing inputs used to print -nan samples with exit code 0; now exit 2 naming
// the field, and nothing on standard output.
TEST(CurveCli, OverflowingCurvesAreUserErrorsNotNaN) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"hermite_huge.json", R"({"type": "hermite", "points": [[0], [1]], "tangents": [[1e308], [-1e308]]})"},
      {"natural_huge.json", R"({"type": "natural", "points": [[0], [1e308], [-1e308]]})"},
      {"chordal_subnormal.json", R"({"type": "catmull-rom", "points": [[0, 0], [1e-320, 0], [2e-320, 0]], "alpha": 1})"},
      {"lagrange_close.json", R"({"type": "lagrange", "points": [[0], [1], [0]], "params": [0, 1e-300, 2e-300]})"},
  };
  for (const auto& [name, json] : cases) {
    SCOPED_TRACE(name);
    const auto f = temp_file(name, json);
    const CliRun r = run_cli("curve sample " + f + " --count 3");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(r.out.find("nan"), std::string::npos);
    EXPECT_NE(r.err.find(f + ":/p"), std::string::npos) << r.err;  // /points or /params
  }
}

// A huge --count used to allocate gigabytes and run for minutes before writing anything; it is a
// user error naming the option, for sample and plot alike, and nothing is written.
// Issue 9, defect 4: a Lagrange curve through 1.6e308, 0, 1 sampled to "0,-nan" and -inf and
// plotted NaN into the SVG, with exit 0.  Its values are all finite (the interpolant is
// 0.8e308·(u − 1)(u − 2) up to rounding, at most 1.6e308 on [0, 2]): sample and plot must print
// finite numbers.
TEST(CurveCli, LagrangeNearTheLargestDoubleSamplesAndPlotsFiniteNumbers) {
  const auto f = temp_file("lagrange_huge.json", R"({"type":"lagrange","points":[1.6e308,0,1]})");
  const CliRun r = run_cli("curve sample " + f + " --count 11");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "u,x");
  int rows = 0;
  while (std::getline(lines, line)) {
    const auto comma = line.find(',');
    ASSERT_NE(comma, std::string::npos) << line;
    const double u = std::stod(line.substr(0, comma));
    const double x = std::strtod(line.c_str() + comma + 1, nullptr);
    EXPECT_TRUE(std::isfinite(x)) << line;
    EXPECT_NEAR(x, 0.8e308 * (u - 1) * (u - 2), 1e295) << line;  // few ulp of 1.6e308
    ++rows;
  }
  EXPECT_EQ(rows, 11);
  const auto out = (inbetween::test::test_dir() / "huge.svg").string();
  const CliRun p = run_cli("curve plot " + f + " -o " + out);
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const std::string svg = inbetween::test::slurp(out);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

// Issue 9, defect 5: this 133-byte curve made `curve info` run 57 s and take 1.55 GB (arc-length
// subdivision to depth 30 everywhere, driven by the rounding noise of a degree-19 speed).  With the
// work budget it is a clear user error, after at most 100 000 speed evaluations (the evaluation
// count is asserted in ArcLength.PathologicalLagrangeStaysWithinTheWorkBudget).
TEST(CurveCli, PathologicalLagrangeInfoIsABudgetErrorNotAMinuteOfWork) {
  const auto f = temp_file("lagrange20.json",
                           R"({"type":"lagrange","points":[9,-9,9,-9,9,-9,9,-9,9,-9,9,-9,9,-9,9,-9,9,-9,9,-9]})");
  const CliRun r = run_cli("curve info " + f);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("work budget"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(f), std::string::npos) << r.err;
}

TEST(CurveCli, HugeCountIsAUserErrorNotAnAllocation) {
  const fs::path svg = inbetween::test::test_dir() / "huge_count.svg";
  fs::remove(svg);
  CliRun r = run_cli("curve sample " + example("natural.json") + " --count 2000000000");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("--count: need between 2 and 1000000 samples, got 2000000000"), std::string::npos) << r.err;
  r = run_cli("curve plot " + example("natural.json") + " --count 100000000 -o " + svg.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--count: need between 2 and 10000 sample dots"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(svg));
  // The largest legal plot count still works.
  r = run_cli("curve plot " + example("natural.json") + " --count 10000 -o " + svg.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(svg));
}

// `--by arclength`: s_i = i·L/(N−1), and the points are that far apart along the curve.  Source: on
// the straight two-segment Bézier path of the test below the arc length between samples is the
// chord, so consecutive sample points must be exactly L/(N−1) apart.
TEST(CurveCli, SampleByArcLengthHasEqualArcSteps) {
  // A straight line drawn as a cubic Bézier with uneven control points: equal u steps are uneven
  // in length, equal s steps are not.
  const auto f = temp_file("line.json", R"({"type": "bezier", "points": [[0, 0], [0.1, 0.2], [0.2, 0.4], [3, 6]]})");
  const CliRun r = run_cli("curve sample " + f + " --count 7 --by arclength");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "u,s,x,y");
  const double length = std::sqrt(3.0 * 3.0 + 6.0 * 6.0);  // closed form: the chord of a line
  std::vector<std::array<double, 4>> rows;
  while (std::getline(in, line)) {
    std::array<double, 4> row{};
    char comma;
    std::istringstream ls(line);
    ls >> row[0] >> comma >> row[1] >> comma >> row[2] >> comma >> row[3];
    rows.push_back(row);
  }
  ASSERT_EQ(rows.size(), 7u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double s_expected = length * double(i) / 6.0;
    EXPECT_NEAR(rows[i][1], s_expected, 1e-12 * length) << "row " << i;
    EXPECT_NEAR(std::hypot(rows[i][2], rows[i][3]), s_expected, 1e-9 * length) << "row " << i;  // default's 1e-9·L
  }
  // The same file sampled by parameter is uneven (the point of arc-length sampling).
  const CliRun by_u = run_cli("curve sample " + f + " --count 7");
  ASSERT_EQ(by_u.exit_code, 0) << by_u.err;
  EXPECT_EQ(by_u.out.substr(0, 6), "u,x,y\n");
}

TEST(CurveCli, InfoLengthIsTheArcLength) {
  const auto f = temp_file("line3.json", R"({"type": "bezier", "points": [[0, 0, 0], [1, 2, 2], [3, 6, 6]]})");
  const CliRun r = run_cli("curve info " + f);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("length: 9 "), std::string::npos) << r.out;  // |(3,6,6)| = 9 (closed form)
}

}  // namespace
