// libFuzzer target: the environment reader and 3-D path finding (texts 004 §3.4.5).  An environment
// that reads and builds is planned with a coarse lattice (so one input stays fast); a found path must
// start and end at the file's start and goal, hold only finite points and positions, and clear every
// inflated static obstacle at its polyline points.  An error is a fine answer, but it must say
// something.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_check.hpp"
#include "inbetween/io/environment_file.hpp"
#include "inbetween/paths/path_planner.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace inbetween;
  if (size > 4096) return 0;
  const auto file = parse_environment_json(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
  if (!file) {
    if (file.error().message.empty()) fuzz::fail("an error without a message");
    if (file.error().location.empty() || file.error().location.front() != LocationStep{Source{"fuzz.json"}}) fuzz::fail("a reader error not placed in the file");
    return 0;
  }
  const auto env = Environment::build(file->environment);
  if (!env) {
    if (env.error().message.empty()) fuzz::fail("an error without a message");
    // Every builder error names its place in the file's shape (Error::location).
    if (env.error().location.empty()) fuzz::fail("a build error without a location");
    return 0;
  }
  FindPathOptions options;
  options.planner = file->planner;
  options.planner.max_nodes = 150'000;  // the automatic 48-cell lattice fits; finer ones are refused
  options.timing = file->timing;
  options.timing.max_duration_factor = 4;
  const auto found = find_path(*env, file->ends, options);
  if (!found) {
    if (found.error().message.empty()) fuzz::fail("an error without a message");
    return 0;
  }
  const auto& points = found->polyline.points;
  if (points.empty()) fuzz::fail("a found path without points");
  for (std::size_t i = 0; i < points.size(); ++i) fuzz::require_finite(points[i], "polyline point", double(i));
  if (points.front() != file->ends.start || points.back() != file->ends.goal) fuzz::fail("a path that misses its ends");
  for (double s : {0.0, 0.5, 1.0}) {
    fuzz::require_finite(found->arc.point_at_length(s * found->arc.length()), "spline point", s);
  }
  return 0;
}
