#pragma once
/// Distance–time functions of degree up to five (texts 004 §3.2.4): the object's distance s(t)
/// built from ⟨t_i, s_i, v_i, a_i⟩ constraint tuples (speed and acceleration optional per tuple),
/// or by integrating an acceleration–time curve twice in closed form.  Both give a
/// PiecewiseDistanceCurve: one polynomial in τ = (t − t_i)/(t_{i+1} − t_i) per interval.
///
/// Constraints: on every interval the Hermite polynomial through the two tuples' distance and
/// speed, raised by one degree for each end whose acceleration is given — a cubic (no
/// acceleration), a quartic (one) or a quintic (both).  The curve is C¹ everywhere and C² at every
/// tuple with an acceleration.  A missing speed is estimated from the distances (the
/// Fritsch–Butland weighted harmonic mean of the neighbouring slopes inside, 0 at a local
/// extremum; at an end the speed that gives the end cubic zero acceleration).  A constraint set
/// whose curve would run backwards (ds/dt < 0 anywhere) is refused, naming the tuple.
///
/// Acceleration–time curves: keys ⟨t_i, a_i⟩ held constant on [t_i, t_{i+1}) or joined linearly,
/// integrated from a start speed and distance: v = v_i + ∫a, s = s_i + ∫v, exactly (the pieces are
/// quadratics or cubics).  Because integration loses the total distance (the texts' remark under
/// Figure 3.18), an optional end distance scales every acceleration by one factor to reach it.

#include <string_view>
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/timing/distance_time.hpp"
#include "inbetween/timing/ease.hpp"
#include "inbetween/math/enum_names.hpp"

namespace inbetween {

/// One constraint tuple ⟨t, s, v, a⟩ of §3.2.4: distance s at time t, and optionally the speed
/// v = ds/dt and the acceleration a = d²s/dt² there.
template <Real T>
struct MotionConstraint {
  T t{};                 ///< time (any unit; speeds and accelerations are per this unit)
  T s{};                 ///< distance travelled at t
  std::optional<T> v{};  ///< speed ds/dt at t, ≥ 0; estimated from the distances when absent
  std::optional<T> a{};  ///< acceleration d²s/dt² at t; free (the curve is only C¹ there) when absent
};

/// A key of an acceleration–time curve: acceleration a at time t.
template <Real T>
struct TimeAccelerationKey {
  T t{};  ///< time
  T a{};  ///< acceleration d²s/dt² at t
};

/// How an acceleration–time curve runs between its keys.
enum class AccelerationShape {
  constant,  ///< a = a_i on [t_i, t_{i+1}) (Figure 3.16); the last key's value is not used
  linear,    ///< a goes linearly from a_i to a_{i+1}
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Constant [[deprecated("use AccelerationShape::constant")]] = constant,
  Linear [[deprecated("use AccelerationShape::linear")]] = linear,
};

/// File names of the AccelerationShape enumerators, in declaration order.
inline constexpr std::array<std::string_view, 2> acceleration_shape_names = {"constant", "linear"};
/// The name table of AccelerationShape (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<AccelerationShape>() noexcept {
  return acceleration_shape_names;
}
/// The file name of v, from the table above (enum_from_string<AccelerationShape> parses it back).
[[nodiscard]] inline std::string_view to_string(AccelerationShape v) noexcept { return enum_name(v); }

/// Options of PiecewiseDistanceCurve::from_acceleration_curve.
template <Real T>
struct AccelerationIntegration {
  AccelerationShape shape = AccelerationShape::constant;  ///< how the keys are joined
  T start_speed{};     ///< v(t_0), ≥ 0
  T start_distance{};  ///< s(t_0)
  /// When given, every acceleration is multiplied by one factor k so that s(t_n) equals it
  /// (s(t_n) is affine in k); an error when the accelerations contribute no distance.
  std::optional<T> end_distance{};
};

/// The relative tolerance below which a negative speed counts as rounding, not as running
/// backwards: speeds are compared with −backwards_tolerance<T>() × (the interval's speed scale).
/// Source: 64 ulps of 1 absorbs the cancellation in the quintic coefficients (≤ 30 terms of size
/// ~1 each), measured by the property tests in tests/timing/piecewise_distance_test.cpp.
template <Real T>
constexpr T backwards_tolerance() noexcept {
  return T(64) * std::numeric_limits<T>::epsilon();
}

/// A piecewise polynomial distance–time function s(t) of degree ≤ 5 over [t_0, t_n].
/// Evaluation is total and noexcept: t is clamped into the domain (NaN reads as t_0), and at a
/// key the speed and acceleration are those of the interval that starts there (right limit),
/// except at the last key.  A single-tuple curve has the domain [t_0, t_0] and rests at s_0.
template <Real T>
class PiecewiseDistanceCurve {
 public:
  /// Coefficients c_0 … c_5 of one interval: s = Σ c_k τ^k with τ = (t − t_i)/(t_{i+1} − t_i).
  using Coefficients = std::array<T, 6>;

  /// From constraint tuples (≥ 1; times strictly increasing; all values finite; given speeds
  /// ≥ 0; distances non-decreasing).  One tuple: the object rests at s_0 (its speed and
  /// acceleration, if given, must be 0).  Errors carry the tuple index as the location ({i}):
  /// TooFewPoints (none), NotFinite, KeysNotIncreasing (equal or reversed times), InvalidArgument
  /// (negative speed), NotMonotone (a distance below the previous one, or a curve whose speed dips
  /// below zero between tuples i and i + 1: the message names both tuples, the time span and the
  /// most negative speed; the location is {i}).
  static Expected<PiecewiseDistanceCurve> from_constraints(std::span<const MotionConstraint<T>> tuples);

  /// From an acceleration–time curve (≥ 2 keys, times strictly increasing, finite) integrated in
  /// closed form from `opt.start_speed` and `opt.start_distance`.  Errors: TooFewPoints,
  /// NotFinite, KeysNotIncreasing ({i}); InvalidArgument for a negative start speed
  /// ({"start_speed"}) or an end distance the accelerations cannot reach ({"end_distance"});
  /// NotMonotone when the speed turns negative (the object would back up) inside interval i
  /// ({i}, with the time and the speed in the message).
  static Expected<PiecewiseDistanceCurve> from_acceleration_curve(std::span<const TimeAccelerationKey<T>> keys,
                                                                  const AccelerationIntegration<T>& opt = {});

  /// s, ds/dt and d²s/dt² at t (clamped into the domain).
  EaseSample<T> sample(T t) const noexcept;
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }
  /// [t_0, t_n].
  Interval<T> domain() const noexcept { return {t_.front(), t_.back()}; }
  /// The key times t_0 … t_n.
  std::span<const T> key_times() const noexcept { return t_; }
  /// The polynomial of interval i (n of them; none for a single tuple).
  std::span<const Coefficients> segments() const noexcept { return seg_; }
  /// The speed used at each key: given, estimated (constraints) or integrated (acceleration).
  std::span<const T> key_speeds() const noexcept { return v_; }

  /// The first interval where ds/dt < 0 beyond backwards_tolerance, or nothing.  Exact up to the
  /// tolerance: the speed polynomial's Bernstein coefficients are subdivided until they are all
  /// non-negative or one of the curve's own values is negative.
  std::optional<BackingUp<T>> find_backing_up() const noexcept;

 private:
  PiecewiseDistanceCurve() = default;
  std::vector<T> t_, v_;
  std::vector<Coefficients> seg_;
};

extern template class PiecewiseDistanceCurve<float>;
extern template class PiecewiseDistanceCurve<double>;

}  // namespace inbetween
