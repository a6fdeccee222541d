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
#include "input.hpp"
#include "inbetween/io/scene.hpp"
#include "preview.hpp"

namespace inbetween::cli {
namespace {

struct ViewOptions {
  InputArgs input;
  std::string frames;
  std::string output;
};

void run_view(const ViewOptions& opt) {
  require_preview();  // before reading anything: the message says how to get the page
  if (input_format_of(opt.input) == InputFormat::scene_json && opt.input.fps > 0) {
    throw CommandError{"--fps: only for glTF, BVH and assimp input (a scene file has its own fps)"};
  }
  const Scene scene = load_scene(opt.input);
  const PreviewFrames frames = preview_frames(opt.frames, scene);
  const std::string name = opt.input.path == "-" ? "standard input" : std::filesystem::path(opt.input.path).filename().string();
  const std::string page = preview_html(scene, frames, {.title = name, .source = opt.input.path == "-" ? name : opt.input.path});
  write_output(opt.output, page);  // a temporary file renamed onto the target: whole or nothing
}

const RegisterCommand kView{{"view", 45, [](CLI::App& root) {
  auto opt = std::make_shared<ViewOptions>();
  auto* cmd = root.add_subcommand("view", "Write a self-contained HTML page that plays the baked scene in 3-D (three.js)");
  add_input_options(cmd, opt->input, "scene",
                    "Scene file (docs/scene-format.md; - for standard input), glTF 2.0 (.gltf, .glb), BVH (.bvh) or "
                    "a file assimp reads (.fbx, .dae, …)");
  output_file(cmd->add_option("-o,--output", opt->output, "The HTML file to write (replaced whole or not at all)"))->required();
  cmd->add_option("--frames", opt->frames,
                  "A:B[:STEP] frames to bake into the page (default: the scene's range, step 1; at most 20000 frames)");
  cmd->add_option("--fps", opt->input.fps, "glTF, BVH, assimp input: frame = time · fps (default: the format's own)")
      ->check(finite_positive_number());
  cmd->callback([opt] { run_view(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
