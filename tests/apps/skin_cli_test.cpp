// Skins through the tool: `convert SCENE.json OUT.glb` writes the skin, `convert OUT.glb BACK.json`
// reads it back into the scene file (the BVH → JSON → .glb route keeps a skeleton's skin).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli.hpp"

namespace {

using inbetween::test::run_cli;
using inbetween::test::slurp;
using inbetween::test::write_test_file;

TEST(SkinCli, SceneToGlbToSceneKeepsTheSkin) {
  const auto scene = write_test_file("skeleton.json", R"({"inbetween": 2, "fps": 30, "range": [0, 4],
    "objects": [{"name": "root", "translation": {"keys": [{"frame": 0, "value": [0, 1, 0]}, {"frame": 4, "value": [1, 1, 0]}]}},
                {"name": "knee", "parent": "root", "translation": [0, -0.5, 0]},
                {"name": "foot", "parent": "knee", "translation": [0, -0.5, 0]}],
    "skins": [{"name": "legs", "joints": ["root", "knee", "foot"]}]})");
  const auto glb = scene.parent_path() / "skeleton.glb", back = scene.parent_path() / "back.json";
  const auto a = run_cli("convert '" + scene.string() + "' '" + glb.string() + "'");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto b = run_cli("convert '" + glb.string() + "' '" + back.string() + "'");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto j = nlohmann::json::parse(slurp(back));
  ASSERT_TRUE(j.contains("skins")) << j.dump();
  EXPECT_EQ(j["skins"], nlohmann::json::parse(R"([{"name": "legs", "joints": ["root", "knee", "foot"]}])"));
  // A skin naming a missing joint: exit 2, one line with the place, nothing written.
  const auto bad = write_test_file("bad.json", R"({"inbetween": 2, "objects": [{"name": "root"}],
    "skins": [{"joints": ["root", "toe"]}]})");
  const auto out = scene.parent_path() / "bad.glb";
  const auto r = run_cli("convert '" + bad.string() + "' '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/skins/0/joints/1: no object named \"toe\""), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
