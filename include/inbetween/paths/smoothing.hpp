#pragma once
/// Smoothing a digitised path (texts 004 §3.4.3).  Every function takes the points in order (any
/// Point type: scalars for y = f(x) data, Vec2, Vec3) and returns a new list of the same length.
/// All estimates of one pass are computed from that pass's input (no in-place updates), and every
/// estimate is averaged with the original point, as the texts' constructions do (Figs. 3.38, 3.40).
///
/// - smooth_linear: Eq. 3.35, P′_i = ¼P_{i−1} + ½P_i + ¼P_{i+1}; the texts give no end rule, so the
///   first and last points stay fixed.
/// - smooth_cubic: the cubic through P_{i−2}, P_{i−1}, P_{i+1}, P_{i+2} at u = 0, ¼, ¾, 1 (Eq. 3.37)
///   evaluated at u = ½ is (2/3)(P_{i−1} + P_{i+1}) − (1/6)(P_{i−2} + P_{i+2}) (Lagrange weights at
///   ½; equal to Fig. 3.38's "average, plus 1/6 of P_{i−1} − P_{i−2} and of P_{i+1} − P_{i+2}").
///   Second points: the parabola through P_0, P_2, P_3 at u = 0, ⅔, 1 (Eq. 3.38) gives
///   P_1 ≈ P_2 + ⅓(P_0 − P_3) (Fig. 3.40), mirrored at the far end.  First and last points: fixed
///   (hard constraints), or with `smooth_ends` the parabolic estimate P_0 ≈ P_3 + 3(P_1 − P_2)
///   (mirrored at the far end).  Fewer than 4 points: the middle point of 3 uses Eq. 3.35, and
///   1 or 2 points are returned unchanged (documented fallback).
/// - smooth_convolution: the points as a step function (value P_j on [j − ½, j + ½]) convolved with a
///   kernel of area 1 on [−r, r] (Eq. 3.39, integrated exactly per step): P′_i = Σ_k w_k P_{i+k} with
///   w_k = ∫_{k−½}^{k+½} g(x) dx.  At the ends the step function is extended by repeating the first
///   and last points; `fix_ends` keeps the first and last points unchanged.  Offsets beyond the
///   number of points always land on an end point, so their mass is added to the outermost weight:
///   any finite radius costs at most 2n − 1 weights.
/// Errors: no points (TooFewPoints, location {"points"}), a non-finite point (NotFinite, location
/// {"points", i}), bad options (InvalidArgument, location {"<option>"}).

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

namespace detail {
/// Checks a point list: at least `min_count` points, all finite; errors name "point i".
template <Point P>
Expected<void> check_path_points(std::span<const P> points, std::size_t min_count = 1) {
  if (points.size() < min_count)
    return Error{ErrorCode::TooFewPoints,
                 "need at least " + std::to_string(min_count) + " points, got " + std::to_string(points.size()),
                 "", {"points"}};
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!is_finite(points[i]))
      return Error{ErrorCode::NotFinite, "point " + std::to_string(i) + " is not finite", "", {"points", std::size_t(i)}};
  return {};
}
}  // namespace detail

/// Options of smooth_linear().
struct LinearSmoothingOptions {
  int iterations = 1;  ///< ≥ 0 passes (each flattens concave parts further)
};

/// Eq. 3.35 applied `iterations` times; first and last points fixed.  Errors in the file comment.
template <Point P>
Expected<std::vector<P>> smooth_linear(std::span<const P> points, const LinearSmoothingOptions& options = {}) {
  using T = scalar_of<P>;
  if (auto ok = detail::check_path_points(points); !ok) return ok.error();
  if (options.iterations < 0)
    return Error{ErrorCode::InvalidArgument, "iterations must be >= 0, got " + std::to_string(options.iterations),
                 "", {"iterations"}};
  std::vector<P> cur(points.begin(), points.end()), next = cur;
  for (int it = 0; it < options.iterations; ++it) {
    for (std::size_t i = 1; i + 1 < cur.size(); ++i)
      next[i] = cur[i - 1] * T(0.25) + cur[i] * T(0.5) + cur[i + 1] * T(0.25);
    cur = next;
  }
  return cur;
}

/// Options of smooth_cubic().
struct CubicSmoothingOptions {
  int iterations = 1;       ///< ≥ 0 passes
  bool smooth_ends = false; ///< false: first and last points fixed; true: parabolic estimates
};

/// Cubic interpolation of adjacent values (Eqs. 3.36–3.38, Figs. 3.38–3.41); see file comment.
template <Point P>
Expected<std::vector<P>> smooth_cubic(std::span<const P> points, const CubicSmoothingOptions& options = {}) {
  using T = scalar_of<P>;
  if (auto ok = detail::check_path_points(points); !ok) return ok.error();
  if (options.iterations < 0)
    return Error{ErrorCode::InvalidArgument, "iterations must be >= 0, got " + std::to_string(options.iterations),
                 "", {"iterations"}};
  std::vector<P> cur(points.begin(), points.end()), next = cur;
  const std::size_t n = cur.size();
  const T half = T(0.5), third = T(1) / T(3);
  for (int it = 0; it < options.iterations && n >= 3; ++it) {
    const auto& p = cur;
    if (n == 3) {
      next[1] = p[0] * T(0.25) + p[1] * half + p[2] * T(0.25);
    } else {
      for (std::size_t i = 2; i + 2 < n; ++i) {
        const P estimate = (p[i - 1] + p[i + 1]) * (T(2) / T(3)) - (p[i - 2] + p[i + 2]) * (T(1) / T(6));
        next[i] = (p[i] + estimate) * half;
      }
      next[1] = (p[1] + (p[2] + (p[0] - p[3]) * third)) * half;
      next[n - 2] = (p[n - 2] + (p[n - 3] + (p[n - 1] - p[n - 4]) * third)) * half;
      if (options.smooth_ends) {
        next[0] = (p[0] + (p[3] + (p[1] - p[2]) * T(3))) * half;
        next[n - 1] = (p[n - 1] + (p[n - 4] + (p[n - 2] - p[n - 3]) * T(3))) * half;
      }
    }
    cur = next;
  }
  return cur;
}

/// Convolution kernels of Fig. 3.44, each of area 1 on its support [−r, r].
enum class SmoothingKernel {
  box,       ///< g(x) = 1/(2r)
  tent,      ///< g(x) = (r − |x|)/r²
  gaussian,  ///< exp(−x²/2σ²) with σ = r/3, truncated at ±r and rescaled to area 1
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Box [[deprecated("use SmoothingKernel::box")]] = box,
  Tent [[deprecated("use SmoothingKernel::tent")]] = tent,
  Gaussian [[deprecated("use SmoothingKernel::gaussian")]] = gaussian,
};

/// Options of smooth_convolution().
template <Real T>
struct ConvolutionOptions {
  SmoothingKernel kernel = SmoothingKernel::tent;  ///< kernel shape
  T radius = T(1);       ///< r > 0, half-width of the support in sample spacings
  bool fix_ends = false; ///< keep the first and last points (animation constraints)
};

namespace detail {
/// G(x) = ∫_{−r}^{x} g: the kernel's integral from the left end of its support, x clamped into
/// [−r, r] (0 at −r, 1 at r).
template <Real T>
T kernel_integral(SmoothingKernel kernel, T radius, T x) noexcept {
  x = clamp(x, -radius, radius);
  switch (kernel) {
    // Written in x/r and d/r so that a radius near the type's maximum does not overflow (r², 2r,
    // x + r) into inf/inf = NaN or a zero scale.
    case SmoothingKernel::box: return x / radius / T(2) + T(0.5);
    case SmoothingKernel::tent: {
      const T d = (radius - std::abs(x)) / radius;  // the tail beyond |x| has area d²/2 (d in units of r)
      const T tail = d * d / T(2);
      return x < T(0) ? tail : T(1) - tail;
    }
    case SmoothingKernel::gaussian: {
      const T scale = T(3) / std::sqrt(T(2)) / radius;  // 1/(σ√2) with σ = r/3
      const T total = std::erf(T(3) / std::sqrt(T(2)));  // mass on [−r, r] before rescaling
      return (std::erf(x * scale) + total) / (T(2) * total);
    }
  }
  return T(0);
}

/// The weights w_{−K} … w_K of a kernel, with the mass beyond ±K lumped into the outermost
/// weights (exact for an input of K + 1 points or fewer, where every index past K clamps to an end).
template <Real T>
std::vector<T> lumped_kernel_weights(SmoothingKernel kernel, T radius, int K) {
  std::vector<T> w(std::size_t(2 * K + 1));
  for (int k = -K; k <= K; ++k) {
    const T lo = k == -K ? -radius : T(k) - T(0.5);
    const T hi = k == K ? radius : T(k) + T(0.5);
    w[std::size_t(k + K)] = kernel_integral(kernel, radius, hi) - kernel_integral(kernel, radius, lo);
  }
  return w;
}
}  // namespace detail

/// The discrete weights w_{−K} … w_K (K = ⌈r − ½⌉) of a kernel of radius r > 0 (finite):
/// w_k = ∫_{k−½}^{k+½} g(x) dx, computed from the kernel's closed-form integral.  They sum to 1 up
/// to rounding.  r ≤ ½ gives {1}.  Allocates 2K + 1 values (smooth_convolution itself needs at
/// most twice the number of points, whatever the radius).
template <Real T>
std::vector<T> kernel_weights(SmoothingKernel kernel, T radius) {
  const int K = radius > T(0.5) ? int(std::ceil(radius - T(0.5))) : 0;
  return detail::lumped_kernel_weights(kernel, radius, K);
}

/// Convolution smoothing (Eq. 3.39 on the step function of the points); see file comment.
template <Point P>
Expected<std::vector<P>> smooth_convolution(std::span<const P> points,
                                            const ConvolutionOptions<scalar_of<P>>& options = {}) {
  using T = scalar_of<P>;
  if (auto ok = detail::check_path_points(points); !ok) return ok.error();
  if (!(options.radius > T(0)) || !std::isfinite(options.radius))
    return Error{ErrorCode::InvalidArgument, "radius must be finite and > 0", "", {"radius"}};
  const int n = int(points.size());
  // Offsets beyond n − 1 always clamp to an end point, so their mass is lumped (any radius works).
  const T reach = std::ceil(options.radius - T(0.5));
  const int K = options.radius > T(0.5) ? int(std::fmin(reach, T(n - 1))) : 0;
  const std::vector<T> w = detail::lumped_kernel_weights(options.kernel, options.radius, K);
  std::vector<P> out(points.size());
  for (int i = 0; i < n; ++i) {
    P acc{};
    for (int k = -K; k <= K; ++k) acc += points[std::size_t(clamp(i + k, 0, n - 1))] * w[std::size_t(k + K)];
    out[std::size_t(i)] = acc;
  }
  if (options.fix_ends) {
    out.front() = points.front();
    out.back() = points.back();
  }
  return out;
}

/// Overloads for vectors (the span template cannot deduce from a vector).
template <Point P>
Expected<std::vector<P>> smooth_linear(const std::vector<P>& points, const LinearSmoothingOptions& options = {}) {
  return smooth_linear(std::span<const P>(points), options);
}
/// See smooth_cubic(std::span).
template <Point P>
Expected<std::vector<P>> smooth_cubic(const std::vector<P>& points, const CubicSmoothingOptions& options = {}) {
  return smooth_cubic(std::span<const P>(points), options);
}
/// See smooth_convolution(std::span).
template <Point P>
Expected<std::vector<P>> smooth_convolution(const std::vector<P>& points,
                                            const ConvolutionOptions<scalar_of<P>>& options = {}) {
  return smooth_convolution(std::span<const P>(points), options);
}

/// Resampling (§3.4.3: smoothing "with or without averaging down the number of points making up
/// the path", and "additional points"): `count` points equally spaced in arc length along the
/// polyline through `points` (arc length = the sum of chord lengths), the first and last points
/// kept exactly; point k lies at arc length L·k/(count − 1), linearly interpolated on its chord.
/// count may be smaller or larger than points.size().  Coincident consecutive points are passed
/// over; a polyline of length 0 gives `count` copies of its first point (documented fallback).
/// Errors: fewer than 2 points (TooFewPoints, {"points"}), a non-finite point (NotFinite,
/// {"points", i}), count < 2 (InvalidArgument, {"count"}), a length that overflows the scalar
/// (NotFinite, {"points"}).  Allocates the result only.
template <Point P>
Expected<std::vector<P>> resample_by_arc_length(std::span<const P> points, std::size_t count) {
  using T = scalar_of<P>;
  if (auto ok = detail::check_path_points(points, 2); !ok) return ok.error();
  if (count < 2)
    return Error{ErrorCode::InvalidArgument, "count must be at least 2 (the two ends), got " + std::to_string(count), "",
                 {"count"}};
  const std::size_t n = points.size();
  T total{};
  for (std::size_t i = 0; i + 1 < n; ++i) total += distance(points[i], points[i + 1]);
  if (!std::isfinite(total))
    return Error{ErrorCode::NotFinite, "the path's length overflows the number type", "", {"points"}};
  std::vector<P> out(count, points[0]);
  if (!(total > T(0))) return out;
  std::size_t j = 0;   // current chord [j, j + 1]
  T s_j{};             // arc length at points[j]
  T len_j = distance(points[0], points[1]);
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const T s = total * (T(k) / T(count - 1));
    while (j + 2 < n && s_j + len_j < s) {
      s_j += len_j;
      ++j;
      len_j = distance(points[j], points[j + 1]);
    }
    const T f = len_j > T(0) ? std::clamp((s - s_j) / len_j, T(0), T(1)) : T(0);
    out[k] = points[j] + (points[j + 1] - points[j]) * f;
  }
  out[count - 1] = points[n - 1];
  return out;
}

/// See resample_by_arc_length(std::span).
template <Point P>
Expected<std::vector<P>> resample_by_arc_length(const std::vector<P>& points, std::size_t count) {
  return resample_by_arc_length(std::span<const P>(points), count);
}

}  // namespace inbetween
