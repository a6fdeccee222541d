#pragma once
// The input of every reading command (bake, convert, plot, view): one positional file and the
// options that choose what is read from it, loaded through the library's one entry for every
// format (inbetween/io/input.hpp) with errors turned into CommandError.
#include <string>

#include <CLI/CLI.hpp>

#include "inbetween/io/input.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween::cli {

/// The input file and the options that apply to some formats only.
struct InputArgs {
  std::string path;       ///< the file; "-" is a scene file on standard input
  std::string animation;  ///< --animation: glTF and assimp input
  double fps = 0;         ///< --fps: 0 for the format's own (a scene file keeps its own; see the commands)
  double scale = 1;       ///< --scale: BVH and assimp input
  std::string axes;       ///< --axes: BVH and assimp input
};

/// Adds the positional `input` (named `name`, described by `what`) and --animation, --scale and
/// --axes to `cmd`, bound to `args`.  --fps is each command's own (its meaning differs).
void add_input_options(CLI::App* cmd, InputArgs& args, const std::string& name, const std::string& what);

/// The format of args.path (a scene file for "-").
[[nodiscard]] InputFormat input_format_of(const InputArgs& args);

/// Reads args.path into a RawScene: "-" and scene files through read_input() and read_scene_json()
/// (curve files relative to the scene's folder), every other format through read_input_file().
/// Options that do not apply to the format are refused ("--animation: only for glTF and assimp
/// input"); the reader's notes go to standard error as `note: <path>: …` lines.  Throws
/// CommandError "<path>: <place>: <message>" (exit code 2).
[[nodiscard]] RawScene load_raw(const InputArgs& args);

/// A raw scene and the scene built from it (export_gltf reads both).
struct LoadedScene {
  RawScene raw;  ///< as read
  Scene scene;   ///< build_scene(raw)
};

/// load_raw() then build_scene(), keeping both; a build error names the scene member.
[[nodiscard]] LoadedScene load_raw_and_scene(const InputArgs& args);

/// load_raw_and_scene()'s scene.
[[nodiscard]] Scene load_scene(const InputArgs& args);

}  // namespace inbetween::cli
