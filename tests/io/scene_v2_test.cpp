// Scene format version 2 through the library: the frame-22 scenario (issue 8's checks, shared with
// the CLI test in tests/support/frame22.hpp), path objects and cameras in a hierarchy, sign-continuous
// rotations through SceneCursor, curve files relative to the scene, and the reader's version check.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "inbetween/io/obj.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "inbetween/io/scene.hpp"
#include "inbetween/math/quat.hpp"
#include "support/cli.hpp"
#include "support/frame22.hpp"

namespace inbetween {
namespace {

namespace fs = std::filesystem;
const fs::path kFrame22 = fs::path(INBETWEEN_SOURCE_DIR) / "examples" / "scenes" / "frame22.json";

// The table of `scene` sampled through a cursor at frames a, a + step, …, b.
test::frame22::Table sample_table(const Scene& scene, double a, double b, double step) {
  test::frame22::Table t;
  t.column["frame"] = 0;
  for (std::size_t c = 0; c < scene.columns().size(); ++c) t.column[scene.columns()[c].name] = c + 1;
  SceneCursor cursor(scene);
  std::vector<double> row(scene.columns().size());
  for (int i = 0; a + i * step <= b; ++i) {
    const double f = a + i * step;
    scene.sample(f, row, cursor);
    std::vector<double> r{f};
    r.insert(r.end(), row.begin(), row.end());
    t.rows.push_back(std::move(r));
  }
  return t;
}

Expected<Scene> parse(const std::string& text, const std::string& source = "") { return parse_scene(text, source); }

TEST(SceneV2, Frame22ThroughTheLibrary) {
  auto scene = parse_scene(test::slurp(kFrame22), kFrame22.string());
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  test::frame22::check(sample_table(*scene, 16, 86, 0.25));
}

TEST(SceneV2, ColumnsOfPathObjectsAndCameras) {
  auto scene = parse_scene(test::slurp(kFrame22), kFrame22.string());
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<std::string> names;
  for (const auto& c : scene->columns()) names.push_back(c.name);
  // ball: 10 TRS + distance, speed; rig: 10; follow_cam: 10 + distance, speed + target; hold_cam: 10 + target.
  ASSERT_EQ(names.size(), 12u + 10u + 15u + 13u);
  EXPECT_EQ(names[10], "ball.distance");
  EXPECT_EQ(names[11], "ball.speed");
  EXPECT_EQ(names[22 + 10], "follow_cam.distance");
  EXPECT_EQ(names[22 + 12], "follow_cam.target.x");
  EXPECT_EQ(names.back(), "hold_cam.target.z");
}

// The hold camera's target: the ball until frame 60, then a sine-eased move to (5, 10, 0) over
// 12 frames, then held (the texts' hold-then-move COI).
TEST(SceneV2, HoldCameraHoldsOnTheBallThenMovesToTheEndPoint) {
  auto scene = parse_scene(test::slurp(kFrame22), kFrame22.string());
  ASSERT_TRUE(scene.has_value());
  const auto t = sample_table(*scene, 16, 86, 1);
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double f = t.at(i, "frame");
    if (f <= 60) {
      EXPECT_EQ(t.at(i, "hold_cam.target.x"), t.at(i, "ball.translation.x")) << f;
      EXPECT_EQ(t.at(i, "hold_cam.target.y"), t.at(i, "ball.translation.y")) << f;
    } else if (f >= 72) {
      EXPECT_EQ(t.at(i, "hold_cam.target.x"), 5.0) << f;
      EXPECT_EQ(t.at(i, "hold_cam.target.y"), 10.0) << f;
    }
  }
}

// A full turn on a circle-like path makes the canonical (w ≥ 0) quaternion jump to −q where
// w crosses 0; the cursor keeps it continuous (and the plain sample() does not: the test of the
// cursor can fail).
TEST(SceneV2, CursorMakesRotationsSignContinuous) {
  const std::string text = R"({"inbetween": 2, "objects": [{"name": "o", "path": {
      "curve": {"type": "catmull-rom", "closed": true, "points": [[1, 0, 0], [0, 0, -1], [-1, 0, 0], [0, 0, 1]]},
      "speed": {"kind": "ease", "start_frame": 0, "end_frame": 100}}}]})";
  auto scene = parse(text);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> row(scene->columns().size()), prev;
  SceneCursor cursor(*scene);
  int plain_flips = 0, cursor_flips = 0;
  std::vector<double> prev_plain;
  for (int f = 0; f <= 100; ++f) {
    scene->sample(f, row);
    if (!prev_plain.empty() && row[3] * prev_plain[3] + row[4] * prev_plain[4] + row[5] * prev_plain[5] + row[6] * prev_plain[6] < 0)
      ++plain_flips;
    prev_plain = row;
    scene->sample(f, row, cursor);
    if (!prev.empty() && row[3] * prev[3] + row[4] * prev[4] + row[5] * prev[5] + row[6] * prev[6] < 0) ++cursor_flips;
    prev = row;
  }
  EXPECT_GT(plain_flips, 0);
  EXPECT_EQ(cursor_flips, 0);
}

// A path object as the child of a keyed object: world = parent ∘ local.  Parent at (1, 2, 3)
// turned 90° about +Y (which maps +X to −Z); the child moves linearly along +X from 0 to 4 over
// frames 0 … 10, so its world position is (1, 2, 3 − 4t) and its front (+Z along the tangent +X
// in the parent) points along R(+X) = −Z.
TEST(SceneV2, PathObjectChildOfAKeyedObject) {
  const double h = std::sqrt(0.5);
  const std::string text = R"({"inbetween": 2, "objects": [
      {"name": "carrier", "translation": [1, 2, 3], "rotation": [)" + std::to_string(h) + ", 0, " + std::to_string(h) +
                           R"(, 0]},
      {"name": "child", "parent": "carrier", "path": {
        "curve": {"type": "bezier", "points": [[0, 0, 0], [1, 0, 0], [3, 0, 0], [4, 0, 0]]},
        "speed": {"kind": "ease", "start_frame": 0, "end_frame": 10}}}]})";
  auto scene = parse(text);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> row(scene->columns().size());
  for (double f : {0.0, 2.5, 5.0, 10.0}) {
    scene->sample(f, row);
    const double tt = f / 10;
    EXPECT_NEAR(row[10], 1, 1e-12);
    EXPECT_NEAR(row[11], 2, 1e-12);
    EXPECT_NEAR(row[12], 3 - 4 * tt, 1e-9);
    const Quatd q = Quatd::from_wxyz(row[13], row[14], row[15], row[16]);
    const Vec3d front = rotate(q, Vec3d{0, 0, 1});
    EXPECT_NEAR(front.x, 0, 1e-12);
    EXPECT_NEAR(front.z, -1, 1e-12);
    EXPECT_NEAR(row[20], 4 * tt, 1e-9);           // distance: linear ease over the length 4
    EXPECT_NEAR(row[21], 4.0 / 10 * 24, 1e-9);     // speed: 4 per 10 frames at 24 fps
  }
}

// A camera parented to a path object: the cart runs along +X from 0 to 10 (frames 0 … 10); the
// camera sits 2 above it (its RMF keeps +Y up on a straight path) and looks at the point (20, 0, 0).
TEST(SceneV2, CameraParentedToAPathObject) {
  const std::string text = R"({"inbetween": 2, "objects": [
      {"name": "cart", "path": {"curve": {"type": "bezier", "points": [[0, 0, 0], [10, 0, 0]]},
                                "speed": {"kind": "ease", "start_frame": 0, "end_frame": 10}}},
      {"name": "cam", "parent": "cart", "translation": [0, 2, 0], "camera": {"look_at": [20, 0, 0]}},
      {"name": "watcher", "translation": [0, 0, 5], "camera": {"look_at": "cam"}}]})";
  auto scene = parse(text);
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> row(scene->columns().size());
  const std::size_t cam = 12, watcher = cam + 13;
  for (double f : {0.0, 3.0, 10.0}) {
    scene->sample(f, row);
    EXPECT_NEAR(row[cam + 0], f, 1e-9);
    EXPECT_NEAR(row[cam + 1], 2, 1e-12);
    EXPECT_NEAR(row[cam + 2], 0, 1e-12);
    EXPECT_EQ(row[cam + 10], 20.0);
    const Quatd q = Quatd::from_wxyz(row[cam + 3], row[cam + 4], row[cam + 5], row[cam + 6]);
    const Vec3d view = rotate(q, Vec3d{0, 0, -1});
    const Vec3d want = Vec3d{20 - f, -2, 0} / norm(Vec3d{20 - f, -2, 0});
    EXPECT_LE(norm(cross(view, want)), 1e-12);
    EXPECT_GT(dot(view, want), 0);
    // The watcher's target is the camera's world position (read back from its columns).
    EXPECT_EQ(row[watcher + 10], row[cam + 0]);
    EXPECT_EQ(row[watcher + 11], row[cam + 1]);
  }
}

TEST(SceneV2, CurveFileRelativeToTheScene) {
  test::write_test_file("line.json", R"({"type": "bezier", "points": [[0, 0, 0], [2, 0, 0]]})");
  const fs::path scene_path = test::write_test_file(
      "s.json", R"({"inbetween": 2, "paths": [{"name": "l", "file": "line.json"}],
                    "objects": [{"name": "o", "path": {"curve": "l", "speed": {"kind": "ease", "start_frame": 0, "end_frame": 1}}}]})");
  auto scene = parse(test::slurp(scene_path), scene_path.string());
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> row(scene->columns().size());
  scene->sample(1, row);
  EXPECT_EQ(row[0], 2.0);
  // Without the scene's path the file is looked for in the current directory, and not found.
  auto lost = parse(test::slurp(scene_path));
  ASSERT_FALSE(lost.has_value());
  EXPECT_EQ(lost.error().place(), "/paths/0/file");
  EXPECT_EQ(lost.error().code, ErrorCode::io);
  // An error inside the included file keeps its own place after the file's name.
  test::write_test_file("bad.json", R"({"type": "bezier", "points": [[0, 0, 0], [2, "x", 0]]})");
  const fs::path bad = test::write_test_file("b.json", R"({"inbetween": 2, "paths": [{"name": "l", "file": "bad.json"}]})");
  auto e = parse(test::slurp(bad), bad.string());
  ASSERT_FALSE(e.has_value());
  EXPECT_EQ(e.error().describe().rfind("/paths/0/file: bad.json:/points/1", 0), 0u) << e.error().describe();
}

// Issue 21: a curve file or mesh that is a device was read to 4 GB (then exit 2, or bad_alloc for a
// mesh); now refused at once as every reader refuses non-regular files (io/read_file.hpp).
TEST(SceneV2, CurveFileOrMeshThatIsADeviceIsRefusedAtOnce) {
  const auto start = std::chrono::steady_clock::now();
  for (const std::string& text :
       {std::string(R"({"inbetween": 2, "paths": [{"name": "l", "file": "/dev/zero"}]})"),
        std::string(R"({"inbetween": 2, "paths": [{"name": "s", "surface": {"mesh": "/dev/zero", "from": 0, "to": 1}}]})")}) {
    auto r = read_scene_json(text);
    ASSERT_FALSE(r.has_value()) << text;
    EXPECT_EQ(r.error().code, ErrorCode::io) << r.error().describe();
    EXPECT_NE(r.error().message.find("not a regular file"), std::string::npos) << r.error().describe();
    EXPECT_EQ(r.error().describe().rfind("/paths/0/", 0), 0u) << r.error().describe();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

TEST(SceneV2, VersionOneRejectsTheNewMembers) {
  for (const std::string& text :
       {std::string(R"({"inbetween": 1, "paths": []})"),
        std::string(R"({"inbetween": 1, "objects": [{"name": "o", "camera": {"look_at": [0, 0, 0]}}]})"),
        std::string(R"({"inbetween": 1, "objects": [{"name": "o", "path": {}}]})")}) {
    auto r = read_scene_json(text);
    ASSERT_FALSE(r.has_value()) << text;
    EXPECT_NE(r.error().message.find("needs \"inbetween\": 2"), std::string::npos) << r.error().message;
  }
}

// Inline curve errors carry the curve's place in the scene.
TEST(SceneV2, InlineCurveErrorsNameTheirPlace) {
  auto r = parse(R"({"inbetween": 2, "objects": [{"name": "o", "path": {"curve": {"type": "bezier", "points": []},
                     "speed": {"kind": "ease", "start_frame": 0, "end_frame": 1}}}]})");
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().place(), "/objects/0/path/curve/points");
}


// Speed forms of §3.2.4 in a scene file: ⟨frame, distance, speed, acceleration⟩ constraints and an
// acceleration–time curve; their errors carry the JSON pointer of the member.
TEST(SceneV2, ConstraintAndAccelerationSpeedsRead) {
  const auto text = [](const std::string& speed) {
    return R"({"inbetween": 2, "objects": [{"name": "o", "path": {"curve": {"type": "bezier", "points": [[0, 0, 0], [10, 0, 0]]},
                                         "speed": )" + speed + "}}]}";
  };
  // Rest to rest over one second (24 frames, the default fps) covering 5: the quintic with zero
  // speed and acceleration at both ends, s = 5·(10τ³ − 15τ⁴ + 6τ⁵); at τ = ½ that is 2.5.
  auto scene = parse(text(R"({"kind": "constraints", "keys": [{"frame": 0, "distance": 0, "speed": 0, "acceleration": 0},
                                                          {"frame": 24, "distance": 5, "speed": 0, "acceleration": 0}]})"));
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> row(scene->columns().size());
  scene->sample(12, row);
  EXPECT_NEAR(row[0], 2.5, 1e-12);  // x on the straight path = distance
  scene->sample(6, row);
  const double tau = 0.25;
  EXPECT_NEAR(row[0], 5 * (10 * tau * tau * tau - 15 * tau * tau * tau * tau + 6 * tau * tau * tau * tau * tau), 1e-12);
  // Constant acceleration 2 per second² from rest: s = t² at t = 1 s (frame 24).
  scene = parse(text(R"({"kind": "acceleration_keys", "accelerations": [{"frame": 0, "acceleration": 2}, {"frame": 48, "acceleration": 2}],
                        "shape": "constant"})"));
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  scene->sample(24, row);
  EXPECT_NEAR(row[0], 1.0, 1e-12);
  // Errors.
  auto bad = parse(text(R"({"kind": "constraints", "keys": [{"frame": 0, "distance": 0}, {"frame": 10, "distance": 2, "speed": 4.8, "acceleration": 0},
                                                        {"frame": 20, "distance": 2.2, "speed": 0, "acceleration": -400}]})"));
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().place(), "/objects/0/path/speed/keys/1");
  EXPECT_NE(bad.error().message.find("backwards"), std::string::npos) << bad.error().message;
  bad = parse(text(R"({"kind": "constraints", "keys": [{"frame": 0, "distance": 0}, {"frame": 0, "distance": 1}]})"));
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().place(), "/objects/0/path/speed/keys/1");
  bad = parse(text(R"({"kind": "acceleration_keys", "accelerations": [{"frame": 0, "acceleration": 1}, {"frame": 4}]})"));
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().place(), "/objects/0/path/speed/accelerations/1/acceleration");
  bad = parse(text(R"({"kind": "acceleration_keys", "shape": "cubic", "accelerations": [{"frame": 0, "acceleration": 1}, {"frame": 4, "acceleration": 1}]})"));
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().place(), "/objects/0/path/speed/shape");
  bad = parse(text(R"({"kind": "acceleration_keys", "accelerations": [{"frame": 0, "acceleration": 0}, {"frame": 4, "acceleration": 0}], "start_speed": -2})"));
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().place(), "/objects/0/path/speed/start_speed");
}

// A path on a mesh (texts 004 §3.4.4) as a scene path: the plane path's points are coplanar, so
// the Catmull-Rom spline through them (and every sampled position) lies in the plane through the
// two vertices that contains the average of their normals — checked against that plane computed
// here from the mesh read independently; the ends are the two vertices.
TEST(SceneV2, SurfacePathIsASceneCurve) {
  const std::string mesh = std::string(INBETWEEN_SOURCE_DIR) + "/examples/meshes/icosphere.obj";
  const auto text = [&](const std::string& surface) {
    return R"({"inbetween": 2, "paths": [{"name": "s", "surface": )" + surface +
           R"(}], "objects": [{"name": "o", "path": {"curve": "s", "speed": {"kind": "ease", "start_frame": 0, "end_frame": 24}}}]})";
  };
  auto scene = parse(text(R"({"mesh": ")" + mesh + R"(", "from": 0, "to": 41})"));
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::ifstream in(mesh);
  std::stringstream ss;
  ss << in.rdbuf();
  auto m = parse_obj(ss.str(), "icosphere.obj");
  ASSERT_TRUE(m);
  const Vec3d a = m->vertex(0), b = m->vertex(41);
  const Vec3d plane_normal = normalized(cross(b - a, m->normal(0) + m->normal(41)), Vec3d{});
  std::vector<double> row(scene->columns().size());
  for (int f = 0; f <= 24; ++f) {
    scene->sample(f, row);
    const Vec3d p{row[0], row[1], row[2]};
    // Coordinates ~1 and a spline of ~10 segments: rounding only (64 ulp).
    EXPECT_NEAR(dot(p - a, plane_normal), 0.0, 64 * 2.2e-16) << f;
    if (f == 0) EXPECT_LE(distance(p, a), 1e-15);
    if (f == 24) EXPECT_LE(distance(p, b), 1e-12);
  }
  // Errors name the member of "surface".
  const auto where = [&](const std::string& surface) {
    auto r = parse(text(surface));
    EXPECT_FALSE(r.has_value()) << surface;
    return r ? std::string() : r.error().place() + " | " + r.error().message;
  };
  EXPECT_EQ(where(R"({"mesh": "no-such.obj", "from": 0, "to": 1})").rfind("/paths/0/surface/mesh |", 0), 0u);
  EXPECT_EQ(where(R"({"mesh": ")" + mesh + R"(", "from": 0, "to": 42})").rfind("/paths/0/surface/to |", 0), 0u);
  EXPECT_EQ(where(R"({"mesh": ")" + mesh + R"(", "from": 1.5, "to": 2})").rfind("/paths/0/surface/from |", 0), 0u);
  EXPECT_EQ(where(R"({"mesh": ")" + mesh + R"(", "from": 3, "to": 3})").rfind("/paths/0/surface/to |", 0), 0u);
  EXPECT_EQ(where(R"({"mesh": ")" + mesh + R"(", "from": 0, "to": 2, "method": "fly"})").rfind("/paths/0/surface/method |", 0), 0u);
  EXPECT_EQ(where(R"({"mesh": ")" + mesh + R"(", "to": 2})").rfind("/paths/0/surface/from |", 0), 0u);
  // Vertices 0 and 11 are antipodal: no plane contains the chord and the average normal.
  const std::string antipodal = where(R"({"mesh": ")" + mesh + R"(", "from": 0, "to": 11})");
  EXPECT_EQ(antipodal.rfind("/paths/0/surface/to |", 0), 0u) << antipodal;
  EXPECT_NE(antipodal.find("parallel"), std::string::npos) << antipodal;
  // A malformed mesh: the OBJ's own line is in the message.
  const fs::path bad = fs::path(INBETWEEN_BINARY_DIR) / "surface-bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  const std::string bad_mesh = where(R"({"mesh": ")" + bad.string() + R"(", "from": 0, "to": 1})");
  EXPECT_EQ(bad_mesh.rfind("/paths/0/surface/mesh |", 0), 0u) << bad_mesh;
  EXPECT_NE(bad_mesh.find("line 4"), std::string::npos) << bad_mesh;
  // "surface" with "curve" in the same entry.
  auto both = parse(R"({"inbetween": 2, "paths": [{"name": "s", "curve": {"type": "bezier", "points": [[0,0,0],[1,0,0]]},
                        "surface": {"mesh": "x.obj", "from": 0, "to": 1}}], "objects": []})");
  ASSERT_FALSE(both.has_value());
  EXPECT_EQ(both.error().place(), "/paths/0/surface");
}

// A scalar track of the scene drives the distance (so a graph editor can); a track key beyond the
// path's length is reported at the track's own key.
TEST(SceneV2, TrackSpeedReadsTheNamedScalarTrack) {
  const auto text = [](double last) {
    return R"({"inbetween": 2, "tracks": [{"name": "d", "keys": [{"frame": 0, "value": 0, "interpolation": "linear"},
                                                                 {"frame": 10, "value": )" +
           std::to_string(last) + R"(, "interpolation": "linear"}]}],
      "objects": [{"name": "o", "path": {"curve": {"type": "bezier", "points": [[0, 0, 0], [3, 0, 0]]},
                                         "speed": {"kind": "track", "track": "d"}}}]})";
  };
  auto scene = parse(text(2));
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> row(scene->columns().size());
  scene->sample(5, row);
  // Column 0 is the track (single precision, exact for 1), then o's TRS, distance, speed.
  EXPECT_EQ(row[0], 1.0);
  EXPECT_NEAR(row[1 + 10], 1.0, 1e-6);     // distance = the track's value (float evaluation)
  EXPECT_NEAR(row[1], 1.0, 1e-6);          // x on the straight path = distance
  EXPECT_NEAR(row[1 + 11], 0.2 * 24, 1e-5);  // speed: slope 0.2 per frame at 24 fps
  auto bad = parse(text(5));
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().place(), "/tracks/0/keys/1");
  EXPECT_NE(bad.error().message.find("/objects/0/path"), std::string::npos) << bad.error().message;
}


// The new columns take part in the column-ownership check.
TEST(SceneV2, PathColumnsAreOwnedLikeAnyOther) {
  auto r = parse(R"({"inbetween": 2, "tracks": [{"name": "o.speed", "keys": [{"frame": 0, "value": 0}]}],
    "objects": [{"name": "o", "path": {"curve": {"type": "bezier", "points": [[0, 0, 0], [1, 0, 0]]},
                                       "speed": {"kind": "ease", "start_frame": 0, "end_frame": 1}}}]})");
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().place(), "/objects/0/name");
  EXPECT_NE(r.error().message.find("/tracks/0/name"), std::string::npos) << r.error().message;
}

// A camera on a path with its COI on a second path (at the same fraction of its length), an up
// path and a keyed tilt: it still points at its target column (the tilt rolls about the view), and
// the target is the second path's point.  The camera path runs along +X (length 10), the COI path
// along +X 5 higher (length 10): at fraction f the COI is (10 f, 5, −4).
TEST(SceneV2, CoiPathCameraWithUpPathAndKeyedTilt) {
  auto scene = parse(R"({"inbetween": 2,
    "tracks": [{"name": "tilt", "keys": [{"frame": 0, "value": 0, "interpolation": "linear"}, {"frame": 10, "value": 90}]}],
    "paths": [{"name": "coi", "curve": {"type": "bezier", "points": [[0, 5, -4], [10, 5, -4]]}},
              {"name": "sky", "curve": {"type": "bezier", "points": [[0, 20, 0], [10, 20, 0]]}}],
    "objects": [{"name": "cam", "path": {"curve": {"type": "bezier", "points": [[0, 0, 0], [10, 0, 0]]},
                                         "speed": {"kind": "ease", "start_frame": 0, "end_frame": 10}},
                 "camera": {"coi_path": "coi", "up_path": "sky", "tilt_track": "tilt"}}]})");
  ASSERT_TRUE(scene.has_value()) << scene.error().describe();
  std::vector<double> row(scene->columns().size());
  for (double f : {0.0, 2.5, 7.0, 10.0}) {
    scene->sample(f, row);
    // Columns: tilt, then cam's TRS (1 … 10), distance, speed, target.
    EXPECT_NEAR(row[13], f, 1e-9);
    EXPECT_NEAR(row[14], 5, 1e-12);
    EXPECT_NEAR(row[15], -4, 1e-12);
    const Quatd q = Quatd::from_wxyz(row[4], row[5], row[6], row[7]);
    const Vec3d view = rotate(q, Vec3d{0, 0, -1});
    const Vec3d d = Vec3d{row[13], row[14], row[15]} - Vec3d{row[1], row[2], row[3]};
    EXPECT_LE(std::atan2(norm(cross(view, d)), dot(view, d)), 1e-9) << "frame " << f;
  }
}

}  // namespace
}  // namespace inbetween
