#pragma once
// A one-line progress bar on standard error for long commands (`bake`).

#include <chrono>
#include <cstdint>
#include <string>

namespace inbetween::cli {

/// When a ProgressBar draws.
enum class ProgressMode : std::uint8_t {
  automatic,  ///< only when standard error is a terminal; the line is cleared at the end
  always,     ///< also into a file or pipe; starts at 0 %, ends with 100 % and a line break
  never,      ///< never
};

/// Reads "auto", "always" or "never" (the values of a --progress option).
[[nodiscard]] ProgressMode parse_progress_mode(const std::string& text);

/// A progress bar over `total` steps: "\r<label> [#####.....]  45%  4500/10000 <unit>  ETA 12 s",
/// redrawn at most every 0.1 s (in automatic mode, first after 0.3 s, so a short run shows
/// nothing).  finish() or the destructor (an error) ends the line, so a message can follow.
class ProgressBar {
 public:
  /// A bar for `total` steps named `unit` ("frames").
  ProgressBar(std::string label, std::uint64_t total, std::string unit, ProgressMode mode);
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  /// Ends the line if finish() was not called.
  ~ProgressBar();

  /// `done` steps of `total` are complete; cheap (one clock read) when nothing is redrawn.
  void update(std::uint64_t done) {
    if (enabled_) maybe_draw(done);
  }
  /// All steps are complete: clears the line (terminal) or draws 100 % and a line break (always).
  void finish();

 private:
  /// Draws when the redraw time has come.
  void maybe_draw(std::uint64_t done);
  /// Draws the bar for `done` steps now.
  void draw(std::uint64_t done);
  /// Clears the line (terminal) or ends it with a line break (always), if anything was drawn.
  void end_line();

  std::string label_, unit_;                ///< "bake", "frames"
  std::uint64_t total_ = 0;                 ///< steps in all
  ProgressMode mode_ = ProgressMode::never; ///< as asked
  bool enabled_ = false;                    ///< drawing at all (mode and terminal)
  bool drawn_ = false;                      ///< something is on the line
  bool ended_ = false;                      ///< finish() or end_line() done
  std::size_t width_ = 0;                   ///< characters of the longest line drawn (for clearing)
  std::chrono::steady_clock::time_point start_, next_;  ///< start time, next redraw time
};

}  // namespace inbetween::cli
