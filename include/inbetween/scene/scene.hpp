#pragma once
/// The runtime scene: build_scene() checks a RawScene once (every check lives here, none in the
/// readers) and makes a Scene, which cannot be invalid or empty.  A Scene has a fixed list of
/// output columns and samples all of them at a frame into a caller's span, noexcept and without
/// allocating.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/curves/any_curve.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/scene/camera_view.hpp"
#include "inbetween/scene/nla.hpp"
#include "inbetween/scene/path_motion.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/math/enum_names.hpp"
#include "inbetween/tracks/track.hpp"
#include "inbetween/tracks/transform_track.hpp"

namespace inbetween {

/// The frame an object's transform columns are expressed in (bake --space, Python load_clip).
enum class Space {
  world,  ///< relative to the scene's root: the parent chain composed in (the default everywhere)
  local,  ///< relative to the object's parent (a root's local transform is its world transform)
};

/// File and command-line names of the Space enumerators, in declaration order.
inline constexpr std::array<std::string_view, 2> space_names = {"world", "local"};
/// The name table of Space (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<Space>() noexcept {
  return space_names;
}

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

/// One built leg of a path object: the motion along one curve and the arc length of the legs
/// before it (so the object's distance column is distance_before + the leg's distance).
struct ScenePathLeg {
  PathMotion motion;                           ///< the built leg (its frame_range() orders the legs)
  double distance_before = 0;                  ///< sum of the lengths of the earlier legs
  std::optional<std::size_t> look_at_object;   ///< object index looked at (orientation look_at an object)
};

/// A built skin: the joints of RawSkin resolved to object indices (into Scene::objects()).
struct SceneSkin {
  std::string name;                 ///< skin name (may be empty)
  std::vector<std::size_t> joints;  ///< object indices in joint order, each once
};

class Scene;

/// A sampling context for a sequence of frames (bake, a preview): it remembers the rotation each
/// path object, camera and descendant of one wrote at the previous sample and flips the sign of
/// the new quaternion (q and −q are the same rotation) when the dot product with it is negative,
/// so rotation columns are sign-continuous from frame to frame.  Objects whose rotation is keyed
/// only (every version-1 object) are left as Scene::sample() writes them; with Space::local it holds the world transforms.
/// Make one per scene and sequence (it allocates once, here); Scene::sample(frame, out, cursor[, space]) never allocates.
class SceneCursor {
 public:
  /// A cursor for `scene` with no previous frame.
  explicit SceneCursor(const Scene& scene);
  /// Forgets the previous frame (the next sample starts a new sequence).
  void reset() noexcept { has_previous_ = false; }

 private:
  friend class Scene;
  std::vector<std::size_t> rotation_columns_;  // column of rotation.w of each tracked object
  std::vector<double> previous_;               // 4 per tracked object: the last written w, x, y, z
  std::size_t column_count_ = 0;               // the scene's column count (checked by sample)
  std::vector<double> world_;                  // Space::local: every column, objects in world space
  bool has_previous_ = false;
};

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
  /// For a path object the node's local animation holds its scale only (path_legs() has the
  /// rest); for a camera, its translation and scale (camera() has the view).
  [[nodiscard]] std::span<const HierarchyNode<double>> objects() const noexcept {
    return objects_ ? objects_->nodes() : std::span<const HierarchyNode<double>>{};
  }

  /// The path legs of object `i` (index into objects()); empty for an object not on a path.
  [[nodiscard]] std::span<const ScenePathLeg> path_legs(std::size_t i) const noexcept { return extras_[i].legs; }
  /// The Blender animation of object `i` (version 3), or nullptr when it has none.
  [[nodiscard]] const BlenderObject* blender_object(std::size_t i) const noexcept {
    return extras_[i].blender ? &*extras_[i].blender : nullptr;
  }
  /// The camera view of object `i`, or nullptr when it is not a camera.
  [[nodiscard]] const CameraView<double>* camera(std::size_t i) const noexcept {
    return extras_[i].camera ? &*extras_[i].camera : nullptr;
  }
  /// The skins, in the RawScene's order, their joints resolved to object indices.
  [[nodiscard]] std::span<const SceneSkin> skins() const noexcept { return skins_; }
  /// Object indices in evaluation order: parents before children, and every object looked at
  /// (a path's look_at object, a camera's targets) before the object that looks at it.
  [[nodiscard]] std::span<const std::size_t> evaluation_order() const noexcept { return order_; }

  /// The output columns, in order: each track's columns in track order, then for each object
  /// <object>.translation.x y z, <object>.rotation.w x y z, <object>.scale.x y z (world TRS),
  /// followed for a path object by <object>.distance and <object>.speed and for a camera by
  /// <object>.target.x y z (the centre of interest, world).
  [[nodiscard]] std::span<const SceneColumn> columns() const noexcept { return columns_; }

  /// Evaluates every column at `frame` into `out` (precondition, asserted: out.size() ==
  /// columns().size()).  Scalar tracks are evaluated at the frame rounded to single precision
  /// (Blender semantics; a frame beyond float's range acts as the largest float); objects give
  /// their world TRS (see compose() for the scale of sheared chains).  Never allocates, at any
  /// object count, and keeps no scratch state: a parent's world transform is read back from its
  /// own columns of `out` (exact: they hold the doubles written), so one Scene may be sampled from
  /// several threads at once, each with its own `out`.
  ///
  /// Path objects: local position and rotation from the current leg (the last leg whose frame
  /// range starts at or before `frame`, else the first), world = parent ∘ local; the distance
  /// column is the leg's distance_before + its distance, the speed column its analytic speed (0
  /// while held).  Cameras: the eye is the world translation (keyed or from the path, through the
  /// parent), the world rotation is the view's world_from_camera (looking down −Z; with own_rotation the
  /// object's own world rotation, tilted), the target columns the COI.  Objects looked at are read back from their columns like parents.
  /// Quaternions are canonical (w ≥ 0) for path objects and cameras; see SceneCursor.
  void sample(double frame, std::span<double> out) const noexcept;

  /// sample(frame, out), then the rotation columns of path objects, cameras and their descendants
  /// made sign-continuous with the cursor's previous frame (and remembered).  `cursor` must have
  /// been made for this scene (asserted).  Never allocates.
  void sample(double frame, std::span<double> out, SceneCursor& cursor) const noexcept;

  /// sample(frame, out, cursor) with the objects' columns in `space`.  Space::world is exactly
  /// sample(frame, out, cursor).  Space::local: each object's translation, rotation and scale
  /// columns hold its transform relative to its parent, `parent_world_T_object` such that
  /// compose(world_T_parent, local) is the world transform sample() writes (a root's local is its
  /// world transform).  For a keyed object that is its keyed channels; for a path object the
  /// leg's position and rotation (the path lives in the parent's space) and its scale; for a
  /// camera its keyed or path position, its scale and its view rotation expressed in the parent's
  /// frame, conjugate(world_T_parent.rotation) · world rotation (canonical, then made sign-continuous
  /// by the cursor like every rotation of a camera).  A camera's
  /// target columns are the centre of interest in the parent's space (the inverse of the parent's
  /// world TRS; a zero scale component maps to 0); distance, speed and every track column are the
  /// same in both spaces.  The world transforms that children, looked-at objects and camera targets
  /// read are kept in the cursor (allocated once when it was made), so this never allocates and
  /// one Scene may still be sampled from several threads, each with its own cursor and `out`.
  void sample(double frame, std::span<double> out, SceneCursor& cursor, Space space) const noexcept;

 private:
  friend class SceneCursor;
  // Tracks into `out`; objects' world transforms into `world` (indexed like `out`, may be
  // out.data()); when `world` is not out.data(), every object's local transform and extra columns
  // into `out`.
  void sample_into(double frame, std::span<double> out, double* world) const noexcept;
  struct ObjectExtra {
    std::size_t column = 0;                      // first output column of the object
    std::vector<ScenePathLeg> legs;              // empty: not on a path
    std::optional<CameraView<double>> camera;    // a camera's view
    std::vector<std::size_t> camera_targets;     // per CameraView::target_names() slot: the object index while
                                                 // building, then its first output column (translation.x)
    std::optional<std::size_t> coi_path;         // index into paths_
    std::optional<std::size_t> up_path;          // index into paths_
    std::optional<std::size_t> tilt_column;      // output column of the tilt track
    bool continuous = false;                     // rotation made sign-continuous by a cursor
    std::optional<BlenderObject> blender;        // version 3: a Blender object's actions and NLA
  };

  friend Expected<Scene> build_scene(const RawScene& raw);
  Scene(double fps, double range_start, double range_end) : fps_(fps), range_start_(range_start), range_end_(range_end) {}

  double fps_, range_start_, range_end_;
  std::vector<SceneTrack> tracks_;
  std::optional<TransformHierarchy<double>> objects_;  // none when the scene has no objects
  std::vector<SceneColumn> columns_;
  std::vector<ArcLength<AnyCurve>> paths_;  // the named paths (coi_path, up_path)
  std::vector<ObjectExtra> extras_;         // one per object
  std::vector<std::size_t> order_;          // evaluation order of the objects
  std::vector<SceneSkin> skins_;            // skins with joint indices
};

/// Checks everything and builds the scene: fps finite and > 0; range first ≤ last; track, path
/// and object names non-empty and unique among tracks, among paths and among objects (one ordered
/// lookup per name: O(n log n); the first repeat in file order is reported, at its name); no two
/// tracks or objects writing the same output column; every track's keys (through build_fcurve,
/// build_track, build_quat_track, build_euler_track); Euler conventions; object rest rotations
/// non-zero; parents that exist and form no cycle.  Version 2: every path leg (build_path_motion,
/// its errors under objects/i/path[/k]/…) and camera (build_camera_view, under objects/i/camera/…);
/// names resolved (paths for a leg's curve and a camera's coi_path/up_path, scalar tracks for
/// speed.track and tilt_track, objects for look_at and hold targets); legs in increasing,
/// non-overlapping frame ranges (a track speed only on a single leg); no translation or rotation
/// with a path, no rotation on a camera (unless it views along it, own_rotation); ahead/coi_path/up_path only on a camera on a path; no cycle through parents, look-ats and
/// camera targets (the error names the member that closes it); skins' joints
/// naming existing objects, each at most once per skin, and at least one joint ({"skins", i, "joints", j}).  The Error's structured `location` names the offending
/// member of `raw` ({"tracks", 2, "keys", 3, "frame"}), which, since RawScene mirrors the file, is
/// the JSON pointer of the value in a scene file.
[[nodiscard]] Expected<Scene> build_scene(const RawScene& raw);

}  // namespace inbetween
