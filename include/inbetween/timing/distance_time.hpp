#pragma once
/// General distance-time functions (texts 004 §3.2.4): a piecewise cubic s(t) built from
/// ⟨t_i, s_i⟩ keys (zero-order constraints), from ⟨t_i, s_i, v_i⟩ keys (first-order constraints),
/// or from a user velocity-time curve (both ways the texts describe); a check that reports where
/// the object would back up (negative velocity), and a monotone repair (Fritsch–Carlson).

#include <string_view>
#include <array>
#include <optional>
#include <span>
#include <vector>

#include "inbetween/curves/curve.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/timing/ease.hpp"
#include "inbetween/math/enum_names.hpp"

namespace inbetween {

/// A zero-order constraint: distance s at time t.
template <Real T>
struct TimeDistanceKey {
  T t{};  ///< time
  T s{};  ///< distance along the curve at t
};

/// A first-order constraint: distance s and velocity v = ds/dt at time t.
template <Real T>
struct TimeDistanceVelocityKey {
  T t{};  ///< time
  T s{};  ///< distance at t
  T v{};  ///< velocity ds/dt at t
};

/// A key of a user velocity-time curve: velocity v at time t (linear in between).
template <Real T>
struct TimeVelocityKey {
  T t{};  ///< time
  T v{};  ///< velocity at t
};

/// How ⟨t_i, s_i⟩ keys are joined.
enum class PositionInterpolation {
  linear,         ///< straight lines: continuous position, velocity jumps at keys (Figure 3.21 top)
  catmull_rom,    ///< C¹ cubic with key velocity (s_{i+1} − s_{i−1})/(t_{i+1} − t_{i−1}); may overshoot
  monotone_cubic,  ///< C¹ cubic with Fritsch–Carlson velocities: never backs up if the s_i do not
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Linear [[deprecated("use PositionInterpolation::linear")]] = linear,
  CatmullRom [[deprecated("use PositionInterpolation::catmull_rom")]] = catmull_rom,
  MonotoneCubic [[deprecated("use PositionInterpolation::monotone_cubic")]] = monotone_cubic,
};

/// File names of the PositionInterpolation enumerators, in declaration order.
inline constexpr std::array<std::string_view, 3> position_interpolation_names = {"linear", "catmull_rom", "monotone_cubic"};
/// The name table of PositionInterpolation (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<PositionInterpolation>() noexcept {
  return position_interpolation_names;
}
/// The file name of v, from the table above (enum_from_string<PositionInterpolation> parses it back).
[[nodiscard]] inline std::string_view to_string(PositionInterpolation v) noexcept { return enum_name(v); }

/// How a user velocity-time curve is made to cover the total distance (texts 004 §3.2.4).
enum class VelocityFit {
  float_to_keep_average,  ///< shift the whole curve up or down by a constant (keys' velocities change)
  /// Keep the keys' velocities; add a bump b_i·6τ(1 − τ) inside interval i.  The bumps first use
  /// the room each interval has between its two keys' speeds (|6b_i| ≤ |Δv_i|, shared in
  /// proportion), so the speed never leaves [min, max] of an interval's keys and two equal keys
  /// give a flat speed; only distance beyond all that room is spread evenly over time (the texts'
  /// c·6τ(1 − τ), e.g. Eq. 3.20 from two keys at rest), and there the speed leaves the keys' range.
  fix_keys_adjust_interior,
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  FloatToKeepAverage [[deprecated("use VelocityFit::float_to_keep_average")]] = float_to_keep_average,
  FixKeysAdjustInterior [[deprecated("use VelocityFit::fix_keys_adjust_interior")]] = fix_keys_adjust_interior,
};

/// File names of the VelocityFit enumerators, in declaration order.
inline constexpr std::array<std::string_view, 2> velocity_fit_names = {"float_to_keep_average", "fix_keys_adjust_interior"};
/// The name table of VelocityFit (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<VelocityFit>() noexcept {
  return velocity_fit_names;
}
/// The file name of v, from the table above (enum_from_string<VelocityFit> parses it back).
[[nodiscard]] inline std::string_view to_string(VelocityFit v) noexcept { return enum_name(v); }

/// Where a distance-time function runs backwards: the first interval of negative velocity.
template <Real T>
struct BackingUp {
  int segment = 0;         ///< index of the key interval [t_i, t_{i+1}] where it happens
  T t_begin{}, t_end{};    ///< the time span of negative velocity inside that interval
  T t_min_velocity{};      ///< the time of the most negative velocity in that span
  T min_velocity{};        ///< that velocity (< 0)
};

/// A piecewise cubic distance-time function s(t) over [t_0, t_n].  Evaluation clamps t; at a key
/// the velocity and acceleration are those of the interval that starts there (right limit), except
/// at the last key.
template <Real T>
class DistanceTimeCurve {
 public:
  /// From ⟨t_i, s_i⟩ (≥ 2 keys, t strictly increasing, all finite).  Errors name the key.
  static Expected<DistanceTimeCurve> from_positions(std::span<const TimeDistanceKey<T>> keys,
                                                    PositionInterpolation how = PositionInterpolation::linear);
  /// From ⟨t_i, s_i, v_i⟩: the C¹ cubic Hermite through every key with the given velocities.
  static Expected<DistanceTimeCurve> from_constraints(std::span<const TimeDistanceVelocityKey<T>> keys);
  /// From a piecewise-linear velocity-time curve: s(t_0) = 0 and s(t_n) = total_distance, the
  /// velocity adjusted by `fit` so that the area under it equals total_distance.  With
  /// FloatToKeepAverage the adjustment is spread evenly over time; with FixKeysAdjustInterior it
  /// goes first where keys differ (see VelocityFit), so the speed between two keys stays within
  /// their speeds whenever |total − area of the key lines| ≤ Σ h_i|v_{i+1} − v_i|/6.
  /// A single interval with v = 0 at both ends and FixKeysAdjustInterior gives −2t³ + 3t² (Eq. 3.20).
  static Expected<DistanceTimeCurve> from_velocity_curve(std::span<const TimeVelocityKey<T>> keys, VelocityFit fit,
                                                         T total_distance = T(1));

  /// s, ds/dt, d²s/dt² at t (clamped into the domain).
  EaseSample<T> sample(T t) const noexcept;
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }
  /// [t_0, t_n].
  Interval<T> domain() const noexcept { return {t_.front(), t_.back()}; }
  /// The key times t_0 … t_n.
  std::span<const T> key_times() const noexcept { return t_; }
  /// s at the key times.
  std::span<const T> key_distances() const noexcept { return s_; }
  /// Interval i as a cubic in τ = (t − t_i)/(t_{i+1} − t_i) ∈ [0, 1].
  std::span<const PowerCubic<T>> segments() const noexcept { return seg_; }

  /// The first interval where the velocity drops below zero (beyond rounding), or nothing when
  /// s(t) never decreases.
  std::optional<BackingUp<T>> find_backing_up() const noexcept;
  /// Success when s(t) never decreases; else ErrorCode::NotMonotone with the time span and the
  /// most negative velocity in the message and "segment i" as the place.
  Expected<void> check_monotone() const;
  /// A monotone C¹ cubic through the same keys (t_i, s_i): key velocities are the curve's own
  /// (averaged across a key where they jump), made non-negative and limited by Fritsch–Carlson
  /// (α² + β² ≤ 9, with α, β the end velocities over the interval's mean velocity).  Error
  /// NotMonotone naming the key when the key distances themselves decrease (no monotone curve
  /// passes through them).
  Expected<DistanceTimeCurve> monotone_repair() const;

 private:
  DistanceTimeCurve() = default;
  static Expected<DistanceTimeCurve> hermite(std::vector<T> t, std::vector<T> s, const std::vector<T>& v);
  std::vector<T> t_, s_;
  std::vector<PowerCubic<T>> seg_;
};

extern template class DistanceTimeCurve<float>;
extern template class DistanceTimeCurve<double>;

}  // namespace inbetween
