// The JSON Schema (docs/scene.schema.json) and the reader agree: the example scene validates
// against the schema and parses; the schema's enumerations are exactly the reader's names.  The
// schema check uses Python's jsonschema (an independent validator) and skips without it.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <vector>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "inbetween/io/scene.hpp"

namespace {

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const std::string kSchema = std::string(INBETWEEN_SOURCE_DIR) + "/docs/scene.schema.json";
const std::string kExample = std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes/bouncing_cube.json";

TEST(SceneSchema, ExampleValidatesAndParses) {
  // Every example scene (version 1: bouncing_cube; version 2: frame22) reads and validates.
  std::vector<std::string> examples;
  for (const auto& e : std::filesystem::directory_iterator(std::string(INBETWEEN_SOURCE_DIR) + "/examples/scenes")) {
    if (e.path().extension() == ".json") examples.push_back(e.path().string());
  }
  ASSERT_GE(examples.size(), 2u);
  for (const std::string& example : examples) {
    auto scene = inbetween::parse_scene(slurp(example), example);
    ASSERT_TRUE(scene.has_value()) << example << ": " << scene.error().describe();
  }
  if (std::system("/usr/bin/python3 -c 'import jsonschema' > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "Debian's python3-jsonschema (/usr/bin/python3) not installed; schema validation not checked";
  }
  for (const std::string& example : examples) {
    SCOPED_TRACE(example);
    const std::string cmd = "/usr/bin/python3 -c \"import json, jsonschema, sys; jsonschema.validate(json.load(open(sys.argv[2])), "
                            "json.load(open(sys.argv[1])), cls=jsonschema.Draft202012Validator)\" '" +
                            kSchema + "' '" + example + "'";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
  }
}

std::set<std::string> enum_of(const nlohmann::json& node) {
  std::set<std::string> out;
  for (const auto& v : node.at("enum")) out.insert(v.get<std::string>());
  return out;
}

TEST(SceneSchema, EnumerationsMatchTheReader) {
  const auto schema = nlohmann::json::parse(slurp(kSchema));
  const auto& defs = schema.at("$defs");
  std::set<std::string> interp;
  for (int i = 0; i <= int(inbetween::Interpolation::sine); ++i) {
    interp.insert(std::string(inbetween::to_string(inbetween::Interpolation(i))));
  }
  EXPECT_EQ(enum_of(defs.at("fcurve_key").at("properties").at("interpolation")), interp);
  std::set<std::string> handles;
  for (int i = 0; i <= int(inbetween::HandleType::auto_clamped); ++i) {
    handles.insert(std::string(inbetween::to_string(inbetween::HandleType(i))));
  }
  EXPECT_EQ(enum_of(defs.at("handle_type")), handles);
  std::set<std::string> cycles;
  for (int i = 0; i <= int(inbetween::CycleMode::mirror); ++i) {
    cycles.insert(std::string(inbetween::to_string(inbetween::CycleMode(i))));
  }
  EXPECT_EQ(enum_of(defs.at("scalar_track").at("properties").at("cycles").at("properties").at("after")), cycles);
  // Version 2: the path-motion enumerations (their one name table is to_string in path_motion.cpp).
  auto names = [](auto last) {
    std::set<std::string> out;
    for (int i = 0; i <= int(last); ++i) out.insert(std::string(inbetween::to_string(decltype(last)(i))));
    return out;
  };
  EXPECT_EQ(enum_of(defs.at("speed").at("properties").at("kind")), names(inbetween::SpeedKind::acceleration_keys));
  EXPECT_EQ(enum_of(defs.at("speed").at("properties").at("shape")), names(inbetween::AccelerationShape::linear));
  EXPECT_EQ(enum_of(defs.at("orientation").at("properties").at("closing")), names(inbetween::RmfClosing::none));
  EXPECT_EQ(enum_of(defs.at("ease").at("properties").at("kind")), names(inbetween::EaseKind::penner));
  EXPECT_EQ(enum_of(defs.at("ease").at("properties").at("curve")), names(inbetween::EasingCurve::elastic));
  EXPECT_EQ(enum_of(defs.at("ease").at("properties").at("direction")), names(inbetween::EasingDirection::in_out));
  EXPECT_EQ(enum_of(defs.at("orientation").at("properties").at("mode")), names(inbetween::OrientationMode::look_at));
  EXPECT_EQ(enum_of(defs.at("speed").at("properties").at("interpolation")),
            names(inbetween::PositionInterpolation::monotone_cubic));
  EXPECT_EQ(enum_of(defs.at("speed").at("properties").at("fit")), names(inbetween::VelocityFit::fix_keys_adjust_interior));
}

}  // namespace
