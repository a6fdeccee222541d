// Agreement of the F-curve modifier stack with Blender 3.4.1, with or without Blender installed:
// tests/data/blender/fmodifiers-blender-3.4.1.json holds 124 seeded random F-curves with random
// modifier stacks built inside Blender 3.4.1 (Debian 3.4.1+dfsg-2) by tools/blender/record_modifiers.py
// — every modifier type alone, stacks of 2 and 3, Cycles first with more below, Cycles below the top
// (Blender disables it) — each modifier muted, with an influence and with a restricted range with
// blend in/out at random, exported by export_fcurves.py, with Blender's FCurve.evaluate() at random
// fractional frames inside and up to three key spans outside the keys, at range ends, envelope
// points, tan poles and whole frames.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "inbetween/io/scene.hpp"
#include "inbetween/io/scene_write.hpp"

#include "support/blender_reference.hpp"

namespace {

const char* const kReferenceFile = INBETWEEN_SOURCE_DIR "/tests/data/blender/fmodifiers-blender-3.4.1.json";

// The keys and every modifier repeat Blender's float operations in its order (docs/tracks.md), and
// the Built-in Function calls the same double-precision libm (glibc's sin, cos, tan, log, sqrt are
// correctly rounded or the same binary), so the values are Blender's bits.
constexpr double kExact = 0.0;
// Easing segments call libm: the bound of tests/support/blender_reference.hpp, of the curve's range.
using inbetween::test::kEasingLibmRelative;
using inbetween::test::uses_libm_easing;

std::string slurp(const char* path) {
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Stats {
  int curves = 0, samples = 0, not_identical = 0;
  double max_abs = 0, max_rel = 0;
};

class BlenderModifiers : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string text = slurp(kReferenceFile);
    ASSERT_FALSE(text.empty()) << "cannot read " << kReferenceFile;
    doc_ = nlohmann::json::parse(text);
  }
  static nlohmann::json doc_;
};
nlohmann::json BlenderModifiers::doc_;

TEST_F(BlenderModifiers, RecordedByBlender341AndCoversEveryModifier) {
  EXPECT_EQ(doc_.at("blender_version").get<std::string>(), "3.4.1");
  const auto& curves = doc_.at("curves");
  ASSERT_GE(curves.size(), 100u);  // a truncated or emptied file must not pass quietly
  std::set<std::string> types, functions, noise_blends, cycle_modes, generator_modes;
  int muted = 0, influenced = 0, ranged = 0, blended = 0, below_top = 0;
  for (const auto& c : curves) {
    const auto& mods = c.at("track").at("modifiers");
    for (std::size_t i = 0; i < mods.size(); ++i) {
      const auto& m = mods[i];
      const std::string type = m.at("type").get<std::string>();
      types.insert(type);
      if (type == "function") functions.insert(m.at("function").get<std::string>());
      if (type == "noise") noise_blends.insert(m.at("blend").get<std::string>());
      if (type == "generator") generator_modes.insert(m.at("mode").get<std::string>() + (m.at("additive").get<bool>() ? "+" : ""));
      if (type == "cycles") {
        cycle_modes.insert(m.at("before").get<std::string>());
        cycle_modes.insert(m.at("after").get<std::string>());
        below_top += i > 0;
      }
      muted += m.value("mute", false);
      influenced += m.contains("influence");
      if (m.contains("range")) {
        ++ranged;
        blended += m.at("range").at("blend_in").get<double>() > 0 && m.at("range").at("blend_out").get<double>() > 0;
      }
    }
  }
  EXPECT_EQ(types.size(), 7u);
  EXPECT_EQ(functions.size(), 6u);
  EXPECT_EQ(noise_blends.size(), 4u);
  EXPECT_EQ(cycle_modes.size(), 4u);
  EXPECT_EQ(generator_modes.size(), 4u);  // expanded and factorised, each additive or not
  EXPECT_GE(muted, 5);
  EXPECT_GE(influenced, 20);
  EXPECT_GE(ranged, 20);
  EXPECT_GE(blended, 5);
  EXPECT_GE(below_top, 5);
}

TEST_F(BlenderModifiers, EveryCurveMatchesBlenderEvaluate) {
  const auto& curves = doc_.at("curves");
  nlohmann::json scene = {{"inbetween", 1}, {"fps", 24}, {"range", {1, 100}}, {"tracks", nlohmann::json::array()}};
  for (std::size_t i = 0; i < curves.size(); ++i) {
    nlohmann::json track = curves[i].at("track");
    track["name"] = "curve" + std::to_string(i) + ":" + track.at("name").get<std::string>();
    scene["tracks"].push_back(std::move(track));
  }
  auto parsed = inbetween::parse_scene(scene.dump());
  ASSERT_TRUE(parsed.has_value()) << parsed.error().describe();
  ASSERT_EQ(parsed->tracks().size(), curves.size());

  std::map<std::string, Stats> by_group, by_type;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const auto& c = curves[i];
    const auto& curve = std::get<inbetween::SceneScalarTrack>(parsed->tracks()[i]).curve;
    const std::string group = c.at("group").get<std::string>();
    const auto& track_json = c.at("track");
    std::set<std::string> types;
    for (const auto& m : track_json.at("modifiers")) types.insert(m.at("type").get<std::string>());
    const double tolerance = uses_libm_easing(track_json) ? kEasingLibmRelative : kExact;
    const auto& frames = c.at("frames");
    const auto& values = c.at("values");
    double lo = values[0].get<double>(), hi = lo;
    for (const auto& v : values) {
      lo = std::min(lo, v.get<double>());
      hi = std::max(hi, v.get<double>());
    }
    const double range = hi - lo > 0 ? hi - lo : 1.0;
    std::vector<Stats*> stats{&by_group[group]};
    for (const auto& t : types) stats.push_back(&by_type[t]);
    for (Stats* s : stats) ++s->curves;
    inbetween::TrackCursor cursor;
    for (std::size_t s = 0; s < frames.size(); ++s) {
      // Numbers are float32 written as the shortest text that reads back (through double) to them.
      const float frame = float(frames[s].get<double>());
      const float expected = float(values[s].get<double>());
      const float got = curve.sample(frame);
      EXPECT_EQ(curve.sample(frame, cursor), got) << track_json.at("name") << " frame " << frame;
      EXPECT_TRUE(std::isfinite(curve.derivative(frame)));
      const double err = std::abs(double(got) - double(expected));
      for (Stats* st : stats) {
        ++st->samples;
        st->not_identical += got != expected;
        st->max_abs = std::max(st->max_abs, err);
        st->max_rel = std::max(st->max_rel, err / range);
      }
      EXPECT_LE(err / range, tolerance) << group << ", " << track_json.dump() << "\n at frame "
                                        << testing::PrintToString(frame) << ": inbetween " << got << ", Blender "
                                        << expected << " (range " << range << ")";
    }
  }
  std::printf("recorded by Blender %s (%s)\n", doc_.at("blender_version").get<std::string>().c_str(), kReferenceFile);
  std::printf("%-32s %6s %7s %9s %12s %12s\n", "group / modifier in the stack", "curves", "samples", "not exact",
              "max abs err", "max rel err");
  for (const auto* table : {&by_group, &by_type}) {
    for (const auto& [name, g] : *table) {
      std::printf("%-32s %6d %7d %9d %12.3g %12.3g\n", name.c_str(), g.curves, g.samples, g.not_identical, g.max_abs,
                  g.max_rel);
    }
  }
}

nlohmann::json all_tracks_scene(const nlohmann::json& curves) {
  nlohmann::json scene = {{"inbetween", 1}, {"fps", 24}, {"range", {1, 100}}, {"tracks", nlohmann::json::array()}};
  for (std::size_t i = 0; i < curves.size(); ++i) {
    nlohmann::json track = curves[i].at("track");
    track["name"] = "curve" + std::to_string(i);
    scene["tracks"].push_back(std::move(track));
  }
  return scene;
}

TEST_F(BlenderModifiers, WrittenAndReadBackSamplesTheSame) {
  // read → write_scene_json → read: every modifier member survives (the writer leaves defaults out).
  const auto& curves = doc_.at("curves");
  const std::string text = all_tracks_scene(curves).dump();
  auto raw = inbetween::read_scene_json(text);
  ASSERT_TRUE(raw.has_value()) << raw.error().describe();
  auto written = inbetween::write_scene_json(*raw);
  ASSERT_TRUE(written.has_value()) << written.error().describe();
  EXPECT_NE(written->find("\"modifiers\""), std::string::npos);
  auto a = inbetween::parse_scene(text);
  auto b = inbetween::parse_scene(*written);
  ASSERT_TRUE(a.has_value() && b.has_value());
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const auto& ca = std::get<inbetween::SceneScalarTrack>(a->tracks()[i]).curve;
    const auto& cb = std::get<inbetween::SceneScalarTrack>(b->tracks()[i]).curve;
    EXPECT_EQ(ca.modifiers().size(), cb.modifiers().size());
    for (const auto& f : curves[i].at("frames")) {
      const float frame = float(f.get<double>());
      EXPECT_EQ(ca.sample(frame), cb.sample(frame)) << "curve " << i << " frame " << frame;
    }
  }
}

TEST(SceneModifiers, SchemaNamesAreTheLibrarysNameTables) {
  const auto schema = nlohmann::json::parse(slurp(INBETWEEN_SOURCE_DIR "/docs/scene.schema.json"));
  const auto& kinds = schema.at("$defs").at("fmodifier").at("oneOf");
  auto as_set = [](auto names) { return std::set<std::string>(names.begin(), names.end()); };
  auto enum_of = [](const nlohmann::json& j) { return j.at("enum").get<std::set<std::string>>(); };
  std::set<std::string> types;
  for (const auto& k : kinds) {
    const auto& props = k.at("properties");
    const std::string type = props.at("type").at("const").get<std::string>();
    types.insert(type);
    if (type == "generator") EXPECT_EQ(enum_of(props.at("mode")), as_set(inbetween::generator_mode_names));
    if (type == "function") EXPECT_EQ(enum_of(props.at("function")), as_set(inbetween::builtin_function_names));
    if (type == "noise") EXPECT_EQ(enum_of(props.at("blend")), as_set(inbetween::noise_blend_names));
    if (type == "cycles") EXPECT_EQ(enum_of(props.at("after")), as_set(inbetween::cycle_mode_names));
  }
  EXPECT_EQ(types, as_set(inbetween::fmodifier_type_names));
}

TEST(SceneModifiers, BadModifiersNameTheirJsonPointer) {
  const std::string keys = R"("keys": [{"frame": 0, "value": 0}, {"frame": 10, "value": 1}])";
  auto where = [&](const std::string& members) {
    const std::string text = R"({"inbetween": 1, "tracks": [{"name": "a", "kind": "scalar", )" + keys + ", " + members + "}]}";
    auto s = inbetween::parse_scene(text);
    return s ? std::string("ok") : inbetween::json_pointer(s.error().location);
  };
  EXPECT_EQ(where(R"("modifiers": [{"type": "limits"}, {"type": "generator", "coefficients": [1]}])"),
            "/tracks/0/modifiers/1/coefficients");
  EXPECT_EQ(where(R"("modifiers": [{"type": "wobble"}])"), "/tracks/0/modifiers/0/type");
  EXPECT_EQ(where(R"("modifiers": [{"type": "noise", "blend": "screen"}])"), "/tracks/0/modifiers/0/blend");
  EXPECT_EQ(where(R"("modifiers": [{"type": "noise", "step": 2}])"), "/tracks/0/modifiers/0/step");
  EXPECT_EQ(where(R"("modifiers": [{"type": "stepped", "step": 0}])"), "/tracks/0/modifiers/0/step");
  EXPECT_EQ(where(R"("modifiers": [{"type": "stepped", "step": "nan"}])"), "/tracks/0/modifiers/0/step");
  EXPECT_EQ(where(R"("modifiers": [{"type": "envelope", "points": [{"frame": 3, "min": 0, "max": 1}, {"frame": 2, "min": 0, "max": 1}]}])"),
            "/tracks/0/modifiers/0/points/1/frame");
  EXPECT_EQ(where(R"("modifiers": [{"type": "cycles", "range": {"start": 4}}])"), "/tracks/0/modifiers/0/range/end");
  EXPECT_EQ(where(R"("modifiers": [{"type": "cycles", "influence": 2}])"), "/tracks/0/modifiers/0/influence");
  EXPECT_EQ(where(R"("modifiers": [{"type": "cycles", "count_after": 1.5}])"), "/tracks/0/modifiers/0/count_after");
  EXPECT_EQ(where(R"("modifiers": [], "cycles": {})"), "/tracks/0/cycles");
  EXPECT_EQ(where(R"("modifiers": [{"type": "limits", "min_x": null, "max_y": 3}])"), "ok");
  EXPECT_EQ(where(R"("cycles": {"after": "mirror"})"), "ok");  // the older spelling still reads
}

}  // namespace
