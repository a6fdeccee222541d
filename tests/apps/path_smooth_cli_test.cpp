// `inbetween path smooth` and the "paths" demo section: runs the built CLI on small CSV files.
// Expected numbers: the texts' §3.4.3 formulas worked by hand (see tests/paths/smoothing_test.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::CliRun;
using inbetween::test::run_cli;
using inbetween::test::test_dir;
using inbetween::test::write_test_file;

const char* kData = "x,y\n1,1.6\n2,1.65\n3,1.6\n4,1.8\n5,2.1\n6,2.2\n7,2.0\n8,1.5\n9,1.3\n10,1.4\n";

std::vector<std::vector<double>> parse_csv(const std::string& text, bool header) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  bool skip = header;
  while (std::getline(in, line)) {
    if (skip) { skip = false; continue; }
    std::vector<double> row;
    std::stringstream f(line);
    std::string cell;
    while (std::getline(f, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

TEST(PathSmoothCli, TentOnTheTextsDataSetKeepsX) {
  const auto csv = write_test_file("data.csv", kData);
  const CliRun r = run_cli("path smooth " + csv.string() + " --method tent --radius 1 --function");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, 4), "x,y\n");  // the header is kept
  const auto rows = parse_csv(r.out, true);
  ASSERT_EQ(rows.size(), 10u);
  // Weights 1/8, 3/4, 1/8, ends extended: y0 = .2 + 1.2 + .20625 = 1.60625, y4 = 2.075.
  const std::vector<double> want{1.60625, 1.6375, 1.63125, 1.8125, 2.075, 2.1625, 1.9625, 1.5375, 1.3375, 1.3875};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][0], double(i + 1));
    EXPECT_NEAR(rows[i][1], want[i], 1e-14) << i;
  }
}

TEST(PathSmoothCli, CubicWithParabolicEndsAndLinearToAFile) {
  const auto csv = write_test_file("data.csv", kData);
  CliRun r = run_cli("path smooth " + csv.string() + " --method cubic --smooth-ends --function");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = parse_csv(r.out, true);
  EXPECT_NEAR(rows[0][1], 1.775, 1e-14);  // (1.6 + (1.8 + 3·0.05))/2
  EXPECT_NEAR(rows[4][1], 2.0833333333333333, 1e-14);
  const fs::path out = test_dir() / "lin.csv";
  fs::remove(out);
  r = run_cli("path smooth " + csv.string() + " --method linear -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  rows = parse_csv(ss.str(), true);
  ASSERT_EQ(rows.size(), 10u);
  // Without --function both columns are smoothed; x is equally spaced, so Eq. 3.35 keeps it.
  EXPECT_NEAR(rows[1][0], 2.0, 1e-15);
  EXPECT_NEAR(rows[1][1], 1.625, 1e-15);
}

TEST(PathSmoothCli, BSplineMatchesTheLibraryFit) {
  const auto csv = write_test_file("data.csv", kData);
  const CliRun r = run_cli("path smooth " + csv.string() + " --method bspline --control-points 6 --function");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = parse_csv(r.out, true);
  EXPECT_NEAR(rows[0][1], 1.6178071725977305, 1e-12);  // scipy make_lsq_spline (smooth_bspline_test.cpp)
  EXPECT_NEAR(rows[8][1], 1.2218199012727096, 1e-12);
}

TEST(PathSmoothCli, BadInputIsNamedAndExitsTwo) {
  const auto bad = write_test_file("bad.csv", "x,y\n1,2\n2,oops\n");
  CliRun r = run_cli("path smooth " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 3"), std::string::npos) << r.err;
  const auto csv = write_test_file("data.csv", kData);
  r = run_cli("path smooth " + csv.string() + " --method gaussian --radius 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--radius"), std::string::npos) << r.err;
  r = run_cli("path smooth " + csv.string() + " --method bspline --control-points 2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--control-points"), std::string::npos) << r.err;
  r = run_cli("path smooth " + csv.string() + " --method spline");
  EXPECT_NE(r.exit_code, 0);
  const auto ragged = write_test_file("ragged.csv", "1,2\n3\n");
  r = run_cli("path smooth " + ragged.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 2"), std::string::npos) << r.err;
  // Output is written whole or not at all: a failed run leaves no file.
  const fs::path out = test_dir() / "never.csv";
  fs::remove(out);
  r = run_cli("path smooth " + bad.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(out));
}

// Nasty input found by the audit: each gives exit code 2, a message naming the place and no output.
TEST(PathSmoothCli, NastyInputIsRejectedClearly) {
  const fs::path out = test_dir() / "never-nasty.csv";
  fs::remove(out);
  auto expect_rejected = [&](const std::string& args, const std::string& needle) {
    SCOPED_TRACE(args);
    const CliRun r = run_cli("path smooth " + args + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  };
  expect_rejected(write_test_file("empty.csv", "").string(), "no data rows");
  // A lone header line: the message says it was read as a header.
  expect_rejected(write_test_file("header.csv", "x,y\n").string(), "\"x,y\", was read as a header");
  // A first line of number-like fields is data with a bad value, not a header to skip silently.
  expect_rejected(write_test_file("nan.csv", "1,nan\n2,3\n3,4\n").string(), "line 1: expected finite numbers");
  expect_rejected(write_test_file("huge.csv", "1e400,2\n2,3\n").string(), "line 1: expected finite numbers");
  // One row is too few for a B-spline fit: the file is named.
  const auto one = write_test_file("one.csv", "1,2\n");
  expect_rejected(one.string() + " --method bspline", one.string() + ": need at least 2 points, got 1");
  // rows x passes beyond 1e9 would only hang the tool.
  const auto csv = write_test_file("data.csv", kData);
  expect_rejected(csv.string() + " --iterations 2000000000", "--iterations");
  // Finite input whose cubic estimate overflows (1.7e308 + 1.7e308): no inf in the output.
  expect_rejected(write_test_file("big.csv", "1e308\n1.7e308\n1e308\n-1.7e308\n1e308\n").string() + " --method cubic",
                  "line 2: the smoothed value overflows");
  // A radius at the double maximum is legal and gives finite values (the lumped ends).
  const CliRun r = run_cli("path smooth " + csv.string() + " --method tent --radius 1.7e308");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  // Output into a folder that does not exist: the file is named.
  const CliRun m = run_cli("path smooth " + csv.string() + " -o " + (test_dir() / "no-such-dir" / "x.csv").string());
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.err.find("no-such-dir"), std::string::npos) << m.err;
}

TEST(PathSmoothCli, PathFitStillWorksAlongside) {
  const auto csv = write_test_file("data.csv", kData);
  const CliRun r = run_cli("path fit " + csv.string() + " --degree 2 --control-points 4");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(PathsDemo, ShowsFramesSmoothingAndAFoundPath) {
  const CliRun r = run_cli("demo");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("== paths =="), std::string::npos);
  EXPECT_NE(r.out.find("0.400000"), std::string::npos);  // the helix's Frenet twist = torsion 0.4
  EXPECT_NE(r.out.find("1.775"), std::string::npos);     // cubic with parabolic ends, row 1
  EXPECT_NE(r.out.find("length 20.82842712474619 cells"), std::string::npos);  // 18 + 2√2: 18 straight moves and 2 diagonals, counted on the printed grid
}

// --resample N: rows first resampled equally in arc length (fewer or more), then smoothed.
TEST(PathSmoothCli, ResampleToFewerAndMoreRows) {
  // An L-shaped polyline of length 4 (3 along x, 1 along y) in 3 rows, resampled to 9 rows: spacing
  // ½ (closed form: (0,0) (0.5,0) … (3,0) (3,0.5) (3,1)); --iterations 0 leaves them unsmoothed.
  const auto csv = write_test_file("ell.csv", "x,y\n0,0\n3,0\n3,1\n");
  CliRun r = run_cli("path smooth " + csv.string() + " --method linear --iterations 0 --resample 9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = parse_csv(r.out, true);
  ASSERT_EQ(rows.size(), 9u);
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_NEAR(rows[k][0], 0.5 * double(k), 1e-15) << k;
    EXPECT_EQ(rows[k][1], 0.0) << k;
  }
  EXPECT_NEAR(rows[7][1], 0.5, 1e-15);
  EXPECT_EQ(rows[8][0], 3.0);
  EXPECT_EQ(rows[8][1], 1.0);
  // The texts' data set (10 rows) down to 4 with smoothing: ends kept by Eq. 3.35, 4 rows out.
  const auto data = write_test_file("data.csv", kData);
  r = run_cli("path smooth " + data.string() + " --method linear --resample 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  rows = parse_csv(r.out, true);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0][0], 1.0);
  EXPECT_EQ(rows[0][1], 1.6);
  EXPECT_EQ(rows[3][0], 10.0);
  EXPECT_EQ(rows[3][1], 1.4);
  // Bad counts exit with 2 naming the option.
  r = run_cli("path smooth " + data.string() + " --resample 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--resample"), std::string::npos) << r.err;
  const auto single = write_test_file("one.csv", "1,2\n");
  r = run_cli("path smooth " + single.string() + " --resample 3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("at least 2 points"), std::string::npos) << r.err;
}

}  // namespace
