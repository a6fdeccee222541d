#pragma once
/// Lagrange interpolation (004 §3.1, the texts' example of global control): the single polynomial
/// of degree n − 1 through n points P_i at strictly increasing parameters u_i (default 0, 1, …,
/// n − 1).  Stored in Newton's divided-difference form and evaluated by nested multiplication, with
/// derivatives carried along.  With many equally spaced parameters it oscillates near the ends
/// (Runge's phenomenon) — the reason animation uses piecewise cubics instead.

#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "inbetween/curves/piecewise_cubic.hpp"
#include "inbetween/math/format.hpp"

namespace inbetween {

/// The interpolating polynomial through (u_i, P_i); domain [u_0, u_{n−1}], one segment.  Every
/// point influences the whole domain (global control).
template <Point P>
class LagrangeCurve {
 public:
  using point_type = P;              ///< the point type (scalar, Vec2, Vec3, Vec4)
  using scalar_type = scalar_of<P>;  ///< its scalar
  using T = scalar_type;             ///< shorthand

  /// Builds through `points` (≥ 2, finite) at `params` (same count, finite, strictly increasing;
  /// empty = 0, 1, …, n − 1).  Error locations: {"points", i}, {"params", i}, or {"params"} when the divided
  /// differences overflow (params too close together for T).
  static Expected<LagrangeCurve> build(std::span<const P> points, std::span<const T> params = {}) {
    if (auto ok = detail::check_points(points, 2, "lagrange"); !ok) return ok.error();
    const int n = int(points.size());
    LagrangeCurve c;
    c.points_.assign(points.begin(), points.end());
    if (params.empty()) {
      c.params_.resize(n);
      for (int i = 0; i < n; ++i) c.params_[i] = T(i);
    } else {
      if (int(params.size()) != n)
        return Error{ErrorCode::wrong_arity,
                     "lagrange needs one param per point: " + std::to_string(n) + " points but " +
                         std::to_string(params.size()) + " params", {"params"}};
      for (int i = 0; i < n; ++i) {
        if (!std::isfinite(params[i]))
          return Error{ErrorCode::not_finite, "param " + std::to_string(i) + " is not finite", {"params", std::size_t(i)}};
        if (i > 0 && !(params[i] > params[i - 1]))
          return Error{ErrorCode::keys_not_increasing,
                       "param " + std::to_string(i) + " (" + shortest_text<double>(double(params[i])) +
                           ") is not greater than param " + std::to_string(i - 1) + " (" +
                           shortest_text<double>(double(params[i - 1])) + ")", {"params", std::size_t(i)}};
      }
      c.params_.assign(params.begin(), params.end());
    }
    // Divided differences in place: coeffs_[k] = P[u_0, …, u_k].
    c.coeffs_ = c.points_;
    for (int k = 1; k < n; ++k)
      for (int i = n - 1; i >= k; --i)
        c.coeffs_[i] = (c.coeffs_[i] - c.coeffs_[i - 1]) / (c.params_[i] - c.params_[i - k]);
    // Finite data can still overflow the divided differences (params too close together for the
    // scalar type, or huge coordinates): an error, never a curve that evaluates to inf or NaN.
    for (int i = 0; i < n; ++i) {
      if (!is_finite(c.coeffs_[i]))
        return Error{ErrorCode::not_finite,
                     "divided difference " + std::to_string(i) +
                         " overflows: the params are too close together (or the points too large) for this "
                         "scalar type", {"params"}};
    }
    return c;
  }

  /// [u_0, u_{n−1}].
  Interval<T> domain() const noexcept { return {params_.front(), params_.back()}; }
  /// 1.
  int segment_count() const noexcept { return 1; }
  /// The domain.
  Interval<T> segment_domain(int) const noexcept { return domain(); }
  /// P(u), u clamped.
  P point(T u) const noexcept { return derivative(u, 0); }
  /// d^kP/du^k for k = 0..3 (higher orders are not provided and return zero), u clamped.  Never
  /// NaN: when the nested evaluation would overflow an intermediate (values near the largest
  /// finite T, where the Newton terms are larger than the result), it is redone with a shared
  /// power-of-two exponent carried beside the partial sums, so the result is finite whenever the
  /// true value is representable and saturates to ±inf only where it is not (a derivative, or a
  /// polynomial overshooting past T between its points).
  P derivative(T u, int k) const noexcept {
    u = domain().clamp(u);
    if (k < 0 || k > 3) return P{};
    const P plain = derivative_plain(u, k);
    if (is_finite(plain)) return plain;
    return derivative_scaled(u, k);
  }
  /// Same as derivative (one segment).
  P segment_derivative(int, T u, int k) const noexcept { return derivative(u, k); }
  /// Number of points.
  int control_point_count() const noexcept { return int(points_.size()); }
  /// Point i (clamped index).
  P control_point(int i) const noexcept { return points_[std::clamp(i, 0, control_point_count() - 1)]; }
  /// All points.
  std::span<const P> control_points() const noexcept { return points_; }
  /// The parameters u_i.
  std::span<const T> params() const noexcept { return params_; }
  /// True.
  bool interpolates_control_points() const noexcept { return true; }
  /// The whole domain (global control).
  Interval<T> influence(int) const noexcept { return domain(); }

 private:
  /// The empty curve build() fills.
  LagrangeCurve() = default;

  // Nested multiplication of the Newton form with the derivatives carried along (u in the domain).
  P derivative_plain(T u, int k) const noexcept {
    P d0{}, d1{}, d2{}, d3{};
    for (int i = int(coeffs_.size()) - 1; i >= 0; --i) {
      const T x = u - params_[i];
      d3 = d3 * x + d2 * T(3);
      d2 = d2 * x + d1 * T(2);
      d1 = d1 * x + d0;
      d0 = d0 * x + coeffs_[i];
    }
    switch (k) {
      case 0: return d0;
      case 1: return d1;
      case 2: return d2;
      default: return d3;
    }
  }

  // The same recurrence on d_j · 2^e with one shared exponent e: before each step the partial
  // sums are brought to the exponent of the larger of x and the coefficient, so every stored
  // number stays below 2^4 in magnitude; the exponent is applied once at the end (±inf there only
  // when the true value exceeds T).  Terms below 2^(e − 1074) are dropped: they are far below
  // the rounding of the result.
  P derivative_scaled(T u, int k) const noexcept {
    std::array<P, 4> d{};
    int e = 0;
    bool started = false;
    const auto rescale = [&](int new_e) {
      for (P& v : d) v = scale_by_pow2(v, e - new_e);
      e = new_e;
    };
    for (int i = int(coeffs_.size()) - 1; i >= 0; --i) {
      const T x = u - params_[i];
      int ex = 0;
      const T fx = std::frexp(x, &ex);  // x = fx·2^ex, |fx| in [0.5, 1) (or 0)
      // Multiply by x: the products get exponent e + ex; the added terms (3·d2, 2·d1, d0) keep e.
      if (ex > 0) {
        const P a3 = d[3] * fx + scale_by_pow2(P(d[2] * T(3)), -ex);
        const P a2 = d[2] * fx + scale_by_pow2(P(d[1] * T(2)), -ex);
        const P a1 = d[1] * fx + scale_by_pow2(d[0], -ex);
        const P a0 = d[0] * fx;
        d = {a0, a1, a2, a3};
        e += ex;
      } else {
        const P a3 = d[3] * x + d[2] * T(3);
        const P a2 = d[2] * x + d[1] * T(2);
        const P a1 = d[1] * x + d[0];
        const P a0 = d[0] * x;
        d = {a0, a1, a2, a3};
      }
      // Add the coefficient at a common exponent.
      const T cbig = max_abs_component(coeffs_[i]);
      int ec = 0;
      if (cbig > T(0)) std::frexp(cbig, &ec);
      if (!started) {
        e = ec;
        started = true;
      } else if (cbig > T(0) && ec > e) {
        rescale(ec);
      }
      d[0] = d[0] + scale_by_pow2(coeffs_[i], -e);
      // Keep the partial sums below 2^4.
      T big{};
      for (const P& v : d) big = std::fmax(big, max_abs_component(v));
      if (big > T(8)) {
        int eb = 0;
        std::frexp(big, &eb);
        rescale(e + eb);
      }
    }
    return scale_by_pow2(d[std::size_t(k)], e);
  }

  std::vector<T> params_;
  std::vector<P> points_;
  std::vector<P> coeffs_;
};

/// Builds a Lagrange interpolating curve; see LagrangeCurve::build.
template <Point P>
Expected<LagrangeCurve<P>> build_lagrange(std::span<const P> points, std::span<const scalar_of<P>> params = {}) {
  return LagrangeCurve<P>::build(points, params);
}
/// Overload for vectors.
template <Point P>
Expected<LagrangeCurve<P>> build_lagrange(const std::vector<P>& points, const std::vector<scalar_of<P>>& params = {}) {
  return LagrangeCurve<P>::build(points, params);
}

}  // namespace inbetween
