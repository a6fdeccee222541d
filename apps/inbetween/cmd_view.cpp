// `inbetween view SCENE|MODEL.gltf|MODEL.glb -o preview.html`: one self-contained HTML page that
// plays the baked scene with three.js (docs/preview.md).  Reading and baking are the library's
// (the same as `bake`); preview.cpp assembles the page; this file handles the arguments.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "command.hpp"
#include "frame_spec.hpp"
#include "gltf_input.hpp"
#include "inbetween/io/scene.hpp"
#include "preview.hpp"

namespace inbetween::cli {
namespace {

struct ViewOptions {
  std::string scene_path;
  std::string animation;
  std::string frames;
  double fps = 0;
  std::string output;
};

void run_view(const ViewOptions& opt) {
  require_preview();  // before reading anything: the message says how to get the page
  const bool gltf = is_gltf_input(opt.scene_path);
  if (!gltf && !opt.animation.empty()) throw CommandError{"--animation: only for glTF input (.gltf, .glb)"};
  if (!gltf && opt.fps > 0) throw CommandError{"--fps: only for glTF input (a scene file has its own fps)"};
  const Scene scene = gltf ? load_gltf_scene(opt.scene_path, opt.animation, opt.fps) : [&] {
    auto parsed = parse_scene(read_input(opt.scene_path), opt.scene_path);
    if (!parsed) throw CommandError{opt.scene_path + ": " + parsed.error().describe()};
    return std::move(*parsed);
  }();
  const PreviewFrames frames = preview_frames(opt.frames, scene);
  const std::string name = opt.scene_path == "-" ? "standard input" : std::filesystem::path(opt.scene_path).filename().string();
  const std::string page = preview_html(scene, frames, {.title = name, .source = opt.scene_path == "-" ? name : opt.scene_path});
  write_output(opt.output, page);  // a temporary file renamed onto the target: whole or nothing
}

const RegisterCommand kView{{"view", 45, [](CLI::App& root) {
  auto opt = std::make_shared<ViewOptions>();
  auto* cmd = root.add_subcommand("view", "Write a self-contained HTML page that plays the baked scene in 3-D (three.js)");
  cmd->add_option("scene", opt->scene_path,
                  "Scene file (docs/scene-format.md; - for standard input) or glTF 2.0 file (.gltf, .glb)")
      ->required();
  cmd->add_option("-o,--output", opt->output, "The HTML file to write (replaced whole or not at all)")->required();
  cmd->add_option("--frames", opt->frames,
                  "A:B[:STEP] frames to bake into the page (default: the scene's range, step 1; at most 20000 frames)");
  cmd->add_option("--animation", opt->animation, "glTF input: the animation's NAME or INDEX (default: the first)");
  cmd->add_option("--fps", opt->fps, "glTF input: frame = time · fps (default 24)")
      ->check(finite_positive_number());
  cmd->callback([opt] { run_view(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
