#include "demo_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <system_error>
#include <vector>

#include "command.hpp"
#include "csv.hpp"
#include "frame22_scene.hpp"
#include "inbetween/io/scene.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "preview.hpp"
#include "progress.hpp"


namespace inbetween::cli {
namespace {


std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v == 0 ? 0.0 : v);
  return buf;
}

// "16–22, 67, 80–86": runs of consecutive frames (step 1) as ranges.
std::string frame_runs(const std::vector<double>& frames) {
  std::string text;
  for (std::size_t i = 0; i < frames.size();) {
    std::size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    text += (text.empty() ? "" : ", ") + format_number(frames[i]);
    if (j > i) text += "–" + format_number(frames[j]);
    i = j + 1;
  }
  return text.empty() ? "none" : text;
}

std::size_t column_of(const Scene& scene, const std::string& name) {
  const auto columns = scene.columns();
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].name == name) return c;
  throw CommandError{"the built-in scene has no column " + name, kInternal};
}

}  // namespace

std::string write_demo_files(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw CommandError{dir + ": cannot create the folder: " + ec.message()};
  const fs::path out = dir;

  auto parsed = parse_scene(kFrame22SceneJson);
  if (!parsed) throw CommandError{"the built-in scene does not read: " + parsed.error().describe(), kInternal};
  const Scene& scene = *parsed;

  std::vector<std::string> written;
  write_output((out / "frame22.json").string(), std::string(kFrame22SceneJson));
  written.push_back("frame22.json   the scene (examples/scenes/frame22.json)");

  // frames.csv: the bake of the scene's range at step 1, in bake's CSV form; the ball's speed
  // column is read on the way for the summary.
  const auto columns = scene.columns();
  const std::size_t speed = column_of(scene, "ball.speed");
  const auto count = std::uint64_t(std::floor(scene.range_end() - scene.range_start())) + 1;
  std::vector<double> row(columns.size());
  SceneCursor cursor(scene);
  OutputFile csv((out / "frames.csv").string());
  ProgressBar progress("bake", count, "frames", ProgressMode::automatic);  // drawn only on a terminal
  std::string line = "frame,time";
  for (const auto& c : columns) line += "," + c.name;  // frame22.json's names need no CSV quoting
  line += "\n";
  csv.write(line);
  double peak_speed = 0, peak_frame = scene.range_start(), path_length = 0;
  std::vector<double> rest;
  for (std::uint64_t i = 0; i < count; ++i) {
    const double f = scene.range_start() + double(i);
    scene.sample(f, row, cursor);
    line.clear();
    append_number(line, f);
    line += ',';
    append_number(line, f / scene.fps());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      line += ',';
      if (columns[c].single_precision) {
        append_number(line, float(row[c]));
      } else {
        append_number(line, row[c]);
      }
    }
    line += '\n';
    csv.write(line);
    progress.update(i + 1);
    if (row[speed] > peak_speed) {
      peak_speed = row[speed];
      peak_frame = f;
    }
    if (row[speed] == 0) rest.push_back(f);
  }
  progress.finish();
  csv.commit();
  for (const auto& leg : scene.path_legs(0)) path_length += leg.motion.length();
  written.push_back("frames.csv     its bake, " + std::to_string(count) + " frames × " +
                    std::to_string(columns.size() + 2) + " columns (= inbetween bake frame22.json)");

  // The graph-editor, path and speed plots of `inbetween plot` (write_plots, plot.hpp) into
  // DIR/plots/ (replaced whole; docs/plots.md).
  {
    auto raw = read_scene_json(kFrame22SceneJson);
    if (!raw) throw CommandError{"the built-in scene does not read: " + raw.error().describe(), kInternal};
    PlotOptions options;
    options.title = "frame22.json";
    auto report = write_plots(scene, *raw, out / "plots", options);
    if (!report) {
      const Error& e = report.error();
      throw CommandError{(e.location.empty() ? (out / "plots").string() : e.place()) + ": " + e.message};
    }
    written.push_back("plots/         " + std::to_string(report->files.size()) +
                      " SVG plots (graph editor, path views, speed curves) and index.html");
  }

  if (preview_available()) {
    const PreviewFrames frames{scene.range_start(), 1, count};
    write_output((out / "preview.html").string(),
                 preview_html(scene, frames, {.title = "frame22.json", .source = (out / "frame22.json").string()}));
    written.push_back("preview.html   the 3-D preview: open it in a browser (file://" +
                      fs::absolute(out / "preview.html").lexically_normal().string() + ")");
  } else {
    written.push_back("preview.html   not written: this build has no preview page (make deps, then rebuild)");
  }

  // The character: the CMU clip's preview and plots (demo_character.cpp).
  for (auto& entry : write_character_demo(out, kDemoCharacterClip)) written.push_back(std::move(entry));

  std::ostringstream summary;
  summary << "wrote " << dir << "/:\n";
  for (const auto& w : written) summary << "  " << w << "\n";
  summary << "the ball: path length (its two legs' arc lengths) " << fixed(path_length, 3) << " units, peak speed "
          << fixed(peak_speed, 3) << " units/s (largest at the baked frames, on frame " << format_number(peak_frame) << ")" << ", at rest on frames "
          << frame_runs(rest) << "\n";
  return summary.str();
}

}  // namespace inbetween::cli
