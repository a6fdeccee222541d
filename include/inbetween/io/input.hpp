#pragma once
/// Every animation file inbetween reads, behind one call: the format is told from the file's name
/// (and the .glb magic), the matching reader fills a RawScene, and every command and the Python
/// module go through here, so a new reader is one branch in one place.
///
///   scene file   .json or anything else          io/scene.hpp (read_scene_json)
///   glTF 2.0     .gltf, .glb, or the "glTF" magic io/gltf.hpp  (read_gltf_file)
///   BVH          .bvh                             io/bvh.hpp   (read_bvh_file)
///   assimp       .fbx .dae .x .md5anim .smd …     io/assimp.hpp (read_assimp_file)
///   compressed   .ibc, or the "IBC\x1a" magic      io/ibc.hpp    (read_ibc_file, ibc_raw_scene)

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"

namespace inbetween {

/// The reader a file goes to.
enum class InputFormat : std::uint8_t {
  scene_json,  ///< inbetween's scene file (docs/scene-format.md): the default for unknown extensions
  gltf,        ///< glTF 2.0 (docs/gltf.md)
  bvh,         ///< Biovision hierarchy motion capture (docs/bvh.md)
  assimp,      ///< what Debian's assimp reads with node animation: FBX, Collada, … (docs/assimp.md)
  ibc,         ///< inbetween's compressed clip, .ibc or its magic (docs/compression.md)
};

/// The name of a format as the commands print it: "scene", "glTF", "BVH", "assimp", "ibc".
[[nodiscard]] std::string_view to_string(InputFormat format) noexcept;

/// Options of read_input_file(); each reader uses those that apply to it.
struct InputOptions {
  /// glTF and assimp: the animation's name, or its index in decimal; empty for the first.
  std::string animation;
  /// Frames per second, finite and > 0, or ≤ 0 for the format's own: glTF 24; BVH 1 / Frame Time;
  /// assimp the animation's ticks per second when in [1, 240], else 24 (docs/assimp.md).  Key times in
  /// seconds become frames = time · fps.  A scene file keeps its own fps (the commands relabel).
  double fps = 0;
  /// BVH and assimp: factor applied to every length (offsets, positions), finite and > 0.
  double scale = 1;
  /// BVH and assimp: axis conversion, "" (keep the file's axes) or a name documented by the reader.
  std::string axes;
  /// When not null, readers append one line per thing imported approximately or not at all; the
  /// commands print them as `note:` lines.
  std::vector<std::string>* notes = nullptr;
};

/// The reader for `file`: by extension (any case), else by the .glb magic "glTF" at its start,
/// else the scene file.  "-" (standard input) is a scene file.
[[nodiscard]] InputFormat input_format(const std::filesystem::path& file);

/// Reads `file` with the reader of input_format(file) into a RawScene (not yet built: call
/// build_scene()).  Errors are the reader's own, with its places (a JSON pointer for scene files
/// and glTF, a line for BVH, a node for assimp).  Not for "-": read standard input yourself and
/// call read_scene_json().
[[nodiscard]] Expected<RawScene> read_input_file(const std::filesystem::path& file, const InputOptions& options = {});

}  // namespace inbetween
