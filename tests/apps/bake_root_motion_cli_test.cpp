// `inbetween bake --root-motion OBJECT` (issue 23): 7 root-motion columns after all others and every
// object in character space.  Checked against a plain bake of the same input: applying the motion
// columns to the character-space columns gives the world columns back (within 1e-6 of the clip's
// extent, as tests/tracks/root_motion_test.cpp), the motion is horizontal and a pure yaw, the first
// frame's is the identity; --space local changes the root's columns only; errors exit 2 with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"
#include "support/tolerances.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::run_cli;
using inbetween::test::write_test_file;

using Table = std::map<std::string, std::vector<double>>;

// A baked CSV: column name → values by row; `names` gets the header in order.
Table parse_csv(const std::string& csv, std::vector<std::string>* names = nullptr) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::istringstream h(line);
  for (std::string name; std::getline(h, name, ',');) header.push_back(name);
  Table t;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::size_t c = 0;
    for (std::string cell; std::getline(cells, cell, ',') && c < header.size(); ++c) {
      t[header[c]].push_back(std::strtod(cell.c_str(), nullptr));
    }
  }
  if (names) *names = header;
  return t;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// Objects: the prefixes of the <name>.translation.x columns other than root_motion's.
std::vector<std::string> object_names(const std::vector<std::string>& header) {
  std::vector<std::string> out;
  const std::string suffix = ".translation.x";
  for (const auto& c : header) {
    if (c.size() > suffix.size() && c.compare(c.size() - suffix.size(), suffix.size(), suffix) == 0 &&
        c != "root_motion.translation.x") {
      out.push_back(c.substr(0, c.size() - suffix.size()));
    }
  }
  return out;
}

struct Worst {
  double position = 0;  ///< largest |compose(motion, character).t − world.t|
  double rotation = 0;  ///< largest 1 − |q · q_world| (sign-free)
  double extent = 0;    ///< largest |world translation component|
};

// compose(motion, character) against `world` for the objects in `objects`, every row; also the
// motion's own properties.
Worst check_reconstruction(Table& world, Table& character, const std::vector<std::string>& objects) {
  constexpr double kUnitTol = 4 * inbetween::test::few_ulp<double>;
  Worst w;
  const std::size_t rows = world["frame"].size();
  EXPECT_EQ(character["frame"].size(), rows);
  EXPECT_EQ(character["root_motion.translation.x"].size(), rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const double tx = character["root_motion.translation.x"][i], ty = character["root_motion.translation.y"][i],
                 tz = character["root_motion.translation.z"][i];
    const double mw = character["root_motion.rotation.w"][i], mx = character["root_motion.rotation.x"][i],
                 my = character["root_motion.rotation.y"][i], mz = character["root_motion.rotation.z"][i];
    // Horizontal and a pure yaw (about +Y), unit.
    EXPECT_EQ(ty, 0) << "row " << i;
    EXPECT_EQ(mx, 0) << "row " << i;
    EXPECT_EQ(mz, 0) << "row " << i;
    EXPECT_NEAR(mw * mw + my * my, 1, kUnitTol) << "row " << i;
    if (i == 0) {
      EXPECT_EQ(tx, 0);
      EXPECT_EQ(tz, 0);
      EXPECT_EQ(mw, 1);
      EXPECT_EQ(my, 0);
    }
    for (const auto& o : objects) {
      auto col = [&](Table& t, const char* c) { return t[o + c].at(i); };
      // p = m_t + m_q · p_c with m_q = (mw, 0, my, 0): a rotation about Y by angle θ, cos θ = mw² − my²,
      // sin θ = 2 mw my.
      const double c = mw * mw - my * my, s = 2 * mw * my;
      const double px = col(character, ".translation.x"), py = col(character, ".translation.y"),
                   pz = col(character, ".translation.z");
      const double wx = tx + c * px + s * pz, wy = ty + py, wz = tz - s * px + c * pz;
      const double ex = col(world, ".translation.x"), ey = col(world, ".translation.y"), ez = col(world, ".translation.z");
      w.extent = std::max({w.extent, std::abs(ex), std::abs(ey), std::abs(ez)});
      w.position = std::max({w.position, std::abs(wx - ex), std::abs(wy - ey), std::abs(wz - ez)});
      // q = m_q · q_c (Hamilton product with m = (mw, 0, my, 0)).
      const double qw = col(character, ".rotation.w"), qx = col(character, ".rotation.x"),
                   qy = col(character, ".rotation.y"), qz = col(character, ".rotation.z");
      const double rw = mw * qw - my * qy, rx = mw * qx + my * qz, ry = mw * qy + my * qw, rz = mw * qz - my * qx;
      const double dot = rw * col(world, ".rotation.w") + rx * col(world, ".rotation.x") +
                         ry * col(world, ".rotation.y") + rz * col(world, ".rotation.z");
      w.rotation = std::max(w.rotation, 1 - std::abs(dot));
      for (const char* sc : {".scale.x", ".scale.y", ".scale.z"}) EXPECT_EQ(col(character, sc), col(world, sc)) << o << sc;
    }
  }
  return w;
}

// A body walking along +X then turning (yaw keyed, plus a little pitch that stays in the body), a head
// child offset up and forward.  Version 1.
constexpr const char* kScene = R"({"inbetween": 1, "fps": 24, "range": [1, 5],
  "objects": [
    {"name": "head", "parent": "body", "translation": [0.5, 1.5, 0], "rotation": [0.8, 0.6, 0, 0]},
    {"name": "body",
     "translation": {"keys": [{"frame": 1, "value": [2, 1, -3]}, {"frame": 5, "value": [6, 1.25, 1]}]},
     "rotation": {"keys": [{"frame": 1, "value": [0.9238795325112867, 0, 0.3826834323650898, 0]},
                           {"frame": 5, "value": [0.5, 0.1, 0.8, 0.3]}]}}]})";

// 1 − |q·q'| of unit quaternions ≈ (angle/2)²/2: 1e-24-rad angles are below double's resolution, so
// the bound is a few ulp of 1.
constexpr double kRotationTol = 4 * inbetween::test::few_ulp<double>;
constexpr double kExtentTol = 1e-6;  // × the clip's extent (as tests/tracks/root_motion_test.cpp)

TEST(BakeRootMotionCli, SceneWorldSpaceReconstructs) {
  const auto scene = write_test_file("walker.json", kScene);
  const auto world = run_cli("bake " + q(scene) + " --frames 1:5:0.5");
  const auto character = run_cli("bake " + q(scene) + " --frames 1:5:0.5 --root-motion body");
  ASSERT_EQ(world.exit_code, 0) << world.err;
  ASSERT_EQ(character.exit_code, 0) << character.err;
  std::vector<std::string> wh, ch;
  auto w = parse_csv(world.out, &wh);
  auto c = parse_csv(character.out, &ch);
  // The 7 columns come after all the existing ones, which keep their names and order.
  ASSERT_EQ(ch.size(), wh.size() + 7);
  EXPECT_TRUE(std::equal(wh.begin(), wh.end(), ch.begin()));
  const std::vector<std::string> extra(ch.end() - 7, ch.end());
  EXPECT_EQ(extra, (std::vector<std::string>{"root_motion.translation.x", "root_motion.translation.y",
                                             "root_motion.translation.z", "root_motion.rotation.w",
                                             "root_motion.rotation.x", "root_motion.rotation.y",
                                             "root_motion.rotation.z"}));
  const auto objects = object_names(wh);
  ASSERT_EQ(objects.size(), 2u);
  const Worst worst = check_reconstruction(w, c, objects);
  EXPECT_LE(worst.position, kExtentTol * worst.extent);
  EXPECT_LE(worst.rotation, kRotationTol);
  // The motion really moves: at the last frame the body has walked (4, 4) on the ground and turned.
  EXPECT_NEAR(c["root_motion.translation.x"].back(), 4, kExtentTol * worst.extent);
  EXPECT_NEAR(c["root_motion.translation.z"].back(), 4, kExtentTol * worst.extent);
  EXPECT_LT(c["root_motion.rotation.w"].back(), 0.99);
  // The body keeps its height in character space (Y is not extracted).
  EXPECT_EQ(c["body.translation.y"], w["body.translation.y"]);
}

TEST(BakeRootMotionCli, LocalSpaceChangesOnlyTheRootAndJsonHasTheColumns) {
  const auto scene = write_test_file("walker.json", kScene);
  const auto world = run_cli("bake " + q(scene) + " --space local");
  const auto character = run_cli("bake " + q(scene) + " --space local --root-motion body");
  ASSERT_EQ(character.exit_code, 0) << character.err;
  auto w = parse_csv(world.out);
  auto c = parse_csv(character.out);
  for (const char* col : {"head.translation.x", "head.translation.y", "head.rotation.w", "head.rotation.x"})
    EXPECT_EQ(c[col], w[col]) << col;
  const Worst worst = check_reconstruction(w, c, {"body"});
  EXPECT_LE(worst.position, kExtentTol * worst.extent);
  EXPECT_LE(worst.rotation, kRotationTol);
  const auto json = run_cli("bake " + q(scene) + " --format json --root-motion body");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find(R"("body.scale.z", "root_motion.translation.x", "root_motion.translation.y", )"
                          R"("root_motion.translation.z", "root_motion.rotation.w", "root_motion.rotation.x", )"
                          R"("root_motion.rotation.y", "root_motion.rotation.z"])"),
            std::string::npos)
      << json.out.substr(0, 400);
}

TEST(BakeRootMotionCli, CmuWalkReconstructs) {
  const fs::path clip = "/usr/share/assimp/models/BVH/01_01.bvh";
  if (!fs::exists(clip)) GTEST_SKIP() << "assimp-testmodels not installed";
  // Every 25th of the 2 752 frames, all 31 joints.
  const auto world = run_cli("bake " + q(clip) + " --frames 0:2751:25");
  const auto character = run_cli("bake " + q(clip) + " --frames 0:2751:25 --root-motion Hips");
  ASSERT_EQ(world.exit_code, 0) << world.err;
  ASSERT_EQ(character.exit_code, 0) << character.err;
  std::vector<std::string> wh;
  auto w = parse_csv(world.out, &wh);
  auto c = parse_csv(character.out);
  const auto objects = object_names(wh);
  ASSERT_EQ(objects.size(), 31u);
  const Worst worst = check_reconstruction(w, c, objects);
  EXPECT_GT(worst.extent, 10);
  EXPECT_LE(worst.position, kExtentTol * worst.extent);
  EXPECT_LE(worst.rotation, kRotationTol);
  std::printf("CMU 01_01 --root-motion Hips: %zu rows, worst position %.3g (extent %.3g), worst 1-|dot| %.3g\n",
              w["frame"].size(), worst.position, worst.extent, worst.rotation);
}

TEST(BakeRootMotionCli, RefusedWithOneLine) {
  const auto scene = write_test_file("walker.json", kScene);
  const auto tracks_only = write_test_file(
      "tracks.json", R"({"inbetween": 1, "tracks": [{"name": "w", "kind": "scalar", "keys": [{"frame": 1, "value": 5}]}]})");
  const auto clash = write_test_file(
      "clash.json", R"({"inbetween": 1, "tracks": [{"name": "root_motion.rotation.w", "kind": "scalar", "keys": [{"frame": 1, "value": 5}]}],
      "objects": [{"name": "a"}]})");
  const auto out = scene.parent_path() / "root_motion_out.csv";
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {q(scene) + " --root-motion head", "--root-motion head: " + scene.string() +
                                             ": the object has a parent (body); root motion needs an object without one"},
      {q(scene) + " --root-motion nobody", "--root-motion nobody: " + scene.string() + " has no object of that name"},
      {q(tracks_only) + " --root-motion a", "--root-motion a: " + tracks_only.string() + " has no objects"},
      {q(clash) + " --root-motion a",
       "--root-motion a: " + clash.string() + " already has a column named root_motion.rotation.w"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli("bake " + c.args + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
