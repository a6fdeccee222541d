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
