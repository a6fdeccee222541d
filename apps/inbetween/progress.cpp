#include "progress.hpp"

#include "run.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace inbetween::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Redraw interval, and the delay before the first drawing on a terminal (a short run shows nothing).
constexpr auto kRedraw = std::chrono::milliseconds(100);
constexpr auto kFirstDraw = std::chrono::milliseconds(300);
constexpr std::size_t kBarCells = 30;

void put(const std::string& text) {
  std::size_t off = 0;
  while (off < text.size()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + off, text.size() - off);
    if (n <= 0) return;  // a progress bar never fails the command
    off += std::size_t(n);
  }
}

}  // namespace

ProgressMode parse_progress_mode(const std::string& text) {
  if (text == "always") return ProgressMode::always;
  if (text == "never") return ProgressMode::never;
  return ProgressMode::automatic;
}

ProgressBar::ProgressBar(std::string label, std::uint64_t total, std::string unit, ProgressMode mode)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), mode_(mode) {
  // Never in an in-process run (run.hpp): the process's standard error is not the run's.
  enabled_ = current_capture() == nullptr &&
             (mode == ProgressMode::always || (mode == ProgressMode::automatic && ::isatty(STDERR_FILENO) == 1));
  start_ = Clock::now();
  next_ = start_ + kFirstDraw;
  if (enabled_ && mode_ == ProgressMode::always) draw(0);
}

ProgressBar::~ProgressBar() {
  if (!ended_) end_line();
}

void ProgressBar::maybe_draw(std::uint64_t done) {
  const auto now = Clock::now();
  if (now < next_) return;
  next_ = now + kRedraw;
  draw(done);
}

void ProgressBar::draw(std::uint64_t done) {
  const double fraction = total_ > 0 ? double(done) / double(total_) : 1.0;
  const auto cells = std::size_t(fraction * double(kBarCells));
  std::string line = "\r" + label_ + " [" + std::string(cells, '#') + std::string(kBarCells - cells, '.') + "] ";
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "%3d%%  %llu/%llu %s", int(fraction * 100), (unsigned long long)done,
                (unsigned long long)total_, unit_.c_str());
  line += numbers;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  if (done > 0 && done < total_) {
    const auto eta_s = (long long)(elapsed * double(total_ - done) / double(done) + 0.5);
    if (eta_s < 60) {
      std::snprintf(numbers, sizeof numbers, "  ETA %lld s", eta_s);
    } else {
      std::snprintf(numbers, sizeof numbers, "  ETA %lld min %02lld s", eta_s / 60, eta_s % 60);
    }
    line += numbers;
  }
  if (line.size() < width_) line += std::string(width_ - line.size(), ' ');  // cover a longer line
  width_ = std::max(width_, line.size());
  put(line);
  drawn_ = true;
}

void ProgressBar::end_line() {
  ended_ = true;
  if (!drawn_) return;
  if (mode_ == ProgressMode::always) {
    put("\n");
  } else {
    std::string blank(width_ + 1, ' ');  // "\r", spaces over the longest line, "\r"
    blank.front() = '\r';
    blank.back() = '\r';
    put(blank);
  }
}

void ProgressBar::finish() {
  if (ended_) return;
  if (enabled_ && mode_ == ProgressMode::always) draw(total_);
  end_line();
}

}  // namespace inbetween::cli
