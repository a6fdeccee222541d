// libFuzzer target: the glTF reader (inbetween/io/gltf.hpp, docs/gltf.md).  Reads the input as a
// .glb or .gltf (told apart by the magic, as the reader does; no base directory, so an external
// URI never touches the file system); a file that reads must build (the reader checks everything
// build_scene() would refuse), and is then baked at a few frames, every value finite.  An error is
// a fine answer.  Seeds: fuzz/corpus/gltf/ (files written by tests/support/gltf_builder.hpp: every
// sampler × path, sparse and normalised accessors, a hierarchy, a morph mesh; perspective and
// orthographic cameras under a turned parent).
// To enable: add `gltf` to INBETWEEN_FUZZ_TARGETS in fuzz/CMakeLists.txt.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_check.hpp"
#include "inbetween/io/gltf.hpp"
#include "inbetween/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  const auto raw = read_gltf(std::as_bytes(std::span<const std::uint8_t>(data, size)), "", {});
  if (!raw) return 0;
  const auto scene = build_scene(*raw);
  if (!scene) fuzz::fail("the glTF reader returned a scene that build_scene() refuses");
  std::vector<double> out(scene->columns().size());
  const double a = scene->range_start(), b = scene->range_end();
  const double frames[] = {a, b, fuzz::lerp_in(a, b, 0.5), fuzz::lerp_in(a, b, 0.37), a - 1.5, b + 2.25, 0.0};
  for (const double frame : frames) {
    if (!std::isfinite(frame)) continue;
    scene->sample(frame, out);
    for (const double v : out) fuzz::require_finite(v, "glTF scene value", frame);
  }
  return 0;
}
