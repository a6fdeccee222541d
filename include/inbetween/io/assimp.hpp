#pragma once
/// Node animation from the formats Debian's assimp (5.2) reads — FBX, Collada, DirectX .x, MD5,
/// Valve SMD, … (docs/assimp.md) — into the RawScene every other format fills, so build_scene()
/// and every command treat an FBX character as any scene.  assimp parses the file; this reader
/// translates its node hierarchy and one of its animations:
///
///   node                 one RawObject per aiNode, depth first from the root (index = visit
///                        order); name = the node's, `node<index>` when empty, `#<index>` appended
///                        while the name is taken (as the glTF reader does)
///   rest pose            aiNode::mTransformation decomposed into TRS (shear, a zero scale or a
///                        projective row: the nearest TRS assimp's own Decompose() gives, and a note)
///   position / scaling   RawVec3Channel, TangentKind::linear (assimp gives keys, not curves: its
///   keys                 players interpolate linearly)
///   rotation keys        RawQuatKeys, QuatInterpolation::slerp (shortest arc, as assimp and three.js)
///   time                 frame = (ticks / ticks per second) · fps
///   pre/post state       CONSTANT → TrackExtend::constant, LINEAR → linear, REPEAT → repeat on
///                        translation and scale; DEFAULT (assimp's unset value: the rest transform
///                        outside the keys) is held like CONSTANT; rotation keys always hold their
///                        end keys; a note for each state that cannot be expressed
///
/// `scale` multiplies every length (rest and keyed translations); `axes` turns the file's axes into
/// others (a signed permutation, applied to every node's transform: world' = A · world · Aᵀ).
/// Only the importers of assimp_extensions() are enabled (plus LightWave objects, which .lws
/// scenes load), also when assimp detects a format by content: a file named .fbx that holds a
/// format not enabled is refused.  Parsers of assimp that fuzzing found unsafe on damaged files
/// are kept away from the input (docs/assimp.md): binary and compressed .x are refused, Collada is
/// parsed without its geometry and controller libraries and text .x without its Mesh objects (mesh
/// data, which node animation does not need), and assimp's internal assertions (on in Debian's
/// build) fail the read instead of aborting the program.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"

namespace inbetween {

/// Options of the assimp reader.
struct AssimpReadOptions {
  /// Animation to import: its name, or (when no animation has that name) its index in decimal;
  /// empty for the first (a file without animations gives the rest pose only).
  std::string animation;
  /// Frames per second of the scene, finite and > 0; ≤ 0 (the default) for the animation's own
  /// ticks per second — or 24 when that is not a frame rate (outside [1, 240]: Collada
  /// are seconds with 1 tick per second) or the file has no animation.
  double fps = 0;
  /// Factor on every length (rest and keyed translations), finite and > 0.
  double scale = 1;
  /// Axis conversion, a name of parse_axes() (io/axes.hpp): "" (keep the file's), "z-up" (a Y-up
  /// file made Z-up), "y-up" (a Z-up file made Y-up), or three signed axis letters giving the new
  /// x, y, z in terms of the file's ("x,-z,y" = "z-up").
  std::string axes;
  /// Files larger than this are refused before assimp sees them (bytes).
  std::uintmax_t max_file_bytes = std::uintmax_t(1) << 30;
  /// When not null, the reader appends one line per thing it imports approximately or not at all.
  std::vector<std::string>* notes = nullptr;
};

/// Extensions (lower case, with the dot) that input_format() sends to this reader.
[[nodiscard]] std::span<const std::string_view> assimp_extensions() noexcept;

/// Reads `file` (a regular file of at most options.max_file_bytes; companion files such as an
/// .md5anim's .md5mesh or an .lws scene's objects are found beside it) into a RawScene: objects
/// in depth-first node order, range = [first, last] key of the animation in frames ([0, 0]
/// without animation).  Errors: Io (missing, not a regular file, unreadable), Unsupported (too
/// large; a format whose importer is not enabled), Parse (assimp's refusal, its message on one
/// line), and for node data NotFinite / KeysNotIncreasing / InvalidArgument with a message that
/// names the animation, the node and the key index.
[[nodiscard]] Expected<RawScene> read_assimp_file(const std::filesystem::path& file,
                                                  const AssimpReadOptions& options = {});

/// The same for bytes in memory; `hint` is a file extension without the dot ("fbx", "dae") or
/// empty for assimp's detection by content.  Formats that need companion files cannot find them.
[[nodiscard]] Expected<RawScene> read_assimp(std::span<const std::byte> bytes, std::string_view hint,
                                             const AssimpReadOptions& options = {});

}  // namespace inbetween
