#pragma once
/// Compound C² cubic splines through points (texts 004 §3.1.1, "the form of Hermite curves that
/// enforces second-order continuity"): the tangents D_i of a Hermite spline are chosen so that the
/// second derivative is continuous at every interior point, which couples all of them in one
/// tridiagonal system — global control.  Parameter u_i = i (uniform).
///
/// Interior rows (C² at point i):  D_{i−1} + 4 D_i + D_{i+1} = 3 (P_{i+1} − P_{i−1}).
/// Natural ends (P'' = 0):         2 D_0 + D_1 = 3 (P_1 − P_0),  D_{n−2} + 2 D_{n−1} = 3 (P_{n−1} − P_{n−2}).
/// Clamped ends:                   D_0 and D_{n−1} given.

#include <span>
#include <vector>

#include "inbetween/curves/cubic_basis.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// How a C² cubic spline ends.
enum class CubicSplineEnd {
  Natural,  ///< zero second derivative at both ends
  Clamped,  ///< given first derivatives dP/du at both ends
};

/// A C² interpolating cubic spline, domain [0, n − 1].  Every control point influences the whole
/// domain (global control); two points give the straight segment (natural) or the Hermite cubic
/// with the given end tangents (clamped).
template <Point P>
class CubicSpline : public PiecewiseCubic<P> {
 public:
  using T = scalar_of<P>;  ///< the scalar of P
  /// An empty curve (no segments); build with the factory below.
  CubicSpline() = default;

  /// Builds the spline through `points` (≥ 2, finite).  For Clamped, `start_tangent` and
  /// `end_tangent` are dP/du at u = 0 and u = n − 1 (ignored for Natural).
  static Expected<CubicSpline> build(std::span<const P> points, CubicSplineEnd end,
                                     const P& start_tangent = P{}, const P& end_tangent = P{}) {
    if (auto ok = detail::check_points(points, 2, end == CubicSplineEnd::Natural ? "natural" : "clamped");
        !ok)
      return ok.error();
    if (end == CubicSplineEnd::Clamped) {
      if (!is_finite(start_tangent)) return Error{ErrorCode::NotFinite, "start tangent is not finite", "", {"start_tangent"}};
      if (!is_finite(end_tangent)) return Error{ErrorCode::NotFinite, "end tangent is not finite", "", {"end_tangent"}};
    }
    const int n = int(points.size());
    // Tridiagonal system sub[i] D_{i−1} + diag[i] D_i + sup[i] D_{i+1} = rhs[i], solved by the
    // Thomas algorithm; it is diagonally dominant, so no pivoting is needed.
    std::vector<T> sub(n, T(1)), diag(n, T(4)), sup(n, T(1));
    std::vector<P> rhs(n);
    for (int i = 1; i + 1 < n; ++i) rhs[i] = (points[i + 1] - points[i - 1]) * T(3);
    if (end == CubicSplineEnd::Natural) {
      diag[0] = T(2), sup[0] = T(1), rhs[0] = (points[1] - points[0]) * T(3);
      sub[n - 1] = T(1), diag[n - 1] = T(2), rhs[n - 1] = (points[n - 1] - points[n - 2]) * T(3);
    } else {
      diag[0] = T(1), sup[0] = T(0), rhs[0] = start_tangent;
      sub[n - 1] = T(0), diag[n - 1] = T(1), rhs[n - 1] = end_tangent;
    }
    sub[0] = T(0);
    sup[n - 1] = T(0);
    for (int i = 1; i < n; ++i) {
      const T w = sub[i] / diag[i - 1];
      diag[i] -= w * sup[i - 1];
      rhs[i] = rhs[i] - rhs[i - 1] * w;
    }
    std::vector<P> d(n);
    d[n - 1] = rhs[n - 1] / diag[n - 1];
    for (int i = n - 2; i >= 0; --i) d[i] = (rhs[i] - d[i + 1] * sup[i]) / diag[i];

    CubicSpline s;
    s.end_ = end;
    s.breaks_.clear();
    s.segments_.clear();
    for (int i = 0; i < n; ++i) s.breaks_.push_back(T(i));
    for (int i = 0; i + 1 < n; ++i) s.segments_.push_back(hermite_power_form(points[i], points[i + 1], d[i], d[i + 1]));
    s.controls_.assign(points.begin(), points.end());
    s.tangents_ = d;
    s.influence_.assign(n, s.domain());
    s.interpolates_ = true;
    if (auto ok = s.check_built(end == CubicSplineEnd::Natural ? "natural" : "clamped"); !ok) return ok.error();
    return s;
  }

  /// The solved tangents dP/du at the points.
  std::span<const P> tangents() const noexcept { return tangents_; }
  /// The end condition used.
  CubicSplineEnd end_condition() const noexcept { return end_; }

 private:
  std::vector<P> tangents_{P{}};
  CubicSplineEnd end_ = CubicSplineEnd::Natural;
};

/// Natural C² spline through the points (zero second derivative at the ends).
template <Point P>
Expected<CubicSpline<P>> build_natural_spline(std::span<const P> points) {
  return CubicSpline<P>::build(points, CubicSplineEnd::Natural);
}
/// Overload for vectors.
template <Point P>
Expected<CubicSpline<P>> build_natural_spline(const std::vector<P>& points) {
  return CubicSpline<P>::build(points, CubicSplineEnd::Natural);
}

/// Clamped C² spline through the points with end tangents dP/du given.
template <Point P>
Expected<CubicSpline<P>> build_clamped_spline(std::span<const P> points, const P& start_tangent,
                                              const P& end_tangent) {
  return CubicSpline<P>::build(points, CubicSplineEnd::Clamped, start_tangent, end_tangent);
}
/// Overload for vectors.
template <Point P>
Expected<CubicSpline<P>> build_clamped_spline(const std::vector<P>& points, const P& start_tangent,
                                              const P& end_tangent) {
  return CubicSpline<P>::build(points, CubicSplineEnd::Clamped, start_tangent, end_tangent);
}

}  // namespace inbetween
