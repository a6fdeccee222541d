#pragma once
/// An object moving along a path at a controlled speed with an orientation: the texts' pipeline
/// p = P(U(S(t))) (000 §2.2–2.4, 004 §3.2.2–3.2.4) plus the frame along the path (004 §3.4.1–3.4.2),
/// as one built object.  RawPathMotion (plain data, member names as in the scene file) →
/// build_path_motion() → PathMotion, whose sample(frame) is total, noexcept and allocation-free.
///
/// Composition, nothing re-derived: the path is an AnyCurve measured by the default error-bounded
/// ArcLength; the distance s(frame) comes from an ease (timing/ease.hpp, cubic_bezier_timing.hpp,
/// penner.hpp) mapped onto a frame span and a distance range, from distance–time keys or a
/// velocity–time curve (timing/distance_time.hpp), or from a scalar F-curve (tracks/fcurve.hpp);
/// the position is P(U(s)); the orientation is a rotation-minimising frame, a Frenet frame, an
/// up-vector frame or a look-at frame (paths/*.hpp), optionally banked (paths/banking.hpp), times a
/// local rotation.  Conventions (glTF): the object's front is +Z and its up +Y; docs/scene-paths.md
/// has the table.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/curves/any_curve.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/paths/frenet_frames.hpp"
#include "inbetween/paths/rotation_minimizing_frames.hpp"
#include "inbetween/timing/cubic_bezier_timing.hpp"
#include "inbetween/timing/distance_time.hpp"
#include "inbetween/timing/ease.hpp"
#include "inbetween/timing/penner.hpp"
#include "inbetween/timing/piecewise_distance.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/math/enum_names.hpp"

namespace inbetween {

// ------------------------------------------------------------------------------------ raw data

/// The normalised ease families (scene file: speed.ease.kind).
enum class EaseKind : std::uint8_t {
  linear,                 ///< s = t
  sine,                   ///< Eq. 3.18: (1 − cos πt)/2
  sine_pieces,            ///< Eq. 3.19 (corrected): sine in on [0, k1], constant, sine out on [k2, 1]
  cubic,                  ///< Eq. 3.20: −2t³ + 3t²
  constant_acceleration,  ///< Eqs. 3.21–3.22 (corrected): accelerate on [0, t1], cruise at v0, decelerate on [t2, 1]
  cubic_bezier,           ///< CSS cubic-bezier(x1, y1, x2, y2)
  penner,                 ///< a Penner easing (curve × direction), as Blender evaluates it
};

/// File names of the EaseKind enumerators, in declaration order.
inline constexpr std::array<std::string_view, 7> ease_kind_names = {"linear", "sine", "sine_pieces", "cubic", "constant_acceleration", "cubic_bezier", "penner"};
/// The name table of EaseKind (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<EaseKind>() noexcept {
  return ease_kind_names;
}
/// The file name of v, from the table above (enum_from_string<EaseKind> parses it back).
[[nodiscard]] inline std::string_view to_string(EaseKind v) noexcept { return enum_name(v); }

/// A normalised ease S(t): [0, 1] → [0, 1] (scene file: speed.ease).  Only the members of `kind`
/// are read.
struct RawEase {
  EaseKind kind = EaseKind::linear;  ///< the family
  /// sine_pieces: end of the acceleration phase, 0 ≤ k1 ≤ k2 (normalised time).
  std::optional<double> k1;
  /// sine_pieces: start of the deceleration phase, k2 ≤ 1.
  std::optional<double> k2;
  /// constant_acceleration: end of the acceleration phase (normalised time).  Give exactly two of
  /// {t1 or accel_frames}, {t2 or decel_frames}, v0, acceleration, deceleration (the rest follow
  /// from Eq. 3.21 and v0 = a·t1 = d·(1 − t2); timing/constant_acceleration.hpp), or — with
  /// speed.to left out — three of acceleration, deceleration, {t1 or accel_frames}, {t2 or
  /// decel_frames}: the fourth follows from the equal areas of Figure 3.16 and the distance
  /// covered, hence `to`, from Eq. 3.21.
  std::optional<double> t1;
  /// constant_acceleration: start of the deceleration phase (normalised time).
  std::optional<double> t2;
  /// constant_acceleration: the cruising speed in normalised units (distance range per frame span);
  /// v0 = 2/(t2 − t1 + 1), so 1 ≤ v0 ≤ 2.
  std::optional<double> v0;
  /// constant_acceleration: the acceleration time in frames (t1 = accel_frames / span).
  std::optional<double> accel_frames;
  /// constant_acceleration: the deceleration time in frames (t2 = 1 − decel_frames / span).
  std::optional<double> decel_frames;
  /// constant_acceleration: the acceleration on [start, t1] in length units per second² (fraction of
  /// the length per second² with speed.fraction), > 0.
  std::optional<double> acceleration;
  /// constant_acceleration: the deceleration on [t2, end] (its magnitude), same units, > 0.
  std::optional<double> deceleration;
  double x1 = 0.25;  ///< cubic_bezier: first control point x, in [0, 1] (default: CSS "ease")
  double y1 = 0.1;   ///< cubic_bezier: first control point y
  double x2 = 0.25;  ///< cubic_bezier: second control point x, in [0, 1]
  double y2 = 1.0;   ///< cubic_bezier: second control point y
  EasingCurve curve = EasingCurve::sine;              ///< penner: the curve
  EasingDirection direction = EasingDirection::in_out;  ///< penner: which end(s) it eases
  /// penner: shape parameters, in units of the normalised ease (elastic amplitude 1 and period 0.3
  /// of the span give Penner's original curve).
  PennerParams<double> params{.back = 1.70158, .amplitude = 1.0, .period = 0.3};
};

/// How distance along the path is given (scene file: speed.kind).
enum class SpeedKind : std::uint8_t {
  ease,           ///< an ease over [start_frame, end_frame] mapped onto the distances [from, to]
  distance_keys,  ///< ⟨frame, distance⟩ or ⟨frame, distance, speed⟩ keys
  velocity_keys,  ///< a piecewise-linear velocity–time curve covering [from, to]
  track,          ///< a scalar F-curve giving the distance at every frame
  constraints,    ///< ⟨frame, distance, speed?, acceleration?⟩ tuples (§3.2.4), C² where accelerations are given
  acceleration_keys,  ///< an acceleration–time curve integrated twice from a start speed and distance
};

/// File names of the SpeedKind enumerators, in declaration order.
inline constexpr std::array<std::string_view, 6> speed_kind_names = {"ease", "distance_keys", "velocity_keys", "track", "constraints", "acceleration_keys"};
/// The name table of SpeedKind (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<SpeedKind>() noexcept {
  return speed_kind_names;
}
/// The file name of v, from the table above (enum_from_string<SpeedKind> parses it back).
[[nodiscard]] inline std::string_view to_string(SpeedKind v) noexcept { return enum_name(v); }

/// A distance–time key (scene file: speed.keys[i]).
struct RawDistanceKey {
  double frame = 0;     ///< animation frame
  double distance = 0;  ///< arc length travelled at `frame` (a fraction of the length with speed.fraction)
  /// Speed at `frame` in length units per second (fraction of the length per second with
  /// speed.fraction).  distance_keys: give it on every key (first-order constraints, C¹ Hermite)
  /// or on none; constraints: on any key (estimated from the distances where absent).
  std::optional<double> speed;
  /// constraints only: acceleration at `frame` in length units per second² (fraction of the length
  /// with speed.fraction); the distance is C² there.
  std::optional<double> acceleration;
};

/// A key of an acceleration–time curve (scene file: speed.accelerations[i]).
struct RawAccelerationKey {
  double frame = 0;         ///< animation frame
  double acceleration = 0;  ///< length units per second² (fraction of the length with speed.fraction)
};

/// A key of a velocity–time curve (scene file: speed.velocities[i]).
struct RawVelocityKey {
  double frame = 0;  ///< animation frame
  double speed = 0;  ///< length units per second (fraction of the length per second with speed.fraction)
};

/// How the distance travelled grows with frames (scene file: speed).  Only the members of `kind`
/// are read (fraction and repair apply to all).
struct RawSpeed {
  SpeedKind kind = SpeedKind::ease;  ///< the form
  double start_frame = 0;            ///< ease: frame at which the motion starts (t = 0)
  double end_frame = 1;              ///< ease: frame at which it ends (t = 1); > start_frame
  /// ease and velocity_keys: distance at the start; default 0.
  std::optional<double> from;
  /// ease and velocity_keys: distance at the end; default the whole length (1 with fraction).
  std::optional<double> to;
  /// Distances (from, to, keys, velocities, track values) are fractions of the path's length.
  bool fraction = false;
  RawEase ease;                       ///< ease: the normalised ease
  std::vector<RawDistanceKey> keys;   ///< distance_keys: ≥ 2 keys, frames strictly increasing
  /// distance_keys without speeds: how the keys are joined (MonotoneCubic never backs up when the
  /// key distances do not decrease).
  PositionInterpolation interpolation = PositionInterpolation::monotone_cubic;
  std::vector<RawVelocityKey> velocities;  ///< velocity_keys: ≥ 2 keys, frames strictly increasing
  /// velocity_keys: how the curve is adjusted so that it covers exactly [from, to].
  VelocityFit fit = VelocityFit::fix_keys_adjust_interior;
  std::optional<FCurve> track;  ///< track: the distance as a scalar F-curve (the scene resolves names)
  /// acceleration_keys: ≥ 2 keys, frames strictly increasing.  The start distance is `from`
  /// (default 0); with `to` every acceleration is scaled by one factor so the motion ends there.
  std::vector<RawAccelerationKey> accelerations;
  /// acceleration_keys: constant on [frame_i, frame_{i+1}) (Figure 3.16) or linear between keys.
  AccelerationShape shape = AccelerationShape::constant;
  /// acceleration_keys: the speed at the first key, length units (or fractions) per second, ≥ 0.
  double start_speed = 0;
  /// distance_keys and velocity_keys: when the distance would run backwards, replace the curve by
  /// the monotone cubic through the same keys (DistanceTimeCurve::monotone_repair) instead of
  /// failing.  Never silent: without it the builder reports the frames where it happens.
  bool repair = false;
};

/// The frame field that orients the object (scene file: orientation.mode).
enum class OrientationMode : std::uint8_t {
  rotation_minimizing,  ///< double-reflection RMF, starting with up projected off the start tangent
  frenet,               ///< Frenet frame (up = the principal normal), straight pieces interpolated
  up,                   ///< front along the tangent, up = the fixed up vector made perpendicular
  look_at,              ///< front towards a point, up = the fixed up vector made perpendicular
};

/// File names of the OrientationMode enumerators, in declaration order.
inline constexpr std::array<std::string_view, 4> orientation_mode_names = {"rotation_minimizing", "frenet", "up", "look_at"};
/// The name table of OrientationMode (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<OrientationMode>() noexcept {
  return orientation_mode_names;
}
/// The file name of v, from the table above (enum_from_string<OrientationMode> parses it back).
[[nodiscard]] inline std::string_view to_string(OrientationMode v) noexcept { return enum_name(v); }

/// Banking into turns (scene file: orientation.banking; paths/banking.hpp): a roll about the front
/// axis by β = atan(gain · lateral curvature), clamped to ±max_bank_rad.
struct RawBanking {
  double gain = 1.0;                      ///< length units (v²/g for a coordinated turn); ≥ 0
  double max_bank_rad = pi_v<double> / 3;  ///< the largest roll, in [0, π/2]
  bool lean_out = false;                  ///< roll away from the turn (the gain's sign flipped)
};

/// How the object is turned along the path (scene file: orientation).
struct RawOrientation {
  OrientationMode mode = OrientationMode::rotation_minimizing;  ///< the frame field
  /// World up: `up` and `look_at` keep the object's +Y towards it, the RMF starts with it, banking
  /// measures turns in the plane perpendicular to it.  Non-zero, finite.
  Vec3d up{0, 1, 0};
  /// look_at: the fixed target point (a caller may pass another point per sample, e.g. an object's).
  Vec3d look_at{};
  std::optional<RawBanking> banking;  ///< roll into (or out of) turns; none by default
  /// rotation_minimizing on a closed path: `automatic` (default) turns the frame about the tangent
  /// by the closing angle spread linearly in arc length so that it comes back to its start frame
  /// (paths/rotation_minimizing_frames.hpp); `distribute` requires a closed path; `none` keeps the
  /// plain RMF.
  RmfClosing closing = RmfClosing::automatic;
  /// A constant rotation on top of the path frame (world_from_object = world_from_path · local).
  Quatd local_rotation{};
  /// A keyed rotation on top of the path frame; when present it replaces local_rotation.
  std::optional<QuatTrack<double>> local_track;
};

/// Everything needed to put an object on a path (scene file: an object's path, speed, orientation).
struct RawPathMotion {
  AnyCurve path;               ///< the curve (any family)
  RawSpeed speed;              ///< distance over frames
  RawOrientation orientation;  ///< orientation along the path
};

// ------------------------------------------------------------------------------------ built

/// One sample of a path motion.
struct PathSample {
  Vec3d position{};  ///< P(U(s)), on the path
  double distance = 0;  ///< s: arc length travelled from the path's start, in [0, length]
  double speed = 0;     ///< ds/dt in length units per second (analytic derivative × fps); ≥ 0
  Quatd rotation{};     ///< world_from_object: +Z the front, +Y the up (unit; canonical w ≥ 0)
  double u = 0;         ///< the curve parameter U(s)
};

/// A built path motion.  Not default-constructible: only build_path_motion() makes one.
class PathMotion {
 public:
  /// The path's arc length L ≥ 0.
  [[nodiscard]] double length() const noexcept { return arc_.length(); }
  /// Frames per second used for speed.
  [[nodiscard]] double fps() const noexcept { return fps_; }
  /// The path.
  [[nodiscard]] const AnyCurve& path() const noexcept { return arc_.curve(); }
  /// The arc-length object of the path.
  [[nodiscard]] const ArcLength<AnyCurve>& arc_length() const noexcept { return arc_; }
  /// The orientation mode.
  [[nodiscard]] OrientationMode mode() const noexcept { return mode_; }
  /// The frames over which the speed spec moves the object: [start_frame, end_frame] of an ease,
  /// the first and last key of keys, the keyed range of a track.
  [[nodiscard]] Interval<double> frame_range() const noexcept { return range_; }

  /// Distance s (length units, clamped into [0, L]), ds/dframe and d²s/dframe² at `frame`, as an
  /// EaseSample {s, velocity, acceleration}, all analytic.  Outside frame_range() an ease or keys
  /// hold their end distance with ds/dframe = d²s/dframe² = 0; inside (ends included) the
  /// derivatives are the one-sided ones of the speed form.  A track follows its own extrapolation
  /// and cycles (its derivatives FCurve::derivative and FCurve::second_derivative, at the frame
  /// rounded to single precision like its value, × the scale); where its value leaves [0, L] the
  /// distance is clamped and both derivatives are 0.  A NaN frame reads as the start of
  /// frame_range().
  [[nodiscard]] EaseSample<double> distance_at(double frame) const noexcept;

  /// The sample at `frame` (see distance_at for frames outside the range).  `look_at_point`, when
  /// given, replaces the stored look_at target (mode look_at only; a scene passes an object's
  /// position).  Never NaN for a finite frame.
  [[nodiscard]] PathSample sample(double frame, const Vec3d* look_at_point = nullptr) const noexcept;
  /// out[i] = sample(frames[i]); equal sizes (asserted); no allocation.
  void sample(std::span<const double> frames, std::span<PathSample> out) const noexcept;

  /// world_from_object at curve parameter u with the object at `position` (orientation only; the
  /// local rotation is that of `frame`).  sample() uses it; exposed for tests and cameras.
  [[nodiscard]] Quatd rotation_at(double u, const Vec3d& position, double frame,
                                  const Vec3d* look_at_point = nullptr) const noexcept;

  /// The normalised ease of an ease spec, boxed (for PathMotion's own use; see RawEase).
  struct PennerUnitEase {
    EasingCurve curve = EasingCurve::sine;                ///< the curve
    EasingDirection direction = EasingDirection::in_out;  ///< its direction
    PennerParams<double> params{};                        ///< its shape
    /// s = ease_unit, velocity = ease_unit_velocity, acceleration = penner_ease_acceleration (all of
    /// the normalised ease, duration 1), t clamped to [0, 1].
    EaseSample<double> sample(double t) const noexcept;
  };
  /// Any of the normalised eases.
  using UnitEase = std::variant<LinearEase<double>, SineEase<double>, SineAccelDecelEase<double>, CubicEase<double>,
                                ConstantAccelerationEase<double>, CubicBezierTiming<double>, PennerUnitEase>;
  /// The normalised ease of an ease speed (with the frames it spans: frame_range()), or null when
  /// the speed is given another way (keys, a track, …).  Plots read phase boundaries from it.
  [[nodiscard]] const UnitEase* unit_ease() const noexcept;


 private:
  struct EaseSpeed {
    UnitEase ease;
    double start = 0, end = 1, from = 0, to = 0;
  };
  struct KeyedSpeed {
    DistanceTimeCurve<double> curve;  // frame → distance (velocity keys: from `offset`)
    double offset = 0;
  };
  struct TrackSpeed {
    FCurve track;
    double scale = 1;  // L with fraction, else 1
  };
  struct PolynomialSpeed {
    PiecewiseDistanceCurve<double> curve;  // frame → distance (constraints, acceleration_keys)
  };
  using Speed = std::variant<EaseSpeed, KeyedSpeed, TrackSpeed, PolynomialSpeed>;

  PathMotion(ArcLength<AnyCurve> arc, Speed speed, double fps) : arc_(std::move(arc)), speed_(std::move(speed)), fps_(fps) {}
  friend Expected<PathMotion> build_path_motion(const RawPathMotion& raw, double fps);

  ArcLength<AnyCurve> arc_;
  Speed speed_;
  double fps_ = 24;
  Interval<double> range_{0, 1};
  OrientationMode mode_ = OrientationMode::rotation_minimizing;
  std::optional<RotationMinimizingFrames<AnyCurve>> rmf_;
  std::optional<FrenetFrames<AnyCurve>> frenet_;
  Vec3d up_{0, 1, 0};
  Vec3d look_at_{};
  std::optional<RawBanking> banking_;
  Quatd local_{};
  std::optional<QuatTrack<double>> local_track_;
};

/// Validates `raw` and builds the motion; `fps` (> 0, finite) converts speeds between per frame and
/// per second.  Errors carry the member path as structured location steps, relative to `raw`
/// ({"speed", "end_frame"}, {"speed", "keys", 3, "distance"}, {"orientation", "up"}, …; a scene
/// prepends the object's place); `where` stays empty:
/// - a path with a non-finite length;
/// - ease: a frame span of zero or reversed, non-finite frames, an ease parameter out of range, a
///   distance range outside [0, L] or running backwards (from > to), an ease that runs backwards
///   (Penner back, elastic and bounce, a cubic-bezier with y outside [0, 1]) naming the frames;
/// - distance_keys / velocity_keys: too few keys, frames not increasing, a key distance outside
///   [0, L] (naming the key), distances that run backwards (naming the frames) unless `repair`;
/// - constraints: no key, frames not increasing, a distance outside [0, L] or below the previous
///   key's, a negative speed, a single key with a speed or acceleration, a curve that would run
///   backwards between keys i and i + 1 ({"speed", "keys", i}; repair does not apply);
/// - acceleration_keys: fewer than 2 keys, frames not increasing, a negative start_speed, a speed
///   that turns negative ({"speed", "accelerations", i}), an end beyond the path's length, a `to`
///   the accelerations cannot reach ({"speed", "to"});
/// - track: missing, a key value outside [0, L] (naming the key) or a curve that runs backwards
///   between keys (naming the frames; repair does not apply to tracks);
/// - orientation: a zero or non-finite up vector, banking options out of range, a non-finite
///   look_at point or local rotation; closing = distribute on a path that is not closed
///   ({"orientation", "closing"}).
[[nodiscard]] Expected<PathMotion> build_path_motion(const RawPathMotion& raw, double fps);


}  // namespace inbetween
