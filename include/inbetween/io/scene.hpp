#pragma once
/// The inbetween scene file (docs/scene-format.md, docs/scene.schema.json): a versioned JSON
/// document with named animation tracks and objects, read into built, ready-to-evaluate tracks.
/// Every error names its place with a JSON pointer ("/tracks/2/keys/3/frame").

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"
#include "inbetween/tracks/transform_track.hpp"

namespace inbetween {

/// A named scalar track with Blender F-curve semantics (kind "scalar", the default).
struct SceneScalarTrack {
  std::string name;  ///< column name in baked output, e.g. "cube.location.x"
  FCurve curve;      ///< the built curve
};

/// A named vector or colour track ("vec2", "vec3", "vec4", "color"): held as Track<Vec4d>, the
/// components beyond `dim` being zero.
struct SceneVectorTrack {
  std::string name;        ///< column prefix, e.g. "cube.color"
  int dim = 3;             ///< number of components (2, 3 or 4)
  std::string components;  ///< component letters for column names: "xy", "xyz", "xyzw" or "rgba"
  Track<Vec4d> track;      ///< the built track
};

/// A named orientation track (kind "quaternion"); columns <name>.w .x .y .z.
struct SceneQuatTrack {
  std::string name;         ///< column prefix
  QuatTrack<double> track;  ///< the built track
};

/// A named Euler-angle track (kind "euler"); columns <name>.w .x .y .z of the orientation.
struct SceneEulerTrack {
  std::string name;          ///< column prefix
  EulerTrack<double> track;  ///< the built track
};

/// Which list a track of the file went to.
enum class SceneTrackKind : std::uint8_t { scalar, vector, quaternion, euler };

/// A parsed scene.
struct Scene {
  int version = 1;                        ///< the "inbetween" format version
  double fps = 24;                        ///< frames per second (> 0)
  double range_start = 1, range_end = 1;  ///< default frame range for baking (start ≤ end)
  std::vector<SceneScalarTrack> scalar_tracks;  ///< kind "scalar"
  std::vector<SceneVectorTrack> vector_tracks;  ///< kinds vec2, vec3, vec4, color
  std::vector<SceneQuatTrack> quat_tracks;      ///< kind quaternion
  std::vector<SceneEulerTrack> euler_tracks;    ///< kind euler
  /// File order of the tracks: (kind, index into the list of that kind).
  std::vector<std::pair<SceneTrackKind, std::size_t>> track_order;
  /// The objects, in file order, with their parent links and animated local transforms.
  std::optional<TransformHierarchy<double>> objects;
};

/// Parses scene JSON text.  Errors carry ErrorCode::Parse for malformed JSON (where = "line L,
/// column C") and otherwise the code of the failed check with `where` = the JSON pointer.
[[nodiscard]] Expected<Scene> parse_scene(std::string_view json_text);

/// One output column of a baked scene.
struct SceneColumn {
  std::string name;               ///< "<track>" for scalar tracks, "<track>.<component>" otherwise
  bool single_precision = false;  ///< true for F-curve columns (their values are exact floats)
};

/// Columns of a baked scene after "frame" and "time": the tracks in file order, then for each
/// object <object>.translation.x…z, <object>.rotation.w…z, <object>.scale.x…z (world transform).
[[nodiscard]] std::vector<SceneColumn> scene_columns(const Scene& scene);

/// Evaluates every track and object at `frame`; `out` has scene_columns(scene).size() entries,
/// filled in that order.  Scalar tracks are evaluated in single precision (Blender semantics; a
/// frame beyond float's range is clamped to the largest float);
/// objects give their world TRS (see compose() for the scale of sheared chains).
void evaluate_scene(const Scene& scene, double frame, std::span<double> out) noexcept;

}  // namespace inbetween
