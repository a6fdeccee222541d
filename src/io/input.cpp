// One entry for every reader (inbetween/io/input.hpp): format by name or magic, then the reader.
#include "inbetween/io/input.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>

#include "inbetween/io/bvh.hpp"
#include "inbetween/io/assimp.hpp"
#include "inbetween/io/gltf.hpp"
#include "inbetween/io/ibc.hpp"
#include "inbetween/io/read_file.hpp"
#include "inbetween/io/scene.hpp"

namespace inbetween {
namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool has_glb_magic(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return false;  // a FIFO would block the open
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && std::memcmp(magic, "glTF", 4) == 0;
}

bool has_ibc_file_magic(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return false;
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && has_ibc_magic(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(magic), 4));
}

}  // namespace

std::string_view to_string(InputFormat format) noexcept {
  switch (format) {
    case InputFormat::scene_json: return "scene";
    case InputFormat::gltf: return "glTF";
    case InputFormat::bvh: return "BVH";
    case InputFormat::assimp: return "assimp";
    case InputFormat::ibc: return "ibc";
  }
  return "scene";
}

InputFormat input_format(const std::filesystem::path& file) {
  if (file.empty() || file == "-") return InputFormat::scene_json;
  const std::string ext = lower_extension(file);
  if (ext == ".gltf" || ext == ".glb") return InputFormat::gltf;
  if (ext == ".bvh") return InputFormat::bvh;
  if (ext == ".ibc") return InputFormat::ibc;
  if (ext == ".json") return InputFormat::scene_json;
  for (const std::string_view known : assimp_extensions())
    if (ext == known) return InputFormat::assimp;
  if (has_glb_magic(file)) return InputFormat::gltf;
  if (has_ibc_file_magic(file)) return InputFormat::ibc;
  return InputFormat::scene_json;
}

Expected<RawScene> read_input_file(const std::filesystem::path& file, const InputOptions& options) {
  switch (input_format(file)) {
    case InputFormat::gltf: {
      GltfReadOptions gltf;
      gltf.animation = options.animation;
      if (options.fps > 0) gltf.fps = options.fps;
      auto imported = import_gltf_file(file, gltf);
      if (!imported) return imported.error();
      if (options.notes) options.notes->insert(options.notes->end(), imported->notes.begin(), imported->notes.end());
      return std::move(imported->scene);
    }
    case InputFormat::bvh: {
      BvhReadOptions bvh;
      bvh.fps = options.fps;
      bvh.scale = options.scale;
      bvh.axes = options.axes;
      bvh.notes = options.notes;
      return read_bvh_file(file, bvh);
    }
    case InputFormat::assimp: {
      AssimpReadOptions assimp;
      assimp.animation = options.animation;
      assimp.fps = options.fps;
      assimp.scale = options.scale;
      assimp.axes = options.axes;
      assimp.notes = options.notes;
      return read_assimp_file(file, assimp);
    }
    case InputFormat::ibc: {
      auto clip = read_ibc_file(file);
      if (!clip) return clip.error();
      RawScene scene = ibc_raw_scene(*clip);
      if (options.fps > 0) scene.fps = options.fps;
      return scene;
    }
    case InputFormat::scene_json: break;
  }
  auto text = read_file_bytes(file);
  if (!text) return text.error();
  return read_scene_json(*text, file.string());
}

}  // namespace inbetween
