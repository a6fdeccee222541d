// `inbetween convert IN OUT`: between file formats, told apart by extension.  Today: a glTF file
// (.gltf, .glb) → a scene file (.json) holding the same animation as keyframes (inbetween/io/gltf.hpp
// reads, inbetween/io/scene_write.hpp writes), so that `bake OUT.json` equals `bake IN.glb`.
// The output is written whole or not at all.
#include <cmath>
#include <memory>
#include <string>

#include "command.hpp"
#include "gltf_input.hpp"
#include "inbetween/io/scene_write.hpp"

namespace inbetween::cli {
namespace {

struct ConvertOptions {
  std::string input;
  std::string output;
  std::string animation;
  double fps = 0;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void run_convert(const ConvertOptions& opt) {
  if (!std::isfinite(opt.fps)) throw CommandError{"--fps: not a finite positive number"};
  if (is_gltf_input(opt.input) && ends_with(opt.output, ".json")) {
    const RawScene raw = load_gltf_raw(opt.input, opt.animation, opt.fps);
    if (auto scene = build_scene(raw); !scene) throw CommandError{opt.input + ": " + scene.error().describe()};
    auto text = write_scene_json(raw);
    if (!text) throw CommandError{opt.input + ": " + text.error().describe()};
    write_output(opt.output, *text);
    return;
  }
  throw CommandError{"convert: " + opt.input + " → " + opt.output +
                     " is not a supported conversion (supported: MODEL.gltf|MODEL.glb → SCENE.json)"};
}

const RegisterCommand kConvert{{"convert", 45, [](CLI::App& root) {
  auto opt = std::make_shared<ConvertOptions>();
  auto* cmd = root.add_subcommand("convert", "Convert between glTF 2.0 and scene files (by extension)");
  cmd->add_option("input", opt->input, "Input file: glTF 2.0 (.gltf, .glb)")->required();
  cmd->add_option("output", opt->output, "Output file: scene file (.json)")->required();
  cmd->add_option("--animation", opt->animation, "glTF input: the animation's NAME or INDEX (default: the first)");
  cmd->add_option("--fps", opt->fps, "glTF input: frames per second, frame = time · fps (default 24)")
      ->check(CLI::PositiveNumber);
  cmd->callback([opt] { run_convert(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
