#pragma once
/// Conversions between the rotation representations: rotation matrix (Mat3, v' = R v), unit
/// quaternion (Hamilton, w first), axis-angle and rotation vector; and a check that a Mat3 is a
/// rotation.  Angles come from atan2 of well-conditioned quantities (never acos/asin of a clamped
/// dot), so every conversion is accurate to a few units in the last place, also near 0 and 180°.
/// Euler angles live in euler.hpp.  See docs/conventions.md.

#include <cmath>
#include <cstdio>
#include <string>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"

namespace inbetween {

namespace detail {
/// A number for an error message: six significant digits ("%g").
inline std::string message_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace detail

/// A rotation by `angle_rad` about the unit vector `axis` (right-hand rule).  Default: identity
/// about x.  Functions that return one give angle_rad in [0, π] and a unit axis.
template <Real T>
struct AxisAngle {
  Vec3<T> axis{T(1), T(0), T(0)};  ///< unit rotation axis
  T angle_rad{};                   ///< rotation angle in radians
  /// Exact equality of axis and angle (not equality of rotations: see angle_between).
  friend constexpr bool operator==(const AxisAngle&, const AxisAngle&) = default;
};

using AxisAnglef = AxisAngle<float>;   ///< single-precision axis-angle
using AxisAngled = AxisAngle<double>;  ///< double-precision axis-angle

/// The representative of ±q with w > 0; when w == 0 the first non-zero of x, y, z is made
/// positive.  Used for every quaternion this library returns from a conversion, so that printed
/// quaternions are unique.
template <Real T>
constexpr Quat<T> canonical(const Quat<T>& q) noexcept {
  if (q.w > T(0)) return q;
  if (q.w < T(0)) return -q;
  if (q.x != T(0)) return q.x > T(0) ? q : -q;
  if (q.y != T(0)) return q.y > T(0) ? q : -q;
  return q.z >= T(0) ? q : -q;
}

/// Rotation matrix of the quaternion q of any non-zero length (the scale cancels; zero or
/// non-finite q gives the identity).
/// v' = R v equals rotate(q, v).
template <Real T>
Mat3<T> matrix_from_quat(const Quat<T>& q_in) noexcept {
  // Scaling by 2/|q|² instead of normalising first saves a square root and a rounding per entry.
  const T n2 = squared_norm(q_in);
  const bool usable = is_finite(q_in) && n2 > T(0) && std::isfinite(n2) && std::isnormal(n2);
  const Quat<T> q = usable ? q_in : normalized(q_in);
  const T s = usable ? T(2) / n2 : T(2);
  const T x2 = q.x * s, y2 = q.y * s, z2 = q.z * s;
  const T xx = q.x * x2, yy = q.y * y2, zz = q.z * z2;
  const T xy = q.x * y2, xz = q.x * z2, yz = q.y * z2;
  const T wx = q.w * x2, wy = q.w * y2, wz = q.w * z2;
  return {{{T(1) - (yy + zz), xy - wz, xz + wy},
           {xy + wz, T(1) - (xx + zz), yz - wx},
           {xz - wy, yz + wx, T(1) - (xx + yy)}}};
}

/// Unit quaternion (canonical: w ≥ 0) of a rotation matrix, by Shepperd's method: the largest of
/// 4w², 4x², 4y², 4z² (read off the trace and the diagonal) is taken by a square root and the other
/// three components come from off-diagonal sums and differences divided by it, so no component is
/// ever obtained from a small, cancelling square root — accurate for every rotation, 180° included.
/// For a matrix that is only nearly a rotation the result is normalised (a nearby rotation).
template <Real T>
Quat<T> quat_from_matrix(const Mat3<T>& r) noexcept {
  const auto& m = r.m;
  const T trace = m[0][0] + m[1][1] + m[2][2];
  Quat<T> q;
  if (trace >= m[0][0] && trace >= m[1][1] && trace >= m[2][2]) {
    const T s = T(2) * std::sqrt(T(1) + trace);  // 4|w|
    q = {s / T(4), (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
  } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
    const T s = T(2) * std::sqrt(T(1) + m[0][0] - m[1][1] - m[2][2]);  // 4|x|
    q = {(m[2][1] - m[1][2]) / s, s / T(4), (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
  } else if (m[1][1] >= m[2][2]) {
    const T s = T(2) * std::sqrt(T(1) + m[1][1] - m[0][0] - m[2][2]);  // 4|y|
    q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, s / T(4), (m[1][2] + m[2][1]) / s};
  } else {
    const T s = T(2) * std::sqrt(T(1) + m[2][2] - m[0][0] - m[1][1]);  // 4|z|
    q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / T(4)};
  }
  return canonical(normalized(q));
}

/// Axis-angle of the rotation q (normalised here): angle = 2·atan2(|v|, |w|) in [0, π], axis the
/// unit vector part of canonical(q).  The identity gives axis (1, 0, 0) and angle 0.
template <Real T>
AxisAngle<T> axis_angle_from_quat(const Quat<T>& q_in) noexcept {
  const Quat<T> q = canonical(normalized(q_in));
  const T n = norm(q.vec());
  if (!(n > T(0))) return {};
  return {q.vec() / n, T(2) * std::atan2(n, q.w)};
}

/// Quaternion of an axis-angle (the axis is normalised; a zero or non-finite axis gives the
/// identity).  Any angle is accepted; the result is canonical (w ≥ 0).
template <Real T>
Quat<T> quat_from_axis_angle(const AxisAngle<T>& aa) noexcept {
  return canonical(Quat<T>::from_axis_angle(aa.axis, aa.angle_rad));
}

/// Rotation vector (axis × angle, |r| in [0, π]) of the rotation q (normalised here).
template <Real T>
Vec3<T> rotation_vector_from_quat(const Quat<T>& q_in) noexcept {
  const Quat<T> q = canonical(normalized(q_in));
  const T n = norm(q.vec());
  if (!(n > T(0))) return {};
  // 2·atan2(n, w)/n is the exact ratio angle/|v|; both factors are accurate for tiny and
  // near-π angles, so no series cut-off is needed (n > 0 here).
  return q.vec() * (T(2) * std::atan2(n, q.w) / n);
}

/// Quaternion of a rotation vector r (angle |r| about r/|r|; any length); zero gives the identity.
/// sin(|r|/2)/|r| is evaluated directly: both are accurate for tiny |r|, so no cut-off is needed.
template <Real T>
Quat<T> quat_from_rotation_vector(const Vec3<T>& r) noexcept {
  const T angle = norm(r);
  if (!(angle > T(0)) || !std::isfinite(angle)) return {};
  const T s = std::sin(angle / T(2)) / angle;
  return canonical(Quat<T>{std::cos(angle / T(2)), r.x * s, r.y * s, r.z * s});
}

/// Rotation matrix of an axis-angle (through the quaternion; zero axis gives the identity).
template <Real T>
Mat3<T> matrix_from_axis_angle(const AxisAngle<T>& aa) noexcept {
  return matrix_from_quat(Quat<T>::from_axis_angle(aa.axis, aa.angle_rad));
}

/// Axis-angle of a rotation matrix (through Shepperd's quaternion); angle in [0, π].
template <Real T>
AxisAngle<T> axis_angle_from_matrix(const Mat3<T>& r) noexcept {
  return axis_angle_from_quat(quat_from_matrix(r));
}

/// Rotation matrix of a rotation vector.
template <Real T>
Mat3<T> matrix_from_rotation_vector(const Vec3<T>& r) noexcept {
  return matrix_from_quat(quat_from_rotation_vector(r));
}

/// Rotation vector of a rotation matrix; |r| in [0, π].
template <Real T>
Vec3<T> rotation_vector_from_matrix(const Mat3<T>& r) noexcept {
  return rotation_vector_from_quat(quat_from_matrix(r));
}

/// Default tolerance of check_rotation(): 1e-6, the figure the rotation calculator promises.
template <Real T>
inline constexpr T rotation_check_tolerance = T(1e-6);

/// Checks that r is a rotation: every entry finite, max |RᵀR − I| ≤ tol and |det R − 1| ≤ tol.
/// Errors: NotFinite, or NotARotation with the measured deviation (a reflection is named as such).
template <Real T>
Expected<void> check_rotation(const Mat3<T>& r, T tol = rotation_check_tolerance<T>) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(r.m[i][j]))
        return Error{ErrorCode::not_finite, "matrix entry (" + std::to_string(i) + ", " + std::to_string(j) +
                                               ") is not finite"};
  const T det = determinant(r);
  if (det < T(0))
    return Error{ErrorCode::not_a_rotation,
                 "determinant is " + detail::message_number(double(det)) + ": a reflection, not a rotation"};
  const T off = max_abs_diff(transpose(r) * r, Mat3<T>::identity());
  if (off > tol)
    return Error{ErrorCode::not_a_rotation,
                 "not orthonormal: max |R^T R - I| = " + detail::message_number(double(off)) + " exceeds " +
                     detail::message_number(double(tol))};
  if (std::abs(det - T(1)) > tol)
    return Error{ErrorCode::not_a_rotation, "determinant is " + detail::message_number(double(det)) + ", not 1"};
  return {};
}

/// quat_from_matrix() after check_rotation(): the quaternion, or why r is not a rotation.
template <Real T>
Expected<Quat<T>> quat_from_rotation_matrix_checked(const Mat3<T>& r, T tol = rotation_check_tolerance<T>) {
  auto ok = check_rotation(r, tol);
  if (!ok) return ok.error();
  return quat_from_matrix(r);
}

}  // namespace inbetween
