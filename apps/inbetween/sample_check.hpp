#pragma once
// The one message of every command that samples a scene (bake, plot, view) for a value that is
// not finite: the input file, the scene member that caused it (scene/non_finite.hpp), the frame
// and the column.
#include <cstddef>

#include "command.hpp"
#include "input.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween::cli {

/// The CommandError for `value` (NaN or ±inf) of column `column` at `frame`:
/// "<path>: [<member>: ]frame F: <column> is not a number (its world transform overflows: …)";
/// the member (a JSON pointer into the file) for scene files only, whose places it names.
[[nodiscard]] CommandError non_finite_error(const InputArgs& args, const Scene& scene, double frame, std::size_t column,
                                            double value);

}  // namespace inbetween::cli
