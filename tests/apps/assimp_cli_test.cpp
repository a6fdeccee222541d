// `inbetween bake MODEL.fbx|MODEL.dae` through the assimp reader (docs/assimp.md): the columns of
// every node, the animation's range, and for bad files exit code 2 with one line naming the file
// (and the node and key for key faults) and no output file.
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
using inbetween::test::run_cli;

const fs::path kModels = "/usr/share/assimp/models";

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

TEST(AssimpCli, BakesTheFbxSkeleton) {
  const fs::path fbx = kModels / "FBX/animation_with_skeleton.fbx";
  if (!fs::exists(fbx)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const auto r = run_cli("bake " + q(fbx));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 22u);  // header + frames 0..20 (24 fps, the file's time mode)
  const std::string header = rows[0];
  for (const char* column : {"RootNode.translation.x", "Armature.rotation.w", "Bone.translation.x", "Bone.013.rotation.z",
                             "Bone.013_end.scale.z"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
  EXPECT_EQ(rows[1].substr(0, 4), "0,0,");
  EXPECT_EQ(rows.back().substr(0, 3), "20,");
  // The first animation by index is the same; an unknown one is one line naming the choices.
  const auto same = run_cli("bake " + q(fbx) + " --animation 0");
  EXPECT_EQ(same.out, r.out);
  const auto none = run_cli("bake " + q(fbx) + " --animation Walk");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("\"Armature|ArmatureAction\""), std::string::npos) << none.err;
}

TEST(AssimpCli, BakesAnimatedColladaFiles) {
  for (const char* name : {"Collada/anims_with_full_rotations_between_keys.DAE", "Collada/box_nested_animation.dae"}) {
    const fs::path dae = kModels / name;
    if (!fs::exists(dae)) GTEST_SKIP() << "assimp-testmodels is not installed";
    const fs::path out = inbetween::test::test_dir() / "collada.csv";
    const auto r = run_cli("bake " + q(dae) + " -o " + q(out));
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const auto rows = lines(inbetween::test::slurp(out));
    // Collada's 1000 ticks per second are not a frame rate: 24 fps, frame = seconds · 24.
    ASSERT_GT(rows.size(), 10u) << name;
    EXPECT_LT(rows.size(), 400u) << name;
    EXPECT_NE(rows[0].find(".rotation.w"), std::string::npos);
    // Values change over the clip (the animation was read, not only the rest pose).
    EXPECT_NE(rows[1].substr(rows[1].find(',', rows[1].find(',') + 1)), rows.back().substr(rows.back().find(',', rows.back().find(',') + 1)))
        << name;
  }
}

TEST(AssimpCli, BadFilesExitTwoWithOneLineAndNoOutput) {
  const fs::path dir = inbetween::test::test_dir();
  const std::string x_head = "xof 0303txt 0032\nFrame Root {\n FrameTransformMatrix { 1.0,0.0,0.0,0.0, 0.0,1.0,0.0,0.0, 0.0,0.0,1.0,0.0, 0.0,0.0,0.0,1.0;; }\n}\n"
                             "AnimTicksPerSecond { 24; }\nAnimationSet Walk {\n Animation {\n  { Root }\n";
  struct Case {
    std::string name, content, expect;
  };
  std::vector<Case> cases = {
      {"nan.x", x_head + "  AnimationKey { 2; 2; 0;3;0.0,0.0,0.0;;, 20;3;1.0,nan,3.0;;; }\n }\n}\n",
       "animation 0 \"Walk\", node \"Root\", position, key 1: value is not finite"},
      {"order.x", x_head + "  AnimationKey { 2; 2; 5;3;0.0,0.0,0.0;;, 5;3;1.0,2.0,3.0;;; }\n }\n}\n",
       "animation 0 \"Walk\", node \"Root\", position, key 1: time 5 is not after the previous key's 5"},
      {"garbage.fbx", std::string(2000, '\x01') + "\"", "assimp cannot read it"},
      {"truncated.x", x_head.substr(0, 120), "assimp cannot read it"},
      {"empty.dae", "", "assimp cannot read it"},
  };
  if (fs::exists(kModels)) {
    std::ifstream in(kModels / "FBX/animation_with_skeleton.fbx", std::ios::binary);
    std::string head(4000, '\0');
    in.read(head.data(), 4000);
    cases.push_back({"truncated.fbx", head, "assimp cannot read it"});
  }
  std::vector<fs::path> files;
  for (const Case& c : cases) files.push_back(inbetween::test::write_test_file(c.name, c.content));
  const fs::path device = dir / "device.fbx";
  fs::remove(device);
  fs::create_symlink("/dev/zero", device);
  cases.push_back({"device.fbx", "", "not a regular file"});
  files.push_back(device);
  cases.push_back({"missing.dae", "", "does not exist"});
  files.push_back(dir / "missing.dae");
  const fs::path huge = dir / "huge.fbx";
  { std::ofstream(huge) << "x"; }
  fs::resize_file(huge, (std::uintmax_t(1) << 30) + 1);  // sparse
  cases.push_back({"huge.fbx", "", "more than the limit"});
  files.push_back(huge);

  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path out = dir / "out.csv";
    fs::remove(out);
    const auto r = run_cli("bake " + q(files[i]) + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 2) << cases[i].name << ": " << r.err;
    const auto err = lines(r.err);
    ASSERT_EQ(err.size(), 1u) << cases[i].name << ": " << r.err;
    EXPECT_NE(err[0].find(files[i].string() + ": "), std::string::npos) << err[0];
    EXPECT_NE(err[0].find(cases[i].expect), std::string::npos) << err[0];
    EXPECT_FALSE(fs::exists(out)) << cases[i].name;
  }
  fs::remove(huge);
}

}  // namespace
