#pragma once
// `--frames A:B[:STEP]` and `--fps F` as bake, view and plot read them (one parser, one message).
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace inbetween::cli {

/// The parts of `--frames A:B[:STEP]`: finite numbers, step > 0 when given.  The order of A and B
/// is the caller's rule (bake and view allow A = B, plot needs A < B).
struct FrameSpec {
  double start = 0;                 ///< A
  double end = 0;                   ///< B
  std::optional<double> step;       ///< STEP, when given (> 0)
  std::string start_text;           ///< A as written, for messages
  std::string end_text;             ///< B as written, for messages
};

/// Parses a non-empty `--frames` value; throws CommandError naming the bad part.
FrameSpec parse_frame_spec(const std::string& spec);

/// A CLI11 validator that accepts only a finite positive number (CLI::PositiveNumber lets "nan"
/// through and prints a 300-digit bound).
CLI::Validator finite_positive_number();

}  // namespace inbetween::cli
