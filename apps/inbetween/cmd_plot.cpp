// `inbetween plot SCENE|MODEL.glb -o DIR`: SVG plots of every track, object and path object of a
// scene file or glTF animation, and an index.html (plot.hpp, docs/plots.md).  Argument handling
// only; the drawing is plot.cpp.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "frame_spec.hpp"
#include "gltf_input.hpp"
#include "inbetween/io/scene.hpp"
#include "plot.hpp"

namespace inbetween::cli {
namespace {

struct PlotCommandOptions {
  std::string input;
  std::string output;
  std::string animation;
  std::string frames;
  double fps = 0;
  std::string progress = "auto";
};

void run_plot(const PlotCommandOptions& opt) {
  const bool gltf = is_gltf_input(opt.input);
  if (!gltf && !opt.animation.empty()) throw CommandError{"--animation: only for glTF input (.gltf, .glb)"};
  // A scene file's fps is part of the scene (speeds per second, the seconds axis).
  if (!gltf && opt.fps > 0) throw CommandError{"--fps: only for glTF input (.gltf, .glb); a scene file has its own fps"};
  RawScene raw;
  if (gltf) {
    raw = load_gltf_raw(opt.input, opt.animation, opt.fps);
  } else {
    auto parsed = read_scene_json(read_input(opt.input), opt.input);
    if (!parsed) throw CommandError{opt.input + ": " + parsed.error().describe()};
    raw = std::move(*parsed);
  }
  auto scene = build_scene(raw);
  if (!scene) throw CommandError{opt.input + ": " + scene.error().describe()};

  PlotOptions options;
  options.progress = parse_progress_mode(opt.progress);
  options.title = opt.input == "-" ? std::string("standard input") : std::filesystem::path(opt.input).filename().string();
  if (!opt.frames.empty()) {
    const FrameSpec f = parse_frame_spec(opt.frames);
    options.frame_start = f.start;
    options.frame_end = f.end;
    if (f.step) options.frame_step = *f.step;
    if (!(f.end > f.start)) {
      throw CommandError{"--frames: end " + f.end_text + " is not after start " + f.start_text};
    }
  }
  auto report = write_plots(*scene, raw, opt.output, options);
  if (!report) {
    const Error& e = report.error();
    // A scene without content is the input's fault: name the input.
    const std::string where = e.where.empty() ? opt.input : e.where;
    throw CommandError{where + ": " + e.message};
  }
  std::cout << "wrote " << report->files.size() << " plots and index.html to " << report->dir.string() << " ("
            << report->frame_count << " frames from " << format_number(report->frame_start) << " every "
            << format_number(report->frame_step) << ")\n";
}

const RegisterCommand kPlot{{"plot", 45, [](CLI::App& root) {
  auto opt = std::make_shared<PlotCommandOptions>();
  auto* cmd = root.add_subcommand(
      "plot", "SVG plots of a scene: graph editor of every track and object, path views, speed curves, index.html");
  cmd->add_option("scene", opt->input,
                  "Scene file (docs/scene-format.md; - for standard input) or glTF 2.0 file (.gltf, .glb; docs/gltf.md)")
      ->required();
  cmd->add_option("-o,--output", opt->output, "Output folder (written whole or not at all; see docs/plots.md)")->required();
  cmd->add_option("--animation", opt->animation, "glTF input: the animation's NAME or INDEX (default: the first)");
  cmd->add_option("--frames", opt->frames,
                  "A:B[:STEP] frame axis and sample step (default: the range and keys padded by 10 %, at most 480 steps)");
  cmd->add_option("--fps", opt->fps, "glTF input: frame = time · fps (default 24); a scene file has its own")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--progress", opt->progress, "Progress bar on standard error: auto (when it is a terminal), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  cmd->callback([opt] { run_plot(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
