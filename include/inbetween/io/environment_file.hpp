#pragma once
/// Environment files for 3-D path finding: the versioned JSON form (docs/paths.md,
/// docs/environment.schema.json) of the obstacles, the moving object's radius, the search bounds,
/// the start, via points and goal, and the speed and frame rate of the timing.  The reader checks
/// the JSON shape (types, arities, unknown fields); the values are checked by the library's
/// builders (Environment::build, plan_polyline, time_path), whose errors carry structured
/// locations of this shape and only need rendering with the file name (locate_environment_error).

#include <string>
#include <string_view>

#include "inbetween/math/expected.hpp"
#include "inbetween/paths/environment.hpp"
#include "inbetween/paths/path_planner.hpp"

namespace inbetween {

/// The environment format version this library reads ("inbetween_env": 1).
inline constexpr int environment_format_version = 1;

/// Everything an environment file holds, unchecked beyond its JSON shape.
struct EnvironmentFile {
  RawEnvironment environment;   ///< radius, bounds, obstacles in file order
  PathEnds ends;                ///< start, via points, goal
  PlannerOptions planner;       ///< "cell_size" and "margin" when given
  PathTimingOptions timing;     ///< "speed" and "fps" when given
};

/// Parses an environment file.  The JSON is read with bounded nesting (at most 512 levels); a
/// syntax error names its line and column.  Errors carry the place in `location`,
/// ({Source{source_name}, "obstacles", 2, "box", "min", 1}, rendered "env.json:/obstacles/2/box/min/1";
/// just the source for errors of the whole text), and say what was expected.
Expected<EnvironmentFile> parse_environment_json(std::string_view text, std::string_view source_name);
/// A library error (Environment::build, plan_polyline, time_path) whose `location` names a place in
/// the environment file ({"obstacles", 3, "sphere", "radius"}) placed in the file: {Source{source_name}, …}
/// ("env.json:/obstacles/3/sphere/radius"); an error without a place in the file (a parameter of
/// the call) gets just the source.
Error locate_environment_error(const Error& error, std::string_view source_name);

}  // namespace inbetween
