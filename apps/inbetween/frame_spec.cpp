#include "frame_spec.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "command.hpp"

namespace inbetween::cli {
namespace {

double finite_number(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || !std::isfinite(v)) {
    return std::nan("");
  }
  return v;
}

double frame_part(const std::string& text, const std::string& what) {
  const double v = finite_number(text);
  if (std::isnan(v)) {
    throw CommandError{"--frames: " + what + " \"" + text + "\" is not a finite number (expected A:B[:STEP])"};
  }
  return v;
}

}  // namespace

FrameSpec parse_frame_spec(const std::string& spec) {
  std::vector<std::string> parts;
  std::stringstream ss(spec);
  for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
  if (parts.size() < 2 || parts.size() > 3 || spec.back() == ':') {
    throw CommandError{"--frames: \"" + spec + "\" is not A:B or A:B:STEP"};
  }
  FrameSpec out;
  out.start = frame_part(parts[0], "start");
  out.end = frame_part(parts[1], "end");
  out.start_text = parts[0];
  out.end_text = parts[1];
  if (parts.size() == 3) {
    out.step = frame_part(parts[2], "step");
    if (!(*out.step > 0)) throw CommandError{"--frames: step must be positive"};
  }
  return out;
}

FrameGrid frame_grid(const std::string& spec, double default_start, double default_end) {
  FrameGrid g;
  g.start = default_start;
  g.end = default_end;
  if (!spec.empty()) {
    const FrameSpec f = parse_frame_spec(spec);
    g.start = f.start;
    g.end = f.end;
    g.step = f.step.value_or(1.0);
    if (g.end < g.start) throw CommandError{"--frames: end " + f.end_text + " is before start " + f.start_text};
  }
  g.count = std::floor((g.end - g.start) / g.step * (1 + 1e-12) + 1e-9) + 1;
  // Without --frames the scene's "range" is to blame; say so.
  g.what = spec.empty() ? "the scene's /range [" + format_number(g.start) + ", " + format_number(g.end) + "]"
                        : "--frames " + spec;
  return g;
}

CLI::Validator finite_positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const double v = finite_number(text);
        if (!(v > 0)) return "\"" + text + "\" is not a finite positive number";
        return {};
      },
      "POSITIVE");
}

}  // namespace inbetween::cli
