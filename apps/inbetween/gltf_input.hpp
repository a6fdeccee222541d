#pragma once
// glTF input of the commands (bake, convert): telling a glTF file from a scene file, and reading
// it through the library (inbetween/io/gltf.hpp) with errors turned into CommandError.
#include <string>

#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween::cli {

/// True for a path ending in .gltf or .glb (any case), or a file that starts with the .glb magic
/// "glTF"; false for "-" (standard input is always a scene file).
bool is_gltf_input(const std::string& path);

/// Reads the glTF file's animation (NAME or INDEX; "" the first) at `fps` (≤ 0: 24) into a
/// RawScene; throws CommandError "<path>: <where>: <message>" (exit code 2) on any error.
RawScene load_gltf_raw(const std::string& path, const std::string& animation, double fps);

/// load_gltf_raw() then build_scene().
Scene load_gltf_scene(const std::string& path, const std::string& animation, double fps);

}  // namespace inbetween::cli
