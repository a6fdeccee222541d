// `inbetween plot` on a skeleton (issue 20, "plot draws a joint's channels and its world
// trajectory"): trajectories/<object>.svg for the roots that move (at most 8) or each --object,
// with the poses of the hierarchy; an unknown --object is exit code 2 with nothing written.  That
// every drawn joint, trail point and dot is the baked value is tests/apps/plot_check.py (ctest
// apps.plot_matches_bake runs it on tests/data/scenes/skeleton_walk.json), which also checks that
// every bone joins its two joints.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;

using inbetween::test::CliRun;
using inbetween::test::run_cli;
using inbetween::test::slurp;
using inbetween::test::test_dir;
using inbetween::test::write_test_file;

// 31 joints shaped like CMU 01_01.bvh, one root (Hips), keyed over frames 0–96
// (tests/data/scenes/make_skeleton_walk.py).
const std::string kWalk = std::string(INBETWEEN_SOURCE_DIR) + "/tests/data/scenes/skeleton_walk.json";

std::string qp(const fs::path& p) { return "\"" + p.string() + "\""; }

std::vector<std::string> files_under(const fs::path& dir) {
  std::vector<std::string> found;
  if (!fs::exists(dir)) return found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) found.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(PlotSkeletonCli, TheMovingRootGetsItsTrajectoryWithThePosesOfItsSkeleton) {
  const fs::path out = test_dir() / "walk-plots";
  fs::remove_all(out);
  const CliRun r = run_cli("plot " + qp(kWalk) + " -o " + qp(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto files = files_under(out);
  // A channel plot per joint, one trajectory (the only root), the index.
  EXPECT_EQ(std::count_if(files.begin(), files.end(), [](const std::string& f) { return f.rfind("objects/", 0) == 0; }), 31);
  EXPECT_EQ(std::count_if(files.begin(), files.end(), [](const std::string& f) { return f.rfind("trajectories/", 0) == 0; }), 1);
  ASSERT_TRUE(fs::exists(out / "trajectories/Hips.svg")) << r.out;
  const std::string svg = slurp(out / "trajectories/Hips.svg");
  EXPECT_NE(svg.find("world trajectory of Hips and its 30 descendants"), std::string::npos);
  // 5 poses in 3 views: 30 bones and 31 joints each; one trail per view.
  EXPECT_EQ(count(svg, "class=\"bone\""), 5u * 30u * 3u);
  EXPECT_EQ(count(svg, "class=\"data joint\""), 5u * 31u * 3u);
  EXPECT_EQ(count(svg, "class=\"data trail\""), 3u);
  // The poses are at frames 0, 24, 48, 72, 96: evenly spaced over the range 0–96.
  for (const char* f : {"pose at frame 0 ", "pose at frame 24 ", "pose at frame 48 ", "pose at frame 72 ", "pose at frame 96 "})
    EXPECT_NE(svg.find(f), std::string::npos) << f;
  const std::string index = slurp(out / "index.html");
  EXPECT_NE(index.find("World trajectories"), std::string::npos);
  EXPECT_NE(index.find("trajectories/Hips.svg"), std::string::npos);
  EXPECT_EQ(r.out.find("note:"), std::string::npos) << r.out;
}

TEST(PlotSkeletonCli, ObjectOptionPlotsAnyJoint) {
  const fs::path out = test_dir() / "walk-hand";
  fs::remove_all(out);
  const CliRun r = run_cli("plot " + qp(kWalk) + " -o " + qp(out) + " --object LeftHand --object RightToeBase");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> trajectories;
  for (const auto& f : files_under(out))
    if (f.rfind("trajectories/", 0) == 0) trajectories.push_back(f);
  EXPECT_EQ(trajectories, (std::vector<std::string>{"trajectories/LeftHand.svg", "trajectories/RightToeBase.svg"}));
  // LeftHand has LeftFingerBase, LeftHandIndex1 and LThumb under it; RightToeBase is a leaf (no poses).
  const std::string hand = slurp(out / "trajectories/LeftHand.svg"), toe = slurp(out / "trajectories/RightToeBase.svg");
  EXPECT_NE(hand.find("world trajectory of LeftHand and its 3 descendants"), std::string::npos);
  EXPECT_EQ(count(hand, "class=\"bone\""), 5u * 3u * 3u);
  EXPECT_NE(toe.find("world trajectory of RightToeBase: top"), std::string::npos);
  EXPECT_EQ(count(toe, "class=\"bone\""), 0u);
  EXPECT_EQ(count(toe, "class=\"data trail\""), 3u);
}

TEST(PlotSkeletonCli, AnUnknownObjectIsExitTwoAndWritesNothing) {
  const fs::path out = test_dir() / "walk-unknown";
  fs::remove_all(out);
  const CliRun r = run_cli("plot " + qp(kWalk) + " -o " + qp(out) + " --object Tail");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--object: no object named 'Tail' (objects: Hips, LHipJoint"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(test_dir()))
    EXPECT_EQ(e.path().filename().string().find(".walk-unknown.tmp"), std::string::npos) << "a temporary was left";
}

TEST(PlotSkeletonCli, DefaultTrajectoriesAreBoundedAndTheRestNamed) {
  // 12 roots that move and 2 that do not: the first 8 movers get a plot; the note says 4 more.
  nlohmann::json objects = nlohmann::json::array();
  for (int i = 0; i < 14; ++i) {
    nlohmann::json o{{"name", "r" + std::to_string(i)}};
    if (i < 12) {
      o["translation"] = {{"keys", {{{"frame", 0}, {"value", {0, 0, i}}}, {{"frame", 10}, {"value", {1, i, 0}}}}}};
    } else {
      o["translation"] = {i, 0, 0};
    }
    objects.push_back(o);
  }
  const auto scene = write_test_file("many_roots.json", nlohmann::json{{"inbetween", 1}, {"fps", 24}, {"range", {0, 10}},
                                                                       {"objects", objects}}.dump());
  const fs::path out = test_dir() / "many-roots";
  fs::remove_all(out);
  const CliRun r = run_cli("plot " + qp(scene) + " -o " + qp(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> trajectories;
  for (const auto& f : files_under(out))
    if (f.rfind("trajectories/", 0) == 0) trajectories.push_back(f);
  std::vector<std::string> expected;
  for (int i = 0; i < 8; ++i) expected.push_back("trajectories/r" + std::to_string(i) + ".svg");
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(trajectories, expected);
  EXPECT_NE(r.out.find("note: 4 more moving roots have no trajectory plot (at most 8 by default); name them with --object"),
            std::string::npos) << r.out;
  // A root that does not move gets a plot when asked for.
  const CliRun asked = run_cli("plot " + qp(scene) + " -o " + qp(out) + " --object r13");
  ASSERT_EQ(asked.exit_code, 0) << asked.err;
  EXPECT_TRUE(fs::exists(out / "trajectories/r13.svg"));
  EXPECT_FALSE(fs::exists(out / "trajectories/r0.svg"));
}

}  // namespace
