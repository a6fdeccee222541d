#pragma once
/// glTF 2.0 export of a scene (docs/gltf.md): every object becomes a node (hierarchy kept, local
/// TRS), with one animation.  glTF time = (frame − first frame of the scene's range) / fps, as
/// Blender's exporter does.  Keys stay keys where glTF holds them exactly (all stepped → STEP,
/// linear tangents and slerp → LINEAR, Hermite-family tangents and glTF cubic rotations →
/// CUBICSPLINE with tangent = slope × fps); every other channel is refitted (tracks/refit.hpp) on
/// a grid of `substeps` points per frame over the range, and the report says why, with how many
/// keys and the measured error.  Path objects (their translation and rotation) and cameras (their
/// rotation, and their translation on a path) have no keys: their local transform is sampled from
/// the built Scene on the grid and refitted the same way ("path with speed control", "camera
/// view").  A camera becomes a glTF perspective camera on its node; the node's rotation is the
/// view's (glTF cameras look down local −Z with +Y up, as scene cameras do).  Each skin of the
/// scene becomes a glTF skin (its joints the objects' nodes, in joint order) with inverse bind
/// matrices: the inverse of each joint's world matrix in the bind pose, which is the pose the nodes'
/// own TRS hold (the scene at the first frame of its range), composed as viewers do (matrix products).
/// Written through
/// Debian's tinygltf (it serialises JSON and GLB).

#include <cstddef>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween {

/// The most grid points export_gltf() samples a scene's range on ((range end − start) × substeps
/// + 2): beyond it the export is refused (Unsupported at {"range"}) instead of allocating without
/// bound.  10 million points are a 24 fps range of 29 hours at the default 4 substeps.
inline constexpr std::size_t kMaxGltfExportGridPoints = 10'000'000;

/// Options of export_gltf().
struct GltfExportOptions {
  /// Largest error of a refitted channel: a fraction of the channel's range (largest max − min
  /// over its components, 1 when constant) for translation and scale; radians for rotations.
  double tolerance = 1e-5;
  int substeps = 4;     ///< grid points per frame where channels are sampled and errors checked (1..64)
  bool reduce = false;  ///< refit every channel, also those glTF could hold exactly
  bool binary = true;   ///< GLB (true) or .gltf JSON with the buffer embedded as a data URI
  /// Allow CUBICSPLINE samplers.  false writes STEP and LINEAR only (cubic channels refitted):
  /// Blender 3.4's importer drops CUBICSPLINE tangents (it sets automatic handles), so files meant
  /// for Blender should be written without them (docs/gltf-export.md).  Without cubic keys, LINEAR
  /// rotation keys are also kept close enough for Blender's component-wise quaternion
  /// interpolation (refitted otherwise).
  bool cubic = true;
  /// Cameras (glTF "perspective", yfov from the scene): near clip plane, > 0, in scene units.
  /// Default 0.1, Blender's default clip start (three.js's default near is 0.1 too).
  double camera_znear = 0.1;
  /// Cameras: far clip plane, > camera_znear.  Default 1000, Blender's default clip end.
  double camera_zfar = 1000;
  /// Cameras: width / height.  0 (the default) leaves aspectRatio out of the file, which glTF
  /// defines as "the aspect ratio of the rendering viewport": the scene gives only the vertical
  /// field of view.  Otherwise > 0.
  double camera_aspect = 0;
};

/// What happened to one animated channel.
struct GltfChannelReport {
  std::string object;        ///< object (node) name
  std::string path;          ///< "translation", "rotation" or "scale"
  std::string interpolation; ///< "STEP", "LINEAR" or "CUBICSPLINE" as written
  bool refitted = false;     ///< false: the authored keys were written as they are
  std::string reason;        ///< why refitted (empty when kept)
  std::size_t keys_before = 0;  ///< authored keys
  std::size_t keys_after = 0;   ///< keys written
  /// Largest error over the grid of what is written (float keys, times and tangents, played with
  /// glTF's formulas) against the scene's own local channel: value units, radians for rotations.
  double max_error = 0;
  double tolerance = 0;      ///< the absolute tolerance used (refitted channels)
  /// One key more than authored at the range's end, holding the value: no channel reached the end,
  /// and a glTF clip ends at its latest key (docs/gltf-export.md).
  bool held_to_range_end = false;
};

/// The exported file and the report.
struct GltfExport {
  std::string bytes;                        ///< the .glb or .gltf content
  std::vector<GltfChannelReport> channels;  ///< one entry per animated channel
  std::vector<std::string> notes;           ///< what the file cannot carry (named tracks, …)
};

/// Exports `scene`, which must have been built from `raw` (build_scene(raw)): `raw` gives the
/// authored keys and their kinds, `scene` everything else.  Errors: InvalidArgument for options
/// ({"tolerance"}, {"substeps"}, {"camera_znear"}, {"camera_zfar"}, {"camera_aspect"}) and for a
/// pair that was not built one from the other (other objects, names or keyed channels:
/// {"objects"}, {"objects", i, "name"}, {"objects", i, "translation"|"rotation"|"scale"}), Unsupported when the scene has no objects or a joint's bind-pose world
/// matrix has no inverse ({"skins", k, "joints", j}), and the refitter's errors prefixed with
/// {"objects", i, channel}.  What glTF's float cannot hold is refused, never written as infinity:
/// a range lasting more than 3.4e38 s or over kMaxGltfExportGridPoints ({"range"}); a key whose
/// time, value or tangent (per second) is beyond float, or whose time rounds to its predecessor's
/// ({"objects", i, channel, "keys", k} for an authored key, {"objects", i, channel} for a refitted
/// one, the message naming the key and its frame).
[[nodiscard]] Expected<GltfExport> export_gltf(const RawScene& raw, const Scene& scene, const GltfExportOptions& options = {});

}  // namespace inbetween
