#pragma once
/// Parabolic blending (004 §3.1 and App. B.5; Overhauser's construction): on the segment from P_i
/// to P_{i+1}, blend the parabola Q through P_{i−1}, P_i, P_{i+1} with the parabola R through P_i,
/// P_{i+1}, P_{i+2} linearly, C(v) = (1 − v) Q(v) + v R(v), v ∈ [0, 1], with the parabolas placed
/// at v = −1, 0, 1 and v = 0, 1, 2 (uniform spacing).  The first segment has no P_{−1} and is R
/// alone; the last has no P_{n} and is Q alone; two points give the straight segment.  Interior
/// segments coincide with Catmull-Rom (s = 1/2); the ends differ (a parabola instead of a phantom
/// point).  C¹ at every joint; segment i runs over u ∈ [t_i, t_{i+1}] (default t_i = i).  With
/// non-uniform parameters the parabolas pass through the points at their parameters: in the local
/// v = (t − t_i)/h_i, Q's nodes are v = −h_{i−1}/h_i, 0, 1 and R's are v = 0, 1, 1 + h_{i+1}/h_i; the
/// blend is still C¹ in t (at t_i both sides have the slope of the parabola through P_{i−1}, P_i, P_{i+1}).

#include <span>
#include <vector>

#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {

/// An interpolating C¹ parabolic-blend spline, domain [0, n − 1].  Local control: point i
/// influences segments i − 2 .. i + 1.
template <Point P>
class ParabolicBlendSpline : public PiecewiseCubic<P> {
 public:
  using T = scalar_of<P>;  ///< the scalar of P

  /// Builds through `points` (≥ 2, finite) at `params` (one per point, strictly increasing; empty:
  /// 0, 1, …; error location {"params", i}).
  static Expected<ParabolicBlendSpline> build(std::span<const P> points, std::span<const T> params = {}) {
    if (auto ok = detail::check_points(points, 2, "parabolic"); !ok) return ok.error();
    const int n = int(points.size());
    auto tp = detail::check_params(params, points.size(), "parabolic");
    if (!tp) return tp.error();
    const std::vector<T>& t = *tp;
    ParabolicBlendSpline s;
    s.breaks_ = t;
    s.segments_.clear();
    const T h = T(0.5);
    for (int i = 0; i + 1 < n; ++i) {
      const P& p0 = points[i];
      const P& p1 = points[i + 1];
      const bool has_prev = i > 0, has_next = i + 2 < n;
      // Power coefficients (constant, linear, square) of Q and R in v.
      P q1{}, q2{}, r1{}, r2{};
      const T hi = t[i + 1] - t[i];
      if (has_prev) {
        const P& pm = points[i - 1];
        const T r = (t[i] - t[i - 1]) / hi;  // Q's first node is at v = −r
        if (r == T(1)) {
          q1 = (p1 - pm) * h;
          q2 = (pm - p0 * T(2) + p1) * h;
        } else {  // q(v) = p0 + q1 v + q2 v² with q(1) = p1, q(−r) = pm
          q2 = (pm - p0 + (p1 - p0) * r) / (r * (r + T(1)));
          q1 = (p1 - p0) - q2;
        }
      }
      if (has_next) {
        const P& p2 = points[i + 2];
        const T r = (t[i + 2] - t[i + 1]) / hi;  // R's last node is at v = 1 + r
        if (r == T(1)) {
          r1 = (p1 * T(4) - p0 * T(3) - p2) * h;
          r2 = (p0 - p1 * T(2) + p2) * h;
        } else {  // r(v) = p0 + r1 v + r2 v² with r(1) = p1, r(1 + r) = p2
          r2 = (p2 - p0 - (p1 - p0) * (T(1) + r)) / (r * (T(1) + r));
          r1 = (p1 - p0) - r2;
        }
      }
      PowerCubic<P> seg;
      seg.d = p0;
      if (has_prev && has_next) {  // (1 − v) Q + v R
        seg.c = q1;
        seg.b = q2 + r1 - q1;
        seg.a = r2 - q2;
      } else if (has_next) {  // R alone
        seg.c = r1;
        seg.b = r2;
      } else if (has_prev) {  // Q alone
        seg.c = q1;
        seg.b = q2;
      } else {  // two points: the straight segment
        seg.c = p1 - p0;
      }
      s.segments_.push_back(seg);
    }
    s.controls_.assign(points.begin(), points.end());
    s.influence_.clear();
    for (int i = 0; i < n; ++i) s.influence_.push_back(s.segments_range(i - 2, i + 1));
    s.interpolates_ = true;
    if (auto ok = s.finish_build("parabolic"); !ok) return ok.error();
    return s;
  }

 private:
  /// The empty curve the builder fills; built curves only come from build() (house style).
  ParabolicBlendSpline() = default;
};

/// Builds a parabolic-blend spline; see ParabolicBlendSpline::build.
template <Point P>
Expected<ParabolicBlendSpline<P>> build_parabolic_blend(std::span<const P> points,
                                                        std::span<const scalar_of<P>> params = {}) {
  return ParabolicBlendSpline<P>::build(points, params);
}
/// Overload for vectors.
template <Point P>
Expected<ParabolicBlendSpline<P>> build_parabolic_blend(const std::vector<P>& points,
                                                        const std::vector<scalar_of<P>>& params = {}) {
  return ParabolicBlendSpline<P>::build(points, params);
}

}  // namespace inbetween
