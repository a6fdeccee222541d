#pragma once
// What the fuzz targets of the file readers that give a RawScene (glTF, BVH, assimp) assert of a
// file that reads: build_scene() accepts it, and sampling at the range's ends, two inner frames,
// just outside and at frame 0 gives finite values only.

#include <cmath>
#include <optional>
#include <vector>

#include "fuzz_check.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween::fuzz {

/// The built scene of `raw`, sampled as above; aborts with `refused` when it does not build, or
/// names `value_name` and the frame when a value is not finite.
inline Scene require_builds_and_samples(const RawScene& raw, const char* refused, const char* value_name) {
  auto scene = build_scene(raw);
  if (!scene) fail(refused);
  std::vector<double> out(scene->columns().size());
  const double a = scene->range_start(), b = scene->range_end();
  const double frames[] = {a, b, lerp_in(a, b, 0.5), lerp_in(a, b, 0.37), a - 1.5, b + 2.25, 0.0};
  for (const double frame : frames) {
    if (!std::isfinite(frame)) continue;
    scene->sample(frame, out);
    for (const double v : out) require_finite(v, value_name, frame);
  }
  return std::move(*scene);
}

}  // namespace inbetween::fuzz
