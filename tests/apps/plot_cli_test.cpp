// `inbetween plot SCENE|MODEL.glb -o DIR` from the command line: what it writes, and bad input
// (missing file, unwritable or unsuitable output folder, a scene with nothing to plot) giving exit
// code 2, a message naming the place, and no folder or temporary left behind.  That the drawn
// values are the baked ones is tests/apps/plot_check.py (ctest apps.plot_matches_bake).
#include <gtest/gtest.h>

#include <algorithm>
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
using inbetween::test::slurp;
using inbetween::test::test_dir;

const std::string kFrame22 = std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes/frame22.json";
const std::string kCube = std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes/bouncing_cube.json";
const std::string kGlb = std::string(INBETWEEN_SOURCE_DIR) + "/fuzz/corpus/gltf/two-animations.glb";

std::string qp(const fs::path& p) { return "\"" + p.string() + "\""; }

// Entries of `dir` whose names start with '.' (our temporary folders are ".<name>.tmp-XXXXXX").
std::vector<std::string> hidden_entries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name[0] == '.') found.push_back(name);
  }
  return found;
}

std::vector<std::string> svg_files(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().extension() == ".svg") found.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

// frame22.json: 4 objects (2 on paths) → 4 transform plots, 2 path views, 2 speed plots.
TEST(PlotCli, WritesEveryPlotAndAnIndex) {
  const fs::path out = test_dir() / "frame22";
  fs::remove_all(out);
  const CliRun r = run_cli("plot " + qp(kFrame22) + " -o " + qp(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // standard error is a file here: no progress bar
  const std::vector<std::string> expected = {"objects/ball.svg",       "objects/follow_cam.svg", "objects/hold_cam.svg",
                                             "objects/rig.svg",        "paths/ball-speed.svg",   "paths/ball-views.svg",
                                             "paths/follow_cam-speed.svg", "paths/follow_cam-views.svg"};
  EXPECT_EQ(svg_files(out), expected);
  const std::string index = slurp(out / "index.html");
  for (const auto& f : expected) EXPECT_NE(index.find("<img src=\"" + f + "\""), std::string::npos) << f;
  // The speed plot marks the ease's phase boundaries: accel_frames 12 and decel_frames 17 of the
  // span 22..67 give t1 = 12/45 and t2 = 1 − 17/45 (docs/scene-paths.md).
  const std::string speed = slurp(out / "paths/ball-speed.svg");
  EXPECT_NE(speed.find("t1 = 0.2667"), std::string::npos);
  EXPECT_NE(speed.find("t2 = 0.6222"), std::string::npos);
  EXPECT_TRUE(hidden_entries(out.parent_path()).empty());

  // bouncing_cube.json: every kind of track and an object with a keyed rotation.
  const fs::path cube = test_dir() / "cube";
  fs::remove_all(cube);
  const CliRun c = run_cli("plot " + qp(kCube) + " -o " + qp(cube));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const std::string z = slurp(cube / "tracks/cube.location.z.svg");
  EXPECT_NE(z.find("quad ease_in"), std::string::npos);         // the segment's interpolation
  EXPECT_NE(z.find("after: cycled (repeat)"), std::string::npos);  // the Cycles modifier, dashed
  EXPECT_NE(slurp(cube / "tracks/cube.location.x.svg").find("class=\"handle\""), std::string::npos);  // Bézier handles
  EXPECT_NE(slurp(cube / "tracks/camera.orientation.svg").find("angle_deg(camera.orientation)"), std::string::npos);
}

// The constraint tuples and acceleration keys of scene format 2 are marked on the speed plots like
// distance keys (tests/data/scenes/plot_speed_forms.json: "constrained" has 4 tuples at frames
// 3, 15, 30, 42; "ramped" 4 acceleration keys at 0, 12, 30, 38), at their frames.
TEST(PlotCli, MarksConstraintTuplesAndAccelerationKeys) {
  const fs::path out = test_dir() / "speed_forms";
  fs::remove_all(out);
  const std::string scene = std::string(INBETWEEN_SOURCE_DIR) + "/tests/data/scenes/plot_speed_forms.json";
  const CliRun r = run_cli("plot " + qp(scene) + " -o " + qp(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string constrained = slurp(out / "paths/constrained-speed.svg");
  for (int k = 0; k < 4; ++k) EXPECT_NE(constrained.find("constraint " + std::to_string(k)), std::string::npos) << k;
  EXPECT_EQ(constrained.find("constraint 4"), std::string::npos);
  const std::string ramped = slurp(out / "paths/ramped-speed.svg");
  for (int k = 0; k < 4; ++k) EXPECT_NE(ramped.find("a key " + std::to_string(k)), std::string::npos) << k;
  EXPECT_EQ(ramped.find("a key 4"), std::string::npos);
  EXPECT_NE(slurp(out / "paths/accelerated-speed.svg").find("a key 3"), std::string::npos);
}

TEST(PlotCli, GltfInput) {
  const fs::path out = test_dir() / "glb";
  fs::remove_all(out);
  const CliRun r = run_cli("plot " + qp(kGlb) + " -o " + qp(out) + " --fps 30");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(svg_files(out).empty());
  EXPECT_NE(slurp(out / "index.html").find("content=\"inbetween plot\""), std::string::npos);
}

// A second run replaces an earlier plot whole (a file of the old plot that the new one does not
// write is gone); a folder that is not an earlier plot is never replaced.
TEST(PlotCli, ReplacesOnlyAnEarlierPlot) {
  const fs::path out = test_dir() / "again";
  fs::remove_all(out);
  ASSERT_EQ(run_cli("plot " + qp(kFrame22) + " -o " + qp(out)).exit_code, 0);
  std::ofstream(out / "stale.txt") << "from before";
  const CliRun again = run_cli("plot " + qp(kCube) + " -o " + qp(out));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_FALSE(fs::exists(out / "stale.txt"));
  EXPECT_TRUE(fs::exists(out / "tracks/cube.location.z.svg"));
  EXPECT_FALSE(fs::exists(out / "paths"));
  EXPECT_TRUE(hidden_entries(out.parent_path()).empty());

  const fs::path mine = test_dir() / "mine";
  fs::remove_all(mine);
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "keep me";
  const CliRun r = run_cli("plot " + qp(kFrame22) + " -o " + qp(mine));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(mine.string() + ": exists and is neither empty nor an earlier plot"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(mine / "notes.txt"), "keep me");
  EXPECT_TRUE(hidden_entries(mine.parent_path()).empty());
}

TEST(PlotCli, BadInputIsExitTwoWithThePlaceAndNothingWritten) {
  const fs::path dir = test_dir() / "bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "plots";
  struct Case {
    std::string args, message;
  };
  const fs::path empty = dir / "empty.json";
  std::ofstream(empty) << R"({"inbetween": 2, "fps": 24, "range": [1, 10]})";
  const fs::path broken = dir / "broken.json";
  std::ofstream(broken) << R"({"inbetween": 1, "fps": 24, "range": [1, 10],
    "tracks": [{"name": "a", "keys": [{"frame": 5, "value": 1}, {"frame": 2, "value": 0}]}]})";
  const fs::path file = dir / "a-file";
  std::ofstream(file) << "x";
  const std::vector<Case> cases = {
      {qp(dir / "missing.json") + " -o " + qp(out), (dir / "missing.json").string() + ": cannot open the file"},
      {qp(dir / "missing.glb") + " -o " + qp(out), (dir / "missing.glb").string()},
      {qp(empty) + " -o " + qp(out), empty.string() + ": the scene has no tracks and no objects: nothing to plot"},
      {qp(broken) + " -o " + qp(out), broken.string() + ": /tracks/0/keys/1"},
      {qp(kFrame22) + " -o " + qp(dir / "no" / "such" / "folder"), (dir / "no" / "such").string() + ": the folder"},
      {qp(kFrame22) + " -o " + qp(file / "plots"), file.string() + ": the folder that would hold the plots does not exist"},
      {qp(kFrame22) + " -o " + qp(file), file.string() + ": exists and is not a folder"},
      {qp(kFrame22) + " -o " + qp(out) + " --frames 10:5", "--frames: end 5 is not after start 10"},
      {qp(kFrame22) + " -o " + qp(out) + " --frames 0:1e9:0.5", "--frames: 2000000001 samples; at most 200000"},
      {qp(kFrame22) + " -o " + qp(out) + " --animation 1", "--animation: only for glTF and assimp input"},
      {qp(kFrame22) + " -o " + qp(out) + " --fps 30", "--fps: only for glTF, BVH and assimp input"},
      // Not writable: mkdtemp in /proc fails (also as root, where permissions would not stop it).
      {qp(kFrame22) + " -o /proc/inbetween-plots", "/proc: cannot create a folder here"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const CliRun r = run_cli("plot " + c.args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(hidden_entries(dir).empty());
  }
  EXPECT_EQ(slurp(file), "x");
}

// --progress always draws the bar on standard error; by default (standard error is a file here,
// not a terminal) nothing is drawn; the plots are the same.
TEST(PlotCli, ProgressBarOnlyOnATerminalOrWhenAsked) {
  const fs::path a = test_dir() / "quiet", b = test_dir() / "bar";
  fs::remove_all(a);
  fs::remove_all(b);
  const CliRun quiet = run_cli("plot " + qp(kFrame22) + " -o " + qp(a));
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  const CliRun bar = run_cli("plot " + qp(kFrame22) + " -o " + qp(b) + " --progress always");
  ASSERT_EQ(bar.exit_code, 0) << bar.err;
  EXPECT_NE(bar.err.find("\rplot: sampling [##############################] 100%  421/421 frames"), std::string::npos)
      << bar.err;
  EXPECT_NE(bar.err.find("\rplot: drawing [##############################] 100%  8/8 plots"), std::string::npos) << bar.err;
  EXPECT_EQ(slurp(a / "paths/ball-speed.svg").size(), slurp(b / "paths/ball-speed.svg").size());
}

}  // namespace

namespace {

// Issue 21: a parent scale of 1e308 times a child's made plot write "-nan" into SVG point lists
// with exit 0, while bake and view refuse the scene.  Now plot refuses it the same way.
TEST(PlotCli, AWorldTransformThatOverflowsIsRefusedAsBakeRefusesIt) {
  const fs::path scene = inbetween::test::write_test_file("overflow.json", R"({"inbetween": 2, "fps": 24, "range": [0, 4],
    "objects": [{"name": "parent", "scale": [1e308, 1, 1], "rotation": [0.9238795, 0, 0, 0.3826834]},
                {"name": "child", "parent": "parent", "scale": [10, 1, 1], "translation": [10, 1, 0],
                 "rotation": {"keys": [{"frame": 0, "value": [1, 0, 0, 0]}, {"frame": 4, "value": [0, 0, 0, 1]}]}}]})");
  const fs::path out = test_dir() / "overflow";
  const CliRun r = run_cli("plot " + qp(scene) + " -o " + qp(out));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("child."), std::string::npos) << r.err;
  EXPECT_TRUE(r.err.find("is not a number") != std::string::npos || r.err.find("overflows") != std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(hidden_entries(test_dir()), std::vector<std::string>{});
  const CliRun bake = run_cli("bake " + qp(scene));
  EXPECT_EQ(bake.exit_code, 2) << bake.err;
}

// Issue 21: a legal 256-character object name made plot fail with "File name too long" on its
// own temporary path.  The file name is cut and hashed; the page keeps the whole name.
TEST(PlotCli, ALongObjectNameGetsAShortFileNameAndKeepsItsTitle) {
  const std::string name(256, 'n');
  const std::string other = std::string(255, 'n') + "m";  // the same first 79 characters: a different hash
  const fs::path scene = inbetween::test::write_test_file(
      "long.json", R"({"inbetween": 2, "fps": 24, "range": [0, 4], "objects": [{"name": ")" + name +
                       R"(", "translation": {"keys": [{"frame": 0, "value": [0, 0, 0]}, {"frame": 4, "value": [1, 0, 0]}]}},
                        {"name": ")" + other + R"(", "translation": [0, 1, 0]}]})");
  const fs::path out = test_dir() / "long";
  const CliRun r = run_cli("plot " + qp(scene) + " -o " + qp(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> files = svg_files(out);
  ASSERT_GE(files.size(), 2u);  // the two objects' pages (and the moving root's trajectory)
  for (const std::string& f : files) EXPECT_LE(fs::path(f).filename().string().size(), 100u) << f;
  EXPECT_NE(files[0], files[1]);
  bool titled = false;
  for (const std::string& f : files) titled = titled || slurp(out / f).find(name) != std::string::npos;
  EXPECT_TRUE(titled);
}

// Issue 21: a 90 KB glTF of 30 000 nodes made plot run 29 s at 824 MB and write 4.2 GB of SVGs.
// Now: at most 1000 pages (the rest counted on the index page and in a note), the sampled table
// at most 20 million values (an automatic grid gets coarser).  5 000 objects (50 000 columns)
// need both bounds and cost less to run; 30 000 by hand: 8 s, 284 MB, 48 MB written.
TEST(PlotCli, ManyObjectsGiveABoundedFolder) {
  std::string scene = R"({"inbetween": 2, "fps": 24, "range": [0, 24], "objects": [)";
  for (int i = 0; i < 5000; ++i) {
    scene += (i ? ",\n" : "") + std::string(R"({"name": "n)") + std::to_string(i) + "\"" +
             (i ? R"(, "parent": "n)" + std::to_string(i / 2) + "\"" : std::string()) +
             R"(, "translation": {"keys": [{"frame": 0, "value": [0, 0, 0]}, {"frame": 24, "value": [1, 0, 0]}]}})";
  }
  scene += "]}";
  const fs::path in = inbetween::test::write_test_file("many.json", scene);
  const fs::path out = test_dir() / "many";
  const CliRun r = run_cli("plot " + qp(in) + " -o " + qp(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LE(svg_files(out).size(), 1000u + 8);  // 1000 pages, and at most 8 trajectory plots (the default)
  std::size_t object_pages = 0;
  for (const auto& e : fs::directory_iterator(out / "objects")) object_pages += e.path().extension() == ".svg";
  EXPECT_EQ(object_pages, 1000u);
  EXPECT_NE(r.err.find("note: 4000 more plots left out"), std::string::npos) << r.err;
  const std::string index = slurp(out / "index.html");
  EXPECT_NE(index.find("4000 more plots left out"), std::string::npos);
  // The grid was made coarser: samples × 50 000 columns within 20 million values.
  const auto grid = index.find("inbetween-grid\" content=\"");
  ASSERT_NE(grid, std::string::npos);
  std::istringstream meta(index.substr(grid + 25));
  double start = 0, step = 0, count = 0;
  meta >> start >> step >> count;
  EXPECT_LE(count * 50000, 2e7) << index.substr(grid, 80);
  EXPECT_GE(count, 100) << index.substr(grid, 80);
  std::uintmax_t bytes = 0;
  for (const auto& e : fs::recursive_directory_iterator(out)) bytes += e.is_regular_file() ? e.file_size() : 0;
  EXPECT_LT(bytes, std::uintmax_t{200} << 20) << "bytes written";
}

}  // namespace
