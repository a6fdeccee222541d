// `inbetween path find ENV.json -o PATH.json`: runs the built tool, reads its curve file back with
// the curve-file reader and its timing JSON, and checks, independently of the planner, that the
// object clears every grown obstacle at every sampled time, passes the via points in order, and
// that impossible problems and malformed files exit 2 with the reason and the JSON pointer.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/environment_file.hpp"
#include "support/cli.hpp"

namespace {

// Named tolerances.  Coordinates are of order 10, so a distance computed in double is off by
// about 1e-14; kExact allows for that.  kRounding also covers the arc-length inverse (16ε·L,
// arclength/arc_length.hpp) and s(t) interpolation; neither hides a real overlap, which the
// guarantees under test make non-negative.
constexpr double kExact = 1e-12;
constexpr double kRounding = 1e-9;


namespace fs = std::filesystem;
using namespace inbetween;
using inbetween::test::CliRun;
using inbetween::test::run_cli;
using inbetween::test::slurp;
using inbetween::test::write_test_file;

const std::string kExample = std::string(INBETWEEN_SOURCE_DIR) + "/examples/environments/hole_and_mover.json";

// s(t) from the timing's keys by linear interpolation (the documented meaning of the keys).
double s_at(const nlohmann::json& keys, double t) {
  for (std::size_t i = 1; i < keys.size(); ++i) {
    const double t0 = keys[i - 1][0], t1 = keys[i][0], s0 = keys[i - 1][1], s1 = keys[i][1];
    if (t <= t1) return s0 + (s1 - s0) * std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
  }
  return keys.back()[1];
}

TEST(PathFindCli, ExamplePathClearsEveryObstacleAtEverySampledTime) {
  const auto out = test::test_dir() / "path.json";
  const CliRun r = run_cli("path find '" + kExample + "' -o '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The curve file reads back, and `curve sample` takes it.
  const auto curve = parse_curve_json(slurp(out), "path.json");
  ASSERT_TRUE(curve) << curve.error().describe();
  EXPECT_EQ(curve->kind, CurveKind::catmull_rom);
  const CliRun sample = run_cli("curve sample '" + out.string() + "' --count 5");
  EXPECT_EQ(sample.exit_code, 0) << sample.err;
  const auto timing = nlohmann::json::parse(r.out);
  EXPECT_EQ(timing.at("inbetween_timing"), 1);
  // The example's mover crosses the hole's exit while the object would be there: it waits.
  EXPECT_EQ(timing.at("avoidance"), "timing");
  EXPECT_GT(timing.at("wait").get<double>(), 0.0);

  const auto file = parse_environment_json(slurp(kExample), "env.json");
  ASSERT_TRUE(file);
  const auto env = Environment::build(file->environment);
  ASSERT_TRUE(env);
  const auto arc = make_arc_length(*curve);
  ASSERT_TRUE(arc);
  EXPECT_NEAR(arc->length(), timing.at("length").get<double>(), kRounding);
  // The start, the via point and the goal, in this order along the curve.
  const std::vector<Vec3d> stops{file->ends.start, file->ends.via[0], file->ends.goal};
  const double L = arc->length(), duration = timing.at("duration");
  const nlohmann::json& keys = timing.at("keys");
  EXPECT_NEAR(s_at(keys, duration), L, kRounding);
  const int n = int(std::ceil(duration * 24 * 16));  // 16 samples per frame of the file's fps 24
  std::vector<double> best(stops.size(), 1e300), best_s(stops.size(), 0);
  double prev_s = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = duration * i / n, s = s_at(keys, t);
    ASSERT_GE(s, prev_s - kExact);
    prev_s = s;
    const Vec3d p = arc->point_at_length(s);
    ASSERT_GE(env->static_clearance(p), -kRounding) << "t = " << t;
    for (int k : env->moving_indices()) ASSERT_GE(env->moving_clearance(k, p, t), -kRounding) << "t = " << t;
  }
  for (int i = 0; i <= 20000; ++i) {
    const double s = L * i / 20000;
    const Vec3d p = arc->point_at_length(s);
    for (std::size_t k = 0; k < stops.size(); ++k)
      if (distance(p, stops[k]) < best[k]) best[k] = distance(p, stops[k]), best_s[k] = s;
  }
  for (std::size_t k = 0; k < stops.size(); ++k) {
    EXPECT_LT(best[k], L / 20000) << k;  // within half a sample step of the curve
    if (k > 0) EXPECT_LT(best_s[k - 1], best_s[k]) << k;
  }
}

std::string edited(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json doc = nlohmann::json::parse(slurp(kExample));
  edit(doc);
  return doc.dump(1);
}

CliRun run_on(const std::string& text) {
  const auto env = write_test_file("env.json", text);
  const auto out = test::test_dir() / "path.json";
  fs::remove(out);
  CliRun r = run_cli("path find '" + env.string() + "' -o '" + out.string() + "'");
  EXPECT_FALSE(fs::exists(out)) << "nothing is written on an error";
  return r;
}

TEST(PathFindCli, ImpossibleProblemsExit2WithTheReason) {
  // The start inside the sphere (obstacle 2, centre (7, 6, 5), radius 1).
  CliRun r = run_on(edited([](auto& d) { d["start"] = {7, 6, 5.5}; }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/start: no path: the start lies inside obstacle 2"), std::string::npos) << r.err;
  // The goal outside the bounds.
  r = run_on(edited([](auto& d) { d["goal"] = {11, 5, 5}; }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/goal: no path: the goal lies outside the bounds"), std::string::npos) << r.err;
  // The hole closed (the object's radius 1.2 does not fit through its half-width 1): the via
  // point in the hole is now inside the grown walls; with the via point removed, the goal cannot
  // be reached from the start.
  r = run_on(edited([](auto& d) { d["radius"] = 1.2; }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/via/0: no path: via point 0 lies inside obstacle"), std::string::npos) << r.err;
  r = run_on(edited([](auto& d) {
    d["radius"] = 1.2;
    d["via"] = nlohmann::json::array();
    d["start"] = {1.3, 2, 5};
    d["cell_size"] = 0.25;
  }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/goal: no path: the goal cannot be reached from the start"), std::string::npos)
      << r.err;
  // A mover that sweeps the whole hole region back and forth forever cannot be waited out: a
  // sphere of radius 3 sitting on the via point, drifting slowly.
  r = run_on(edited([](auto& d) {
    d["obstacles"][4] = {{"moving_sphere", {{"center", {5, 5, 5}}, {"velocity", {0, 0, 0.01}}, {"radius", 3}}}};
  }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/obstacles/4: no timing:"), std::string::npos) << r.err;
}

// A mover coming head-on down the straight path: the timing alone cannot avoid it (exit 2 with
// --no-steering); the default steers around it and says so.
TEST(PathFindCli, SteeringIsReportedWhenTheTimingAloneFails) {
  const std::string text =
      R"({"inbetween_env": 1, "radius": 0.3, "start": [1, 5, 5], "goal": [9, 5, 5],
          "bounds": {"min": [0, 0, 0], "max": [10, 10, 10]},
          "obstacles": [{"moving_sphere": {"center": [9, 5, 5], "velocity": [-1, 0, 0], "radius": 1}}],
          "speed": 2, "fps": 24})";
  const auto env = write_test_file("env.json", text);
  const auto out = test::test_dir() / "path.json";
  CliRun r = run_cli("path find '" + env.string() + "' -o '" + out.string() + "' --no-steering");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/obstacles/0: no timing:"), std::string::npos) << r.err;
  r = run_cli("path find '" + env.string() + "' -o '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto timing = nlohmann::json::parse(r.out);
  EXPECT_EQ(timing.at("avoidance"), "steering");
  ASSERT_GE(timing.at("detours").size(), 1u);
  EXPECT_EQ(timing.at("detours")[0].at("obstacle"), 0);
  // The timed motion read back from the files clears the mover at every sampled time.
  const auto curve = parse_curve_json(slurp(out), "path.json");
  ASSERT_TRUE(curve);
  const auto arc = make_arc_length(*curve);
  ASSERT_TRUE(arc);
  const double duration = timing.at("duration");
  const int n = int(std::ceil(duration * 24 * 16));
  for (int i = 0; i <= n; ++i) {
    const double t = duration * i / n;
    const Vec3d p = arc->point_at_length(s_at(timing.at("keys"), t));
    // centre(t) = (9 − t, 5, 5); clearance ≥ 1 + 0.3.
    ASSERT_GE(distance(p, Vec3d{9 - t, 5, 5}), 1.3 - kRounding) << "t = " << t;
  }
}

TEST(PathFindCli, MalformedFilesExit2WithThePointer) {
  CliRun r = run_on(edited([](auto& d) { d["obstacles"][1]["box"]["max"] = {5, 10}; }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/obstacles/1/box/max: expected 3 numbers, got 2"), std::string::npos) << r.err;
  r = run_on(edited([](auto& d) { d.erase("goal"); }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/goal: missing required field"), std::string::npos) << r.err;
  r = run_on(edited([](auto& d) { d["obstacles"][3]["obb"]["rotation"] = {0, 0, 0, 0}; }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/obstacles/3/obb/rotation: obstacle 3:"), std::string::npos) << r.err;
  r = run_on(edited([](auto& d) { d["fps"] = 0; }));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json:/fps:"), std::string::npos) << r.err;
  r = run_on("{\"inbetween_env\": 1, \"radius\": ");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("env.json: invalid JSON"), std::string::npos) << r.err;
  r = run_on("");
  EXPECT_EQ(r.exit_code, 2);
  // A missing file.
  r = run_cli("path find /nonexistent/env.json -o x.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/env.json"), std::string::npos) << r.err;
}


// A capsule mover (examples/environments/capsule_slot.json): the poses written by --poses, read
// back from the CSV, keep the capsule (axis = the rotation's +x, half length 1, radius 0.2) clear
// of both walls by the exact segment-to-box distance at every frame, lie on the curve written by
// -o, and the timing lists the turns.
TEST(PathFindCli, CapsulePosesClearTheWallsAtEveryFrame) {
  const std::string env = std::string(INBETWEEN_SOURCE_DIR) + "/examples/environments/capsule_slot.json";
  const fs::path dir = inbetween::test::test_dir();
  const CliRun r = run_cli("path find " + env + " -o " + (dir / "capsule.json").string() + " --poses " +
                           (dir / "poses.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json timing = nlohmann::json::parse(r.out);
  ASSERT_TRUE(timing["mover"].contains("capsule"));
  ASSERT_GE(timing["turns"].size(), 1u);
  const BoxObstacle walls[] = {{{4.5, -1, -1}, {5.5, 4.6, 1.5}}, {{4.5, 5.4, -1}, {5.5, 11, 1.5}}};
  std::istringstream in(slurp(dir / "poses.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,x,y,z,qw,qx,qy,qz");
  int rows = 0;
  double worst = 1e300, last_t = -1;
  while (std::getline(in, line)) {
    double v[8];
    char comma = 0;
    std::istringstream ls(line);
    ls >> v[0];
    for (int k = 1; k < 8; ++k) ls >> comma >> v[k];
    ASSERT_TRUE(ls) << line;
    EXPECT_GT(v[0], last_t);
    last_t = v[0];
    const Vec3d p{v[1], v[2], v[3]};
    const Vec3d axis = rotate(Quatd::from_wxyz(v[4], v[5], v[6], v[7]), Vec3d{1, 0, 0});
    EXPECT_NEAR(norm(axis), 1.0, kExact);
    for (const BoxObstacle& w : walls) worst = std::min(worst, segment_distance_to_obstacle(w, p - axis, p + axis) - 0.2);
    ++rows;
  }
  // One row per frame at 24 fps over the duration, and the end.
  const double duration = timing["duration"];
  EXPECT_EQ(rows, int(std::ceil(duration * 24)) + 1);
  EXPECT_NEAR(last_t, duration, kExact);
  EXPECT_GE(worst, -kExact);
  // --poses needs a capsule.
  const CliRun sphere = run_cli("path find " + kExample + " -o " + (dir / "s.json").string() + " --poses " +
                                (dir / "s.csv").string());
  EXPECT_EQ(sphere.exit_code, 2);
  EXPECT_NE(sphere.err.find("--poses: "), std::string::npos) << sphere.err;
  EXPECT_FALSE(fs::exists(dir / "s.json"));
  // A capsule among moving spheres is refused, naming the mover.
  auto doc = nlohmann::json::parse(slurp(env));
  doc["obstacles"].push_back({{"moving_sphere", {{"center", {5, 5, 0}}, {"velocity", {0, 1, 0}}, {"radius", 0.3}}}});
  const CliRun moving = run_cli("path find " + write_test_file("env.json", doc.dump()).string() + " -o x.json");
  EXPECT_EQ(moving.exit_code, 2);
  EXPECT_NE(moving.err.find("env.json:/mover/capsule: a capsule mover is planned among static obstacles only"), std::string::npos)
      << moving.err;
  // A slot narrower than 2r: no path, with the reason.
  doc = nlohmann::json::parse(slurp(env));
  doc["obstacles"][1]["box"]["min"][1] = 4.9;
  const CliRun narrow = run_cli("path find " + write_test_file("env.json", doc.dump()).string() + " -o x.json");
  EXPECT_EQ(narrow.exit_code, 2);
  EXPECT_NE(narrow.err.find("env.json:/goal: no path: the goal cannot be reached from the start"), std::string::npos) << narrow.err;
  EXPECT_NE(narrow.err.find("for the capsule of half length 1 and radius 0.2"), std::string::npos) << narrow.err;
}

}  // namespace
