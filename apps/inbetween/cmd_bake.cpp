// `inbetween bake SCENE`: evaluates every track of a scene file at every frame of a range and
// writes a CSV or JSON table, whole or not at all.  Parsing and evaluation live in the library
// (inbetween/io/scene.hpp reads, inbetween/scene/scene.hpp builds and samples); this file only handles arguments and formatting.
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/io/scene.hpp"

namespace inbetween::cli {
namespace {

// Guards against a typo such as --frames 1:1e9: the whole table is built in memory before it is
// written, so both the frame count and the number of cells (frames × (2 + columns), ~25 bytes of
// text each at most) are bounded.
constexpr double kMaxRows = 10'000'000;
constexpr double kMaxCells = 20'000'000;

double parse_real(const std::string& text, const std::string& what) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || !std::isfinite(v)) {
    throw CommandError{"--frames: " + what + " \"" + text + "\" is not a finite number (expected A:B[:STEP])"};
  }
  return v;
}

std::vector<double> frame_list(const std::string& spec, double scene_start, double scene_end, std::size_t columns) {
  double a = scene_start, b = scene_end, step = 1;
  if (!spec.empty()) {
    std::vector<std::string> parts;
    std::stringstream ss(spec);
    for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
    if (parts.size() < 2 || parts.size() > 3 || spec.back() == ':') {
      throw CommandError{"--frames: \"" + spec + "\" is not A:B or A:B:STEP"};
    }
    a = parse_real(parts[0], "start");
    b = parse_real(parts[1], "end");
    if (parts.size() == 3) step = parse_real(parts[2], "step");
    if (!(step > 0)) throw CommandError{"--frames: step must be positive"};
    if (b < a) throw CommandError{"--frames: end " + parts[1] + " is before start " + parts[0]};
  }
  const double count_d = std::floor((b - a) / step * (1 + 1e-12) + 1e-9) + 1;
  // Without --frames the scene's "range" is to blame; say so.
  const std::string what = spec.empty() ? "the scene's /range [" + format_number(a) + ", " + format_number(b) + "]"
                                        : "--frames " + spec;
  if (!(count_d <= kMaxRows)) {
    throw CommandError{what + ": " + format_number(count_d) + " frames; at most 10000000 (narrow the range or raise STEP)"};
  }
  if (count_d * double(2 + columns) > kMaxCells) {
    throw CommandError{what + ": " + format_number(count_d) + " frames x " + std::to_string(2 + columns) +
                       " columns; at most 20000000 values (narrow the range or raise STEP)"};
  }
  std::vector<double> frames;
  const auto count = std::size_t(count_d);
  frames.reserve(count);
  for (std::size_t i = 0; i < count; ++i) frames.push_back(a + double(i) * step);
  return frames;
}

// A CSV header field (RFC 4180): names with a comma, quote or line break are quoted, quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

std::string format_float(float v) {
  std::string s = shortest_text(v);
  if (s == "-0") s = "0";
  return s;
}

struct BakeOptions {
  std::string scene_path;
  std::string frames;
  double fps = 0;
  std::string format = "csv";
  std::string output = "-";
};

void run_bake(const BakeOptions& opt) {
  const std::string text = read_input(opt.scene_path);
  auto scene = parse_scene(text);
  if (!scene) throw CommandError{opt.scene_path + ": " + scene.error().describe()};
  const double fps = opt.fps > 0 ? opt.fps : scene->fps();
  const std::span<const SceneColumn> columns = scene->columns();
  const std::vector<double> frames = frame_list(opt.frames, scene->range_start(), scene->range_end(), columns.size());
  std::vector<double> row(columns.size());

  // Finite keys can still give values beyond the number type (linear extrapolation to frame 1e300,
  // a tiny fps): name the frame and column instead of writing inf.
  auto evaluate_row = [&](double f) {
    if (!std::isfinite(f / fps)) {
      throw CommandError{"frame " + format_number(f) + ": time = frame / fps " + format_number(fps) + " overflows"};
    }
    scene->sample(f, row);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double v = columns[c].single_precision ? double(float(row[c])) : row[c];
      if (!std::isfinite(v)) {
        throw CommandError{"frame " + format_number(f) + ": " + columns[c].name +
                           (std::isnan(v) ? " is not a number" : " overflows (" + format_number(v) +
                                                                     (columns[c].single_precision ? ", single precision" : "") + ")")};
      }
    }
  };

  auto cell = [&](std::size_t c) {
    return columns[c].single_precision ? format_float(float(row[c])) : format_number(row[c]);
  };
  std::string out;
  if (opt.format == "csv") {
    out += "frame,time";
    for (const auto& c : columns) out += "," + csv_field(c.name);
    out += "\n";
    for (double f : frames) {
      evaluate_row(f);
      out += format_number(f) + "," + format_number(f / fps);
      for (std::size_t c = 0; c < columns.size(); ++c) out += "," + cell(c);
      out += "\n";
    }
  } else {
    // JSON: {"fps": F, "columns": ["frame", "time", ...], "rows": [[...], ...]}; numbers written
    // with the same shortest round-trip text as the CSV.
    out += "{\"fps\": " + format_number(fps) + ", \"columns\": [\"frame\", \"time\"";
    for (const auto& c : columns) out += ", " + nlohmann::json(c.name).dump();
    out += "],\n \"rows\": [";
    for (std::size_t i = 0; i < frames.size(); ++i) {
      evaluate_row(frames[i]);
      out += (i ? ",\n  [" : "\n  [") + format_number(frames[i]) + ", " + format_number(frames[i] / fps);
      for (std::size_t c = 0; c < columns.size(); ++c) out += ", " + cell(c);
      out += "]";
    }
    out += "]}\n";
  }
  write_output(opt.output, out);
}

const RegisterCommand kBake{{"bake", 40, [](CLI::App& root) {
  auto opt = std::make_shared<BakeOptions>();
  auto* cmd = root.add_subcommand("bake", "Evaluate every track of a scene file at every frame (CSV or JSON)");
  cmd->add_option("scene", opt->scene_path, "Scene file (docs/scene-format.md); - for standard input")->required();
  cmd->add_option("--frames", opt->frames, "A:B[:STEP] frames to evaluate (default: the scene's range, step 1)");
  cmd->add_option("--fps", opt->fps, "Frames per second for the time column (default: the scene's fps)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            // CLI::PositiveNumber lets "nan" through (then silently ignored) and prints a 300-digit bound.
            const char* begin = text.c_str();
            char* end = nullptr;
            const double v = std::strtod(begin, &end);
            if (text.empty() || end != begin + text.size() || !std::isfinite(v) || !(v > 0)) {
              return "\"" + text + "\" is not a finite positive number";
            }
            return {};
          },
          "POSITIVE"));
  cmd->add_option("--format", opt->format, "Output format")->check(CLI::IsMember({"csv", "json"}));
  cmd->add_option("-o,--output", opt->output, "Output file (default: standard output); written whole or not at all");
  cmd->callback([opt] { run_bake(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
