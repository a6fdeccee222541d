#pragma once
/// B-spline curves of any degree p over any valid knot vector (004 §3.1, App. B.5): P(u) =
/// Σ_i N_{i,p}(u) P_i on the domain [u_p, u_n], evaluated by de Boor's algorithm; derivatives by
/// differencing the control points (the derivative of a degree-p B-spline is a degree p − 1
/// B-spline with control points p (P_{i+1} − P_i)/(u_{i+p+1} − u_{i+1})).
/// Knot vectors: clamped uniform (default; the curve starts at P_0 and ends at P_{n−1}), uniform,
/// any user vector, and periodic (closed curves, build_periodic_bspline).
/// Continuity at a knot of multiplicity r is C^{p−r}; control point i influences [u_i, u_{i+p+1}].

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "inbetween/curves/bspline_basis.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// A B-spline curve.  Segments are the knot spans of positive length inside the domain.
/// Not interpolating in general (a clamped curve passes through its first and last points only).
template <Point P>
class BSpline {
 public:
  using point_type = P;              ///< the point type (scalar, Vec2, Vec3, Vec4)
  using scalar_type = scalar_of<P>;  ///< its scalar
  using T = scalar_type;             ///< shorthand

  /// Maximum supported degree (evaluation uses fixed-size scratch; no allocation).
  static constexpr int max_degree = 15;

  /// Builds from control points (≥ degree + 1, finite), 1 ≤ degree ≤ max_degree, and a knot vector
  /// (points + degree + 1 non-decreasing finite values; empty = clamped uniform on [0, 1]).
  static Expected<BSpline> build(std::span<const P> points, int degree, std::span<const T> knots = {}) {
    if (degree < 1 || degree > max_degree)
      return Error{ErrorCode::invalid_argument,
                   "degree must be between 1 and " + std::to_string(max_degree) + ", got " + std::to_string(degree), {"degree"}};
    if (auto ok = detail::check_points(points, degree + 1, "bspline"); !ok) return ok.error();
    std::vector<T> k = knots.empty() ? clamped_uniform_knots<T>(int(points.size()), degree)
                                     : std::vector<T>(knots.begin(), knots.end());
    if (auto ok = check_knots<T>(k, int(points.size()), degree); !ok) return ok.error();
    return BSpline(std::vector<P>(points.begin(), points.end()), std::move(k), degree, false);
  }

  /// A closed (periodic) uniform B-spline through the loop of `points` (≥ 2, finite): the first
  /// `degree` points are repeated at the end and the knots are 0, 1, 2, …; the curve is C^{p−1}
  /// everywhere including the seam.  Domain [degree, degree + points.size()].
  static Expected<BSpline> build_periodic(std::span<const P> points, int degree) {
    if (degree < 1 || degree > max_degree)
      return Error{ErrorCode::invalid_argument,
                   "degree must be between 1 and " + std::to_string(max_degree) + ", got " + std::to_string(degree), {"degree"}};
    if (auto ok = detail::check_points(points, 2, "periodic bspline"); !ok) return ok.error();
    std::vector<P> wrapped(points.begin(), points.end());
    for (int i = 0; i < degree; ++i) wrapped.push_back(points[i % points.size()]);
    const int n = int(wrapped.size());
    return BSpline(std::move(wrapped), uniform_knots<T>(n, degree), degree, true);
  }

  /// Degree p.
  int degree() const noexcept { return degree_; }
  /// The knot vector.
  std::span<const T> knots() const noexcept { return knots_; }
  /// True for a periodic (closed) curve.
  bool closed() const noexcept { return closed_; }
  /// [u_p, u_n].
  Interval<T> domain() const noexcept { return {knots_[degree_], knots_[points_.size()]}; }
  /// Number of knot spans of positive length in the domain.
  int segment_count() const noexcept { return int(spans_.size()); }
  /// The knot span of segment i (clamped index).
  Interval<T> segment_domain(int i) const noexcept {
    const int s = spans_[std::clamp(i, 0, segment_count() - 1)];
    return {knots_[s], knots_[s + 1]};
  }
  /// P(u) by de Boor, u clamped into the domain.
  P point(T u) const noexcept { return derivative(u, 0); }
  /// d^kP/du^k (k ≥ 0; zero for k > p), right limit at knots, u clamped.  Never NaN for a built
  /// curve: a derivative whose intermediates would overflow (control points near the largest
  /// finite value) is evaluated with power-of-two scaling, and a component whose true value
  /// exceeds T saturates to ±inf.
  P derivative(T u, int k) const noexcept {
    u = domain().clamp(u);
    return eval(bspline_span<T>(knots_, degree_, u), u, k);
  }
  /// d^kP/du^k of segment i's polynomial at u clamped into segment_domain(i).
  P segment_derivative(int i, T u, int k) const noexcept {
    const int s = spans_[std::clamp(i, 0, segment_count() - 1)];
    return eval(s, std::clamp(u, knots_[s], knots_[s + 1]), k);
  }
  /// Number of control points (for a periodic curve, including the repeated ones).
  int control_point_count() const noexcept { return int(points_.size()); }
  /// Control point i (clamped index).
  P control_point(int i) const noexcept { return points_[std::clamp(i, 0, control_point_count() - 1)]; }
  /// All control points.
  std::span<const P> control_points() const noexcept { return points_; }
  /// False: a B-spline approximates its control polygon (a clamped one touches only its ends;
  /// degree 1 interpolates, and reports true).
  bool interpolates_control_points() const noexcept { return degree_ == 1; }
  /// [max(u_i, u_p), min(u_{i+p+1}, u_n)]: where N_{i,p} is non-zero (local control).
  Interval<T> influence(int i) const noexcept {
    i = std::clamp(i, 0, control_point_count() - 1);
    const auto d = domain();
    const T lo = std::max(knots_[i], d.lo), hi = std::min(knots_[i + degree_ + 1], d.hi);
    return {std::min(lo, hi), hi};
  }
  /// Continuity order C^{p − r} expected at the knot value of segment i's start (r its multiplicity).
  int theoretical_continuity(int segment) const noexcept {
    const T u = segment_domain(segment).lo;
    const int r = int(std::count(knots_.begin(), knots_.end(), u));
    return degree_ - r;
  }

 private:
  BSpline(std::vector<P> points, std::vector<T> knots, int degree, bool closed)
      : points_(std::move(points)), knots_(std::move(knots)), degree_(degree), closed_(closed) {
    const int n = int(points_.size());
    for (int s = degree_; s < n; ++s)
      if (knots_[s] < knots_[s + 1]) spans_.push_back(s);
  }

  // de Boor on knot span s, after differentiating the local control points k times.  When a
  // derivative comes out non-finite (differences of points near the largest value times p/Δu
  // overflow, then inf − inf), it is recomputed by eval_scaled().
  P eval(int s, T u, int k) const noexcept {
    P out = eval_plain(s, u, k);
    if (k > 0 && !is_finite(out)) out = eval_scaled(s, u, k);
    return out;
  }

  // The same algorithm on control points and factors p/Δu split into a mantissa part and a
  // power-of-two exponent that is carried separately and applied once at the end (scale_by_pow2):
  // every intermediate stays below 2^7 per level, and power-of-two scaling commutes with
  // rounding, so the result equals the plain evaluation wherever that one does not overflow and
  // is ±inf only where the true derivative exceeds T (documented saturation; never NaN).
  P eval_scaled(int s, T u, int k) const noexcept {
    const int p = degree_;
    std::array<P, max_degree + 1> d;
    T big{};
    for (int j = 0; j <= p; ++j) big = std::fmax(big, max_abs_component(points_[s - p + j]));
    if (!(big > T(0)) || !std::isfinite(big)) return eval_plain(s, u, k);
    int e = 0;  // the true coefficients are d[j] · 2^e
    std::frexp(big, &e);
    for (int j = 0; j <= p; ++j) d[j] = scale_by_pow2(points_[s - p + j], -e);
    for (int r = 1; r <= k; ++r) {
      const int q = p - r + 1;
      std::array<int, max_degree + 1> de{};
      int top = std::numeric_limits<int>::min();
      for (int j = 0; j <= p - r; ++j) {
        const int i = s - p + r + j;
        std::frexp(knots_[i + q] - knots_[i], &de[j]);  // Δu = f·2^de, f in [0.5, 1)
        top = std::max(top, -de[j]);
      }
      for (int j = 0; j <= p - r; ++j) {
        const int i = s - p + r + j;
        const T du = knots_[i + q] - knots_[i];
        // q/Δu = (q/f)·2^−de: the mantissa factor q/f ≤ 2q, the exponent moved into e.
        d[j] = scale_by_pow2(P((d[j + 1] - d[j]) * (T(q) / std::ldexp(du, -de[j]))), -de[j] - top);
      }
      e += top;
      // Renormalise so that the largest coefficient is below 1 again.
      T level_big{};
      for (int j = 0; j <= p - r; ++j) level_big = std::fmax(level_big, max_abs_component(d[j]));
      if (level_big > T(0)) {
        int le = 0;
        std::frexp(level_big, &le);
        for (int j = 0; j <= p - r; ++j) d[j] = scale_by_pow2(d[j], -le);
        e += le;
      }
    }
    const int q = p - k;
    for (int r = 1; r <= q; ++r) {
      for (int j = q; j >= r; --j) {
        const int i = s - q + j;
        const T alpha = (u - knots_[i]) / (knots_[i + q + 1 - r] - knots_[i]);
        d[j] = d[j - 1] + (d[j] - d[j - 1]) * alpha;
      }
    }
    return scale_by_pow2(d[q], e);
  }

  P eval_plain(int s, T u, int k) const noexcept {
    const int p = degree_;
    if (k > p) return P{};
    std::array<P, max_degree + 1> d;
    for (int j = 0; j <= p; ++j) d[j] = points_[s - p + j];
    // Level r: d[j] holds the coefficient of N_{s−p+r+j, p−r}, j = 0..p−r.
    for (int r = 1; r <= k; ++r) {
      const int q = p - r + 1;  // degree before this step
      for (int j = 0; j <= p - r; ++j) {
        const int i = s - p + r + j;
        d[j] = (d[j + 1] - d[j]) * (T(q) / (knots_[i + q] - knots_[i]));
      }
    }
    const int q = p - k;
    for (int r = 1; r <= q; ++r) {
      for (int j = q; j >= r; --j) {
        const int i = s - q + j;
        const T alpha = (u - knots_[i]) / (knots_[i + q + 1 - r] - knots_[i]);
        d[j] = d[j - 1] + (d[j] - d[j - 1]) * alpha;
      }
    }
    return d[q];
  }

  std::vector<P> points_;
  std::vector<T> knots_;
  int degree_ = 1;
  bool closed_ = false;
  std::vector<int> spans_;
};

/// The same curve as a chain of power-form cubics (one per non-empty knot span, breakpoints at the
/// knots), for degree ≤ 3; coefficients from the derivatives at each span start (d = P, c = P′h,
/// b = P″h²/2, a = P‴h³/6).  Lets B-splines use code written for PiecewiseCubicCurve (analytic
/// arc length).  Error Unsupported at {"degree"} for degree > 3.
template <Point P>
Expected<PiecewiseCubic<P>> to_piecewise_cubic(const BSpline<P>& spline) {
  using T = scalar_of<P>;
  if (spline.degree() > 3)
    return Error{ErrorCode::unsupported,
                 "only B-splines of degree <= 3 are piecewise cubics, got degree " + std::to_string(spline.degree()), {"degree"}};
  std::vector<T> breaks;
  std::vector<PowerCubic<P>> segs;
  for (int i = 0; i < spline.segment_count(); ++i) {
    const auto d = spline.segment_domain(i);
    const T h = d.length();
    breaks.push_back(d.lo);
    segs.push_back({spline.segment_derivative(i, d.lo, 3) * (h * h * h / T(6)),
                    spline.segment_derivative(i, d.lo, 2) * (h * h / T(2)), spline.segment_derivative(i, d.lo, 1) * h,
                    spline.segment_derivative(i, d.lo, 0)});
  }
  breaks.push_back(spline.domain().hi);
  return PiecewiseCubic<P>::from_power_forms(std::move(breaks), std::move(segs));
}

/// Builds a B-spline; see BSpline::build (empty knots = clamped uniform).
template <Point P>
Expected<BSpline<P>> build_bspline(std::span<const P> points, int degree, std::span<const scalar_of<P>> knots = {}) {
  return BSpline<P>::build(points, degree, knots);
}
/// Overload for vectors.
template <Point P>
Expected<BSpline<P>> build_bspline(const std::vector<P>& points, int degree,
                                   const std::vector<scalar_of<P>>& knots = {}) {
  return BSpline<P>::build(points, degree, knots);
}
/// Builds a closed periodic uniform B-spline; see BSpline::build_periodic.
template <Point P>
Expected<BSpline<P>> build_periodic_bspline(const std::vector<P>& points, int degree) {
  return BSpline<P>::build_periodic(points, degree);
}

}  // namespace inbetween
