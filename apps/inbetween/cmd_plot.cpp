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
#include "input.hpp"
#include "plot.hpp"
#include "plot_skeleton.hpp"

namespace inbetween::cli {
namespace {

struct PlotCommandOptions {
  InputArgs input;
  std::string output;
  std::string frames;
  std::string progress = "auto";
  std::vector<std::string> objects;
};

void run_plot(const PlotCommandOptions& opt) {
  // A scene file's fps is part of the scene (speeds per second, the seconds axis).
  if (input_format_of(opt.input) == InputFormat::scene_json && opt.input.fps > 0) {
    throw CommandError{"--fps: only for glTF, BVH and assimp input; a scene file has its own fps"};
  }
  const RawScene raw = load_raw(opt.input);
  auto scene = build_scene(raw);
  if (!scene) throw CommandError{opt.input.path + ": " + scene.error().describe()};

  PlotOptions options;
  options.progress = parse_progress_mode(opt.progress);
  options.objects = opt.objects;
  options.title = opt.input.path == "-" ? std::string("standard input") : std::filesystem::path(opt.input.path).filename().string();
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
    const std::string where = e.location.empty() ? opt.input.path : e.place();
    throw CommandError{where + ": " + e.message};
  }
  tool_out() << "wrote " << report->files.size() << " plots and index.html to " << report->dir.string() << " ("
            << report->frame_count << " frames from " << format_number(report->frame_start) << " every "
            << format_number(report->frame_step) << ")\n";
  if (report->left_out > 0) {
    tool_err() << "note: " << report->left_out << " more plots left out: a plot folder holds at most 1000 pages of tracks, "
                 "objects and paths (index.html says which)\n";
  }
  if (report->trajectory_roots_skipped > 0) {
    tool_out() << "note: " << report->trajectory_roots_skipped << " more moving roots have no trajectory plot (at most "
              << kMaxDefaultTrajectories << " by default); name them with --object\n";
  }
}

const RegisterCommand kPlot{{"plot", 45, [](CLI::App& root) {
  auto opt = std::make_shared<PlotCommandOptions>();
  auto* cmd = root.add_subcommand(
      "plot", "SVG plots of a scene: graph editor of every track and object, path views, speed curves, index.html");
  add_input_options(cmd, opt->input, "scene",
                    "Scene file (docs/scene-format.md; - for standard input), glTF 2.0 (.gltf, .glb; docs/gltf.md), "
                    "BVH (.bvh) or a file assimp reads (.fbx, .dae, …)");
  output_file(cmd->add_option("-o,--output", opt->output, "Output folder (written whole or not at all; see docs/plots.md)"))->required();
  cmd->add_option("--frames", opt->frames,
                  "A:B[:STEP] frame axis and sample step (default: the range and keys padded by 10 %, at most 480 steps)");
  cmd->add_option("--fps", opt->input.fps,
                  "glTF, BVH, assimp input: frame = time · fps (default: the format's own); a scene file has its own")
      ->check(finite_positive_number());
  cmd->add_option("--object", opt->objects,
                  "World trajectory (top, front, side views; with the poses of its descendants) of this object; "
                  "repeatable; default: the roots that move, at most 8")
      ->allow_extra_args(false);
  cmd->add_option("--progress", opt->progress, "Progress bar on standard error: auto (when it is a terminal), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  cmd->callback([opt] { run_plot(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
