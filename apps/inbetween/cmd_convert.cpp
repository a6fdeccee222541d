// `inbetween convert SCENE.json OUT.gltf|OUT.glb [--tolerance T] [--reduce TOL] [--substeps N]`:
// exports a scene as glTF 2.0 (io/gltf_write.hpp) and prints which channels kept their keys and
// which were refitted (why, keys before/after, measured max error).  glTF input (convert
// MODEL.glb OUT.json, --reduce on a .glb) belongs to the glTF reader.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "command.hpp"
#include "inbetween/io/gltf_write.hpp"
#include "inbetween/io/scene.hpp"

namespace inbetween::cli {
namespace {

struct ConvertOptions {
  std::string input, output;
  double tolerance = 1e-5;
  double reduce = 0;  // 0: keep keys where glTF holds them exactly
  int substeps = 4;
  bool quiet = false;
  bool no_cubic = false;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void run_convert(const ConvertOptions& opt) {
  const bool glb = ends_with(opt.output, ".glb"), gltf = ends_with(opt.output, ".gltf");
  if (ends_with(opt.input, ".glb") || ends_with(opt.input, ".gltf")) {
    throw CommandError{opt.input + ": reading glTF needs the glTF reader (convert of glTF input is not in this build)"};
  }
  if (!glb && !gltf) throw CommandError{opt.output + ": the output must end in .gltf or .glb"};
  const std::string text = read_input(opt.input);
  auto raw = read_scene_json(text);
  if (!raw) throw CommandError{opt.input + ": " + raw.error().describe()};
  auto scene = build_scene(*raw);
  if (!scene) throw CommandError{opt.input + ": " + scene.error().describe()};
  GltfExportOptions o;
  o.tolerance = opt.reduce > 0 ? opt.reduce : opt.tolerance;
  o.reduce = opt.reduce > 0;
  o.substeps = opt.substeps;
  o.binary = glb;
  o.cubic = !opt.no_cubic;
  auto out = export_gltf(*raw, *scene, o);
  if (!out) throw CommandError{opt.input + ": " + out.error().describe()};
  write_output(opt.output, out->bytes);
  if (opt.quiet) return;
  for (const std::string& note : out->notes) std::cerr << "note: " << note << '\n';
  for (const GltfChannelReport& c : out->channels) {
    char line[512];
    std::snprintf(line, sizeof line, "%s.%s: %s, %zu keys -> %zu, max error %.3g%s", c.object.c_str(), c.path.c_str(),
                  c.interpolation.c_str(), c.keys_before, c.keys_after, c.max_error,
                  c.path == "rotation" ? " rad" : "");
    std::cerr << line;
    if (c.refitted) {
      std::snprintf(line, sizeof line, " (refitted: %s; tolerance %.3g)", c.reason.c_str(), c.tolerance);
      std::cerr << line;
    } else {
      std::cerr << " (keys kept)";
    }
    std::cerr << '\n';
  }
}

const RegisterCommand kConvert{{"convert", 45, [](CLI::App& root) {
  auto opt = std::make_shared<ConvertOptions>();
  auto* cmd = root.add_subcommand("convert", "Export a scene as glTF 2.0 (.gltf or .glb), refitting what glTF cannot hold");
  cmd->add_option("input", opt->input, "Scene file (docs/scene-format.md); - for standard input")->required();
  cmd->add_option("output", opt->output, "Output file ending in .gltf or .glb")->required();
  cmd->add_option("--tolerance", opt->tolerance,
                  "Largest error of a refitted channel: fraction of its range (translation, scale), radians (rotation)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--reduce", opt->reduce, "Refit every channel with this tolerance (keyframe reduction)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--substeps", opt->substeps, "Grid points per frame where channels are sampled and checked")
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--no-cubic", opt->no_cubic,
                 "Write STEP and LINEAR samplers only (Blender 3.4's importer ignores CUBICSPLINE tangents)");
  cmd->add_flag("-q,--quiet", opt->quiet, "Do not print the channel report");
  cmd->callback([opt] { run_convert(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
