#pragma once
/// The contract every curve of the library meets, so that arc length, timing and paths work with
/// any of them: a parameter domain split into segments, the point and its derivatives at u.

#include <concepts>

#include "inbetween/math/vec.hpp"

namespace inbetween {

/// A closed parameter interval [lo, hi].
template <Real T>
struct Interval {
  T lo{}, hi{};  ///< ends, lo ≤ hi
  /// hi − lo.
  constexpr T length() const noexcept { return hi - lo; }
  /// True when lo ≤ u ≤ hi.
  constexpr bool contains(T u) const noexcept { return lo <= u && u <= hi; }
  /// u clamped into [lo, hi].
  constexpr T clamp(T u) const noexcept { return u < lo ? lo : (hi < u ? hi : u); }
  /// Exact equality of both ends.
  friend constexpr bool operator==(const Interval&, const Interval&) = default;
};

/// A parametric curve P(u) over point type `point_type` (a Real or Vec2/3/4).
/// - `domain()` is the parameter interval; `point(u)` and `derivative(u, k)` clamp u into it and are
///   total (never NaN for a built curve).
/// - `derivative(u, k)` is the k-th derivative d^kP/du^k for k = 1, 2, 3 (0 gives the point).  At a
///   joint between segments it is the derivative of the segment that starts there (right limit),
///   except at the end of the domain.
/// - `segment_count()` and `segment_domain(i)` describe the pieces; arc-length code integrates each
///   piece separately because derivatives may jump at joints.
template <class C>
concept Curve = requires(const C& c, typename C::scalar_type u, int i) {
  typename C::point_type;
  typename C::scalar_type;
  { c.domain() } -> std::same_as<Interval<typename C::scalar_type>>;
  { c.point(u) } -> std::same_as<typename C::point_type>;
  { c.derivative(u, i) } -> std::same_as<typename C::point_type>;
  { c.segment_count() } -> std::convertible_to<int>;
  { c.segment_domain(i) } -> std::same_as<Interval<typename C::scalar_type>>;
};

/// A cubic in power form P(v) = a v³ + b v² + c v + d for a local parameter v ∈ [0, 1].
template <Point P>
struct PowerCubic {
  P a{}, b{}, c{}, d{};              ///< coefficients of v³, v², v, 1
  using point_type = P;              ///< the point type
  using scalar_type = scalar_of<P>;  ///< its scalar
  /// P(v), by Horner's rule.
  constexpr P point(scalar_type v) const noexcept { return ((a * v + b) * v + c) * v + d; }
  /// k-th derivative at v (k = 0..3; higher orders are zero).
  constexpr P derivative(scalar_type v, int k) const noexcept {
    using T = scalar_type;
    switch (k) {
      case 0: return point(v);
      case 1: return (a * T(3) * v + b * T(2)) * v + c;
      case 2: return a * (T(6) * v) + b * T(2);
      case 3: return a * T(6);
      default: return P{};
    }
  }
};

/// A curve made of cubic pieces that can expose each piece in power form over its local
/// parameter v ∈ [0, 1], with u = lo + v·(hi − lo) on segment_domain(i).  Analytic arc length
/// (texts 004 Eqs. 3.3–3.7) uses this.
template <class C>
concept PiecewiseCubicCurve = Curve<C> && requires(const C& c, int i) {
  { c.segment_power_form(i) } -> std::same_as<PowerCubic<typename C::point_type>>;
};

/// The optional queries every curve of the curves module answers: its control points, whether it
/// passes through all of them, and local control.  `influence(i)` is the parameter range outside
/// of which moving control point i leaves the curve unchanged (the whole domain for global control).
template <class C>
concept ControlledCurve = Curve<C> && requires(const C& c, int i) {
  { c.control_point_count() } -> std::convertible_to<int>;
  { c.control_point(i) } -> std::same_as<typename C::point_type>;
  { c.interpolates_control_points() } -> std::same_as<bool>;
  { c.influence(i) } -> std::same_as<Interval<typename C::scalar_type>>;
};

/// A curve whose pieces can be evaluated one at a time: `segment_derivative(i, u, k)` is the k-th
/// derivative of piece i's polynomial at u, with u clamped into segment_domain(i).  Evaluating piece
/// i − 1 at the start of piece i gives the left limit at a joint (used to measure continuity).
template <class C>
concept SegmentedCurve = Curve<C> && requires(const C& c, int i, typename C::scalar_type u) {
  { c.segment_derivative(i, u, i) } -> std::same_as<typename C::point_type>;
};

}  // namespace inbetween
