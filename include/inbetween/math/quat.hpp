#pragma once
/// Hamilton quaternions q = w + x i + y j + z k, stored and constructed w first (no storage-order
/// trap).  Unit quaternions represent rotations: v' = q v q⁻¹, and q2·q1 applies q1 first.

#include <cmath>

#include "inbetween/math/vec.hpp"

namespace inbetween {

/// Quaternion w + xi + yj + zk; default-constructed is the identity rotation (1, 0, 0, 0).
template <Real T>
struct Quat {
  T w{1}, x{}, y{}, z{};  ///< scalar part w and vector part (x, y, z), stored w first
  using scalar_type = T;  ///< the component type

  /// From components in w, x, y, z order.
  static constexpr Quat from_wxyz(T w, T x, T y, T z) noexcept { return {w, x, y, z}; }
  /// From components in x, y, z, w order (glTF, Eigen's storage, SciPy's as_quat()).
  static constexpr Quat from_xyzw(T x, T y, T z, T w) noexcept { return {w, x, y, z}; }
  /// The identity rotation.
  static constexpr Quat identity() noexcept { return {}; }
  /// The pure quaternion (0, v) used to rotate a vector by q v q⁻¹.
  static constexpr Quat pure(const Vec3<T>& v) noexcept { return {T(0), v.x, v.y, v.z}; }
  /// Rotation by angle_rad about `axis` (right-hand rule).  The axis is normalised here, at any
  /// finite scale (subnormal components included: the axis is first divided by its largest
  /// component, so the norm that divides sin(angle/2) lies in [1, √3]); a zero or non-finite axis
  /// gives the identity (documented fallback).
  static Quat from_axis_angle(const Vec3<T>& axis, T angle_rad) noexcept {
    const T big = std::fmax(std::abs(axis.x), std::fmax(std::abs(axis.y), std::abs(axis.z)));
    if (!(big > T(0)) || !std::isfinite(big)) return {};
    // Exact for the largest component (±1); the others are correctly rounded quotients.
    const Vec3<T> a{axis.x / big, axis.y / big, axis.z / big};
    const T n = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    const T h = angle_rad / T(2);
    const T s = std::sin(h) / n;
    return {std::cos(h), a.x * s, a.y * s, a.z * s};
  }
  /// The vector part (x, y, z).
  constexpr Vec3<T> vec() const noexcept { return {x, y, z}; }
  /// Converts to another precision.
  template <Real U>
  constexpr Quat<U> cast() const noexcept { return {U(w), U(x), U(y), U(z)}; }
  /// Exact component equality (q and −q compare unequal; see same_rotation()).
  friend constexpr bool operator==(const Quat&, const Quat&) = default;
};

/// Precision aliases: f = float, d = double.
using Quatf = Quat<float>;
using Quatd = Quat<double>;

/// Component-wise sum.
template <Real T>
constexpr Quat<T> operator+(const Quat<T>& a, const Quat<T>& b) noexcept {
  return {a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z};
}
/// Component-wise difference.
template <Real T>
constexpr Quat<T> operator-(const Quat<T>& a, const Quat<T>& b) noexcept {
  return {a.w - b.w, a.x - b.x, a.y - b.y, a.z - b.z};
}
/// Negation (the same rotation, the other sign).
template <Real T>
constexpr Quat<T> operator-(const Quat<T>& a) noexcept { return {-a.w, -a.x, -a.y, -a.z}; }
/// Scaling by a real number.
template <Real T>
constexpr Quat<T> operator*(const Quat<T>& a, T s) noexcept { return {a.w * s, a.x * s, a.y * s, a.z * s}; }
/// Scaling by a real number, scalar first.
template <Real T>
constexpr Quat<T> operator*(T s, const Quat<T>& a) noexcept { return a * s; }
/// Division by a real number (no check for zero: that is the caller's choice).
template <Real T>
constexpr Quat<T> operator/(const Quat<T>& a, T s) noexcept { return {a.w / s, a.x / s, a.y / s, a.z / s}; }

/// Hamilton product a·b (ij = k).  As rotations, a·b applies b first, then a.
template <Real T>
constexpr Quat<T> operator*(const Quat<T>& a, const Quat<T>& b) noexcept {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

/// Conjugate w − xi − yj − zk.  (ab)* = b* a*.
template <Real T>
constexpr Quat<T> conjugate(const Quat<T>& q) noexcept { return {q.w, -q.x, -q.y, -q.z}; }

/// Four-dimensional dot product.
template <Real T>
constexpr T dot(const Quat<T>& a, const Quat<T>& b) noexcept {
  return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}

/// Squared norm w² + x² + y² + z².
template <Real T>
constexpr T squared_norm(const Quat<T>& q) noexcept { return dot(q, q); }

/// Norm |q| = √(q q*), computed without overflow or underflow.
template <Real T>
[[gnu::always_inline]] inline T norm(const Quat<T>& q) noexcept { return norm(Vec4<T>{q.w, q.x, q.y, q.z}); }

/// q/|q|; a zero or non-finite quaternion gives the identity (documented fallback).
template <Real T>
[[gnu::always_inline]] inline Quat<T> normalized(const Quat<T>& q) noexcept {
  const T n = norm(q);
  if (!(n > T(0)) || !std::isfinite(n)) return {};
  return q / n;
}

/// Multiplicative inverse q*/|q|² of any non-zero quaternion (zero gives non-finite values).
template <Real T>
Quat<T> inverse(const Quat<T>& q) noexcept {
  const T n = norm(q);
  return conjugate(q) / n / n;
}

/// True when every component is finite.
template <Real T>
bool is_finite(const Quat<T>& q) noexcept {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

/// Rotates v by the unit quaternion q: the vector part of q (0, v) q*, in the fast form
/// v + 2w(u × v) + 2u × (u × v) with u = (x, y, z) (15 multiplies instead of 2 products).
template <Real T>
constexpr Vec3<T> rotate(const Quat<T>& q, const Vec3<T>& v) noexcept {
  const Vec3<T> u = q.vec();
  const Vec3<T> t = cross(u, v) * T(2);
  return v + t * q.w + cross(u, t);
}

/// Rotates v by the literal sandwich q (0, v) q⁻¹; works for non-unit q too (the scale cancels).
template <Real T>
Vec3<T> rotate_sandwich(const Quat<T>& q, const Vec3<T>& v) noexcept {
  return (q * Quat<T>::pure(v) * inverse(q)).vec();
}

/// Quaternion exponential e^q = e^w (cos|u| + û sin|u|).
template <Real T>
Quat<T> exp(const Quat<T>& q) noexcept {
  const T a = norm(q.vec());
  const T ew = std::exp(q.w);
  // sin(a)/a, with its Taylor series where the division would lose precision.
  const T sinc = a < T(1e-4) ? T(1) - a * a / T(6) : std::sin(a) / a;
  return {ew * std::cos(a), ew * sinc * q.x, ew * sinc * q.y, ew * sinc * q.z};
}

/// Principal logarithm ln q = ln|q| + û atan2(|u|, w).  For a unit quaternion the vector part is
/// half the rotation vector.  For a negative real q the axis is undefined: x is used (documented).
template <Real T>
Quat<T> log(const Quat<T>& q) noexcept {
  const T vn = norm(q.vec());
  const T qn = norm(q);
  const T angle = std::atan2(vn, q.w);  // in [0, π], accurate everywhere
  if (vn == T(0)) {
    if (q.w < T(0)) return {std::log(qn), angle, T(0), T(0)};
    return {std::log(qn), T(0), T(0), T(0)};
  }
  const T k = angle / vn;
  return {std::log(qn), q.x * k, q.y * k, q.z * k};
}

/// q^e = exp(e · ln q) for a non-zero q; for a unit quaternion it scales the rotation angle by e.
template <Real T>
Quat<T> pow(const Quat<T>& q, T e) noexcept {
  if (q.x == T(0) && q.y == T(0) && q.z == T(0) && q.w > T(0)) return {std::pow(q.w, e), T(0), T(0), T(0)};
  return exp(log(q) * e);
}

/// Rotation angle in [0, π] between the rotations a and b (unit quaternions, either sign):
/// 2·atan2(|a* b|_vec, |w|), accurate for tiny and near-π angles alike (no acos of a dot).
template <Real T>
T angle_between(const Quat<T>& a, const Quat<T>& b) noexcept {
  const Quat<T> d = conjugate(a) * b;
  return T(2) * std::atan2(norm(d.vec()), std::abs(d.w));
}

/// True when a and b represent the same rotation within `tol_rad` (q and −q are equal rotations).
template <Real T>
bool same_rotation(const Quat<T>& a, const Quat<T>& b, T tol_rad) noexcept {
  return angle_between(normalized(a), normalized(b)) <= tol_rad;
}

}  // namespace inbetween
