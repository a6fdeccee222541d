// libFuzzer target: the scene reader.  Reads the input as scene JSON; a scene that parses is baked
// at a few frames (the range ends and middle, and frames far outside) and every value must be
// finite (docs/scene-format.md: no NaN or infinity from finite input).  An error is a fine answer.
// The scene's F-curve tracks (Cycles modifiers included) also go through the F-curve runtime
// (tracks/runtime/fcurve_clip.hpp), which must agree with FCurve::sample at those frames and at
// far ones (fcurve_runtime_agrees), forwards and backwards.
#include <cstddef>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <span>
#include <variant>
#include <string_view>
#include <vector>

#include "fuzz_check.hpp"
#include "inbetween/io/scene.hpp"
#include "inbetween/scene/scene.hpp"
#include "inbetween/tracks/runtime/fcurve_clip.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  const auto scene = parse_scene(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!scene) return 0;
  std::vector<double> out(scene->columns().size());
  const double a = scene->range_start(), b = scene->range_end();
  const double frames[] = {a, b, fuzz::lerp_in(a, b, 0.5), fuzz::lerp_in(a, b, 0.37), a - 1.5, b + 2.25,
                           0.0, -1e9, 1e9};
  for (const double frame : frames) {
    if (!std::isfinite(frame)) continue;  // a - 1.5 cannot overflow, but keep the guard obvious
    scene->sample(frame, out);
    for (const double v : out) fuzz::require_finite(v, "scene value", frame);
  }
  // The runtime on the F-curves (a few small ones: compiling fits every segment, which would
  // dominate the run on large inputs).
  std::vector<FCurve> curves;
  std::size_t keys = 0;
  for (const auto& track : scene->tracks()) {
    if (const auto* scalar = std::get_if<SceneScalarTrack>(&track)) {
      curves.push_back(scalar->curve);
      keys += scalar->curve.keys().size();
    }
  }
  if (curves.empty() || curves.size() > 16 || keys > 256) return 0;
  const auto clip = build_fcurve_clip(curves);
  if (!clip) return 0;
  auto ctx = make_fcurve_clip_cursor(*clip);
  std::vector<float> values(curves.size());
  const float runtime_frames[] = {float(a), float(fuzz::lerp_in(a, b, 0.37)), float(b), float(b) + 7.25f, 1e6f,
                                  -1e6f, 3e38f, float(a) - 0.5f, -31.75f};
  for (const float frame : runtime_frames) {
    sample_fcurves(*clip, frame, ctx, std::span<float>(values));
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const float ref = curves[c].sample(frame);
      if (std::isnan(values[c])) fuzz::fail("FCurveClip sample is NaN");
      float lo = curves[c].keys()[0].y, hi = lo;
      for (const auto& k : curves[c].keys())
        for (const float v : {k.y, k.left.y, k.right.y}) lo = std::min(lo, v), hi = std::max(hi, v);
      // The value scale as build_fcurve_clip defines it, at least its floor of 8 ε·max |value| / tolerance.
      float big = 0;
      for (const auto& k : curves[c].keys())
        for (const float v : {k.y, k.left.y, k.right.y}) big = std::max(big, std::abs(v));
      float scale = std::max(hi - lo, 8.0f * std::numeric_limits<float>::epsilon() * big / FCurveClipOptions{}.tolerance);
      if (!(scale > 0)) scale = 1;
      // The fit's own check: a curve whose fit stopped at max_pieces_per_segment says so.
      if (clip->max_fit_error() <= FCurveClipOptions{}.tolerance && !fcurve_runtime_agrees(values[c], ref, scale)) {
        std::fprintf(stderr, "fuzz: curve %zu at frame %.9g: runtime %.9g, FCurve::sample %.9g\n", c, double(frame),
                     double(values[c]), double(ref));
        fuzz::fail("FCurveClip disagrees with FCurve::sample");
      }
    }
  }
  return 0;
}
