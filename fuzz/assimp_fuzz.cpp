// libFuzzer target: the assimp reader (inbetween/io/assimp.hpp, docs/assimp.md) on bytes in memory,
// with no extension hint: assimp tells the format by content among the importers the reader
// enables (FBX, Collada, .x, MD5, SMD, B3D, MS3D, ASE, LWS/LWO, CSM), and no file beside the
// input can be opened.  A file that reads must build (the reader checks what build_scene() would
// refuse) and is then sampled at a few frames, every value finite.  An error is a fine answer.
// Seeds: fuzz/corpus/assimp/ (small files of Debian's assimp-testmodels, BSD-3-clause, and a
// hand-written animated .x).  assimp itself is not built with coverage instrumentation, so
// libFuzzer steers by our code's coverage only; ASan still sees assimp's heap through its
// interceptors (memcpy, malloc/free) but not its plain loads and stores.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_scene.hpp"
#include "inbetween/io/assimp.hpp"
#include "inbetween/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  if (size > (std::size_t(1) << 20)) return 0;  // the seeds are a few KB; keep each run short
  const auto raw = read_assimp(std::as_bytes(std::span<const std::uint8_t>(data, size)), "", {});
  if (!raw) return 0;
  fuzz::require_builds_and_samples(*raw, "the assimp reader returned a scene that build_scene() refuses", "assimp scene value");
  return 0;
}
