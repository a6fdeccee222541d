#pragma once
/// glTF 2.0 animation import (docs/gltf.md): a `.gltf` (embedded data URIs or external buffers,
/// resolved relative to the file) or `.glb` file → RawScene, so that build_scene() and `bake` treat
/// it as any scene file.  The file is parsed by Debian's tinygltf (no glTF parser here); this
/// reader decodes accessors (float, normalised byte/ubyte/short/ushort, sparse), checks what the
/// animation needs, and maps each channel onto the track whose semantics equal the
/// specification's Appendix C:
///
///   translation / scale   STEP → TangentKind::stepped, LINEAR → TangentKind::linear,
///                         CUBICSPLINE → TangentKind::explicit_hermite with slope = tangent / fps
///   rotation              STEP → QuatInterpolation::step, LINEAR → slerp (shortest path),
///                         CUBICSPLINE → gltf_cubic (4-D Hermite, normalised), tangents / fps
///   weights               one VectorKind::vec1 track "<node>.weights.<i>" per morph target,
///                         with the translation mapping
///   camera (perspective)  the object becomes a scene camera viewing along its own rotation
///                         (RawOwnRotation: local −Z forward, +Y up) with the camera's yfov;
///                         an orthographic camera leaves a plain object and a note
///
/// Every node becomes an object (name: the node's name, `node<index>` when it has none; a name
/// already taken gets `#<index>` appended), its parent the node that lists it as a child, its rest
/// pose the node's TRS (a `matrix` decomposed).  Times become frames: frame = time · fps; values
/// are held before the first and after the last key (TrackExtend::constant).

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"

namespace inbetween {

/// Options of the glTF reader.
struct GltfReadOptions {
  /// Animation to import: its name, or (when no animation has that name) its index in decimal;
  /// empty for the first animation (a file without animations gives the rest pose only).
  std::string animation;
  /// Frames per second: glTF keys are in seconds, the scene in frames (frame = time · fps); finite, > 0.
  double fps = 24;
  /// Deprecated, kept for one release: import_gltf() / import_gltf_file() return the notes (as
  /// export_gltf() does); read_gltf() and read_gltf_file() still append them here when it is set.
  /// (Not marked [[deprecated]]: GCC would then warn wherever the options are default-constructed.)
  std::vector<std::string>* notes = nullptr;
};

/// What import_gltf() made: the scene and the notes on what it imported approximately or not at
/// all (an orthographic camera; a camera's znear, zfar or aspectRatio, which a scene camera does
/// not keep), one line each; the commands print them as `note:` lines.  The reader's counterpart
/// of GltfExport.
struct GltfImport {
  RawScene scene;                  ///< the file as a raw scene (see read_gltf_file())
  std::vector<std::string> notes;  ///< one line each, for `note:` output
};

/// Reads a `.gltf` or `.glb` file and returns the raw scene with the reader's notes; errors as
/// read_gltf_file().
[[nodiscard]] Expected<GltfImport> import_gltf_file(const std::filesystem::path& file, const GltfReadOptions& options = {});

/// import_gltf_file() for bytes in memory (see read_gltf()).
[[nodiscard]] Expected<GltfImport> import_gltf(std::span<const std::byte> bytes, const std::filesystem::path& base_dir,
                                               const GltfReadOptions& options = {});

/// Reads a `.gltf` or `.glb` file (told apart by the glb magic "glTF", not by the extension) and
/// the selected animation into a RawScene: objects = nodes in index order, weights tracks first,
/// fps = options.fps, range = [start, end] of the animation × fps ([0, 0] without animation).
/// Errors: ErrorCode::Io for a file (or external buffer) that cannot be read, Parse for what
/// tinygltf rejects (truncated .glb, bad JSON), and for animation data (accessor out of its
/// buffer, count disagreeing with the sampler, NaN, times not increasing, unknown interpolation)
/// the code of the fault with a structured `location` into the glTF JSON
/// ({"animations", 0, "channels", 2} or {"accessors", 5}) and a message that names the
/// animation, channel, sampler and accessor indices.
[[nodiscard]] Expected<RawScene> read_gltf_file(const std::filesystem::path& file, const GltfReadOptions& options = {});

/// The same as read_gltf_file() for bytes in memory (a .glb, or .gltf JSON text); relative
/// buffer URIs are resolved against `base_dir` (empty: external buffers are an error).  The
/// scene of import_gltf(), without its notes.
[[nodiscard]] Expected<RawScene> read_gltf(std::span<const std::byte> bytes, const std::filesystem::path& base_dir,
                                           const GltfReadOptions& options = {});

/// True when `bytes` start with the .glb magic "glTF".
[[nodiscard]] bool is_glb(std::span<const std::byte> bytes) noexcept;

}  // namespace inbetween
