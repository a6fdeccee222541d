#pragma once
/// Interpolation of orientation in every representation the texts discuss, so that the
/// differences can be shown side by side: element-wise matrix lerp (wrong: leaves the rotation
/// group), Euler-angle lerp (uneven speed, convention dependent), axis-angle interpolation, nlerp
/// (right path, uneven speed) and slerp (the great arc at constant angular speed).
/// u is the interpolation parameter in [0, 1] (not clamped: values outside extrapolate).

#include <cmath>

#include "inbetween/math/euler.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"

namespace inbetween {

/// Which of the two arcs between the rotations a quaternion interpolation follows.
enum class RotationPath {
  Shortest,  ///< flip b to −b when a·b < 0: the rotation turns by at most 180° (the default)
  Longest,   ///< flip b to −b when a·b > 0: the same end rotations reached the long way round
  AsGiven,   ///< no flip: the great arc between the quaternions exactly as given on S³
};

/// Options of nlerp() and slerp().
struct SlerpOptions {
  RotationPath path = RotationPath::Shortest;  ///< which arc to follow
};

/// Element-wise linear blend (1 − u)·A + u·B of two matrices.  Shown only as the texts' warning:
/// the result is in general not a rotation — R_z(90°) and R_z(−90°) blend at u = ½ to
/// diag(0, 0, 1), which flattens every object onto the z axis.
template <Real T>
Mat3<T> matrix_lerp(const Mat3<T>& a, const Mat3<T>& b, T u) noexcept {
  if (u == T(1)) return b;
  return a + (b - a) * u;
}

/// Angle-by-angle linear blend of two Euler triples of the same convention (radians).  The path
/// depends on the convention and on the 2π representatives chosen (see euler_filter()), and its
/// angular speed is uneven.
template <Real T>
EulerTriple<T> euler_lerp(const EulerTriple<T>& a, const EulerTriple<T>& b, T u) noexcept {
  return {lerp(a[0], b[0], u), lerp(a[1], b[1], u), lerp(a[2], b[2], u)};
}

namespace detail {
/// A unit vector perpendicular to the unit vector v.
template <Real T>
Vec3<T> any_perpendicular(const Vec3<T>& v) noexcept {
  const Vec3<T> helper = std::abs(v.x) <= std::abs(v.y) && std::abs(v.x) <= std::abs(v.z)
                             ? Vec3<T>{T(1), T(0), T(0)}
                             : (std::abs(v.y) <= std::abs(v.z) ? Vec3<T>{T(0), T(1), T(0)} : Vec3<T>{T(0), T(0), T(1)});
  return normalized(cross(v, helper), Vec3<T>{T(1), T(0), T(0)});
}
}  // namespace detail

/// Interpolation of the axis-angle pairs themselves, as the texts suggest: the unit axis moves
/// along the great circle from a.axis to b.axis at constant speed, and the angle is blended
/// linearly.  Not the geodesic between the rotations (slerp is); axes are normalised first.
/// Opposite axes have no unique great circle: a documented perpendicular is used.
template <Real T>
AxisAngle<T> axis_angle_interp(const AxisAngle<T>& a, const AxisAngle<T>& b, T u) noexcept {
  if (u == T(0)) return a;
  if (u == T(1)) return b;
  const Vec3<T> ea = normalized(a.axis, Vec3<T>{T(1), T(0), T(0)});
  const Vec3<T> eb = normalized(b.axis, Vec3<T>{T(1), T(0), T(0)});
  const T angle = T(2) * std::atan2(norm(eb - ea), norm(eb + ea));  // angle between the axes
  Vec3<T> dir = eb - ea * dot(ea, eb);
  dir = normalized(dir, detail::any_perpendicular(ea));
  const Vec3<T> axis = ea * std::cos(u * angle) + dir * std::sin(u * angle);
  return {normalized(axis, ea), lerp(a.angle_rad, b.angle_rad, u)};
}

namespace detail {
/// b or −b according to the path choice relative to a.
template <Real T>
Quat<T> oriented_end(const Quat<T>& a, const Quat<T>& b, RotationPath path) noexcept {
  const T d = dot(a, b);
  if (path == RotationPath::Shortest && d < T(0)) return -b;
  if (path == RotationPath::Longest && d > T(0)) return -b;
  return b;
}
}  // namespace detail

/// Normalised linear blend of unit quaternions: follows the same arc as slerp but with uneven
/// angular speed (fastest in the middle).  Returns a at u = 0 and the oriented b (b or −b) at u = 1
/// exactly.  A zero blend (antipodal inputs with RotationPath::AsGiven at u = ½) gives a.
template <Real T>
Quat<T> nlerp(const Quat<T>& a, const Quat<T>& b_in, T u, const SlerpOptions& options = {}) noexcept {
  const Quat<T> b = detail::oriented_end(a, b_in, options.path);
  if (u == T(0)) return a;
  if (u == T(1)) return b;
  const Quat<T> m = a * (T(1) - u) + b * u;
  const T n = norm(m);
  if (!(n > T(0))) return a;
  return m / n;
}

/// Spherical linear interpolation of unit quaternions: the great arc from a to the oriented b at
/// constant angular speed.  Computed in an orthonormal basis of the arc's plane,
///   q(u) = cos(uθ)·a + sin(uθ)·d̂,  d = b − (a·b)·a,  θ = 2·atan2(|b − a|, |b + a|),
/// which needs no division by sin θ and hence no small-angle cut-off: for θ → 0 the error of d̂
/// (relative eps/θ) is multiplied by sin(uθ) ≈ uθ, leaving an absolute error of a few ulp.  Only
/// d = 0 is special: for identical inputs the result is a; for exactly antipodal inputs under
/// Longest/AsGiven (no unique arc) the arc through a·i (a full turn about the body x axis) is
/// taken.  Returns a at u = 0 and the oriented b at u = 1 exactly; unit norm within a few ulp;
/// never NaN for finite unit inputs.
template <Real T>
Quat<T> slerp(const Quat<T>& a, const Quat<T>& b_in, T u, const SlerpOptions& options = {}) noexcept {
  const Quat<T> b = detail::oriented_end(a, b_in, options.path);
  if (u == T(0)) return a;
  if (u == T(1)) return b;
  // Plain √(Σx²) suffices for unit-magnitude inputs (no overflow; an underflowing square only
  // affects differences below 1e-154, whose contribution is below any ulp of the result).
  const T theta = T(2) * std::atan2(std::sqrt(squared_norm(b - a)), std::sqrt(squared_norm(b + a)));
  Quat<T> d = b - a * dot(a, b);
  const T dn = std::sqrt(squared_norm(d));
  if (dn > T(0)) {
    d = d / dn;
  } else {
    d = a * Quat<T>{T(0), T(1), T(0), T(0)};  // a·i is perpendicular to a on S³
  }
  const T phi = u * theta;
  return a * std::cos(phi) + d * std::sin(phi);
}

/// Slerp through quaternion powers, a·(a⁻¹b)^u, using exp/log of quat.hpp — the textbook
/// identity, kept as an independent second formulation for tests and benchmarks.
template <Real T>
Quat<T> slerp_by_power(const Quat<T>& a, const Quat<T>& b_in, T u, const SlerpOptions& options = {}) noexcept {
  const Quat<T> b = detail::oriented_end(a, b_in, options.path);
  return a * pow(conjugate(a) * b, u);
}

}  // namespace inbetween
