#pragma once
/// Measuring continuity at the joints of a curve (004 §3.1 "Continuity"; parametric C^k versus
/// geometric G¹): at each joint u_j between segments j − 1 and j, the jump of the position and of
/// the first three derivatives between the left limit (segment j − 1 at its end) and the right limit
/// (segment j at its start), and the angle between the two tangent directions.  For a closed curve
/// (one with `closed()` returning true) the seam from the end back to the start is a joint too.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "inbetween/curves/curve.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// Tolerances deciding when a measured jump counts as continuous.
template <Real T>
struct ContinuityTolerance {
  /// A derivative jump counts as zero when |jump| ≤ relative · max(|left|, |right|, scale), where
  /// scale is the size of the curve's control polygon (so zero-vs-tiny is not a discontinuity).
  T relative = T(1000) * std::numeric_limits<T>::epsilon();
  /// Tangent directions count as equal (G¹) when their angle is at most this (radians).
  T angle_rad = T(1e3) * std::sqrt(std::numeric_limits<T>::epsilon());
};

/// What happens at one joint.
template <Real T>
struct JointContinuity {
  T u{};                  ///< parameter of the joint (for the seam of a closed curve: the domain end)
  int left_segment = 0;   ///< the segment ending at the joint
  int right_segment = 0;  ///< the segment starting at the joint
  T jump[4]{};            ///< |right − left| of the position (0) and derivatives 1..3
  T size[4]{};            ///< max(|left|, |right|) of the same quantities
  bool continuous[4]{};   ///< jump[k] within tolerance: C^k holds when continuous[0..k] all hold
  bool tangent_defined = false;  ///< both first derivatives are non-zero
  T tangent_angle_rad{};  ///< angle between the left and right tangent directions (0 if undefined)
  bool g1 = false;        ///< C⁰ and tangent directions agree (G¹); false where a tangent vanishes

  /// The highest k (−1..3) such that C⁰..C^k all hold.
  int c_order() const noexcept {
    int k = -1;
    while (k < 3 && continuous[k + 1]) ++k;
    return k;
  }
};

namespace detail {
template <Point P>
scalar_of<P> tangent_angle(const P& a, const P& b) noexcept {
  using T = scalar_of<P>;
  const T na = norm(a), nb = norm(b);
  const P ua = a / na, ub = b / nb;
  // 2·atan2(|ua − ub|, |ua + ub|) is accurate for tiny and near-π angles alike.
  return T(2) * std::atan2(norm(P(ua - ub)), norm(P(ua + ub)));
}
}  // namespace detail

/// Measures one joint between the end of segment `left` (at u_left) and the start of segment
/// `right` (at u_right); `scale` is the size of the curve (see ContinuityTolerance).
template <SegmentedCurve C>
JointContinuity<typename C::scalar_type> measure_joint(const C& curve, int left, typename C::scalar_type u_left,
                                                       int right, typename C::scalar_type u_right,
                                                       typename C::scalar_type scale,
                                                       const ContinuityTolerance<typename C::scalar_type>& tol = {}) {
  using T = typename C::scalar_type;
  using P = typename C::point_type;
  JointContinuity<T> j;
  j.u = u_left;
  j.left_segment = left;
  j.right_segment = right;
  P l1{}, r1{};
  for (int k = 0; k < 4; ++k) {
    const P l = curve.segment_derivative(left, u_left, k);
    const P r = curve.segment_derivative(right, u_right, k);
    if (k == 1) l1 = l, r1 = r;
    j.jump[k] = norm(P(r - l));
    j.size[k] = std::max(norm(l), norm(r));
    j.continuous[k] = j.jump[k] <= tol.relative * std::max(j.size[k], scale);
  }
  j.tangent_defined = norm(l1) > T(0) && norm(r1) > T(0);
  if (j.tangent_defined) j.tangent_angle_rad = detail::tangent_angle(l1, r1);
  j.g1 = j.continuous[0] && j.tangent_defined && j.tangent_angle_rad <= tol.angle_rad;
  return j;
}

/// Measures every joint of `curve` (segment_count() − 1 joints, plus the seam of a closed curve).
template <SegmentedCurve C>
std::vector<JointContinuity<typename C::scalar_type>> measure_continuity(
    const C& curve, const ContinuityTolerance<typename C::scalar_type>& tol = {}) {
  using T = typename C::scalar_type;
  // Scale: the largest distance of a sampled point from the start, at least 1e-300-ish tiny.
  T scale = T(0);
  const auto dom = curve.domain();
  const auto p0 = curve.point(dom.lo);
  for (int i = 1; i <= 16; ++i) scale = std::max(scale, distance(p0, curve.point(dom.lo + dom.length() * T(i) / T(16))));
  std::vector<JointContinuity<T>> out;
  const int n = curve.segment_count();
  for (int i = 1; i < n; ++i) {
    const T u = curve.segment_domain(i).lo;
    out.push_back(measure_joint(curve, i - 1, u, i, u, scale, tol));
  }
  if constexpr (requires { curve.closed(); }) {
    if (curve.closed()) out.push_back(measure_joint(curve, n - 1, dom.hi, 0, dom.lo, scale, tol));
  }
  return out;
}

}  // namespace inbetween
