// `inbetween bake --space world|local`: the default is world (unchanged output), local gives each
// object's transform relative to its parent under the same column names, for a scene file and for
// the same scene through glTF; --space on a scene without objects is refused with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"
#include "support/tolerances.hpp"

namespace {

using inbetween::test::run_cli;
using inbetween::test::write_test_file;

// A baked CSV: column name → values by row.
std::map<std::string, std::vector<double>> parse_csv(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> t;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::size_t c = 0;
    for (std::string cell; std::getline(cells, cell, ',') && c < names.size(); ++c) {
      t[names[c]].push_back(std::strtod(cell.c_str(), nullptr));
    }
  }
  return t;
}

// An arm at (1, 2, 3), a quarter turn about z, scale 2; its child hand keyed (1, 0, 0) at frame 1
// and (0, 1, 0) at frame 2 with a constant rotation.  World of the hand, closed form:
// t = (1, 2, 3) + R_z(90°)(2 · local): frame 1 (1, 4, 3), frame 2 (−1, 2, 3).
constexpr const char* kScene = R"({"inbetween": 1, "fps": 24, "range": [1, 2],
  "tracks": [{"name": "w", "kind": "scalar", "keys": [{"frame": 1, "value": 5}]}],
  "objects": [
    {"name": "hand", "parent": "arm",
     "translation": {"keys": [{"frame": 1, "value": [1, 0, 0]}, {"frame": 2, "value": [0, 1, 0]}]},
     "rotation": [0.8, 0.6, 0, 0]},
    {"name": "arm", "translation": [1, 2, 3], "rotation": [0.7071067811865476, 0, 0, 0.7071067811865476],
     "scale": [2, 2, 2]}]})";

TEST(BakeSpaceCli, WorldIsTheDefaultAndLocalIsRelativeToTheParent) {
  // sqrt(1/2) is rounded, so the rotated world translation is exact to a few ulp of its size (4).
  constexpr double kWorldTol = 4 * inbetween::test::few_ulp<double>;
  const auto scene = write_test_file("arm.json", kScene);
  const auto plain = run_cli("bake '" + scene.string() + "'");
  const auto world = run_cli("bake '" + scene.string() + "' --space world");
  const auto local = run_cli("bake '" + scene.string() + "' --space local");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(world.exit_code, 0) << world.err;
  ASSERT_EQ(local.exit_code, 0) << local.err;
  EXPECT_EQ(plain.out, world.out);  // the default stays world, byte for byte
  auto w = parse_csv(world.out), l = parse_csv(local.out);
  ASSERT_EQ(w.size(), l.size());  // same column names
  ASSERT_EQ(l["hand.translation.x"].size(), 2u);
  EXPECT_EQ(l["w"], w["w"]);  // tracks are the same in both spaces
  // Local: the keys themselves.
  EXPECT_EQ(l["hand.translation.x"], (std::vector<double>{1, 0}));
  EXPECT_EQ(l["hand.translation.y"], (std::vector<double>{0, 1}));
  EXPECT_EQ(l["hand.rotation.w"], (std::vector<double>{0.8, 0.8}));
  EXPECT_EQ(l["hand.rotation.x"], (std::vector<double>{0.6, 0.6}));
  EXPECT_EQ(l["hand.scale.x"], (std::vector<double>{1, 1}));
  // The root's local is its world.
  for (const char* c : {"arm.translation.x", "arm.rotation.w", "arm.rotation.z", "arm.scale.y"}) EXPECT_EQ(l[c], w[c]) << c;
  // World: the closed form.
  const double want[2][3] = {{1, 4, 3}, {-1, 2, 3}};
  for (int f = 0; f < 2; ++f) {
    EXPECT_NEAR(w["hand.translation.x"][f], want[f][0], kWorldTol) << f;
    EXPECT_NEAR(w["hand.translation.y"][f], want[f][1], kWorldTol) << f;
    EXPECT_NEAR(w["hand.translation.z"][f], want[f][2], kWorldTol) << f;
    EXPECT_EQ(w["hand.scale.x"][f], 2);
  }
}

TEST(BakeSpaceCli, GltfInputHasTheSameLocalColumns) {
  // The scene through convert → .glb → bake: glTF nodes keep their parents, so local columns are
  // the keys again (to the float precision of glTF's accessors).
  constexpr double kFloatTol = 4 * inbetween::test::few_ulp<float>;
  const auto scene = write_test_file("arm.json", kScene);
  const auto glb = scene.parent_path() / "arm.glb";
  const auto converted = run_cli("convert '" + scene.string() + "' '" + glb.string() + "'");
  ASSERT_EQ(converted.exit_code, 0) << converted.err;
  const auto local = run_cli("bake '" + glb.string() + "' --space local");
  ASSERT_EQ(local.exit_code, 0) << local.err;
  auto l = parse_csv(local.out);
  ASSERT_FALSE(l["hand.translation.x"].empty()) << local.out;
  EXPECT_NEAR(l["hand.translation.x"].front(), 1, kFloatTol);
  EXPECT_NEAR(l["hand.rotation.x"].front(), 0.6, kFloatTol);
  EXPECT_NEAR(l["hand.scale.x"].front(), 1, kFloatTol);
}

TEST(BakeSpaceCli, RefusedWhereItCannotApply) {
  const auto tracks_only = write_test_file(
      "tracks.json", R"({"inbetween": 1, "tracks": [{"name": "w", "kind": "scalar", "keys": [{"frame": 1, "value": 5}]}]})");
  const auto out = tracks_only.parent_path() / "out.csv";
  const auto r = run_cli("bake '" + tracks_only.string() + "' --space local -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--space: " + tracks_only.string() + " has no objects"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // Without --space the same file bakes (the default applies to objects only).
  EXPECT_EQ(run_cli("bake '" + tracks_only.string() + "'").exit_code, 0);
  const auto bad = run_cli("bake '" + tracks_only.string() + "' --space parent");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--space"), std::string::npos) << bad.err;
}

}  // namespace
