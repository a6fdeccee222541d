// Every example scene bakes to exactly the bytes recorded in tests/data/scenes (recorded with the
// bake of commit 2b29b1d, before the scene module existed), as CSV and as JSON; and a version-2
// file with the same content bakes to the same bytes as version 1.  Re-recorded once on branch
// `slerp` (issue 12), when Track segments became power forms built once (tracks/track.hpp): every
// number of bouncing_cube then moved by at most 3.6e-15 absolute (values of magnitude ≤ 4, i.e. a
// few ulp: the new evaluation order's rounding, bounded in TrackPowerForm.MatchesTheHermiteBasis…),
// 490 of the numbers changed in their last digits, none in the leading digits (compared by script).
// Re-recorded again on branch `slerpnear` (issue 12), when slerp() took the part of b across a from
// b ∓ a instead of b − (a·b)a (math/orientation_interp.hpp; the old form failed its contract near
// antipodal ends and under -march=native): 244 of 2156 numbers changed, all in the slerp-interpolated
// columns camera.orientation and lamp.euler_slerp, by at most 3.3e-16 absolute (unit-quaternion
// components: 1.5 ulp of 1), none in the leading digits (compared by script, CSV and JSON alike).
// Re-recorded for issue 20's speed (2026-11-27), when norm() took the plain √(Σc²) wherever the sum
// of squares neither overflows nor underflows (math/vec.hpp; one rounding fewer than dividing by the
// largest component): 325 of 2156 numbers changed, in the normalised quaternion columns
// (camera.orientation, cube.rotation, lamp.euler_slerp) and cube.translation x/y, by at most
// 8.9e-16 absolute (values of magnitude ≤ 4: one ulp), none in the leading digits (by script).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::run_cli;
using inbetween::test::slurp;

const fs::path kExamples = fs::path(INBETWEEN_SOURCE_DIR) / "examples" / "scenes";
const fs::path kExpected = fs::path(INBETWEEN_SOURCE_DIR) / "tests" / "data" / "scenes";

TEST(BakeExamples, EveryRecordedExampleBakesToTheSameBytes) {
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(kExamples)) {
    if (entry.path().extension() != ".json") continue;
    const std::string stem = entry.path().stem().string();
    for (const auto& [suffix, args] : {std::pair<std::string, std::string>{".csv", ""}, {".json", " --format json"}}) {
      const fs::path expected = kExpected / (stem + suffix);
      if (!fs::exists(expected)) continue;
      SCOPED_TRACE(expected.string());
      const auto r = run_cli("bake \"" + entry.path().string() + "\"" + args);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_TRUE(r.out == slurp(expected)) << "bake of " << entry.path() << args << " differs from " << expected;
      ++compared;
    }
  }
  EXPECT_GE(compared, 2);  // at least bouncing_cube as CSV and JSON
}

TEST(BakeExamples, VersionTwoReadsAndBakesAsVersionOne) {
  std::string text = slurp(kExamples / "bouncing_cube.json");
  const std::string v1 = "\"inbetween\": 1,";
  const auto at = text.find(v1);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, v1.size(), "\"inbetween\": 2,");
  const fs::path v2 = inbetween::test::write_test_file("bouncing_cube_v2.json", text);
  const auto r = run_cli("bake \"" + v2.string() + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out == slurp(kExpected / "bouncing_cube.csv"));
  const auto bad = run_cli("bake -", "{\"inbetween\": 4}");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "inbetween: -: /inbetween: unsupported format version 4 (this reader knows 1, 2 and 3)\n");
}

// Issue 9, defects 1 and 2: a number beyond double's range and a 100 000-level nesting are user
// errors (exit 2, one short message with line and column), not an internal error or a crash.
TEST(BakeExamples, HugeNumbersAndDeepNestingAreUserErrors) {
  auto r = run_cli("bake -", "1e318\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "inbetween: -: line 1, column 1: the number 1e318 is beyond double precision's range\n");
  r = run_cli("bake -", "{\"inbetween\": 1, \"fps\": -1e400}");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "inbetween: -: line 1, column 25: the number -1e400 is beyond double precision's range\n");
  const std::string deep = "{\"inbetween\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  r = run_cli("bake -", deep);
  EXPECT_EQ(r.exit_code, 2);
  // The root object is level 1 and the first '[' (column 15) level 2, so level 513 is opened by
  // the 512th '[', column 15 + 511 = 526.
  EXPECT_EQ(r.err, "inbetween: -: line 1, column 526: JSON nested deeper than 512 levels (not accepted)\n");
  // Within the limit, a nested value is reported by type, never dumped whole.
  const std::string nested = "{\"inbetween\": " + std::string(500, '[') + std::string(500, ']') + "}";
  r = run_cli("bake -", nested);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "inbetween: -: /inbetween: unsupported format version array (this reader knows 1, 2 and 3)\n");
  const std::string long_string = "{\"inbetween\": \"" + std::string(100000, 'x') + "\"}";
  r = run_cli("bake -", long_string);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_LT(r.err.size(), 200u) << r.err.substr(0, 200);
}

TEST(BakeExamples, CurveReaderHasTheSameBounds) {
  auto r = run_cli("curve info -", "{\"type\": \"bezier\", \"points\": [1e318, 2]}");
  EXPECT_EQ(r.exit_code, 2);
  // Columns counted by hand: the number starts after `{"type": "bezier", "points": [` (30 characters).
  EXPECT_NE(r.err.find("the number 1e318 at line 1, column 31 is beyond double precision's range"), std::string::npos) << r.err;
  const std::string deep = "{\"version\": " + std::string(100000, '[') + std::string(100000, ']') +
                           ", \"type\": \"bezier\", \"points\": [0, 1]}";
  r = run_cli("curve info -", deep);
  EXPECT_EQ(r.exit_code, 2);
  // `{"version": ` is 12 characters; the 512th '[' (level 513 with the root object) is column 13 + 511.
  EXPECT_NE(r.err.find("nested deeper than 512 levels at line 1, column 524"), std::string::npos) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 300u);
  const std::string nested = "{\"version\": " + std::string(300, '[') + std::string(300, ']') +
                             ", \"type\": \"bezier\", \"points\": [0, 1]}";
  r = run_cli("curve info -", nested);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/version: unsupported version array"), std::string::npos) << r.err.substr(0, 300);
}

}  // namespace
