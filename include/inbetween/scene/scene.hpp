#pragma once
/// The runtime scene: build_scene() checks a RawScene once (every check lives here, none in the
/// readers) and makes a Scene, which cannot be invalid or empty.  A Scene has a fixed list of
/// output columns and samples all of them at a frame into a caller's span, noexcept and without
/// allocating.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"
#include "inbetween/tracks/transform_track.hpp"

namespace inbetween {

/// One output column of a scene.
struct SceneColumn {
  std::string name;               ///< "<track>" for scalar tracks, "<track>.<component>" otherwise
  bool single_precision = false;  ///< true for F-curve columns (their values are exact floats)
};

/// A built scalar track: one column <name>, evaluated in single precision (Blender semantics).
struct SceneScalarTrack {
  std::string name;  ///< column name
  FCurve curve;      ///< the built curve
};

/// A built vector or colour track: columns <name>.<letter> for each letter of `components`;
/// one column <name> for a vec1 track (empty `components`).
struct SceneVectorTrack {
  std::string name;        ///< column prefix
  std::string components;  ///< column letters: "" (vec1), "xy", "xyz", "xyzw" or "rgba"
  Track<Vec4d> track;      ///< the built track (components beyond the count are zero)
};

/// A built quaternion track: columns <name>.w .x .y .z.
struct SceneQuatTrack {
  std::string name;         ///< column prefix
  QuatTrack<double> track;  ///< the built track
};

/// A built Euler track: columns <name>.w .x .y .z of the orientation.
struct SceneEulerTrack {
  std::string name;          ///< column prefix
  EulerTrack<double> track;  ///< the built track
};

/// One built track of a scene: exactly one kind.
using SceneTrack = std::variant<SceneScalarTrack, SceneVectorTrack, SceneQuatTrack, SceneEulerTrack>;

/// A validated, ready-to-sample scene.  Only build_scene() makes one.
class Scene {
 public:
  /// Frames per second (finite, > 0).
  [[nodiscard]] double fps() const noexcept { return fps_; }
  /// First frame of the default bake range.
  [[nodiscard]] double range_start() const noexcept { return range_start_; }
  /// Last frame of the default bake range (≥ range_start()).
  [[nodiscard]] double range_end() const noexcept { return range_end_; }
  /// The tracks, in the RawScene's order.
  [[nodiscard]] std::span<const SceneTrack> tracks() const noexcept { return tracks_; }
  /// The objects with their parent links and local animation; empty when the scene has none.
  [[nodiscard]] std::span<const HierarchyNode<double>> objects() const noexcept {
    return objects_ ? objects_->nodes() : std::span<const HierarchyNode<double>>{};
  }

  /// The output columns, in order: each track's columns in track order, then for each object
  /// <object>.translation.x y z, <object>.rotation.w x y z, <object>.scale.x y z (world TRS).
  [[nodiscard]] std::span<const SceneColumn> columns() const noexcept { return columns_; }

  /// Evaluates every column at `frame` into `out` (precondition, asserted: out.size() ==
  /// columns().size()).  Scalar tracks are evaluated at the frame rounded to single precision
  /// (Blender semantics; a frame beyond float's range acts as the largest float); objects give
  /// their world TRS (see compose() for the scale of sheared chains).  Never allocates, at any
  /// object count, and keeps no scratch state: a parent's world transform is read back from its
  /// own columns of `out` (exact: they hold the doubles written), so one Scene may be sampled from
  /// several threads at once, each with its own `out`.
  void sample(double frame, std::span<double> out) const noexcept;

 private:
  friend Expected<Scene> build_scene(const RawScene& raw);
  Scene(double fps, double range_start, double range_end, std::vector<SceneTrack> tracks,
        std::optional<TransformHierarchy<double>> objects, std::vector<SceneColumn> columns);

  double fps_, range_start_, range_end_;
  std::vector<SceneTrack> tracks_;
  std::optional<TransformHierarchy<double>> objects_;  // none when the scene has no objects
  std::vector<SceneColumn> columns_;
  std::size_t object_column_ = 0;  // index of the first object column
};

/// Checks everything and builds the scene: fps finite and > 0; range first ≤ last; track and
/// object names non-empty and unique among tracks and among objects; no two tracks or objects
/// writing the same output column; every track's keys (through build_fcurve, build_track,
/// build_quat_track, build_euler_track); Euler conventions; object rest rotations non-zero;
/// parents that exist and form no cycle.  The Error's structured `location` names the offending
/// member of `raw` ({"tracks", 2, "keys", 3, "frame"}), which, since RawScene mirrors the file, is
/// the JSON pointer of the value in a scene file.
[[nodiscard]] Expected<Scene> build_scene(const RawScene& raw);

}  // namespace inbetween
