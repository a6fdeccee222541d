// `inbetween path fit`: runs the built CLI on small CSV files.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

fs::path work_dir() {
  const fs::path d = fs::path(INBETWEEN_BINARY_DIR) / "path-fit-cli-test";
  fs::create_directories(d);
  return d;
}

CliRun run_cli(const std::string& args) {
  const fs::path out = work_dir() / "stdout.txt", err = work_dir() / "stderr.txt";
  const std::string cmd = std::string(INBETWEEN_CLI) + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream o(out), e(err);
  std::stringstream so, se;
  so << o.rdbuf();
  se << e.rdbuf();
  r.out = so.str();
  r.err = se.str();
  return r;
}

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path p = work_dir() / name;
  std::ofstream(p) << text;
  return p;
}

TEST(PathFitCli, InterpolatesByDefaultAndWritesABsplineCurveFile) {
  const auto csv = write_file("square.csv", "t,x,y\n0,0,0\n1,1,2\n2,3,1\n3,4,4\n4,5,0\n");
  const CliRun r = run_cli("path fit " + csv.string() + " --degree 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["type"], "bspline");
  EXPECT_EQ(j["degree"], 3);
  EXPECT_EQ(j["points"].size(), 5u);         // square case: one control point per row
  EXPECT_EQ(j["points"][0].size(), 2u);      // 2-D rows give 2-D points
  EXPECT_EQ(j["knots"].size(), 5u + 3 + 1);  // n + k + 1
  EXPECT_EQ(j["knots"][0], 0.0);
  EXPECT_EQ(j["knots"][8], 4.0);
  // Clamped: the first control point is the first data point.
  EXPECT_NEAR(j["points"][0][0].template get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(j["points"][4][1].template get<double>(), 0.0, 1e-12);
}

TEST(PathFitCli, LeastSquaresToAFileWithOutput) {
  const auto csv = write_file("ls.csv", "1,1.6\n2,1.65\n3,1.6\n4,1.8\n5,2.1\n6,2.2\n7,2.0\n8,1.5\n9,1.3\n10,1.4\n");
  const fs::path out = work_dir() / "ls.json";
  fs::remove(out);
  const CliRun r = run_cli("path fit " + csv.string() + " --degree 2 --control-points 5 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["points"].size(), 5u);
  EXPECT_EQ(j["knots"].size(), 8u);
  EXPECT_DOUBLE_EQ(j["knots"][3].get<double>(), 4.0);  // interior knots 1 + 9·{1/3, 2/3}
  EXPECT_DOUBLE_EQ(j["knots"][4].get<double>(), 7.0);
}

TEST(PathFitCli, BadRowsAndOptionsExitTwoNamingThePlace) {
  const auto bad = write_file("bad.csv", "t,x\n0,1\n1,oops\n");
  CliRun r = run_cli("path fit " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 3"), std::string::npos) << r.err;
  const auto ragged = write_file("ragged.csv", "0,1,2\n1,2\n");
  r = run_cli("path fit " + ragged.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 2"), std::string::npos) << r.err;
  const auto back = write_file("back.csv", "0,1\n2,2\n1,3\n3,3\n");
  r = run_cli("path fit " + back.string() + " --degree 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 3"), std::string::npos) << r.err;  // the row whose time goes back
  const auto ok = write_file("ok.csv", "0,1\n1,2\n2,3\n");
  r = run_cli("path fit " + ok.string() + " --degree 3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--control-points"), std::string::npos) << r.err;
  r = run_cli("path fit " + (work_dir() / "missing.csv").string());
  EXPECT_EQ(r.exit_code, 2);
}

TEST(PathFitCli, DemoHasTheSpeedControlSection) {
  const CliRun r = run_cli("demo");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("== speed control =="), std::string::npos);
  EXPECT_NE(r.out.find("s(0.73) = 0.953"), std::string::npos);
  EXPECT_NE(r.out.find("u(0.75) = 0.41875"), std::string::npos);
}

}  // namespace
