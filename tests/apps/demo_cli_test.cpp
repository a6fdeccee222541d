// `inbetween demo --out DIR` (what `make demo` runs with out/demo): the files it writes and the
// summary that ends its output (issue 11, "make demo").
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::slurp;
using test::test_dir;

std::string fixed3(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

TEST(DemoCli, WritesTheSceneItsBakeAndThePreviewAndEndsWithTheSummary) {
  const fs::path dir = test_dir() / "demo";
  const auto r = run_cli("demo --out '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "no progress bar when standard error is not a terminal: " << r.err;

  // The scene file is examples/scenes/frame22.json, and frames.csv is exactly its bake.
  const fs::path source = fs::path(INBETWEEN_SOURCE_DIR) / "examples/scenes/frame22.json";
  EXPECT_EQ(slurp(dir / "frame22.json"), slurp(source));
  const auto bake = run_cli("bake '" + (dir / "frame22.json").string() + "'");
  ASSERT_EQ(bake.exit_code, 0) << bake.err;
  const std::string csv = slurp(dir / "frames.csv");
  EXPECT_EQ(csv, bake.out);

  // The summary is last: what was written, then the numbers, then the time taken.
  const auto at = r.out.rfind("\n== summary ==\n");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string summary = r.out.substr(at);
  EXPECT_EQ(summary.find("\n== ", 1), std::string::npos) << "a section after the summary";
  for (const char* file : {"frame22.json", "frames.csv", "preview.html", "plots/"})
    EXPECT_NE(summary.find(std::string("  ") + file), std::string::npos) << file << "\n" << summary;
  const auto last_line = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
  EXPECT_EQ(last_line.rfind("took ", 0), 0u) << last_line;

  // The numbers, against the bake: the path length is the ball's distance on the last frame
  // (it ends at the end of its second leg), the peak speed the largest ball.speed, and it rests
  // where ball.speed is 0: frame22.json's range starts at 16, the ease runs 22–67 and the cubic
  // ease 67–80 with zero speed at both ends, and the range ends at 86.
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::size_t d = 0, v = 0;
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c] == "ball.distance") d = c;
    if (names[c] == "ball.speed") v = c;
  }
  ASSERT_TRUE(d > 0 && v > 0);
  double last_distance = 0, peak = 0;
  std::string rest;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) row.push_back(std::stod(x));
    last_distance = row[d];
    peak = std::max(peak, row[v]);
  }
  EXPECT_NE(summary.find("path length (its two legs' arc lengths) " + fixed3(last_distance) + " units"), std::string::npos) << summary;
  EXPECT_NE(summary.find("peak speed " + fixed3(peak) + " units/s"), std::string::npos) << summary;
  EXPECT_NE(summary.find("at rest on frames 16–22, 67, 80–86"), std::string::npos) << summary;

  // The plots of `inbetween plot`, as many SVG files as the summary says, and their index page.
  EXPECT_TRUE(fs::exists(dir / "plots" / "index.html"));
  std::size_t svgs = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "plots")) svgs += e.path().extension() == ".svg";
  EXPECT_GT(svgs, 0u);
  EXPECT_NE(summary.find("plots/         " + std::to_string(svgs) + " SVG plots"), std::string::npos) << summary;

  // The preview page, when the tool has it, embeds the scene.
  const std::string page = slurp(dir / "preview.html");
  if (!page.empty()) EXPECT_NE(page.find("window.INBETWEEN_DATA = "), std::string::npos);

  // The character (issue 20): CMU 01_01.bvh's page and plots once the tool reads BVH (checked as
  // `inbetween bake` would: one frame), otherwise one summary line saying why it is not there.
  const fs::path clip = "/usr/share/assimp/models/BVH/01_01.bvh";
  const bool readable = fs::exists(clip) && run_cli("bake '" + clip.string() + "' --frames 0:0").exit_code == 0;
  if (readable) {
    EXPECT_NE(summary.find("  01_01.html     the CMU motion-capture clip 01_01.bvh (31 joints, 1 root, 2752 frames)"),
              std::string::npos) << summary;
    const std::string clip_page = slurp(dir / "01_01.html");
    if (!page.empty()) EXPECT_NE(clip_page.find("window.INBETWEEN_DATA = "), std::string::npos);
    EXPECT_TRUE(fs::exists(dir / "01_01-plots" / "index.html"));
    EXPECT_TRUE(fs::exists(dir / "01_01-plots" / "trajectories" / "Hips.svg"));
    std::size_t clip_svgs = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir / "01_01-plots")) clip_svgs += e.path().extension() == ".svg";
    EXPECT_EQ(clip_svgs, 32u) << "31 joints' channels and the root's trajectory";
    EXPECT_NE(summary.find("  01_01-plots/   " + std::to_string(clip_svgs) + " SVG plots"), std::string::npos) << summary;
  } else {
    EXPECT_NE(summary.find("  01_01.html     not written: "), std::string::npos) << summary;
    EXPECT_FALSE(fs::exists(dir / "01_01.html"));
  }
}

TEST(DemoCli, AnOutputFolderThatCannotBeMadeIsExitTwo) {
  const auto file = test::write_test_file("a-file", "x");
  const auto r = run_cli("demo --out '" + (file / "demo").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot create the folder"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << "the output is printed only after the files are written";
}

}  // namespace
}  // namespace inbetween
