#pragma once
/// Bézier curves of any degree n (texts 000 §2.3.2, 002 on why control points are intuitive):
/// P(u) = Σ_k B_{k,n}(u) P_k with the Bernstein polynomials B_{k,n}(u) = C(n,k) u^k (1 − u)^{n−k},
/// u ∈ [0, 1].  Evaluation by de Casteljau's repeated linear interpolation; derivatives from the
/// hodograph (the k-th derivative is the degree n − k Bézier curve of the k-th forward differences
/// times n!/(n − k)!); subdivision at u; degree elevation.

#include <array>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// The Bernstein polynomial B_{i,n}(u) = C(n,i) u^i (1 − u)^{n−i}; zero for i outside [0, n].
template <Real T>
T bernstein(int n, int i, T u) noexcept {
  if (i < 0 || i > n) return T(0);
  T binom = T(1);
  for (int j = 1; j <= i; ++j) binom = binom * T(n - i + j) / T(j);
  T r = binom;
  for (int j = 0; j < i; ++j) r *= u;
  for (int j = 0; j < n - i; ++j) r *= (T(1) - u);
  return r;
}

/// de Casteljau's algorithm on `scratch` (the control points, overwritten): the point at u.  Each
/// step is the convex blend (1 − u)·a + u·b, so u = 0 and u = 1 return the end points exactly.
/// Precondition: scratch is not empty.
template <Point P>
P de_casteljau(std::span<P> scratch, scalar_of<P> u) noexcept {
  const int n = int(scratch.size());
  const scalar_of<P> v = scalar_of<P>(1) - u;
  for (int r = 1; r < n; ++r)
    for (int i = 0; i < n - r; ++i) scratch[i] = scratch[i] * v + scratch[i + 1] * u;
  return scratch[0];
}

/// Σ_k B_{k,n}(u) P_k evaluated literally with bernstein() (the reference form; slower than de Casteljau).
template <Point P>
P bernstein_sum(std::span<const P> points, scalar_of<P> u) noexcept {
  P r{};
  const int n = int(points.size()) - 1;
  for (int k = 0; k <= n; ++k) r = r + points[k] * bernstein(n, k, u);
  return r;
}

/// A single Bézier curve of degree n = (number of points − 1) ≥ 1, domain [0, 1], one segment.
/// Passes through its first and last control points only; every control point influences the
/// whole curve (global control).
template <Point P>
class BezierCurve {
 public:
  using point_type = P;              ///< the point type (scalar, Vec2, Vec3, Vec4)
  using scalar_type = scalar_of<P>;  ///< its scalar
  using T = scalar_type;             ///< shorthand

  /// Builds from ≥ 2 finite control points.
  static Expected<BezierCurve> build(std::span<const P> points) {
    if (auto ok = detail::check_points(points, 2, "bezier"); !ok) return ok.error();
    return BezierCurve(std::vector<P>(points.begin(), points.end()));
  }

  /// Degree n.
  int degree() const noexcept { return int(points_.size()) - 1; }
  /// [0, 1].
  Interval<T> domain() const noexcept { return {T(0), T(1)}; }
  /// 1.
  int segment_count() const noexcept { return 1; }
  /// [0, 1].
  Interval<T> segment_domain(int) const noexcept { return domain(); }
  /// P(u) by de Casteljau, u clamped into [0, 1].
  P point(T u) const noexcept { return evaluate(points_, domain().clamp(u)); }
  /// d^kP/du^k (any k ≥ 0; zero for k > n), u clamped.
  P derivative(T u, int k) const noexcept {
    if (k <= 0) return point(u);
    if (k > degree()) return P{};
    if (k <= 3) return evaluate(hodographs_[k - 1], domain().clamp(u)) * falling_[k - 1];
    std::vector<P> d = points_;
    for (int r = 0; r < k; ++r)
      for (std::size_t i = 0; i + 1 < d.size() - r; ++i) d[i] = (d[i + 1] - d[i]) * T(degree() - r);
    d.resize(points_.size() - k);
    return evaluate(d, domain().clamp(u));
  }
  /// Same as derivative (one segment).
  P segment_derivative(int, T u, int k) const noexcept { return derivative(u, k); }
  /// Number of control points (n + 1).
  int control_point_count() const noexcept { return int(points_.size()); }
  /// Control point i (clamped index).
  P control_point(int i) const noexcept { return points_[std::clamp(i, 0, control_point_count() - 1)]; }
  /// The control points.
  std::span<const P> control_points() const noexcept { return points_; }
  /// False: only the end points lie on the curve (true for degree 1).
  bool interpolates_control_points() const noexcept { return degree() == 1; }
  /// [0, 1] for every control point (global control).
  Interval<T> influence(int) const noexcept { return domain(); }

  /// The two halves [0, u] and [u, 1], each reparameterised to [0, 1] (u clamped into [0, 1]).
  std::pair<BezierCurve, BezierCurve> subdivide(T u) const {
    u = domain().clamp(u);
    std::vector<P> d = points_, left, right(points_.size());
    const int n = degree();
    left.push_back(d[0]);
    right[n] = d[n];
    for (int r = 1; r <= n; ++r) {
      for (int i = 0; i <= n - r; ++i) d[i] = d[i] + (d[i + 1] - d[i]) * u;
      left.push_back(d[0]);
      right[n - r] = d[n - r];
    }
    return {BezierCurve(std::move(left)), BezierCurve(std::move(right))};
  }

  /// The same curve as a Bézier curve of degree n + 1: Q_i = (i/(n+1)) P_{i−1} + (1 − i/(n+1)) P_i.
  BezierCurve elevate_degree() const {
    const int n = degree();
    std::vector<P> q(n + 2);
    q[0] = points_[0];
    q[n + 1] = points_[n];
    for (int i = 1; i <= n; ++i) {
      const T a = T(i) / T(n + 1);
      q[i] = points_[i - 1] * a + points_[i] * (T(1) - a);
    }
    return BezierCurve(std::move(q));
  }

 private:
  explicit BezierCurve(std::vector<P> points) : points_(std::move(points)) {
    std::vector<P> d = points_;
    for (int k = 0; k < 3; ++k) {
      const int m = int(d.size()) - 1;
      if (m < 1) {
        hodographs_[k] = {P{}};
        falling_[k] = T(0);
        continue;
      }
      for (int i = 0; i < m; ++i) d[i] = d[i + 1] - d[i];
      d.resize(m);
      hodographs_[k] = d;
      falling_[k] = (k == 0 ? T(1) : falling_[k - 1]) * T(m);
    }
  }

  static P evaluate(const std::vector<P>& pts, T u) noexcept {
    constexpr std::size_t kInline = 24;
    if (pts.size() <= kInline) {
      // Raw storage: a std::array<P, 24> would value-initialise all 24 points (Vec has default
      // member initialisers) on every call, to use only pts.size() of them.
      static_assert(std::is_trivially_copyable_v<P> && std::is_trivially_destructible_v<P>);
      alignas(P) unsigned char storage[sizeof(P) * kInline];
      P* scratch = std::uninitialized_copy(pts.begin(), pts.end(), reinterpret_cast<P*>(storage)) - pts.size();
      return de_casteljau(std::span<P>(scratch, pts.size()), u);
    }
    return bernstein_sum(std::span<const P>(pts), u);
  }

  std::vector<P> points_;
  std::array<std::vector<P>, 3> hodographs_;  ///< forward differences of order 1..3
  std::array<T, 3> falling_{};                ///< n, n(n−1), n(n−1)(n−2)
};

/// The same curve as a one-segment PiecewiseCubic over [0, 1], for degree ≤ 3 (power form from the
/// Bernstein coefficients).  Error Unsupported at {"degree"} for degree > 3.
template <Point P>
Expected<PiecewiseCubic<P>> to_piecewise_cubic(const BezierCurve<P>& bezier) {
  using T = scalar_of<P>;
  if (bezier.degree() > 3)
    return Error{ErrorCode::unsupported,
                 "only Bezier curves of degree <= 3 are cubics, got degree " + std::to_string(bezier.degree()), {"degree"}};
  const auto e = bezier.degree() == 3 ? bezier : bezier.degree() == 2 ? bezier.elevate_degree()
                                                                      : bezier.elevate_degree().elevate_degree();
  const auto p = e.control_points();
  // Bézier basis matrix rows (000 §2.3.2): a = −P0 + 3P1 − 3P2 + P3, b = 3P0 − 6P1 + 3P2, c = −3P0 + 3P1, d = P0.
  PowerCubic<P> g{p[3] - p[0] + (p[1] - p[2]) * T(3), (p[0] - p[1] * T(2) + p[2]) * T(3), (p[1] - p[0]) * T(3), p[0]};
  return PiecewiseCubic<P>::from_power_forms(std::vector<T>{T(0), T(1)}, std::vector<PowerCubic<P>>{g});
}

/// Builds a Bézier curve of degree points.size() − 1; see BezierCurve::build.
template <Point P>
Expected<BezierCurve<P>> build_bezier(std::span<const P> points) {
  return BezierCurve<P>::build(points);
}
/// Overload for vectors.
template <Point P>
Expected<BezierCurve<P>> build_bezier(const std::vector<P>& points) {
  return BezierCurve<P>::build(points);
}

}  // namespace inbetween
