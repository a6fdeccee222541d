// `inbetween view`: the page embeds exactly the values `bake` writes (the browser test,
// tests/browser, checks that the page plays them); bad input is exit 2 with one message and
// nothing written (no target, no temporary file left beside it).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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

const fs::path kFrame22 = fs::path(INBETWEEN_SOURCE_DIR) / "examples/scenes/frame22.json";

// True when the tool was built with the page (esbuild and tools/threejs found).  Otherwise `view`
// must fail with exit 2, say how to get the page and write nothing, which is checked here (and
// the callers then skip).
bool has_preview() {
  const fs::path probe = test_dir() / "probe.html";
  const auto r = run_cli("view '" + kFrame22.string() + "' -o '" + probe.string() + "'");
  if (r.exit_code == 0) return true;
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("make deps"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(probe));
  return false;
}

// The data object the page embeds (window.INBETWEEN_DATA = {...};).
nlohmann::json embedded_data(const std::string& page) {
  const std::string open = "window.INBETWEEN_DATA = ";
  const auto begin = page.find(open);
  const auto end = page.find(";\n</script>", begin);
  if (begin == std::string::npos || end == std::string::npos) return nullptr;
  std::string text = page.substr(begin + open.size(), end - begin - open.size());
  // "<\/" (kept out of the script element) is "</" to JSON as well.
  return nlohmann::json::parse(text, nullptr, false);
}

// The files in `dir` (to see that nothing was left behind).
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

TEST(ViewCli, EmbedsTheValuesBakeWritesAndFetchesNothing) {
  if (!has_preview()) GTEST_SKIP() << "built without the preview page (esbuild or tools/threejs missing: make deps)";
  const fs::path page = test_dir() / "frame22.html";
  auto r = run_cli("view '" + kFrame22.string() + "' -o '" + page.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  const std::string html = slurp(page);
  // Self-contained: no script or style from elsewhere, no module loading.
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("import("), std::string::npos);
  const auto data = embedded_data(html);
  ASSERT_TRUE(data.is_object()) << "no embedded data";

  // The same table as `bake --format json`: columns, frames and every value (JSON numbers of the
  // same shortest text parse to the same doubles, so == is the check).
  r = run_cli("bake '" + kFrame22.string() + "' --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto bake = nlohmann::json::parse(r.out);
  const auto& bake_columns = bake["columns"];
  ASSERT_EQ(data["columns"].size() + 2, bake_columns.size());
  for (std::size_t c = 0; c < data["columns"].size(); ++c) EXPECT_EQ(data["columns"][c], bake_columns[c + 2]);
  ASSERT_EQ(data["rows"].size(), bake["rows"].size());
  ASSERT_EQ(data["rows"].size(), 71u);  // frames 16 … 86 of frame22.json's range
  for (std::size_t i = 0; i < data["rows"].size(); ++i) {
    EXPECT_EQ(data["frames"][i], bake["rows"][i][0]);
    for (std::size_t c = 0; c < data["columns"].size(); ++c)
      ASSERT_EQ(data["rows"][i][c].get<double>(), bake["rows"][i][c + 2].get<double>())
          << data["columns"][c] << " at frame " << data["frames"][i];
  }
  // Objects: kinds, parents, the cameras' fields of view (frame22.json: yfov_deg 45 and 40).
  const auto& objects = data["objects"];
  ASSERT_EQ(objects.size(), 4u);
  EXPECT_EQ(objects[0]["kind"], "path");
  EXPECT_EQ(objects[1]["kind"], "object");
  EXPECT_EQ(objects[2]["kind"], "camera");
  EXPECT_EQ(objects[2]["parent"], 1);
  EXPECT_NEAR(objects[2]["yfov_deg"].get<double>(), 45, 1e-12);
  EXPECT_NEAR(objects[3]["yfov_deg"].get<double>(), 40, 1e-12);
  // The ball's path lines start and end where its legs do (frame22.json's control points).
  const auto& legs = objects[0]["path_points"];
  ASSERT_EQ(legs.size(), 2u);
  EXPECT_EQ(legs[0][0], nlohmann::json({-5, 0, 0}));
  EXPECT_NEAR(legs[1].back()[1].get<double>(), 10, 1e-12);
}

// Every example scene (reach_and_grasp.json's constraint tuples and acceleration keys,
// surface_walk.json's surface paths included) gives a page whose rows are its bake.
TEST(ViewCli, EveryExampleSceneEmbedsItsBake) {
  if (!has_preview()) GTEST_SKIP() << "built without the preview page (esbuild or tools/threejs missing: make deps)";
  std::vector<fs::path> scenes;
  for (const auto& e : fs::directory_iterator(fs::path(INBETWEEN_SOURCE_DIR) / "examples/scenes")) {
    if (e.path().extension() == ".json") scenes.push_back(e.path());
  }
  ASSERT_GE(scenes.size(), 4u);
  for (const fs::path& scene : scenes) {
    SCOPED_TRACE(scene.filename().string());
    const fs::path page = test_dir() / (scene.stem().string() + ".html");
    auto r = run_cli("view '" + scene.string() + "' -o '" + page.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto data = embedded_data(slurp(page));
    ASSERT_TRUE(data.is_object()) << "no embedded data";
    r = run_cli("bake '" + scene.string() + "' --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto bake = nlohmann::json::parse(r.out);
    ASSERT_EQ(data["rows"].size(), bake["rows"].size());
    ASSERT_GT(data["rows"].size(), 1u);
    for (std::size_t i = 0; i < data["rows"].size(); ++i) {
      for (std::size_t c = 0; c < data["columns"].size(); ++c)
        ASSERT_EQ(data["rows"][i][c].get<double>(), bake["rows"][i][c + 2].get<double>())
            << data["columns"][c] << " at frame " << data["frames"][i];
    }
  }
}

TEST(ViewCli, FramesOptionPicksTheRows) {
  if (!has_preview()) GTEST_SKIP() << "built without the preview page";
  const fs::path page = test_dir() / "p.html";
  const auto r = run_cli("view '" + kFrame22.string() + "' --frames 20:30:2.5 -o '" + page.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(embedded_data(slurp(page))["frames"], nlohmann::json({20, 22.5, 25, 27.5, 30}));
}

struct BadView {
  const char* name;
  std::string args;    // after "view"
  std::string phrase;  // the message must contain it
};

TEST(ViewCli, BadInputIsExitTwoWithAMessageAndWritesNothing) {
  if (!has_preview()) GTEST_SKIP() << "built without the preview page";
  const fs::path dir = test_dir() / "out";
  fs::create_directories(dir);
  const fs::path page = dir / "p.html";
  const auto empty_scene = test::write_test_file("tracks_only.json",
      R"({"inbetween": 1, "tracks": [{"name": "v", "keys": [{"frame": 0, "value": 1}, {"frame": 9, "value": 2}]}]})");
  const std::vector<BadView> bad{
      {"missing scene file", "'" + (test_dir() / "no-such.json").string() + "' -o '" + page.string() + "'", "cannot open the file"},
      {"missing glTF file", "'" + (test_dir() / "no-such.glb").string() + "' -o '" + page.string() + "'", "no-such.glb"},
      {"output folder missing", "'" + kFrame22.string() + "' -o '" + (dir / "no-such-folder" / "p.html").string() + "'",
       "No such file or directory"},
      {"output is a folder", "'" + kFrame22.string() + "' -o '" + dir.string() + "'", "Is a directory"},
      {"scene with no objects", "'" + empty_scene.string() + "' -o '" + page.string() + "'", "the scene has no objects"},
      {"too many frames", "'" + kFrame22.string() + "' --frames 0:1e6 -o '" + page.string() + "'", "at most 20000"},
      {"reversed frames", "'" + kFrame22.string() + "' --frames 9:1 -o '" + page.string() + "'", "is before start"},
      {"no output", "'" + kFrame22.string() + "'", "--output is required"},
  };
  for (const auto& b : bad) {
    const auto r = run_cli("view " + b.args);
    EXPECT_EQ(r.exit_code, 2) << b.name << ": " << r.err;
    EXPECT_NE(r.err.find(b.phrase), std::string::npos) << b.name << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << b.name;
    EXPECT_TRUE(files_in(dir).empty()) << b.name << ": left " << files_in(dir).front();
  }
}

}  // namespace
}  // namespace inbetween
