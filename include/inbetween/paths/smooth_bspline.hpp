#pragma once
/// Smoothing by B-spline approximation (texts 004 §3.4.3, last part): a least-squares B-spline with
/// fewer control points than data is fitted to the points against their index (t_i = i), and the
/// smoothed points are the fitted curve at the same t_i.  The curve no longer passes through the
/// data but is smooth (C^{k−1}).  Uses timing/bspline_fit.hpp's fit_bspline (clamped uniform knots
/// over [0, n − 1]; QR least squares), which lives in inbetween_eigen: link inbetween::eigen.

#include <span>
#include <vector>

#include "inbetween/paths/smoothing.hpp"
#include "inbetween/timing/bspline_fit.hpp"

namespace inbetween {

/// The smoothed points and the fit behind them.
template <Point P>
struct BSplineSmoothing {
  std::vector<P> points;  ///< the fitted curve at t_i = i
  BSplineFit<P> fit;      ///< control points, knots, residuals (rms_residual, max_residual)
};

/// Fits a B-spline of `options.degree` with `options.control_points` control points (0: one per
/// point, which interpolates and returns the input) to the points at t_i = i.  Errors: fewer than
/// 2 points ({"points"}), a non-finite point ({"points", i}), and fit_bspline's errors for bad options
/// ({"degree"} / {"control_points"}).
template <Point P>
Expected<BSplineSmoothing<P>> smooth_bspline(std::span<const P> points, BSplineFitOptions options = {}) {
  using T = scalar_of<P>;
  // At least 2 points (fit_bspline's own minimum, checked here so the error names "points").
  if (auto ok = detail::check_path_points(points, 2); !ok) return ok.error();
  std::vector<TimedPoint<P>> data(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) data[i] = {T(i), points[i]};
  auto fit = fit_bspline<P>(std::span<const TimedPoint<P>>(data), options);
  if (!fit) return fit.error();
  BSplineSmoothing<P> out;
  out.points.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out.points[i] = fit->curve.point(T(i));
  out.fit = std::move(*fit);
  return out;
}

/// Overload for vectors.
template <Point P>
Expected<BSplineSmoothing<P>> smooth_bspline(const std::vector<P>& points, BSplineFitOptions options = {}) {
  return smooth_bspline(std::span<const P>(points), options);
}

}  // namespace inbetween
