// B-spline fitting to position-time pairs (texts 004 §3.2.5) with Eigen's column-pivoted
// Householder QR.  The basis functions are the curves module's (bspline_basis_all), so the fitted
// curve is exactly the BSpline that `curve sample` evaluates.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/format.hpp"
#include "inbetween/curves/bspline_basis.hpp"
#include "inbetween/timing/bspline_fit.hpp"

namespace inbetween {

template <Point P>
Expected<BSplineFit<P>> fit_bspline(std::span<const TimedPoint<P>> data, BSplineFitOptions options) {
  using T = scalar_of<P>;
  constexpr int dim = PointTraits<P>::dim;
  const int j = int(data.size());
  const int k = options.degree;
  if (k < 1 || k > kMaxFitDegree) {
    return Error{ErrorCode::invalid_argument,
                 "degree " + std::to_string(k) + " is outside [1, " + std::to_string(kMaxFitDegree) + "]", {"degree"}};
  }
  if (j < 2) return Error{ErrorCode::too_few_points, "needs at least 2 data points, got " + std::to_string(j)};
  const int n = options.control_points == 0 ? j : options.control_points;
  if (n < k + 1 || n > j) {
    return Error{ErrorCode::invalid_argument,
                 std::to_string(n) + " control points: needs degree + 1 = " + std::to_string(k + 1) +
                     " <= control points <= " + std::to_string(j) + " (the number of data)", {"control_points"}};
  }
  for (int i = 0; i < j; ++i) {
    const std::vector<LocationStep> where = {"points", std::size_t(i)};
    if (!std::isfinite(data[std::size_t(i)].t) || !is_finite(data[std::size_t(i)].p)) {
      return Error{ErrorCode::not_finite, "a time or coordinate is not finite", where};
    }
    if (i > 0 && !(data[std::size_t(i - 1)].t < data[std::size_t(i)].t)) {
      return Error{ErrorCode::keys_not_increasing,
                   "time " + shortest_text<double>(double(data[std::size_t(i)].t)) + " is not after " +
                       shortest_text<double>(double(data[std::size_t(i - 1)].t)), where};
    }
  }
  const double t_first = double(data.front().t), t_last = double(data.back().t);
  const std::vector<double> knots = clamped_uniform_knots(t_first, t_last, k, n);

  // N (j × n) and the data (j × dim), in double whatever T is.  The data are divided by 2^scale
  // (exact) so that their largest coordinate is below 1: the QR solve and the residuals then never
  // overflow, and a fit whose control points are representable succeeds however large the data.
  int scale = 0, biggest_row = 0;
  double biggest = 0;
  for (int i = 0; i < j; ++i) {
    const double m = double(max_abs_component(data[std::size_t(i)].p));
    if (m > biggest) biggest = m, biggest_row = i;
  }
  if (biggest > 0) std::frexp(biggest, &scale);
  Eigen::MatrixXd N(j, n);
  Eigen::MatrixXd rhs(j, dim);
  std::vector<double> row(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < j; ++i) {
    bspline_basis_all<double>(knots, k, double(data[std::size_t(i)].t), 0, row);
    for (int c = 0; c < n; ++c) N(i, c) = row[std::size_t(c)];
    for (int d = 0; d < dim; ++d) rhs(i, d) = std::ldexp(double(PointTraits<P>::get(data[std::size_t(i)].p, d)), -scale);
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(N);
  if (qr.rank() < n) {
    return Error{ErrorCode::invalid_argument,
                 "the basis matrix has rank " + std::to_string(qr.rank()) + " < " + std::to_string(n) +
                     " control points: some knot span holds too few data times (Schoenberg-Whitney); "
                     "use fewer control points or spread the times", {"control_points"}};
  }
  const Eigen::MatrixXd B = qr.solve(rhs);

  BSplineFit<P> fit;
  fit.square = n == j;
  fit.curve.degree = k;
  for (double x : knots) fit.curve.knots.push_back(T(x));
  for (int c = 0; c < n; ++c) {
    P p{};
    for (int d = 0; d < dim; ++d) PointTraits<P>::set(p, d, T(std::ldexp(B(c, d), scale)));
    // Finite data can still give control points beyond the range of T (a spline through data near
    // the largest value overshoots them, or a double solution cast to float): an error that names
    // the cause — the data's magnitude, at its largest row — never a curve holding inf/NaN.
    if (!is_finite(p)) {
      return Error{ErrorCode::not_finite,
                   "the data are too large for this fit: control point " + std::to_string(c) +
                       " would exceed the largest " + (sizeof(T) >= 8 ? "double" : "float") +
                       " (the largest coordinate is " + shortest_text<double>(biggest) +
                       " at this point); scale the data down", {"points", std::size_t(biggest_row)}};
    }
    fit.curve.control_points.push_back(p);
  }
  // The residuals at the data's scale 2^-scale, so that neither N·B − rhs nor the sum of squares
  // overflows for data near the largest double (fuzz/csv_fuzz.cpp: rows of ±1e300 gave an infinite
  // rms residual); back at the data's scale a residual beyond the scalar type is an error.
  const Eigen::MatrixXd residual = N * B - rhs;
  double sum = 0, worst = 0;
  for (int i = 0; i < j; ++i) {
    const double r = residual.row(i).norm();
    sum += r * r;
    worst = std::max(worst, r);
  }
  fit.rms_residual = T(std::ldexp(std::sqrt(sum / j), scale));
  fit.max_residual = T(std::ldexp(worst, scale));
  if (!std::isfinite(fit.rms_residual) || !std::isfinite(fit.max_residual)) {
    return Error{ErrorCode::not_finite,
                 "the fit's residual is beyond the range of the scalar type (data too close to its largest value)"};
  }
  return fit;
}

template Expected<BSplineFit<float>> fit_bspline(std::span<const TimedPoint<float>>, BSplineFitOptions);
template Expected<BSplineFit<double>> fit_bspline(std::span<const TimedPoint<double>>, BSplineFitOptions);
template Expected<BSplineFit<Vec2f>> fit_bspline(std::span<const TimedPoint<Vec2f>>, BSplineFitOptions);
template Expected<BSplineFit<Vec2d>> fit_bspline(std::span<const TimedPoint<Vec2d>>, BSplineFitOptions);
template Expected<BSplineFit<Vec3f>> fit_bspline(std::span<const TimedPoint<Vec3f>>, BSplineFitOptions);
template Expected<BSplineFit<Vec3d>> fit_bspline(std::span<const TimedPoint<Vec3d>>, BSplineFitOptions);

}  // namespace inbetween
