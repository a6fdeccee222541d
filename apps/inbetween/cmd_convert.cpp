// `inbetween convert IN OUT`: between file formats, told apart by extension.
//   - glTF (.gltf, .glb) → scene file (.json): the same animation as keyframes (inbetween/io/gltf.hpp
//     reads, inbetween/io/scene_write.hpp writes), so that `bake OUT.json` equals `bake IN.glb`;
//   - scene file → scene file (.json): read, checked by building, written back (version 2, paths
//     and cameras included), so that `bake OUT.json` equals `bake IN.json`;
//   - scene file or glTF → glTF (.gltf, .glb): exported by io/gltf_write.hpp, keys kept where glTF
//     holds them exactly and refitted otherwise (or every channel with --reduce), with a report of
//     each channel (why, keys before/after, measured max error) on standard error;
//   - any input → BVH (.bvh): the objects sampled at every whole frame of the range
//     (inbetween/io/bvh.hpp, docs/bvh.md), notes on standard error.
// The input is read and built once (load_raw_and_scene) and each output takes what it needs.
// The output is written whole or not at all.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "command.hpp"
#include "frame_spec.hpp"
#include "input.hpp"
#include "inbetween/io/bvh.hpp"
#include "inbetween/io/gltf_write.hpp"
#include "inbetween/io/scene.hpp"
#include "inbetween/io/scene_write.hpp"

namespace inbetween::cli {
namespace {

struct ConvertOptions {
  InputArgs input;  // input.fps: keys in seconds, frame = time · fps (0: the format's own)
  std::string output;
  double tolerance = 1e-5;
  double reduce = 0;  // 0: keep keys where glTF holds them exactly
  int substeps = 4;
  bool quiet = false;
  bool no_cubic = false;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void print_report(const GltfExport& out) {
  for (const std::string& note : out.notes) tool_err() << "note: " << note << '\n';
  for (const GltfChannelReport& c : out.channels) {
    char line[512];
    std::snprintf(line, sizeof line, "%s.%s: %s, %zu keys -> %zu, max error %.3g%s", c.object.c_str(), c.path.c_str(),
                  c.interpolation.c_str(), c.keys_before, c.keys_after, c.max_error, c.path == "rotation" ? " rad" : "");
    tool_err() << line;
    if (c.refitted) {
      std::snprintf(line, sizeof line, " (refitted: %s; tolerance %.3g)", c.reason.c_str(), c.tolerance);
      tool_err() << line;
    } else {
      tool_err() << " (keys kept)";
    }
    tool_err() << '\n';
  }
}

void run_convert(const ConvertOptions& opt) {
  if (!std::isfinite(opt.input.fps)) throw CommandError{"--fps: not a finite positive number"};
  const bool to_json = ends_with(opt.output, ".json"), to_bvh = ends_with(opt.output, ".bvh");
  const bool glb = ends_with(opt.output, ".glb"), gltf = ends_with(opt.output, ".gltf");
  if (!to_json && !to_bvh && !glb && !gltf) {
    throw CommandError{"convert: " + opt.input.path + " → " + opt.output +
                       " is not a supported conversion: the output must end in .gltf or .glb (export of a scene or glTF "
                       "file), .bvh (BVH motion, docs/bvh.md) or .json (a scene file)"};
  }
  // Read and built once for every output, each taking what it needs: BVH the scene, the scene
  // file writer the raw scene (checked by the build), the glTF exporter both.
  const LoadedScene in = load_raw_and_scene(opt.input);
  if (to_bvh) {
    auto out = write_bvh(in.scene);
    if (!out) throw CommandError{opt.input.path + ": " + out.error().describe()};
    write_output(opt.output, out->text);
    if (!opt.quiet)
      for (const std::string& note : out->notes) tool_err() << "note: " << note << '\n';
    return;
  }
  if (to_json) {
    // glTF → scene file, or scene file → scene file (the writer's form: version 2, defaults left
    // out, curve files inlined).
    auto text = write_scene_json(in.raw);
    if (!text) throw CommandError{opt.input.path + ": " + text.error().describe()};
    write_output(opt.output, *text);
    return;
  }
  GltfExportOptions o;
  o.tolerance = opt.reduce > 0 ? opt.reduce : opt.tolerance;
  o.reduce = opt.reduce > 0;
  o.substeps = opt.substeps;
  o.binary = glb;
  o.cubic = !opt.no_cubic;
  auto out = export_gltf(in.raw, in.scene, o);
  if (!out) throw CommandError{opt.input.path + ": " + out.error().describe()};
  write_output(opt.output, out->bytes);
  if (!opt.quiet) print_report(*out);
}

const RegisterCommand kConvert{{"convert", 45, [](CLI::App& root) {
  auto opt = std::make_shared<ConvertOptions>();
  auto* cmd = root.add_subcommand("convert", "Convert between scene files, glTF 2.0 and BVH (by extension), refitting what glTF cannot hold");
  add_input_options(cmd, opt->input, "input",
                    "Scene file (docs/scene-format.md; - for standard input), glTF 2.0 (.gltf, .glb), BVH (.bvh) or a "
                    "file assimp reads (.fbx, .dae, …)");
  output_file(cmd->add_option("output", opt->output, "Output: .gltf or .glb (export), .bvh (BVH motion) or .json (scene file)"))->required();
  cmd->add_option("--fps", opt->input.fps,
                  "glTF, BVH, assimp input: frames per second, frame = time · fps (default: the format's own)")
      ->check(finite_positive_number());
  cmd->add_option("--tolerance", opt->tolerance,
                  "Largest error of a refitted channel: fraction of its range (translation, scale), radians (rotation)")
      ->check(finite_positive_number());
  cmd->add_option("--reduce", opt->reduce, "Refit every channel with this tolerance (keyframe reduction)")
      ->check(finite_positive_number());
  cmd->add_option("--substeps", opt->substeps, "Grid points per frame where channels are sampled and checked")
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--no-cubic", opt->no_cubic,
                "Write STEP and LINEAR samplers only (Blender 3.4's importer ignores CUBICSPLINE tangents)");
  cmd->add_flag("-q,--quiet", opt->quiet, "Do not print the channel report (nor the notes of a BVH export)");
  cmd->callback([opt] { run_convert(*opt); });
}}};

}  // namespace
}  // namespace inbetween::cli
