#pragma once
/// ArcLength<C>: the recommended arc-length object.  Built once from any Curve, it answers the
/// length, s(u) = LENGTH(u₀, u), u(s) and P(U(s)) noexcept, clamping its arguments.
///
/// How (texts 004 §3.2.1, "Adaptive Gaussian integration" and "Find a point that is a given
/// distance along a curve"): an adaptive Gaussian table of (u, s) rows is built per segment
/// (Figure 3.8, corrected) with a tolerance relative to the curve length; s(u) is the row below
/// plus the same Gauss–Legendre rule from that row to u; u(s) is found by Newton–Raphson on
/// s − LENGTH(u_i, u) inside the bracketing rows, seeded by linear interpolation, and falls back to
/// bisection whenever the speed is near zero or an iterate leaves its bracket (coincident control
/// points, cusps).  The seed is the cubic Hermite inverse through the interval's ends (du/ds =
/// 1/speed there), and later iterates only integrate the short step from the previous one (3-point
/// rule), so a u(s) query costs about order + 8 derivative evaluations.  In double precision u(s) lands within 1e-9·length of the requested s (the
/// tests measure 1e-13 or better on the museum curves; see docs/arclength.md).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "inbetween/arclength/arc_length_table.hpp"
#include "inbetween/arclength/gauss_legendre.hpp"
#include "inbetween/arclength/quadrature_length.hpp"
#include "inbetween/curves/curve.hpp"
#include "inbetween/math/expected.hpp"

namespace inbetween {

/// The default relative tolerance of ArcLength's table: 1e-11 in double, 1e-5 in float.
template <Real T>
inline constexpr T default_arc_length_tolerance = sizeof(T) <= sizeof(float) ? T(1e-5) : T(1e-11);

/// Options of ArcLength::build.
template <Real T>
struct ArcLengthOptions {
  /// Table tolerance relative to the curve length (ε = relative_tolerance · L, halved per level).
  T relative_tolerance = default_arc_length_tolerance<T>;
  int order = 10;      ///< Gauss–Legendre nodes per interval (10 as in texts 004 Figure 3.8)
  int min_depth = 3;   ///< forced subdivision levels per segment (dense rows make good Newton seeds)
  int max_depth = 30;  ///< subdivision cap (cusps, rounding)
  /// Work budget of the table build, per curve segment (see AdaptiveGaussOptions); running out
  /// is the error BudgetExceeded.
  std::int64_t max_evaluations_per_segment = 100'000;
};

/// Arc-length parameterisation of a curve (a copy of the curve is kept).  Invariants: length() ≥ 0
/// and finite; s_at is non-decreasing in u; u_at(s_at(u)) = u wherever the speed is non-zero.
template <Curve C>
class ArcLength {
 public:
  using scalar_type = typename C::scalar_type;  ///< T
  using point_type = typename C::point_type;    ///< the curve's point type
  using T = scalar_type;                         ///< shorthand

  /// Builds the table.  Errors: options out of range (InvalidArgument), a curve whose speed is
  /// not finite somewhere (NotFinite), or a table that needs more than
  /// opt.max_evaluations_per_segment × segments speed evaluations (BudgetExceeded).
  static Expected<ArcLength> build(C curve, const ArcLengthOptions<T>& opt = {}) {
    if (!(opt.relative_tolerance > T(0)) || opt.order < 1 || opt.order > kMaxGaussLegendreOrder ||
        opt.min_depth < 0 || opt.max_depth < opt.min_depth) {
      return Error{ErrorCode::invalid_argument,
                   "needs relative_tolerance > 0, 1 <= order <= 64 and 0 <= min_depth <= max_depth", {Parameter{"options"}}};
    }
    const auto dom = curve.domain();
    const T estimate = gauss_length(curve, dom.lo, dom.hi, opt.order);
    if (!std::isfinite(estimate)) {
      return Error{ErrorCode::not_finite, "the curve's speed is not finite"};
    }
    const T tol = estimate > T(0) ? opt.relative_tolerance * estimate : opt.relative_tolerance;
    auto table = adaptive_gauss_table(
        curve, AdaptiveGaussOptions<T>{.tolerance = tol, .order = opt.order, .min_depth = opt.min_depth,
                                       .max_depth = opt.max_depth,
                                       .max_evaluations_per_segment = opt.max_evaluations_per_segment});
    if (!table) return table.error();
    if (!std::isfinite(table->length())) {
      return Error{ErrorCode::not_finite, "the curve's length is not finite"};
    }
    return ArcLength(std::move(curve), std::move(*table), gauss_legendre_rule(opt.order));
  }

  /// The curve this object measures.
  [[nodiscard]] const C& curve() const noexcept { return curve_; }
  /// The table of (u, s) rows behind the queries (adaptive Gaussian, Figure 3.8).
  [[nodiscard]] const ArcLengthTable<T>& table() const noexcept { return table_; }
  /// Total length L ≥ 0.
  [[nodiscard]] T length() const noexcept { return table_.length(); }
  /// The curve's parameter domain.
  [[nodiscard]] Interval<T> domain() const noexcept { return table_.domain(); }

  /// s(u) = LENGTH(u₀, u), u clamped into the domain (NaN reads as u₀).
  [[nodiscard]] T s_at(T u) const noexcept {
    const auto dom = domain();
    if (!(u > dom.lo)) return T(0);
    if (!(u < dom.hi)) return length();
    const auto i = std::size_t(table_.interval_index_for_u(u));
    const T ui = table_.u_values()[i];
    return table_.s_values()[i] + partial(ui, u);
  }

  /// u(s): the parameter at arc length s from the start, s clamped into [0, L] (NaN reads as 0).
  /// Newton–Raphson seeded from the table, with bisection fallback; a zero-length piece (equal s at
  /// several u) answers the u at its end, and a curve of length zero answers u₀.
  [[nodiscard]] T u_at(T s) const noexcept {
    const auto su = table_.s_values();
    const auto uu = table_.u_values();
    if (!(s > T(0)) || !(length() > T(0))) return uu.front();
    if (!(s < length())) return uu.back();
    const auto i = std::size_t(table_.interval_index_for_s(s));
    const T u0 = uu[i], u1 = uu[i + 1], s0 = su[i], s1 = su[i + 1];
    if (!(s1 > s0)) return u0;
    const T target = s - s0;
    const T slope = (s1 - s0) / (u1 - u0);         // mean speed on the interval
    const T tiny_speed = T(1e-8) * slope;           // "near zero" for the Newton step
    const T tol = T(16) * std::numeric_limits<T>::epsilon() * length();
    T a = u0, b = u1;
    T u = seed(i, target);
    // LENGTH(u0, u) is kept for the last iterate; a nearby next iterate adds a 3-point Gauss rule
    // over the short step instead of integrating from u0 again.
    const GaussLegendreRule short_rule = gauss_legendre_rule(3);
    const T near_step = T(1e-3) * (u1 - u0);
    T u_known = u0, len_known = T(0);
    for (int iter = 0; iter < 100; ++iter) {
      const T len = std::fabs(u - u_known) <= near_step ? len_known + partial(u_known, u, short_rule)
                                                         : partial(u0, u, rule_);
      u_known = u;
      len_known = len;
      const T f = len - target;
      if (std::fabs(f) <= tol) return u;
      if (f < T(0)) a = u; else b = u;
      const T speed = speed_at(curve_, u);
      T next = u - f / speed;
      const bool newton_ok = speed > tiny_speed && a < next && next < b;
      // Newton's next error is about ½·|speed'|·step² (in length units); when that is below the
      // tolerance, accept the step without integrating again.  |speed'| is estimated by the
      // steepest secant from u to the interval's ends.
      if (newton_ok) {
        const T lo_slope = u > u0 ? std::fabs(speed - speed_lo_[i]) / (u - u0) : T(0);
        const T hi_slope = u < u1 ? std::fabs(speed_hi_[i] - speed) / (u1 - u) : T(0);
        const T step = next - u;
        if (T(0.5) * std::max(lo_slope, hi_slope) * step * step <= tol) return next;
      }
      if (!newton_ok) next = a + (b - a) / T(2);  // bisection fallback
      if (next == u || !(a < next && next < b)) return u;
      u = next;
    }
    return u;
  }

  /// P(U(s)): the point at arc length s from the start (s clamped into [0, L]).
  [[nodiscard]] point_type point_at_length(T s) const noexcept { return curve_.point(u_at(s)); }
  /// LENGTH(u_a, u_b) = s(u_b) − s(u_a); negative when u_b < u_a.
  [[nodiscard]] T length_between(T ua, T ub) const noexcept { return s_at(ub) - s_at(ua); }
  /// The parameter at arc distance ds from u_a (problem 2 of the texts): u(s(u_a) + ds), clamped.
  [[nodiscard]] T u_at_distance(T ua, T ds) const noexcept { return u_at(s_at(ua) + ds); }

 private:
  ArcLength(C curve, ArcLengthTable<T> table, GaussLegendreRule rule)
      : curve_(std::move(curve)), table_(std::move(table)), rule_(rule) {
    // End speeds of every table interval; at a joint the speed of the segment on the interval's
    // side (just inside the interval, since derivative() answers the segment that starts there).
    const auto uu = table_.u_values();
    for (std::size_t i = 0; i + 1 < uu.size(); ++i) {
      speed_lo_.push_back(speed_at(curve_, uu[i]));
      speed_hi_.push_back(speed_at(curve_, std::nextafter(uu[i + 1], uu[i])));
    }
  }

  // Initial iterate for u on table interval i at distance `target` past its start: the cubic
  // Hermite inverse using the end speeds (du/ds = 1/speed), or linear (Eq. 3.11) where an end speed
  // is near zero; clamped into the interval.
  T seed(std::size_t i, T target) const noexcept {
    const auto su = table_.s_values();
    const auto uu = table_.u_values();
    const T u0 = uu[i], u1 = uu[i + 1], ds = su[i + 1] - su[i];
    const T x = target / ds;  // σ ∈ [0, 1]
    const T linear = u0 + x * (u1 - u0);
    const T v0 = speed_lo_[i], v1 = speed_hi_[i];
    const T mean = ds / (u1 - u0);
    if (!(v0 > T(0.05) * mean) || !(v1 > T(0.05) * mean)) return linear;
    const T m0 = ds / v0, m1 = ds / v1;  // du/dσ at the ends
    const T x2 = x * x, x3 = x2 * x;
    const T u = (T(2) * x3 - T(3) * x2 + T(1)) * u0 + (x3 - T(2) * x2 + x) * m0 + (T(3) * x2 - T(2) * x3) * u1 +
                (x3 - x2) * m1;
    return (u > u0 && u < u1) ? u : linear;
  }

  // Gauss–Legendre length from ua to u, both inside the same table interval.
  T partial(T ua, T u, const GaussLegendreRule& rule) const noexcept {
    const auto f = [this](T x) { return speed_at(curve_, x); };
    return integrate_gauss_legendre<T>(f, ua, u, rule);
  }
  T partial(T ua, T u) const noexcept { return partial(ua, u, rule_); }

  C curve_;
  ArcLengthTable<T> table_;
  GaussLegendreRule rule_;
  std::vector<T> speed_lo_, speed_hi_;  // speed at the start and end of each table interval
};

/// Fills u_out with the parameters of N = u_out.size() points evenly spaced along the curve:
/// u_i = u(i·L/(N − 1)), so u_out.front() is the start and u_out.back() the end (N = 1 gives the
/// start).  For `curve sample --by arclength`.  Does not allocate.
template <Curve C>
void uniform_arc_length_parameters(const ArcLength<C>& arc, std::span<typename C::scalar_type> u_out) noexcept {
  using T = typename C::scalar_type;
  const std::size_t n = u_out.size();
  if (n == 0) return;
  if (n == 1) { u_out[0] = arc.domain().lo; return; }
  const T L = arc.length();
  for (std::size_t i = 0; i < n; ++i) {
    u_out[i] = i + 1 == n ? arc.domain().hi : arc.u_at(L * (T(i) / T(n - 1)));
  }
}

/// Builds the default arc-length object: ArcLength<C>::build(curve, opt).
template <Curve C>
Expected<ArcLength<C>> make_arc_length(C curve, const ArcLengthOptions<typename C::scalar_type>& opt = {}) {
  return ArcLength<C>::build(std::move(curve), opt);
}

}  // namespace inbetween
