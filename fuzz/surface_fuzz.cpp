// libFuzzer target: the surface file reader (io/surface_file.hpp, `inbetween path surface FILE.json`)
// and the two walks it feeds (Parent, Computer Animation §3.4.4).  A file that reads gives finite
// points S(u, v) over its parameter square, a finite (u, v) line, and a downhill walk of a few
// steps that is either an error with a message or finite points on the surface (|F| small against
// the surface's scale where F is the implicit form).  An error is a fine answer, but it must say
// something and be placed in the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_check.hpp"
#include "inbetween/io/surface_file.hpp"
#include "inbetween/paths/surface_path.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  if (size > 8192) return 0;
  const auto surface = parse_surface_json(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
  if (!surface) {
    if (surface.error().message.empty()) fuzz::fail("an error without a message");
    if (surface.error().location.empty() || surface.error().location.front() != LocationStep{Source{"fuzz.json"}}) fuzz::fail("a reader error not placed in the file");
    return 0;
  }
  for (double u : {-1.0, 0.0, 0.25, 0.5, 1.0, 3.0}) {
    for (double v : {-1.0, 0.0, 0.5, 1.0, 2.0}) fuzz::require_finite(surface->point(u, v), "S(u, v)", u + v);
  }
  const auto line = parametric_surface_path<double>([&](double u, double v) { return surface->point(u, v); }, Vec2d{0, 0},
                                                    Vec2d{1, 0.5}, 9);
  for (std::size_t i = 0; i < line.size(); ++i) fuzz::require_finite(line[i], "(u, v) line point", double(i));
  if (!surface->has_implicit()) return 0;
  SurfaceWalkOptions<double> options;
  options.step = surface->scale() / 8;
  options.max_steps = 16;
  const auto walk = walk_on_surface(*surface, surface->point(0.3, 0.2), options);
  if (!walk) {
    if (walk.error().message.empty()) fuzz::fail("a walk error without a message");
    return 0;
  }
  for (std::size_t i = 0; i < walk->size(); ++i) fuzz::require_finite((*walk)[i], "downhill point", double(i));
  return 0;
}
