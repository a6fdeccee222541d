// `inbetween view` on a skeleton (issue 20, "view draws skeletons"): the page embeds every joint
// with its parent (the page draws a bone from each to its parent; tests/browser checks the drawing)
// and the bound on the embedded values (kMaxPreviewValues: frames × columns) holds with a message
// that names the largest frame count that fits, writing nothing.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>

#include "support/cli.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::slurp;
using test::test_dir;
using test::write_test_file;

const fs::path kWalk = fs::path(INBETWEEN_SOURCE_DIR) / "tests/data/scenes/skeleton_walk.json";

// The data object the page embeds (window.INBETWEEN_DATA = {...};), or null without a page.
nlohmann::json embedded_data(const std::string& page) {
  const std::string open = "window.INBETWEEN_DATA = ";
  const auto begin = page.find(open);
  const auto end = page.find(";\n</script>", begin);
  if (begin == std::string::npos || end == std::string::npos) return nullptr;
  return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()), nullptr, false);
}

TEST(ViewSkeletonCli, EveryJointIsEmbeddedWithItsParent) {
  const fs::path page = test_dir() / "walk.html";
  const auto r = run_cli("view '" + kWalk.string() + "' -o '" + page.string() + "'");
  if (r.exit_code == 2 && r.err.find("make deps") != std::string::npos) GTEST_SKIP() << "built without the preview page";
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json data = embedded_data(slurp(page));
  ASSERT_TRUE(data.is_object());
  const nlohmann::json scene = nlohmann::json::parse(slurp(kWalk));
  std::map<std::string, std::string> parent_of;
  for (const auto& o : scene["objects"]) parent_of[o["name"]] = o.value("parent", "");
  ASSERT_EQ(data["objects"].size(), parent_of.size());
  std::size_t bones = 0;
  for (const auto& o : data["objects"]) {
    const std::string name = o["name"];
    EXPECT_EQ(o["kind"], "object") << name;
    if (o["parent"].is_null()) {
      EXPECT_EQ(parent_of[name], "") << name;
    } else {
      ++bones;
      EXPECT_EQ(data["objects"][o["parent"].get<std::size_t>()]["name"], parent_of[name]) << name;
    }
  }
  EXPECT_EQ(bones, 30u);
  EXPECT_EQ(data["rows"].size(), 97u);  // frames 0–96
}

TEST(ViewSkeletonCli, TooManyValuesIsExitTwoNamingTheFramesThatFit) {
  // 1 000 objects (10 000 columns) over frames 0–1000: 10 010 000 values > 8 000 000; 800 frames fit.
  nlohmann::json objects = nlohmann::json::array();
  objects.push_back({{"name", "root"}, {"translation", {{"keys", {{{"frame", 0}, {"value", {0, 0, 0}}},
                                                                  {{"frame", 1000}, {"value", {1, 0, 0}}}}}}}});
  for (int i = 1; i < 1000; ++i) objects.push_back({{"name", "j" + std::to_string(i)}, {"parent", "root"}, {"translation", {i, 0, 0}}});
  const auto scene = write_test_file("wide.json", nlohmann::json{{"inbetween", 1}, {"fps", 24}, {"range", {0, 1000}},
                                                                 {"objects", objects}}.dump());
  const fs::path page = test_dir() / "wide.html";
  auto r = run_cli("view '" + scene.string() + "' -o '" + page.string() + "'");
  if (r.exit_code == 2 && r.err.find("make deps") != std::string::npos) GTEST_SKIP() << "built without the preview page";
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("1001 frames × 10000 columns = 10010000 values; a preview embeds at most 8000000 (at most 800 "
                       "frames of this scene"),
            std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(page));
  // A step that fits: 0:1000:2 is 501 frames.
  r = run_cli("view '" + scene.string() + "' -o '" + page.string() + "' --frames 0:1000:2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(page));
}

}  // namespace
}  // namespace inbetween
