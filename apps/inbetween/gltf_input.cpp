#include "gltf_input.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include "command.hpp"
#include "inbetween/io/gltf.hpp"

namespace inbetween::cli {

bool is_gltf_input(const std::string& path) {
  if (path == "-" || path.empty()) return false;
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".gltf" || ext == ".glb") return true;
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && std::memcmp(magic, "glTF", 4) == 0;
}

RawScene load_gltf_raw(const std::string& path, const std::string& animation, double fps) {
  GltfReadOptions options;
  options.animation = animation;
  if (fps > 0) options.fps = fps;
  std::vector<std::string> notes;
  options.notes = &notes;
  auto raw = read_gltf_file(path, options);
  for (const std::string& note : notes) std::cerr << "note: " << path << ": " << note << '\n';
  if (!raw) {
    Error e = raw.error();
    if (!e.location.empty()) e.where = json_pointer(e.location);
    throw CommandError{path + ": " + (e.where.empty() || e.where == path ? e.message : e.where + ": " + e.message)};
  }
  return std::move(*raw);
}

Scene load_gltf_scene(const std::string& path, const std::string& animation, double fps) {
  RawScene raw = load_gltf_raw(path, animation, fps);
  auto scene = build_scene(raw);
  // The reader checks what build_scene() would refuse; a failure here names the scene member.
  if (!scene) throw CommandError{path + ": " + scene.error().describe()};
  return std::move(*scene);
}

}  // namespace inbetween::cli
