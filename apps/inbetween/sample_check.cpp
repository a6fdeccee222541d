#include "sample_check.hpp"

#include "inbetween/scene/non_finite.hpp"

namespace inbetween::cli {

CommandError non_finite_error(const InputArgs& args, const Scene& scene, double frame, std::size_t column, double value) {
  const Error e = non_finite_value_error(scene, frame, column, value);
  const bool scene_file = input_format_of(args) == InputFormat::scene_json;
  return CommandError{args.path + ": " + (scene_file && !e.location.empty() ? json_pointer(e.location) + ": " : std::string()) +
                      e.message};
}

}  // namespace inbetween::cli
