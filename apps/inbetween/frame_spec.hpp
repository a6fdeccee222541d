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

/// The frames bake and view write: start, start + step, … up to end (`count` of them, a whole
/// number as a double so the caller can check its own limit before converting).
struct FrameGrid {
  double start = 0;   ///< first frame
  double end = 0;     ///< last frame asked for
  double step = 1;    ///< > 0
  double count = 1;   ///< number of frames (≥ 1)
  std::string what;   ///< "--frames SPEC" or "the scene's /range [A, B]", for limit messages
};

/// `--frames` (empty: [default_start, default_end], step 1) as a grid; end before start is an
/// error.  The count allows 1e-12 relative slack so 0:1:0.1 ends on 1.
FrameGrid frame_grid(const std::string& spec, double default_start, double default_end);

/// A CLI11 validator that accepts only a finite positive number (CLI::PositiveNumber lets "nan"
/// through and prints a 300-digit bound).
CLI::Validator finite_positive_number();

}  // namespace inbetween::cli
