// The page of `inbetween view` in Debian's chromium (issue 11, "Preview"): it opens from file://
// with nothing fetched, draws a 3-D canvas that is not blank, shows at three scrubbed frames the
// object positions and rotations that `inbetween bake` writes (to 1e-9), looks through a scene camera and saves
// screenshots.  tests/browser/preview_page.mjs drives the page (playwright-core from npm,
// tools/browser) and prints what it read; the checks are here.  Skips, with the reason, only
// where node, playwright-core or chromium is missing or chromium cannot start (exit 77 of the script).
//
// The free-view screenshot it saves (build/<preset>/preview-test/preview.png) is the README's
// image: `make screenshots` copies it to docs/images/preview.png.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::test::run_cli;
using inbetween::test::slurp;

// The tolerance for the position (and rotation) read back from the page against `bake`
// (the page plays the embedded round-trip text of the same doubles, so the difference is expected
// to be 0).
constexpr double kPositionTolerance = 1e-9;
// Luminance variance (grey levels², 0–255) above which the canvas shows something: a canvas
// cleared to one colour has exactly 0; the frame-22 page measured 127 in the free view.
constexpr double kMinCanvasVariance = 1.0;
// Exit code of preview_page.mjs when the browser cannot run here (a skip, not a failure).
constexpr int kSkipExit = 77;

const fs::path kSource = INBETWEEN_SOURCE_DIR;
const fs::path kOut = fs::path(INBETWEEN_BINARY_DIR) / "preview-test";

struct Run {
  int exit_code = -1;
  std::string out, err;
};

// Runs preview_page.mjs with node; standard output and error captured.
Run run_page_script(const std::string& args) {
  const fs::path out = kOut / ("page-" + std::to_string(::getpid()) + ".out"), err = out.string() + ".err";
  const std::string command = std::string("'") + INBETWEEN_NODE + "' '" +
                              (kSource / "tests/browser/preview_page.mjs").string() + "' " + args + " > '" +
                              out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  Run r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// A bake CSV: the header's names and the rows by frame.
struct Bake {
  std::vector<std::string> names;
  std::map<double, std::vector<double>> rows;
  [[nodiscard]] std::size_t column(const std::string& name) const {
    for (std::size_t c = 0; c < names.size(); ++c)
      if (names[c] == name) return c;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

Bake read_bake(const std::string& csv) {
  Bake bake;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) bake.names.push_back(name);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');) row.push_back(std::strtod(v.c_str(), nullptr));
    if (!row.empty()) bake.rows[row[0]] = row;
  }
  return bake;
}

// The shortest round-trip text of a frame number.
std::string number_text(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& item : items) s += (s.empty() ? "" : ",") + item;
  return s;
}

// What preview_page.mjs read, or why it could not run.
struct Page {
  bool skipped = false;
  std::string skip_reason;  ///< the script's standard error when skipped
  nlohmann::json data;      ///< its JSON otherwise
};

// Makes the page of `input` and reads it in chromium at `frames`; checks what every preview must
// show and returns what the script read.
Page check_page(const fs::path& input, const std::string& name, const std::vector<double>& frames,
                          const std::vector<std::string>& objects, const std::string& camera,
                          const std::string& extra_args = "") {
  fs::create_directories(kOut);
  const fs::path page = kOut / (name + ".html"), csv = kOut / (name + ".csv");
  auto r = run_cli("view '" + input.string() + "' -o '" + page.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_cli("bake '" + input.string() + "' -o '" + csv.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const Bake bake = read_bake(slurp(csv));

  std::string frame_list;
  for (double f : frames) frame_list += (frame_list.empty() ? "" : ",") + number_text(f);
  std::string args = "'" + page.string() + "' --frames " + frame_list + " --objects " + joined(objects);
  if (!camera.empty()) args += " --camera " + camera + " --screenshot '" + (kOut / (name + "-" + camera + ".png")).string() + "'";
  args += " " + extra_args;
  const Run run = run_page_script(args);
  if (run.exit_code == kSkipExit) return Page{true, run.err, nullptr};
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const auto result = nlohmann::json::parse(run.out, nullptr, false);
  if (result.is_discarded()) {
    ADD_FAILURE() << "not JSON: " << run.out << run.err;
    return {};
  }
  EXPECT_TRUE(result["errors"].empty()) << result["errors"].dump();
  EXPECT_GT(result["variance"].get<double>(), kMinCanvasVariance) << "the 3-D canvas is blank";
  // Playing from the first frame shows a later frame (within 10 s).
  EXPECT_GT(result["played"]["to"].get<double>(), result["played"]["from"].get<double>()) << result["played"].dump();
  EXPECT_EQ(result["frames"].size(), frames.size());
  for (std::size_t k = 0; k < result["frames"].size(); ++k) {
    const auto& shown = result["frames"][k];
    const double f = shown["shown"].get<double>();
    EXPECT_EQ(f, frames[k]) << "the page shows another frame than the one scrubbed to";
    if (!bake.rows.count(f)) {
      ADD_FAILURE() << "frame " << f << " is not in the bake";
      continue;
    }
    const auto& row = bake.rows.at(f);
    for (const auto& object : objects) {
      const std::size_t c = bake.column(object + ".translation.x");
      const auto& p = shown["positions"][object];
      EXPECT_EQ(p.size(), 3u) << object;
      for (std::size_t i = 0; i < 3 && i < p.size(); ++i)
        EXPECT_NEAR(p[i].get<double>(), row[c + i], kPositionTolerance) << object << " at frame " << f << ", axis " << i;
      // The rotation shown, w x y z, is bake's rotation columns (sign included: the page plays the
      // sign-continuous quaternions of the cursor, as bake writes them).
      const std::size_t r = bake.column(object + ".rotation.w");
      const auto& q = shown["rotations"][object];
      EXPECT_EQ(q.size(), 4u) << object;
      for (std::size_t i = 0; i < 4 && i < q.size(); ++i)
        EXPECT_NEAR(q[i].get<double>(), row[r + i], kPositionTolerance) << object << " rotation at frame " << f << ", component " << i;
    }
  }
  if (!camera.empty()) {
    EXPECT_EQ(result["camera"], camera);
    EXPECT_GT(result["cameraVariance"].get<double>(), kMinCanvasVariance) << "the view through " << camera << " is blank";
    const std::string png = slurp(kOut / (name + "-" + camera + ".png"));
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << "no screenshot";
  }
  return Page{false, "", result};
}

#define SKIP_WITHOUT_NODE()                                                                   \
  if (std::string(INBETWEEN_NODE).empty())                                                    \
  GTEST_SKIP() << "node was not found when the tests were configured (`make deps` installs npm and node)"

TEST(PreviewBrowser, Frame22ShowsTheBakedPositionsAndLooksThroughACamera) {
  SKIP_WITHOUT_NODE();
  // Frames 22 (at rest at the start), 40 (cruising on the arc), 75 (climbing, banked): three
  // phases of the texts' scenario (docs/scene-paths.md).
  const Page page = check_page(kSource / "examples/scenes/frame22.json", "frame22", {22, 40, 75},
                               {"ball", "follow_cam", "hold_cam", "rig"}, "hold_cam",
                               "--overview '" + (kOut / "preview.png").string() + "'");
  if (page.skipped) GTEST_SKIP() << page.skip_reason;
  if (HasFailure()) return;
  EXPECT_EQ(page.data["cameras"], nlohmann::json({"follow_cam", "hold_cam"}));
  const std::string png = slurp(kOut / "preview.png");
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << "no overview screenshot";
}

TEST(PreviewBrowser, GltfFileShowsTheBakedNodes) {
  SKIP_WITHOUT_NODE();
  // A .glb made by `inbetween convert` from frame22.json (docs/gltf-export.md): its path objects and
  // cameras become node animations, follow_cam stays a child of rig; its two glTF cameras read back
  // as scene cameras (viewing along their nodes' rotation), so the page can look through one.
  fs::create_directories(kOut);
  const fs::path glb = kOut / "frame22.glb";
  const auto r = run_cli("convert '" + (kSource / "examples/scenes/frame22.json").string() + "' '" + glb.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = run_cli("bake '" + glb.string() + "'").out;
  const Bake bake = read_bake(csv);
  ASSERT_GE(bake.rows.size(), 3u);
  std::vector<std::string> nodes;
  for (const auto& name : bake.names)
    if (name.size() > 14 && name.ends_with(".translation.x")) nodes.push_back(name.substr(0, name.size() - 14));
  EXPECT_EQ(nodes, (std::vector<std::string>{"ball", "rig", "follow_cam", "hold_cam"})) << csv.substr(0, 200);
  // The first, a middle and the last baked frame.
  const auto first = bake.rows.begin()->first, last = bake.rows.rbegin()->first;
  auto middle = bake.rows.begin();
  std::advance(middle, bake.rows.size() / 2);
  const fs::path shot = kOut / "frame22_glb.png";
  const Page page = check_page(glb, "frame22_glb", {first, middle->first, last}, nodes, "hold_cam",
                               "--overview '" + shot.string() + "'");
  if (page.skipped) GTEST_SKIP() << page.skip_reason;
  EXPECT_EQ(page.data["cameras"], nlohmann::json({"follow_cam", "hold_cam"})) << "glTF camera nodes are scene cameras";
  EXPECT_EQ(slurp(shot).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << "no screenshot";
}

// A character-sized hierarchy written as a scene file: the 31 joints of the CMU skeleton (names,
// parents and rest offsets shaped like 01_01.bvh's), the root walking along +x and bobbing, every
// joint turning about its own axis, keyed every 4 frames over frames 0–120 at 120 fps.
fs::path write_skeleton_scene() {
  struct Joint {
    const char* name;
    const char* parent;
    double x, y, z;
  };
  static const Joint joints[] = {
      {"Hips", nullptr, 0, 0, 0}, {"LHipJoint", "Hips", 0, 0, 0}, {"LeftUpLeg", "LHipJoint", 1.6, -1.9, 0.8},
      {"LeftLeg", "LeftUpLeg", 2.4, -6.7, 0}, {"LeftFoot", "LeftLeg", 2.5, -6.9, 0}, {"LeftToeBase", "LeftFoot", 0.1, -0.4, 2.2},
      {"RHipJoint", "Hips", 0, 0, 0}, {"RightUpLeg", "RHipJoint", -1.6, -1.9, 0.8}, {"RightLeg", "RightUpLeg", -2.4, -6.7, 0},
      {"RightFoot", "RightLeg", -2.5, -6.9, 0}, {"RightToeBase", "RightFoot", -0.1, -0.4, 2.2}, {"LowerBack", "Hips", 0, 0, 0},
      {"Spine", "LowerBack", 0, 2.0, -0.1}, {"Spine1", "Spine", 0, 2.0, 0}, {"Neck", "Spine1", 0, 2.0, 0},
      {"Neck1", "Neck", 0, 1.6, 0.1}, {"Head", "Neck1", 0, 1.6, 0.1}, {"LeftShoulder", "Spine1", 0, 0, 0},
      {"LeftArm", "LeftShoulder", 3.4, 1.8, 0.5}, {"LeftForeArm", "LeftArm", 5.3, 0, 0}, {"LeftHand", "LeftForeArm", 3.6, 0, 0},
      {"LeftFingerBase", "LeftHand", 0, 0, 0}, {"LeftHandIndex1", "LeftFingerBase", 0.7, 0, 0}, {"LThumb", "LeftHand", 0, 0, 0},
      {"RightShoulder", "Spine1", 0, 0, 0}, {"RightArm", "RightShoulder", -3.4, 1.8, 0.5},
      {"RightForeArm", "RightArm", -5.3, 0, 0}, {"RightHand", "RightForeArm", -3.6, 0, 0},
      {"RightFingerBase", "RightHand", 0, 0, 0}, {"RightHandIndex1", "RightFingerBase", -0.7, 0, 0},
      {"RThumb", "RightHand", 0, 0, 0}};
  nlohmann::json objects = nlohmann::json::array();
  for (std::size_t j = 0; j < std::size(joints); ++j) {
    nlohmann::json o{{"name", joints[j].name}};
    if (joints[j].parent) o["parent"] = joints[j].parent;
    nlohmann::json rotation = nlohmann::json::array(), translation = nlohmann::json::array();
    for (int f = 0; f <= 120; f += 4) {
      const double t = f / 120.0, phase = 2 * M_PI * 0.8 * t + 0.7 * double(j);
      const double angle = 0.35 * std::sin(phase), axis_y = 0.2 * std::sin(double(j));
      const double n = std::sqrt(1 + axis_y * axis_y + 0.01), s = std::sin(angle / 2) / n;
      rotation.push_back({{"frame", f}, {"value", {std::cos(angle / 2), s, s * axis_y, s * 0.1}}});
      translation.push_back({{"frame", f}, {"value", {10 * t, 17 + 0.5 * std::sin(2 * phase), 0}}});
    }
    o["rotation"] = {{"keys", rotation}};
    if (joints[j].parent) {
      o["translation"] = {joints[j].x, joints[j].y, joints[j].z};
    } else {
      o["translation"] = {{"keys", translation}};
    }
    objects.push_back(o);
  }
  fs::create_directories(kOut);
  const fs::path path = kOut / "skeleton.json";
  std::ofstream(path) << nlohmann::json{{"inbetween", 1}, {"fps", 120}, {"range", {0, 120}}, {"objects", objects}}.dump();
  return path;
}

// Every bone the page drew at each scrubbed frame runs from its parent's baked world position to
// its child's, as float32 (the line's vertices are a Float32BufferAttribute, what WebGL draws):
// each vertex equals the baked double rounded to float, exactly.  Returns the bones of the first frame.
nlohmann::json check_bones(const Page& page, const Bake& bake) {
  nlohmann::json first;
  for (const auto& shown : page.data["frames"]) {
    const double f = shown["shown"].get<double>();
    if (!bake.rows.count(f)) continue;
    const auto& row = bake.rows.at(f);
    EXPECT_EQ(shown["bones"].size(), page.data["boneCount"].get<std::size_t>());
    for (const auto& bone : shown["bones"]) {
      const std::size_t p = bake.column(bone["parent"].get<std::string>() + ".translation.x");
      const std::size_t c = bake.column(bone["child"].get<std::string>() + ".translation.x");
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(bone["from"][i].get<double>(), double(float(row[p + i]))) << bone.dump() << " frame " << f;
        EXPECT_EQ(bone["to"][i].get<double>(), double(float(row[c + i]))) << bone.dump() << " frame " << f;
      }
    }
    if (first.is_null()) first = shown["bones"];
  }
  return first;
}

TEST(PreviewBrowser, SkeletonDrawsABoneFromEveryJointToItsParentAndTheRootsTrail) {
  SKIP_WITHOUT_NODE();
  const fs::path scene = write_skeleton_scene();
  const fs::path shot = kOut / "skeleton.png";
  const Page page = check_page(scene, "skeleton", {0, 60, 120}, {"Hips", "Head", "LeftHand", "RightToeBase"}, "",
                               "--overview '" + shot.string() + "'");
  if (page.skipped) GTEST_SKIP() << page.skip_reason;
  if (HasFailure()) return;
  // 31 joints, one root: 30 bones, each joint to the parent the scene gives it; the trail is the
  // root's only (a scene of more than 12 objects draws roots' trails only).
  EXPECT_EQ(page.data["boneCount"], 30);
  EXPECT_EQ(page.data["trails"], nlohmann::json({"Hips"}));
  const nlohmann::json file = nlohmann::json::parse(slurp(scene));
  std::map<std::string, std::string> parent_of;
  for (const auto& o : file["objects"])
    if (o.contains("parent")) parent_of[o["name"]] = o["parent"];
  const nlohmann::json bones = check_bones(page, read_bake(slurp(kOut / "skeleton.csv")));
  ASSERT_EQ(bones.size(), parent_of.size());
  for (const auto& bone : bones) EXPECT_EQ(parent_of[bone["child"].get<std::string>()], bone["parent"].get<std::string>()) << bone.dump();
  EXPECT_EQ(slurp(shot).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << "no screenshot";
}

TEST(PreviewBrowser, CmuClipDrawsItsSkeleton) {
  SKIP_WITHOUT_NODE();
  // The CMU clip of the demo (Debian package assimp-testmodels): 31 joints, 2 752 frames at 120 fps,
  // every frame embedded.  Runs once the tool reads BVH (`inbetween bake 01_01.bvh` succeeds).
  const fs::path clip = "/usr/share/assimp/models/BVH/01_01.bvh";
  if (!fs::exists(clip)) GTEST_SKIP() << clip << " is missing (Debian package assimp-testmodels)";
  const auto probe = run_cli("bake '" + clip.string() + "' --frames 0:0");
  if (probe.exit_code != 0) GTEST_SKIP() << "this inbetween does not read BVH yet: " << probe.err;
  const Bake one = read_bake(probe.out);
  std::vector<std::string> joints;
  for (const auto& name : one.names)
    if (name.size() > 14 && name.ends_with(".translation.x")) joints.push_back(name.substr(0, name.size() - 14));
  ASSERT_EQ(joints.size(), 31u);
  const fs::path shot = kOut / "01_01.png";
  const Page page = check_page(clip, "01_01", {0, 1375, 2751}, {joints.front(), joints.back()}, "",
                               "--overview '" + shot.string() + "'");
  if (page.skipped) GTEST_SKIP() << page.skip_reason;
  if (HasFailure()) return;
  EXPECT_EQ(page.data["boneCount"], 30);
  EXPECT_EQ(page.data["trails"], nlohmann::json({joints.front()}));
  check_bones(page, read_bake(slurp(kOut / "01_01.csv")));
  std::cout << "01_01.bvh: page " << fs::file_size(kOut / "01_01.html") << " bytes, opened in "
            << page.data["openSeconds"].get<double>() << " s\n";
}

}  // namespace
