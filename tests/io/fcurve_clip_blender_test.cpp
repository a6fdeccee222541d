// The F-curve runtime (tracks/runtime/fcurve_clip.hpp) on every Blender-agreement case recorded in
// tests/data/blender/fcurves-blender-3.4.1.json (the curves blender_reference_test.cpp and
// blender_agreement_test.cpp check FCurve::sample on): an FCurveClip of all of them, played
// forwards in small steps over each curve's range and beyond, backwards, and at the recorded
// frames, agrees with FCurve::sample (the scalar reference, bit-identical to Blender on these
// cases) to fcurve_runtime_tolerance of the curve's value scale — and so with Blender's recorded
// values to the same.  Curves with a Cycles modifier (every mode pair, counts, cycle-aware handles
// among the cases) are in the clip too, folded into their keyed range at sampling; they are also
// played over several cycle copies each way, at their cycle boundaries and at far frames.  The
// check is fcurve_runtime_agrees (the tolerance plus one float ulp, for repeat_offset's offset).
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
    cycled += curve.simple_cycles() != nullptr;
    curves.push_back(curve);
    case_of.push_back(i);
  }
  ASSERT_GE(cycled, 1);  // the file records Cycles cases: they must not drop out silently
  const auto clip = inbetween::build_fcurve_clip(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  const float fit_tolerance = inbetween::FCurveClipOptions{}.tolerance;
  auto ctx = inbetween::make_fcurve_clip_cursor(*clip);
  std::vector<float> out(curves.size());
  std::vector<float> scale(curves.size());
  float first = 1e30f, last = -1e30f;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    scale[c] = value_scale(curves[c], fit_tolerance);
    first = std::min(first, curves[c].keys().front().x);
    last = std::max(last, curves[c].keys().back().x);
  }
  double worst = 0, worst_blender = 0;  // beyond one float ulp, relative to the value scale
  long samples = 0;
  const auto beyond_ulp = [](double value, double reference) {
    const float big = float(std::max(std::abs(value), std::abs(reference)));
    return std::max(0.0, std::abs(value - reference) - (double(std::nextafter(big, INFINITY)) - double(big)));
  };
  const auto check = [&](float frame) {
    inbetween::sample_fcurves(*clip, frame, ctx, std::span<float>(out));
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const float ref = curves[c].sample(frame);
      ASSERT_FALSE(std::isnan(out[c])) << "case " << case_of[c] << " frame " << frame;
      if (std::isfinite(ref)) worst = std::max(worst, beyond_ulp(out[c], ref) / scale[c]);
      ++samples;
      EXPECT_TRUE(inbetween::fcurve_runtime_agrees(out[c], ref, scale[c]))
          << "case " << case_of[c] << " frame " << frame << ": runtime " << out[c] << ", FCurve::sample " << ref;
    }
  };
  const float span = last - first;
  for (float f = first - 0.1f * span; f <= last + 0.1f * span; f += span / 4000) check(f);  // forwards
  for (float f = last + 0.05f * span; f >= first - 0.05f * span; f -= span / 997) check(f);  // backwards
  // Several cycle copies of every cycling case each way, forwards then backwards.
  for (float f = first - 3 * span; f <= last + 3 * span; f += span / 1511) check(f);
  for (float f = last + 3 * span; f >= first - 3 * span; f -= span / 89) check(f);
  // The cycling cases' cycle boundaries first/last + k·period (k = −5 … 5) and 3 float steps each
  // side, and far frames (one-frame folds beyond 2^23 cycles, the float extremes).
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (curves[c].simple_cycles() == nullptr) continue;
    const float x0 = curves[c].keys().front().x, x1 = curves[c].keys().back().x, period = x1 - x0;
    for (int k = -5; k <= 5; ++k) {
      for (const float end : {x0, x1}) {
        float t = float(double(end) + double(k) * double(period));
        for (int s = 0; s < 3; ++s) t = std::nextafter(t, -INFINITY);
        for (int s = 0; s < 7; ++s, t = std::nextafter(t, INFINITY)) check(t);
      }
    }
  }
  for (const float big : {1e4f, 1e6f, 1e8f, 1e20f, 3.4e38f})
    for (const float sign : {1.0f, -1.0f}) check(sign * big);
  // The recorded frames (around each key, inside and outside the 1e-4 snap band), and Blender's values.
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const auto& frames = cases[case_of[c]].at("frames");
    const auto& values = cases[case_of[c]].at("values");
    for (std::size_t s = 0; s < frames.size(); ++s) {
      const float frame = float(frames[s].get<double>());
      check(frame);
      worst_blender = std::max(worst_blender, beyond_ulp(out[c], values[s].get<double>()) / scale[c]);
    }
  }
  EXPECT_LE(worst_blender, inbetween::fcurve_runtime_tolerance);
  std::cout << "[ measured ] FCurveClip on " << curves.size() << " Blender cases (" << cycled
            << " with Cycles, " << clip->cycling_channels() << " of them cycling), " << clip->pieces() << " pieces, " << samples
            << " samples: max |runtime - FCurve::sample| - 1 ulp = " << worst << " of the value scale (fit check "
            << clip->max_fit_error() << "), vs Blender's recorded values " << worst_blender << "\n";
}

}  // namespace
