// libFuzzer target: the BVH reader and writer (inbetween/io/bvh.hpp, docs/bvh.md).  A file that
// reads must build (the reader checks everything build_scene() would refuse at a place that is not
// a line), is baked at a few frames (every value finite), and is written back as BVH, which must
// read again with the same joints.  An error is a fine answer.  Seeds: fuzz/corpus/bvh/ (small
// hand-made files: every rotation order, position channels on a child, names with blanks, extra
// and blank MOTION lines, CRLF; and truncated heads of the CMU clips of assimp-testmodels).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_scene.hpp"
#include "inbetween/io/bvh.hpp"
#include "inbetween/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> notes;
  const auto raw = read_bvh(text, {.notes = &notes});
  if (!raw) {
    if (raw.error().location.empty() || raw.error().message.empty()) fuzz::fail("a BVH error without a place or message");
    return 0;
  }
  const Scene scene = fuzz::require_builds_and_samples(*raw, "the BVH reader returned a scene that build_scene() refuses",
                                                      "BVH scene value");
  const auto written = write_bvh(scene);
  if (!written) return 0;  // e.g. two names equal once blanks become '_'
  const auto back = read_bvh(written->text);
  if (!back) fuzz::fail("write_bvh() wrote a file that read_bvh() refuses");
  if (back->objects.size() != raw->objects.size()) fuzz::fail("write_bvh() lost or added joints");
  return 0;
}
