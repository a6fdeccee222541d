// The F-curve runtime (tracks/runtime/fcurve_clip.hpp) on every Blender-agreement case recorded in
// tests/data/blender/fcurves-blender-3.4.1.json (the curves blender_reference_test.cpp and
// blender_agreement_test.cpp check FCurve::sample on): an FCurveClip of all of them, played
// forwards in small steps over each curve's range and beyond, backwards, and at the recorded
// frames, agrees with FCurve::sample (the scalar reference, bit-identical to Blender on these
// cases) to fcurve_runtime_tolerance of the curve's value scale — and so with Blender's recorded
// values to the same.  Curves with a Cycles modifier are refused by the runtime (Unsupported) and
// stay on the scalar path: counted and printed, not compared.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "inbetween/io/scene.hpp"
#include "inbetween/tracks/runtime/fcurve_clip.hpp"

namespace {

const char* const kReferenceFile = INBETWEEN_SOURCE_DIR "/tests/data/blender/fcurves-blender-3.4.1.json";

// The value scale fcurve_runtime_tolerance is relative to (as build_fcurve_clip defines it).
float value_scale(const inbetween::FCurve& c, float tolerance) {
  float lo = c.keys()[0].y, hi = lo, big = std::abs(lo);
  for (const auto& k : c.keys())
    for (const float v : {k.y, k.left.y, k.right.y}) lo = std::min(lo, v), hi = std::max(hi, v), big = std::max(big, std::abs(v));
  float s = std::max(hi - lo, 8.0f * std::numeric_limits<float>::epsilon() * big / tolerance);
  return s > 0 ? s : 1.0f;
}

TEST(FCurveClipBlender, AgreesWithFCurveSampleOnEveryRecordedCase) {
  std::ifstream in(kReferenceFile);
  std::ostringstream ss;
  ss << in.rdbuf();
  const auto doc = nlohmann::json::parse(ss.str());
  const auto& cases = doc.at("curves");
  ASSERT_GE(cases.size(), 250u);  // a truncated file must not pass quietly
  nlohmann::json scene = {{"inbetween", 1}, {"fps", 24}, {"range", {1, 100}}, {"tracks", nlohmann::json::array()}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    nlohmann::json track = cases[i].at("track");
    track["name"] = "curve" + std::to_string(i);
    scene["tracks"].push_back(std::move(track));
  }
  auto parsed = inbetween::parse_scene(scene.dump());
  ASSERT_TRUE(parsed.has_value()) << parsed.error().describe();
  std::vector<inbetween::FCurve> curves;
  std::vector<std::size_t> case_of;
  int cycled = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& curve = std::get<inbetween::SceneScalarTrack>(parsed->tracks()[i]).curve;
    if (curve.cycles()) {
      ++cycled;
      const auto one = std::vector<inbetween::FCurve>{curve};
      const auto refused = inbetween::build_fcurve_clip(one);
      ASSERT_FALSE(refused);
      EXPECT_EQ(refused.error().code, inbetween::ErrorCode::Unsupported);
      continue;
    }
    curves.push_back(curve);
    case_of.push_back(i);
  }
  const auto clip = inbetween::build_fcurve_clip(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  const float fit_tolerance = inbetween::FCurveClipOptions{}.tolerance;
  auto ctx = inbetween::make_fcurve_context(*clip);
  std::vector<float> out(curves.size());
  std::vector<float> scale(curves.size());
  float first = 1e30f, last = -1e30f;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    scale[c] = value_scale(curves[c], fit_tolerance);
    first = std::min(first, curves[c].keys().front().x);
    last = std::max(last, curves[c].keys().back().x);
  }
  double worst = 0, worst_blender = 0;
  long samples = 0;
  const auto check = [&](float frame) {
    inbetween::sample_fcurves(*clip, frame, ctx, std::span<float>(out));
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const double err = std::abs(double(out[c]) - double(curves[c].sample(frame))) / scale[c];
      worst = std::max(worst, err);
      ++samples;
      EXPECT_LE(err, inbetween::fcurve_runtime_tolerance) << "case " << case_of[c] << " frame " << frame;
    }
  };
  const float span = last - first;
  for (float f = first - 0.1f * span; f <= last + 0.1f * span; f += span / 4000) check(f);  // forwards
  for (float f = last + 0.05f * span; f >= first - 0.05f * span; f -= span / 997) check(f);  // backwards
  // The recorded frames (around each key, inside and outside the 1e-4 snap band), and Blender's values.
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const auto& frames = cases[case_of[c]].at("frames");
    const auto& values = cases[case_of[c]].at("values");
    for (std::size_t s = 0; s < frames.size(); ++s) {
      const float frame = float(frames[s].get<double>());
      check(frame);
      worst_blender = std::max(worst_blender, std::abs(double(out[c]) - values[s].get<double>()) / scale[c]);
    }
  }
  EXPECT_LE(worst_blender, inbetween::fcurve_runtime_tolerance);
  std::cout << "[ measured ] FCurveClip on " << curves.size() << " Blender cases (" << cycled
            << " with Cycles: scalar path), " << clip->pieces() << " pieces, " << samples
            << " samples: max |runtime - FCurve::sample| = " << worst << " of the value scale (fit check "
            << clip->max_fit_error() << "), vs Blender's recorded values " << worst_blender << "\n";
}

}  // namespace
