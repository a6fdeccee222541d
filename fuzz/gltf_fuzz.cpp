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

#include "fuzz_scene.hpp"
#include "inbetween/io/gltf.hpp"
#include "inbetween/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  const auto raw = read_gltf(std::as_bytes(std::span<const std::uint8_t>(data, size)), "", {});
  if (!raw) return 0;
  fuzz::require_builds_and_samples(*raw, "the glTF reader returned a scene that build_scene() refuses", "glTF scene value");
  return 0;
}
