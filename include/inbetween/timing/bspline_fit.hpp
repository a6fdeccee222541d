#pragma once
/// Fitting a B-spline curve of degree k to position-time pairs ⟨P_i, t_i⟩ (texts 004 §3.2.5,
/// Eqs. 3.23–3.27): P = N B with N_{ij} = N_{j,k}(t_i).  With as many control points as data the
/// system is square and B = N⁻¹P (the curve passes through every P_i at t_i); with fewer it is
/// solved in the least-squares sense by column-pivoted Householder QR of N (not the normal
/// equations of Eq. 3.27, which square the condition number).  Knots are clamped (k + 1 copies of
/// t_first and of t_last) with the interior knots uniformly spaced over [t_first, t_last].
/// Implemented with Eigen in src/timing/fit_eigen.cpp (library inbetween_eigen); this header does
/// not include Eigen.

#include <algorithm>
#include <array>
#include <span>
#include <vector>

#include "inbetween/curves/bspline_basis.hpp"

#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// The highest degree fit_bspline accepts.
inline constexpr int kMaxFitDegree = 15;

/// A position P at time t.
template <Point P>
struct TimedPoint {
  scalar_of<P> t{};  ///< time
  P p{};             ///< position at t
};

/// A B-spline curve as plain data: degree k, n control points and n + k + 1 non-decreasing knots.
/// The curve is defined on [knots[k], knots[n]].
template <Point P>
struct FittedBSpline {
  using T = scalar_of<P>;  ///< the scalar of P
  int degree = 3;                ///< k
  std::vector<P> control_points; ///< B_1 … B_n
  std::vector<T> knots;          ///< clamped knot vector

  /// The point at time t (clamped into [knots[k], knots[n]]), by de Boor's algorithm.  Requires a
  /// well-formed spline (as fit_bspline returns).
  P point(T t) const noexcept {
    const int k = degree, n = int(control_points.size());
    INBETWEEN_ASSERT(k >= 1 && k <= kMaxFitDegree && n >= k + 1 && knots.size() == std::size_t(n + k + 1));
    const T lo = knots[std::size_t(k)], hi = knots[std::size_t(n)];
    t = t < lo ? lo : (t > hi ? hi : t);
    if (!(t == t)) t = lo;
    // Span s with knots[s] ≤ t < knots[s+1], k ≤ s ≤ n − 1 (the last span at t = hi).
    int s = int(std::upper_bound(knots.begin() + k, knots.begin() + n, t) - knots.begin()) - 1;
    s = std::clamp(s, k, n - 1);
    std::array<P, kMaxFitDegree + 1> d{};
    for (int j = 0; j <= k; ++j) d[std::size_t(j)] = control_points[std::size_t(j + s - k)];
    for (int r = 1; r <= k; ++r) {
      for (int j = k; j >= r; --j) {
        const T a = knots[std::size_t(j + s - k)], b = knots[std::size_t(j + 1 + s - r)];
        const T alpha = b > a ? (t - a) / (b - a) : T(0);
        d[std::size_t(j)] = d[std::size_t(j - 1)] * (T(1) - alpha) + d[std::size_t(j)] * alpha;
      }
    }
    return d[std::size_t(k)];
  }
};

/// Options of fit_bspline.
struct BSplineFitOptions {
  int degree = 3;          ///< k ≥ 1 (at most kMaxFitDegree)
  int control_points = 0;  ///< n with k + 1 ≤ n ≤ number of data; 0 means n = number of data (square)
};

/// The fitted curve and how well it fits.
template <Point P>
struct BSplineFit {
  using T = scalar_of<P>;  ///< the scalar of P
  FittedBSpline<P> curve;  ///< control points, knots, degree
  T rms_residual{};        ///< √(mean |B(t_i) − P_i|²)
  T max_residual{};        ///< max |B(t_i) − P_i|
  bool square = false;     ///< true when n equals the number of data (interpolation, Eq. 3.26)
};

/// The clamped knot vector of `control_points` control points of degree `degree` over
/// [t_first, t_last]: degree + 1 copies of each end, interior knots uniformly spaced.
template <Real T>
std::vector<T> clamped_uniform_knots(T t_first, T t_last, int degree, int control_points) {
  std::vector<T> k = clamped_uniform_knots<T>(control_points, degree);  // on [0, 1]
  for (T& x : k) x = x == T(1) ? t_last : t_first + (t_last - t_first) * x;  // ends exact
  return k;
}

/// Fits a B-spline to the data (times strictly increasing, everything finite, at least 2 data).
/// Errors: bad options (InvalidArgument at {"degree"} or {"control_points"}), bad data (at
/// {"points", i}), or a singular basis matrix (InvalidArgument: the data times leave some control
/// point without support — the Schoenberg–Whitney condition — so no unique fit exists).
template <Point P>
Expected<BSplineFit<P>> fit_bspline(std::span<const TimedPoint<P>> data, BSplineFitOptions options = {});

extern template Expected<BSplineFit<float>> fit_bspline(std::span<const TimedPoint<float>>, BSplineFitOptions);
extern template Expected<BSplineFit<double>> fit_bspline(std::span<const TimedPoint<double>>, BSplineFitOptions);
extern template Expected<BSplineFit<Vec2f>> fit_bspline(std::span<const TimedPoint<Vec2f>>, BSplineFitOptions);
extern template Expected<BSplineFit<Vec2d>> fit_bspline(std::span<const TimedPoint<Vec2d>>, BSplineFitOptions);
extern template Expected<BSplineFit<Vec3f>> fit_bspline(std::span<const TimedPoint<Vec3f>>, BSplineFitOptions);
extern template Expected<BSplineFit<Vec3d>> fit_bspline(std::span<const TimedPoint<Vec3d>>, BSplineFitOptions);

}  // namespace inbetween
