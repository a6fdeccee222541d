// libFuzzer target: the scene reader.  Reads the input as scene JSON; a scene that parses is baked
// at a few frames (the range ends and middle, and frames far outside) and every value must be
// finite (docs/scene-format.md: no NaN or infinity from finite input).  An error is a fine answer.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_check.hpp"
#include "inbetween/io/scene.hpp"
#include "inbetween/scene/scene.hpp"

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
  return 0;
}
