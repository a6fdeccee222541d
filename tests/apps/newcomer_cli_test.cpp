// What a newcomer meets first (issue 26, "A newcomer's path"): the help text says what each
// command does and shows its defaults, a file of the wrong kind names the command that reads it,
// and the argument parser's errors look like every other usage error.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "support/cli.hpp"

namespace {

using inbetween::test::CliRun;
using inbetween::test::run_cli;

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The line of `text` that contains `part` ("" when none).
std::string line_with(const std::string& text, const std::string& part) {
  const auto at = text.find(part);
  if (at == std::string::npos) return "";
  const auto begin = text.rfind('\n', at);
  const auto end = text.find('\n', at);
  return text.substr(begin == std::string::npos ? 0 : begin + 1, end == std::string::npos ? std::string::npos : end - begin - 1);
}

// `path` fits, smooths, walks surfaces and finds paths: the top-level help and `path --help` say all four.
TEST(NewcomerCli, PathHelpNamesEverythingPathDoes) {
  const CliRun top = run_cli("--help");
  ASSERT_EQ(top.exit_code, 0) << top.err;
  const std::string line = line_with(top.out, "  path");
  for (const char* word : {"fit", "smooth", "surface", "find"}) EXPECT_TRUE(has(line, word)) << word << " not in: " << line;
  const CliRun path = run_cli("path --help");
  ASSERT_EQ(path.exit_code, 0) << path.err;
  for (const char* word : {"fit", "smooth", "surface", "find"}) EXPECT_TRUE(has(path.out, word)) << word << " not in: " << path.out;
  const std::string first = path.out.substr(0, path.out.find('\n'));
  for (const char* word : {"smooth", "surface", "find"}) EXPECT_TRUE(has(first, word)) << word << " not in: " << first;
}

// A file of another kind inbetween knows: one line saying what it is and which commands read it.
TEST(NewcomerCli, AFileOfAnotherKindNamesTheCommandThatReadsIt) {
  const std::string scene = std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes/bouncing_cube.json";
  const std::string curve = std::string(INBETWEEN_SOURCE_DIR) + "/examples/curves/hermite.json";
  for (const char* cmd : {"curve info ", "curve sample ", "curve plot "}) {
    const std::string out = (inbetween::test::test_dir() / "x.svg").string();
    const CliRun r = run_cli(cmd + scene + (std::string(cmd) == "curve plot " ? " -o " + out : ""));
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_TRUE(has(r.err, "inbetween: " + scene + ": a scene file, not a curve file")) << cmd << r.err;
    EXPECT_TRUE(has(r.err, "inbetween bake")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // view: the same loader (only when built with the preview page).
  for (const char* cmd : {"bake ", "plot ", "convert "}) {
    const std::string out = (inbetween::test::test_dir() / "x.json").string();
    const CliRun r = run_cli(cmd + curve + (std::string(cmd) == "convert " ? " " + out : std::string(cmd) == "bake " ? "" : " -o " + out));
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_TRUE(has(r.err, "inbetween: " + curve + ": a curve file, not a scene file")) << cmd << r.err;
    EXPECT_TRUE(has(r.err, "inbetween curve info")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// Downhill is a method too: `--method downhill --from I` gives the same path as `--downhill I`, and
// the help says when --from/--to are needed.
TEST(NewcomerCli, PathSurfaceTakesDownhillAsAMethod) {
  const std::string mesh = std::string(INBETWEEN_SOURCE_DIR) + "/tests/data/obj/blender_torus.obj";
  const CliRun option = run_cli("path surface " + mesh + " --downhill 3");
  ASSERT_EQ(option.exit_code, 0) << option.err;
  const CliRun method = run_cli("path surface " + mesh + " --method downhill --from 3");
  EXPECT_EQ(method.exit_code, 0) << method.err;
  EXPECT_EQ(method.out, option.out);
  const CliRun both = run_cli("path surface " + mesh + " --method downhill --from 3 --to 5");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_TRUE(has(both.err, "--to")) << both.err;
  const CliRun help = run_cli("path surface --help");
  EXPECT_TRUE(has(line_with(help.out, "--from"), "unless")) << help.out;
  EXPECT_TRUE(has(line_with(help.out, "--method"), "downhill")) << help.out;
}

// Every option with a value shows its default in --help; the parser's own errors are usage errors
// like the others: "inbetween: " and one line, exit 2.
TEST(NewcomerCli, HelpShowsDefaultsAndParserErrorsAreUsageErrors) {
  const CliRun convert = run_cli("convert --help");
  for (const char* opt : {"--tolerance", "--substeps"}) {
    const std::string line = line_with(convert.out, opt);
    const auto name = line.find(opt);
    EXPECT_TRUE(name != std::string::npos && has(line.substr(name, line.find("  ", name) - name), "=")) << line;
  }
  EXPECT_TRUE(has(run_cli("demo --help").out, "--out TEXT=out/demo")) << run_cli("demo --help").out;
  const CliRun sample = run_cli("curve sample --help");
  const std::string by = sample.out.substr(sample.out.find("--by"));
  const std::string by_text = by.substr(0, by.find("\n  -o"));
  EXPECT_EQ(by_text.find_last_not_of(" \n"), by_text.rfind('.')) << by_text;
  const std::string scene = std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes/frame22.json";
  const CliRun missing = run_cli("plot " + scene);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.err, "inbetween: --output is required (--help for usage)\n");
  const CliRun unknown = run_cli("bake " + scene + " --no-such-option");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.err.rfind("inbetween: ", 0), 0u) << unknown.err;
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1) << unknown.err;
}

}  // namespace
