#pragma once
/// The view of a scene camera (texts 004 §3.4.2 "Camera path following", Eqs. 3.33–3.34): a
/// vertical field of view and one of the texts' ways to aim the camera, authored as plain data
/// (RawCameraView), checked once (build_camera_view) and evaluated per frame without allocating
/// (CameraView::evaluate).  See docs/scene-cameras.md.
///
/// Conventions (glTF's): the world is right-handed; a camera looks down its own −Z axis with +Y up
/// and +X to the right.  The pose is the one of paths/camera.hpp's look_at(): world_from_camera has
/// columns (right, up, −forward).
///
/// Centre of interest (COI), one of:
///   - look_at a fixed point (world) or an object (its world position, supplied by the scene);
///   - ahead: COI = P(s + Δs) on the camera's own path, optionally averaged over n points spread
///     over a distance; past the path's end P continues along the end tangent, so the view blends
///     into the end tangent as s approaches L;
///   - coi_path: COI = C(f·L_C) on a second path with f = s / L_P, the camera's normalised distance;
///   - hold: the COI holds on one target until a frame, then moves to the next target by linear
///     interpolation in space and the sine ease-in/ease-out (Eq. 3.18) in time, holds there, …;
///   - own_rotation: no COI is chosen: the camera object's own world rotation (keyed, or from its
///     path, through its parent) is the view, looking down its −Z with +Y up (a glTF camera node);
///     the COI is the point a distance ahead on that axis.
/// Up direction: a fixed general up vector (default +Y, Eq. 3.33) or an up path, U(f·L_U) − eye
/// (Eq. 3.34); then a tilt rolls the camera about its view direction: a constant, plus optionally
/// a keyed value from a scalar track (the texts' "user-specified value (or interpolated set of
/// values)").
///
/// Never NaN (fallbacks, all documented in docs/scene-cameras.md):
///   - COI at the eye (zero view vector): forward = the camera path's unit tangent at s when the
///     camera is on a path, else world −Z (the camera's rest direction);
///   - up parallel to the view (sine of the angle ≤ √ε) or zero: with a fixed up, world +Z; with an
///     up path, the fixed `up` of the RawCameraView; if that is parallel too, any_perpendicular;
///   - s outside [0, L] or NaN is clamped (NaN reads as 0); a path of length zero gives f = 0;
///   - a NaN frame reads as the first hold segment's target; a non-finite keyed tilt reads as 0.

#include <concepts>
#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/paths/camera.hpp"
#include "inbetween/paths/path_frame.hpp"

namespace inbetween {

// ------------------------------------------------------------------------------------------ paths

/// A non-owning, type-erased view of an arc-length parameterised 3-D path (an ArcLength<C> of any
/// curve family over Vec3<T>), so a built CameraView needs no curve type.  The ArcLength must
/// outlive the view.  Copying is two pointers and a length; queries do not allocate.  An empty
/// view (default-constructed) has length 0, point (0, 0, 0) and tangent +X.
template <Real T>
class PathView {
 public:
  /// An empty view: no path.
  PathView() = default;

  /// A view of `arc`.
  template <Curve C>
    requires std::same_as<typename C::point_type, Vec3<T>>
  static PathView of(const ArcLength<C>& arc) noexcept {
    PathView v;
    v.arc_ = &arc;
    v.length_ = arc.length();
    v.point_ = [](const void* a, T s) noexcept { return static_cast<const ArcLength<C>*>(a)->point_at_length(s); };
    v.tangent_ = [](const void* a, T s) noexcept {
      const auto& arc_ref = *static_cast<const ArcLength<C>*>(a);
      return unit_tangent(arc_ref.curve(), arc_ref.u_at(s));
    };
    return v;
  }

  /// True when no path is viewed.
  [[nodiscard]] bool empty() const noexcept { return arc_ == nullptr; }
  /// The path length L ≥ 0 (0 when empty).
  [[nodiscard]] T length() const noexcept { return length_; }
  /// P(s), s clamped into [0, L] (NaN reads as 0), as ArcLength::point_at_length.
  [[nodiscard]] Vec3<T> point_at_length(T s) const noexcept { return empty() ? Vec3<T>{} : point_(arc_, s); }
  /// The unit tangent at arc length s (clamped), with unit_tangent()'s fallbacks (never NaN).
  [[nodiscard]] Vec3<T> unit_tangent_at_length(T s) const noexcept {
    return empty() ? Vec3<T>{T(1), T(0), T(0)} : tangent_(arc_, s);
  }

 private:
  const void* arc_ = nullptr;
  T length_ = T(0);
  Vec3<T> (*point_)(const void*, T) noexcept = nullptr;
  Vec3<T> (*tangent_)(const void*, T) noexcept = nullptr;
};

/// A view of `arc` (shorthand for PathView<T>::of(arc)); `arc` must outlive the view.
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
PathView<typename C::scalar_type> path_view(const ArcLength<C>& arc) noexcept {
  return PathView<typename C::scalar_type>::of(arc);
}

// -------------------------------------------------------------------------------------- raw data

/// A target of the view: a fixed point in world coordinates, or the name of a scene object whose
/// world position the scene supplies per frame (JSON: `[x, y, z]` or `"name"`).
template <Real T>
using RawTarget = std::variant<Vec3<T>, std::string>;

/// COI mode `look_at`: a fixed point or an object (Eq. 3.33's COI).
template <Real T>
struct RawLookAt {
  RawTarget<T> target = Vec3<T>{};  ///< the point or object looked at
};

/// COI mode `ahead`: points ahead on the camera's own path.  The COI is the mean of P(s + d_k),
/// d_k = distance + spread·k/(n − 1), k = 0 … n − 1 (n = 1: d_0 = distance).  Past L, P continues
/// into the next leg's path when the camera has one (CameraInputs::next_camera_path, moved so that
/// it starts at P(L): the COI and the view direction do not jump when the camera changes leg),
/// else, and past that leg's end, along the end tangent.  (paths/camera.hpp's look_ahead_camera with ahead A and n points is
/// distance = A/n, spread = A(n − 1)/n.)
template <Real T>
struct RawLookAhead {
  T distance = T(0);  ///< Δs ≥ 0, path length units: the first point looked at is P(s + Δs)
  int count = 1;      ///< n ≥ 1: how many points are averaged
  T spread = T(0);    ///< ≥ 0, length units: the n points are spaced evenly over [Δs, Δs + spread]
};

/// COI mode `coi_path`: the COI is C(f·L_C) on a second path, f = s / L_P (texts: P(s) and C(s)).
/// For a COI with its own timing, put an object on the path and `look_at` it instead.
struct RawCoiPath {
  std::string path;  ///< name of the path, resolved by the scene (CameraView::coi_path_name())
};

/// One hold-then-move segment: the COI holds on `target` until frame `hold_until`, then moves to
/// the next segment's target over `move_frames` frames (sine ease-in/ease-out, linear in space).
template <Real T>
struct RawHoldSegment {
  RawTarget<T> target = Vec3<T>{};  ///< the point or object held on
  T hold_until = T(0);              ///< last frame of the hold (finite)
  T move_frames = T(0);             ///< ≥ 0 frames of the move to the next target; 0 cuts; 0 on the last segment
};

/// COI mode `hold`: the texts' "fix it at one location for an interval of time and then move it
/// to another location … and fix it there for a number of frames, and so on".  Before the first
/// hold_until the COI is the first target; after the last move it is the last target.
template <Real T>
struct RawHoldThenMove {
  std::vector<RawHoldSegment<T>> segments;  ///< ≥ 1, hold_until[i] + move_frames[i] ≤ hold_until[i + 1]
};

/// Mode `own_rotation`: the view is the camera object's own world rotation (its keyed rotation or
/// path orientation composed with its parent's), looking down its local −Z with +Y up, as a glTF
/// camera node does.  `up` and `up_path` have no part in it (the builder refuses an up_path or a
/// non-default up); the tilt still rolls the view.  The COI (bake's target columns) is the point
/// `distance` ahead on the view axis.
template <Real T>
struct RawOwnRotation {
  T distance = T(1);  ///< > 0, finite, length units: how far ahead of the eye the reported COI lies
};

/// The centre-of-interest mode: one of the five alternatives (JSON members `look_at`, `ahead`,
/// `coi_path`, `hold`, `own_rotation`).
template <Real T>
using RawCoi = std::variant<RawLookAt<T>, RawLookAhead<T>, RawCoiPath, RawHoldThenMove<T>, RawOwnRotation<T>>;

/// A camera's view as authored: plain data, checked by build_camera_view().  Member names are the
/// JSON members; errors name them as structured location steps relative to this object
/// ({"ahead", "count"}, {"hold", 2, "move_frames"}).
template <Real T>
struct RawCameraView {
  T yfov_deg = T(50);             ///< vertical field of view in degrees, 0 < yfov < 180 (default: three.js's 50)
  RawCoi<T> coi = RawLookAt<T>{}; ///< how the centre of interest is found
  Vec3<T> up{T(0), T(1), T(0)};   ///< general up direction (Eq. 3.33), finite and non-zero; with up_path, its fallback
  std::string up_path;            ///< when non-empty: the up path U of Eq. 3.34, resolved by the scene
  T tilt_deg = T(0);              ///< roll about the view direction in degrees (finite); + turns up towards right
  std::string tilt_track;         ///< when non-empty: a scalar track of the scene whose value (degrees) adds to tilt_deg per frame
};

using RawCameraViewf = RawCameraView<float>;   ///< single-precision raw camera view
using RawCameraViewd = RawCameraView<double>;  ///< double-precision raw camera view

// ------------------------------------------------------------------------------------ evaluation

/// What the scene supplies per frame to CameraView::evaluate.  Nothing is owned; the spans and
/// path views must stay valid during the call.
/// The world positions of the objects a view names (CameraView::target_names()), by slot: either a
/// span of points, or the translation columns of a scene's output row read in place (so a scene
/// passes any number of targets without copying or allocating).  The viewed memory must outlive
/// the view.  Caller bugs (a slot ≥ size()) are asserted.
template <Real T>
class TargetPositions {
 public:
  /// No targets.
  TargetPositions() = default;
  /// The points, slot k = points[k].  Implicit, so that `{.targets = points}` reads as before.
  template <class R>
    requires std::convertible_to<R&&, std::span<const Vec3<T>>>
  TargetPositions(R&& points) noexcept  // NOLINT(google-explicit-constructor)
      : points_(std::span<const Vec3<T>>(std::forward<R>(points))), size_(points_.size()) {}
  /// Slot k = (row[columns[k]], row[columns[k] + 1], row[columns[k] + 2]): an object's world
  /// translation in a scene's output row (Scene::sample).
  static TargetPositions from_columns(const T* row, std::span<const std::size_t> columns) noexcept {
    TargetPositions t;
    t.row_ = row;
    t.columns_ = columns;
    t.size_ = columns.size();
    return t;
  }
  /// The number of slots.
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  /// The position in slot k < size().
  [[nodiscard]] Vec3<T> operator[](std::size_t k) const noexcept {
    INBETWEEN_ASSERT(k < size_);
    if (row_ == nullptr) return points_[k];
    const T* p = row_ + columns_[k];
    return {p[0], p[1], p[2]};
  }

 private:
  std::span<const Vec3<T>> points_{};
  const T* row_ = nullptr;
  std::span<const std::size_t> columns_{};
  std::size_t size_ = 0;
};

template <Real T>
struct CameraInputs {
  T frame = T(0);                      ///< scene frame (used by `hold`)
  Vec3<T> eye{};                       ///< the camera's world position
  PathView<T> camera_path{};           ///< the camera's own path, in path space; empty when not on a path
  /// The path of the camera's next leg (same path space), or empty: look-ahead points past the end
  /// of camera_path continue along it, attached at camera_path's end (see RawLookAhead).
  PathView<T> next_camera_path{};
  T s = T(0);                          ///< arc length travelled on camera_path (clamped into [0, L])
  PathView<T> coi_path{};              ///< the path named by coi_path_name(), in path space, or empty
  PathView<T> up_path{};               ///< the path named by up_path_name(), in path space, or empty
  Transform<T> world_from_path{};      ///< maps path space to world (the camera parent's world transform)
  TargetPositions<T> targets{};        ///< world positions of target_names(), in that order
  T tilt_track_deg = T(0);             ///< value of the track tilt_track_name() at this frame (degrees), else 0
  /// The camera object's own world rotation (parent ∘ local; keyed or from its path), read by mode
  /// own_rotation only (normalised there; a zero or non-finite quaternion reads as identity).
  Quat<T> world_rotation{};
};

/// The result of a view evaluation: the camera pose and the centre of interest it aims at.
template <Real T>
struct CameraViewSample {
  CameraPose<T> pose{};  ///< eye and world axes; pose.rotation() is world_from_camera
  Vec3<T> target{};      ///< the COI in world coordinates (bake: `<camera>.target.x/y/z`)
};

/// The COI mode of a built view.
enum class CoiMode {
  point,         ///< look_at a fixed point
  object,        ///< look_at an object
  ahead,         ///< ahead on the camera's own path
  path,          ///< on a second path
  hold_then_move,  ///< hold, then move, between targets
  own_rotation,  ///< the camera object's own rotation is the view (a glTF camera node)
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Point [[deprecated("use CoiMode::point")]] = point,
  Object [[deprecated("use CoiMode::object")]] = object,
  Ahead [[deprecated("use CoiMode::ahead")]] = ahead,
  Path [[deprecated("use CoiMode::path")]] = path,
  HoldThenMove [[deprecated("use CoiMode::hold_then_move")]] = hold_then_move,
  OwnRotation [[deprecated("use CoiMode::own_rotation")]] = own_rotation,
};

template <Real T>
class CameraView;

/// Checks a raw view and builds it.  Errors (location = member steps relative to the view):
/// yfov_deg not in (0, 180) or not finite; tilt_deg or up not finite; up zero; ahead with
/// distance or spread negative or not finite, or count < 1; an empty object or path name; a
/// non-finite point; hold with no segment, a non-finite frame, move_frames < 0, a last segment
/// with move_frames ≠ 0, or hold_until[i] + move_frames[i] > hold_until[i + 1]; own_rotation with
/// a distance not finite and > 0, with an up_path, or with an up other than the default +Y.
template <Real T>
Expected<CameraView<T>> build_camera_view(const RawCameraView<T>& raw);

/// A checked camera view.  Built only by build_camera_view(); evaluating it is total and noexcept.
/// The scene resolves target_names(), coi_path_name() and up_path_name() once when it builds, and
/// passes the positions and paths in CameraInputs each frame.  Instantiated for float and double.
template <Real T>
class CameraView {
 public:
  /// The vertical field of view in radians, in (0, π).
  [[nodiscard]] T yfov_rad() const noexcept { return yfov_rad_; }
  /// The roll about the view direction in radians.
  [[nodiscard]] T tilt_rad() const noexcept { return tilt_rad_; }
  /// The COI mode.
  [[nodiscard]] CoiMode coi_mode() const noexcept { return mode_; }
  /// Names of the objects whose world positions evaluate() reads from CameraInputs::targets
  /// (each once, in order of first use); empty when no object is looked at.
  [[nodiscard]] std::span<const std::string> target_names() const noexcept { return target_names_; }
  /// True when evaluate() needs CameraInputs::camera_path and s (ahead, coi_path, up_path): the
  /// scene reports an error for a camera that is not on a path.
  [[nodiscard]] bool needs_camera_path() const noexcept {
    return mode_ == CoiMode::ahead || mode_ == CoiMode::path || !up_path_name_.empty();
  }
  /// Name of the COI path (mode Path), else empty.
  [[nodiscard]] const std::string& coi_path_name() const noexcept { return coi_path_name_; }
  /// Name of the up path (Eq. 3.34), else empty.
  [[nodiscard]] const std::string& up_path_name() const noexcept { return up_path_name_; }
  /// Name of the scalar track that adds a keyed tilt (degrees), else empty.
  [[nodiscard]] const std::string& tilt_track_name() const noexcept { return tilt_track_name_; }

  /// The pose and COI for one frame.  Preconditions (asserted; caller bugs): targets.size() ==
  /// target_names().size(); camera_path, coi_path and up_path non-empty where the view needs them.
  /// Never allocates; never NaN for finite inputs (fallbacks in the file comment).
  [[nodiscard]] CameraViewSample<T> evaluate(const CameraInputs<T>& in) const noexcept;

  /// The COI alone (world), as evaluate() computes it.
  [[nodiscard]] Vec3<T> centre_of_interest(const CameraInputs<T>& in) const noexcept;

 private:
  struct Target {
    Vec3<T> point{};         // fixed point (slot < 0)
    std::ptrdiff_t slot = -1;  // index into CameraInputs::targets, or −1
  };
  struct Segment {
    Target target{};
    T hold_until = T(0);
    T move_frames = T(0);
  };

  CameraView() = default;
  Vec3<T> position(const Target& t, const TargetPositions<T>& targets) const noexcept;
  Quat<T> own_rotation(const CameraInputs<T>& in) const noexcept;  // OwnRotation: world rotation with tilt
  Vec3<T> own_forward(const CameraInputs<T>& in) const noexcept;    // OwnRotation: its −Z in world
  friend Expected<CameraView<T>> build_camera_view<T>(const RawCameraView<T>& raw);

  T yfov_rad_ = T(0);
  T tilt_rad_ = T(0);
  CoiMode mode_ = CoiMode::point;
  Target look_{};                    // Point, Object
  T ahead_distance_ = T(0);          // Ahead
  int ahead_count_ = 1;
  T ahead_spread_ = T(0);
  T own_distance_ = T(1);            // OwnRotation
  std::vector<Segment> segments_;    // HoldThenMove
  Vec3<T> up_{T(0), T(1), T(0)};
  std::string coi_path_name_;
  std::string up_path_name_;
  std::string tilt_track_name_;
  std::vector<std::string> target_names_;
};

using CameraViewf = CameraView<float>;   ///< single-precision camera view
using CameraViewd = CameraView<double>;  ///< double-precision camera view

}  // namespace inbetween
