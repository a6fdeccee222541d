// Environment files (io/environment_file.hpp): the example parses and validates against
// docs/environment.schema.json (Python's jsonschema, an independent validator; skipped without
// it), every field lands where it should, and malformed files get the JSON pointer of the fault.
#include "inbetween/io/environment_file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/random.hpp"

namespace {

using namespace inbetween;

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const std::string kSchema = std::string(INBETWEEN_SOURCE_DIR) + "/docs/environment.schema.json";
const std::string kExample = std::string(INBETWEEN_SOURCE_DIR) + "/examples/environments/hole_and_mover.json";

bool have_jsonschema() { return std::system("/usr/bin/python3 -c 'import jsonschema' > /dev/null 2>&1") == 0; }

// 0 when `file` validates against the schema.
int validate(const std::string& file) {
  const std::string cmd = "/usr/bin/python3 -c \"import json, jsonschema, sys; jsonschema.validate(json.load(open(sys.argv[2])), "
                          "json.load(open(sys.argv[1])), cls=jsonschema.Draft202012Validator)\" '" +
                          kSchema + "' '" + file + "' > /dev/null 2>&1";
  return std::system(cmd.c_str());
}

TEST(EnvironmentFile, ExampleParsesEveryField) {
  const auto f = parse_environment_json(slurp(kExample), "env.json");
  ASSERT_TRUE(f) << f.error().describe();
  EXPECT_EQ(f->environment.radius, 0.3);
  EXPECT_EQ(f->environment.bounds_max, (Vec3d{10, 10, 10}));
  EXPECT_EQ(f->ends.start, (Vec3d{0.5, 2, 5}));
  EXPECT_EQ(f->ends.goal, (Vec3d{9.5, 8, 5}));
  ASSERT_EQ(f->ends.via.size(), 1u);
  ASSERT_EQ(f->environment.obstacles.size(), 5u);
  EXPECT_EQ(std::get<SphereObstacle>(f->environment.obstacles[2]).radius, 1.0);
  EXPECT_EQ(std::get<OrientedBoxObstacle>(f->environment.obstacles[3]).rotation.z, 0.3826834);
  EXPECT_EQ(std::get<MovingSphereObstacle>(f->environment.obstacles[4]).velocity, (Vec3d{0, 1.5, 0}));
  EXPECT_EQ(f->timing.speed, 2.0);
  EXPECT_EQ(f->timing.fps, 24.0);
  EXPECT_TRUE(Environment::build(f->environment));
  if (!have_jsonschema()) GTEST_SKIP() << "python3-jsonschema not installed; schema validation not checked";
  EXPECT_EQ(validate(kExample), 0);
}

// Each edit of the example breaks it at one place: the reader names that pointer, and the schema
// (where it can see the fault) rejects it too.
TEST(EnvironmentFile, CapsuleMoverIsRead) {
  const auto f = parse_environment_json(slurp(std::string(INBETWEEN_SOURCE_DIR) + "/examples/environments/capsule_slot.json"),
                                        "capsule_slot.json");
  ASSERT_TRUE(f) << f.error().describe();
  ASSERT_TRUE(f->environment.capsule);
  EXPECT_EQ(f->environment.capsule->half_length, 1.0);
  EXPECT_EQ(f->environment.capsule->turn_rate_deg, 90.0);
  EXPECT_EQ(f->environment.radius, 0.2);
  const auto sphere = parse_environment_json(R"({"inbetween_env": 1, "radius": 0.5, "mover": {"sphere": {}},
      "start": [0, 0, 0], "goal": [1, 1, 1], "bounds": {"min": [0, 0, 0], "max": [1, 1, 1]}, "obstacles": []})", "e.json");
  ASSERT_TRUE(sphere) << sphere.error().describe();
  EXPECT_FALSE(sphere->environment.capsule);
}

TEST(EnvironmentFile, MalformedFilesNameThePointer) {
  const nlohmann::json good = nlohmann::json::parse(slurp(kExample));
  struct Case {
    const char* pointer;  // where the edit is made
    nlohmann::json value;
    const char* where;    // expected error place
    bool schema_sees_it;
  };
  const Case cases[] = {
      {"/inbetween_env", 2, "env.json:/inbetween_env", true},
      {"/start", nlohmann::json::array({1, 2}), "env.json:/start", true},
      {"/goal/2", "x", "env.json:/goal/2", true},
      {"/bounds/min", nullptr, "env.json:/bounds/min", true},
      {"/obstacles/1/box/max/0", true, "env.json:/obstacles/1/box/max/0", true},
      {"/obstacles/2/sphere/raduis", 1, "env.json:/obstacles/2/sphere/raduis", true},
      {"/obstacles/0", nlohmann::json::object({{"cone", nlohmann::json::object()}}), "env.json:/obstacles/0/cone", true},
      {"/obstacles/3/obb/rotation", nlohmann::json::array({1, 0, 0}), "env.json:/obstacles/3/obb/rotation", true},
      {"/via/0", "here", "env.json:/via/0", true},
      {"/speed", "fast", "env.json:/speed", true},
      {"/mover", nlohmann::json::object({{"cube", nlohmann::json::object()}}), "env.json:/mover/cube", false},
      {"/mover", nlohmann::json::object({{"capsule", {{"length", 1}}}}), "env.json:/mover/capsule/length", true},
      {"/mover", nlohmann::json::object({{"capsule", {{"turn_rate_deg", 1}}}}), "env.json:/mover/capsule/half_length", false},
      {"/mover", nlohmann::json::object({{"capsule", {{"half_length", "long"}}}}), "env.json:/mover/capsule/half_length", false},
  };
  for (const Case& c : cases) {
    nlohmann::json doc = good;
    if (c.value.is_null() && std::string(c.pointer) == "/bounds/min") doc["bounds"].erase("min");
    else doc[nlohmann::json::json_pointer(c.pointer)] = c.value;
    const std::string text = doc.dump();
    const auto f = parse_environment_json(text, "env.json");
    ASSERT_FALSE(f) << c.pointer;
    EXPECT_EQ(f.error().place(), c.where) << c.pointer << ": " << f.error().message;
    // The structured location is the same place (the pointer after "env.json:").
    EXPECT_EQ("env.json:" + json_pointer(f.error().location), std::string(c.where)) << c.pointer;
    if (have_jsonschema() && c.schema_sees_it) {
      const std::string path = std::string(INBETWEEN_BINARY_DIR) + "/env-bad-" + std::to_string(&c - cases) + ".json";
      std::ofstream(path) << text;
      EXPECT_NE(validate(path), 0) << c.pointer;
    }
  }
  // A number beyond the double range is refused by the JSON parser (no infinity gets through).
  std::string text = good.dump();
  const auto at = text.find("\"t0\":");
  text.replace(at, text.find_first_of(",}", at) - at, "\"t0\":1e400");
  const auto big = parse_environment_json(text, "env.json");
  ASSERT_FALSE(big);
  EXPECT_EQ(big.error().place(), "env.json");
  // Messages stay short whatever the file holds: an unterminated string of 10⁵ characters, a member
  // name of 10⁵ characters, 10⁵ nested arrays where the version goes.
  const std::string long_text(100000, 'a');
  for (const std::string& bad : {"{\"inbetween_env\": \"" + long_text,
                                 "{\"inbetween_env\": 1, \"" + long_text + "\": 1}",
                                 "{\"inbetween_env\": " + std::string(100000, '[') + std::string(100000, ']') + "}"}) {
    const auto e = parse_environment_json(bad, "env.json");
    ASSERT_FALSE(e);
    EXPECT_LT(e.error().describe().size(), 400u) << e.error().describe().substr(0, 400);
  }
  // Not JSON at all: the file is the place.
  const auto f = parse_environment_json("{\"inbetween_env\": 1", "env.json");
  ASSERT_FALSE(f);
  EXPECT_EQ(f.error().place(), "env.json");
  // A syntax error names its line and column; nesting beyond 512 levels is refused, not recursed into.
  const auto line3 = parse_environment_json("{\"inbetween_env\": 1,\n\"radius\": 1,\n\"start\": [1, 2,, 3]}", "env.json");
  ASSERT_FALSE(line3);
  EXPECT_NE(line3.error().message.find("line 3"), std::string::npos) << line3.error().message;
  const auto deep = parse_environment_json("{\"via\": " + std::string(1000, '[') + std::string(1000, ']') + "}", "env.json");
  ASSERT_FALSE(deep);
  EXPECT_NE(deep.error().message.find("nested deeper than 512"), std::string::npos) << deep.error().message;
}

// Robustness: one number of the example replaced by an extreme value, then the whole pipeline of
// `path find` (parse, build, plan, smooth, arc length, timing).  Each run ends in an Error with a
// place, or in finite numbers everywhere; never a crash or a NaN.
void collect_numbers(const nlohmann::json& j, const nlohmann::json::json_pointer& at,
                     std::vector<nlohmann::json::json_pointer>& out) {
  if (j.is_number()) out.push_back(at);
  else if (j.is_array()) for (std::size_t i = 0; i < j.size(); ++i) collect_numbers(j[i], at / i, out);
  else if (j.is_object()) for (const auto& item : j.items()) collect_numbers(item.value(), at / item.key(), out);
}

TEST(EnvironmentFile, ExtremeNumbersGiveErrorsOrFiniteResultsSeededLoop) {
  const nlohmann::json good = nlohmann::json::parse(slurp(kExample));
  std::vector<nlohmann::json::json_pointer> leaves;
  collect_numbers(good, nlohmann::json::json_pointer(), leaves);
  const double extremes[] = {0, -1, 1e-300, -1e-300, 1e300, -1e300, 1.7e308, -1.7e308, 0.5, 50, -50, 1e6};
  test::Random rng(test::seed_for(1305));
  SCOPED_TRACE(rng.trace());
  auto finite3 = [](const Vec3d& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
  for (int trial = 0; trial < 150; ++trial) {
    nlohmann::json doc = good;
    const auto& at = leaves[std::size_t(rng.integer(0, int(leaves.size()) - 1))];
    const double v = extremes[rng.integer(0, 11)];
    doc[at] = v;
    SCOPED_TRACE(at.to_string() + " = " + std::to_string(v));
    auto f = parse_environment_json(doc.dump(), "env.json");
    if (!f) continue;
    auto env = Environment::build(f->environment);
    if (!env) {
      EXPECT_FALSE(env.error().location.empty()) << env.error().describe();
      continue;
    }
    f->planner.max_nodes = 200'000;
    auto poly = plan_polyline(*env, f->ends, f->planner);
    if (!poly) {
      EXPECT_FALSE(poly.error().location.empty()) << poly.error().describe();
      continue;
    }
    for (const Vec3d& p : poly->points) ASSERT_TRUE(finite3(p));
    auto smooth = smooth_planned_path(*env, *poly);
    ASSERT_TRUE(smooth) << smooth.error().describe();
    for (const Vec3d& p : smooth->control_points) ASSERT_TRUE(finite3(p));
    auto arc = ArcLength<CatmullRomSpline<Vec3d>>::build(smooth->curve);
    if (!arc) continue;  // a path of astronomical length: the arc-length builder refuses it
    auto timing = time_path(*env, *arc, f->timing);
    if (!timing) {
      EXPECT_FALSE(timing.error().location.empty()) << timing.error().describe();
      continue;
    }
    for (const auto& k : timing->keys) ASSERT_TRUE(std::isfinite(k.t) && std::isfinite(k.s));
  }
}

TEST(EnvironmentFile, LibraryErrorsGetTheFileName) {
  const Error e{ErrorCode::invalid_argument, "obstacle 2: radius must be finite and > 0",
                {std::string("obstacles"), std::size_t{2}, std::string("sphere"), std::string("radius")}};
  EXPECT_EQ(locate_environment_error(e, "env.json").describe(),
            "env.json:/obstacles/2/sphere/radius: obstacle 2: radius must be finite and > 0");
}

}  // namespace
