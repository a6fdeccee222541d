// The rotation calculator, run as a program: `inbetween rotation convert`.  Each case writes its
// input to a temporary file, runs the binary at INBETWEEN_CLI with std::system, and checks standard
// output, standard error and the exit code.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "inbetween/math/euler.hpp"
#include "inbetween/math/rotation.hpp"
#include "support/cli.hpp"

namespace inbetween {
namespace {

using test::CliRun;
using test::run_cli;

std::vector<std::vector<double>> numbers_of(const std::string& text) {
  std::vector<std::vector<double>> rows;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream ls(line);
    std::vector<double> row;
    double v;
    while (ls >> v) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

TEST(RotationCli, QuaternionToMatrixWithCommentsBlanksAndCommas) {
  const CliRun r = run_cli("rotation convert --from quat --to matrix",
                        "# identity, then a third of a turn about (1,1,1)\n\n1 0 0 0\n  0.5, 0.5 ,0.5,0.5\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Closed forms: the identity; the 120° turn about (1,1,1) permutes the axes x→y→z→x.
  EXPECT_EQ(r.out, "1 0 0 0 1 0 0 0 1\n0 0 1 1 0 0 0 1 0\n");
  EXPECT_EQ(r.err, "");
}

TEST(RotationCli, QuaternionOrdersAndNormalisation) {
  const CliRun r = run_cli("rotation convert --from quat-xyzw --to quat", "0 0 0 2\n0 0 -1 0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Normalised on input; the output is canonical (w ≥ 0, else the first non-zero component > 0).
  EXPECT_EQ(r.out, "1 0 0 0\n0 0 0 1\n");
}

TEST(RotationCli, EulerInDegreesAndGimbalLockWarning) {
  // SciPy: Rotation.from_euler('xyz', [30, 90, 40], degrees=True).as_euler('xyz', degrees=True)
  // gives (−10, 90, 0) with a gimbal-lock warning; the second line is an ordinary triple.
  const CliRun r = run_cli("rotation convert --from euler:xyz --to euler:xyz --degrees", "30 90 40\n10 20 30\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = numbers_of(r.out);
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].size(), 3u);
  EXPECT_NEAR(rows[0][0], -10, 1e-12);
  EXPECT_NEAR(rows[0][1], 90, 1e-12);
  EXPECT_EQ(rows[0][2], 0);
  EXPECT_NEAR(rows[1][0], 10, 1e-12);
  EXPECT_NEAR(rows[1][1], 20, 1e-12);
  EXPECT_NEAR(rows[1][2], 30, 1e-12);
  EXPECT_NE(r.err.find("warning"), std::string::npos);
  EXPECT_NE(r.err.find("line 1"), std::string::npos);
  EXPECT_NE(r.err.find("gimbal lock"), std::string::npos);
  EXPECT_EQ(r.err.find("line 2"), std::string::npos);
}

TEST(RotationCli, EulerXYZEqualsFixedZYX) {
  // The texts' fact through the tool: XYZ (a, b, c) and zyx (c, b, a) print the same quaternion.
  const CliRun a = run_cli("rotation convert --from euler:XYZ --to quat --degrees", "30 45 60\n");
  const CliRun b = run_cli("rotation convert --from euler:zyx --to quat --degrees", "60 45 30\n");
  ASSERT_EQ(a.exit_code, 0);
  ASSERT_EQ(b.exit_code, 0);
  const auto qa = numbers_of(a.out), qb = numbers_of(b.out);
  ASSERT_EQ(qa.size(), 1u);
  ASSERT_EQ(qb.size(), 1u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(qa[0][k], qb[0][k], 1e-15);
}

TEST(RotationCli, NumbersRoundTripExactly) {
  // Shortest round-trip printing: quat → rotvec → quat reproduces the canonical unit quaternion to
  // the last bits the conversions allow (a few ulp), and every printed number reads back exactly.
  const Quatd q = normalized(Quatd{0.3, -0.5, 0.7, 0.1});
  char line[200];
  std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g\n", q.w, q.x, q.y, q.z);
  const CliRun r1 = run_cli("rotation convert --from quat --to rotvec", line);
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  const CliRun r2 = run_cli("rotation convert --from rotvec --to quat", r1.out);
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const auto back = numbers_of(r2.out);
  ASSERT_EQ(back.size(), 1u);
  const Quatd c = canonical(q);
  EXPECT_NEAR(back[0][0], c.w, 1e-15);
  EXPECT_NEAR(back[0][1], c.x, 1e-15);
  EXPECT_NEAR(back[0][2], c.y, 1e-15);
  EXPECT_NEAR(back[0][3], c.z, 1e-15);
  const Vec3d rv = rotation_vector_from_quat(normalized(q));  // the tool normalises its input once more
  const auto rows = numbers_of(r1.out);
  EXPECT_EQ(rows[0][0], rv.x);  // exact: the tool prints the double that the library computed
  EXPECT_EQ(rows[0][1], rv.y);
  EXPECT_EQ(rows[0][2], rv.z);
  // Single spaces between numbers, one line per rotation.
  EXPECT_EQ(r1.out.find("  "), std::string::npos);
  EXPECT_EQ(std::count(r1.out.begin(), r1.out.end(), '\n'), 1);
}

TEST(RotationCli, AxisAngleAndMatrixFormats) {
  const CliRun r = run_cli("rotation convert --from axis-angle --to matrix --degrees", "0 0 2 90\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = numbers_of(r.out);
  ASSERT_EQ(m[0].size(), 9u);
  const double expect[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};  // the texts' R(90°) about z
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(m[0][k], expect[k], 1e-15);
  const CliRun back = run_cli("rotation convert --from matrix --to axis-angle --degrees", "0 -1 0 1 0 0 0 0 1\n");
  ASSERT_EQ(back.exit_code, 0) << back.err;
  const auto aa = numbers_of(back.out);
  EXPECT_NEAR(aa[0][2], 1, 1e-15);
  EXPECT_NEAR(aa[0][3], 90, 1e-12);
}

TEST(RotationCli, MalformedLineIsAnErrorNamingTheLineAndWritesNothing) {
  const CliRun r = run_cli("rotation convert --from quat --to rotvec", "1 0 0 0\n# fine so far\n1 2 x 4\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");  // nothing written for a failed run
  EXPECT_NE(r.err.find("line 3"), std::string::npos) << r.err;
  const CliRun arity = run_cli("rotation convert --from quat --to rotvec", "1 0 0\n");
  EXPECT_EQ(arity.exit_code, 2);
  EXPECT_NE(arity.err.find("line 1"), std::string::npos);
  EXPECT_NE(arity.err.find("4 numbers"), std::string::npos);
  const CliRun commas = run_cli("rotation convert --from rotvec --to quat", "1,,2,3\n");
  EXPECT_EQ(commas.exit_code, 2);
  const CliRun inf = run_cli("rotation convert --from rotvec --to quat", "1 inf 2\n");
  EXPECT_EQ(inf.exit_code, 2);
}

TEST(RotationCli, InvalidRotationsAreErrors) {
  const CliRun zero = run_cli("rotation convert --from quat --to matrix", "\n0 0 0 0\n");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("line 2"), std::string::npos);
  EXPECT_EQ(zero.out, "");
  // Not a rotation within 1e-6: scaled, and a mirror; 1e-7 noise is accepted.
  const CliRun scaled = run_cli("rotation convert --from matrix --to quat", "1 0 0 0 1 0 0 0 1.00001\n");
  EXPECT_EQ(scaled.exit_code, 2);
  EXPECT_NE(scaled.err.find("not a rotation"), std::string::npos) << scaled.err;
  const CliRun mirror = run_cli("rotation convert --from matrix --to quat", "-1 0 0 0 1 0 0 0 1\n");
  EXPECT_EQ(mirror.exit_code, 2);
  EXPECT_NE(mirror.err.find("reflection"), std::string::npos) << mirror.err;
  const CliRun noisy = run_cli("rotation convert --from matrix --to quat", "1 1e-7 0 0 1 0 0 0 1\n");
  EXPECT_EQ(noisy.exit_code, 0) << noisy.err;
  const CliRun axis = run_cli("rotation convert --from axis-angle --to quat", "0 0 0 1\n");
  EXPECT_EQ(axis.exit_code, 2);
}

TEST(RotationCli, BadFormatsAreUserErrors) {
  EXPECT_EQ(run_cli("rotation convert --from bogus --to quat", "").exit_code, 2);
  const CliRun seq = run_cli("rotation convert --from quat --to euler:XyZ", "1 0 0 0\n");
  EXPECT_EQ(seq.exit_code, 2);
  EXPECT_NE(seq.err.find("XyZ"), std::string::npos);
  EXPECT_EQ(run_cli("rotation convert --from quat", "").exit_code, 2);  // --to is required
  // An empty input is a successful run with empty output.
  const CliRun empty = run_cli("rotation convert --from quat --to quat", "# nothing\n\n");
  EXPECT_EQ(empty.exit_code, 0);
  EXPECT_EQ(empty.out, "");
}

TEST(RotationCli, AllTwentyFourEulerConventionsRoundTripThroughTheTool) {
  // Every convention parses, and euler → quat → euler through two runs reproduces the angles.
  for (const EulerSequence& seq : all_euler_sequences()) {
    SCOPED_TRACE(seq.name());
    const std::string input = seq.proper() ? "10 50 -70\n" : "10 -50 -70\n";
    const CliRun to_quat = run_cli("rotation convert --from euler:" + seq.name() + " --to quat --degrees", input);
    ASSERT_EQ(to_quat.exit_code, 0) << to_quat.err;
    const CliRun back = run_cli("rotation convert --from quat --to euler:" + seq.name() + " --degrees", to_quat.out);
    ASSERT_EQ(back.exit_code, 0) << back.err;
    const auto rows = numbers_of(back.out);
    EXPECT_NEAR(rows[0][0], 10, 1e-12);
    EXPECT_NEAR(rows[0][1], seq.proper() ? 50 : -50, 1e-12);
    EXPECT_NEAR(rows[0][2], -70, 1e-12);
  }
}

TEST(RotationCli, AxisAngleWithSubnormalAxisIsTheRotationAboutItsDirection) {
  // Issue 9, defect 3: these printed "inf -nan -inf" and the identity.  Closed forms: the axis
  // (5e-324, 0, −5e-324) is the direction (1, 0, −1)/√2, so 1 rad about it is
  // (cos ½, sin ½/√2, 0, −sin ½/√2); the axis (1e-310, 0, 0) is x, so 1 rad about it is (cos ½, sin ½, 0, 0).
  const CliRun r = run_cli("rotation convert --from axis-angle --to quat", "5e-324 0 -5e-324 1\n1e-310 0 0 1\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = numbers_of(r.out);
  ASSERT_EQ(rows.size(), 2u) << r.out;
  ASSERT_EQ(rows[0].size(), 4u) << r.out;
  ASSERT_EQ(rows[1].size(), 4u) << r.out;
  for (const auto& row : rows)
    for (double v : row) EXPECT_TRUE(std::isfinite(v)) << r.out;
  const double c = std::cos(0.5), s = std::sin(0.5);
  const double expect[2][4] = {{c, s / std::sqrt(2.0), 0, -s / std::sqrt(2.0)}, {c, s, 0, 0}};
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(rows[std::size_t(i)][std::size_t(k)], expect[i][k], 1e-15) << r.out;
}

TEST(RotationCli, DemoShowsTheRotationSection) {
  const CliRun r = run_cli("demo", "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("== rotations =="), std::string::npos);
  EXPECT_NE(r.out.find("gimbal_lock = true"), std::string::npos);
  EXPECT_NE(r.out.find("flattens"), std::string::npos);
}

}  // namespace
}  // namespace inbetween
