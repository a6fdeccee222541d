#include "input.hpp"

#include <iostream>
#include <vector>

#include "command.hpp"
#include "frame_spec.hpp"
#include "inbetween/io/scene.hpp"

namespace inbetween::cli {
namespace {

// A scene file's error: its place as a JSON pointer, "/" for the document root.
std::string scene_file_error(const std::string& path, const Error& e) { return describe_in(e, path, "/"); }

}  // namespace

void add_input_options(CLI::App* cmd, InputArgs& args, const std::string& name, const std::string& what) {
  input_file(cmd->add_option(name, args.path, what))->required();
  cmd->add_option("--animation", args.animation,
                  "glTF and assimp input: the animation's NAME or INDEX (default: the first)");
  cmd->add_option("--scale", args.scale, "BVH and assimp input: factor on every length (default 1: the file's units)")
      ->check(finite_positive_number());
  cmd->add_option("--axes", args.axes, "BVH and assimp input: axis conversion (default: the file's axes; docs/bvh.md)");
}

InputFormat input_format_of(const InputArgs& args) { return input_format(args.path); }

RawScene load_raw(const InputArgs& args) {
  const InputFormat format = input_format_of(args);
  const bool keyed_in_time = format != InputFormat::scene_json;
  if (!args.animation.empty() && format != InputFormat::gltf && format != InputFormat::assimp) {
    throw CommandError{"--animation: only for glTF and assimp input (.gltf, .glb, .fbx, .dae, …)"};
  }
  if ((args.scale != 1 || !args.axes.empty()) && (format == InputFormat::scene_json || format == InputFormat::gltf || format == InputFormat::ibc)) {
    throw CommandError{std::string(args.scale != 1 ? "--scale" : "--axes") + ": only for BVH and assimp input"};
  }
  if (!keyed_in_time) {
    // The path too: curve files named by "file" members are relative to the scene's folder.
    const std::string text = read_input(args.path);
    auto raw = read_scene_json(text, args.path);
    if (!raw) {
      if (const std::string other = other_kind_message(args.path, text, "scene"); !other.empty()) throw CommandError{other};
      throw CommandError{scene_file_error(args.path, raw.error())};
    }
    return std::move(*raw);
  }
  InputOptions options;
  options.animation = args.animation;
  options.fps = args.fps;
  options.scale = args.scale;
  options.axes = args.axes;
  std::vector<std::string> notes;
  options.notes = &notes;
  auto raw = read_input_file(args.path, options);
  for (const std::string& note : notes) tool_err() << "note: " << args.path << ": " << note << '\n';
  if (!raw) {
    throw CommandError{describe_in(raw.error(), args.path)};
  }
  return std::move(*raw);
}

LoadedScene load_raw_and_scene(const InputArgs& args) {
  RawScene raw = load_raw(args);
  auto scene = build_scene(raw);
  if (!scene) {
    if (input_format_of(args) == InputFormat::scene_json) throw CommandError{scene_file_error(args.path, scene.error())};
    throw CommandError{args.path + ": " + scene.error().describe()};
  }
  return LoadedScene{std::move(raw), std::move(*scene)};
}

Scene load_scene(const InputArgs& args) { return std::move(load_raw_and_scene(args).scene); }

}  // namespace inbetween::cli
