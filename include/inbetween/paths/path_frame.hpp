#pragma once
/// Orientation along a path (texts 004 §3.4.2): the frame type shared by the Frenet and the
/// rotation-minimising frames, the unit tangent with its cusp fallback, and the raw Frenet frame
/// at one parameter value (Eq. 3.32).
///
/// Convention: PathFrame holds a right-handed orthonormal triple (tangent, normal, binormal) with
/// binormal = tangent × normal.  Its matrix has those three as columns, so it maps the local x axis
/// to the tangent, y to the normal and z to the binormal.  The texts' left-handed (u, v, w) of
/// Eq. 3.32 is (binormal, normal, tangent): w = P′, u = P′ × P″, v = u × w.

#include <cmath>
#include <limits>

#include "inbetween/curves/curve.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// A right-handed orthonormal frame along a path: binormal = tangent × normal.  Default: the axes.
template <Real T>
struct PathFrame {
  Vec3<T> tangent{T(1), T(0), T(0)};   ///< unit direction of travel (texts' w)
  Vec3<T> normal{T(0), T(1), T(0)};    ///< unit normal (texts' v)
  Vec3<T> binormal{T(0), T(0), T(1)};  ///< tangent × normal (texts' u)

  /// Rotation matrix with columns (tangent, normal, binormal): world_from_frame.
  Mat3<T> matrix() const noexcept { return Mat3<T>::from_columns(tangent, normal, binormal); }
  /// The same rotation as a unit quaternion (canonical, w ≥ 0).
  Quat<T> rotation() const noexcept { return quat_from_matrix(matrix()); }
};

using PathFramef = PathFrame<float>;   ///< single-precision path frame
using PathFramed = PathFrame<double>;  ///< double-precision path frame

/// A unit vector perpendicular to v: v crossed with the coordinate axis on which |v| has its
/// smallest component, normalised.  A zero or non-finite v gives (0, 1, 0).
template <Real T>
Vec3<T> any_perpendicular(const Vec3<T>& v) noexcept {
  const T ax = std::abs(v.x), ay = std::abs(v.y), az = std::abs(v.z);
  Vec3<T> axis{T(0), T(0), T(1)};
  if (ax <= ay && ax <= az) {
    axis = {T(1), T(0), T(0)};
  } else if (ay <= az) {
    axis = {T(0), T(1), T(0)};
  }
  return normalized(cross(v, axis), Vec3<T>{T(0), T(1), T(0)});
}

/// `v` with its component along the unit vector `t` removed, normalised; when that leaves nothing
/// (v parallel to t, zero or non-finite) the result is any_perpendicular(t).
template <Real T>
Vec3<T> perpendicular_part(const Vec3<T>& v, const Vec3<T>& t) noexcept {
  const Vec3<T> p = v - t * dot(v, t);
  const T n = norm(p), scale = norm(v);
  if (!(n > T(64) * std::numeric_limits<T>::epsilon() * scale) || !std::isfinite(n)) return any_perpendicular(t);
  return p / n;
}

/// Unit tangent of a 3-D curve at u (clamped).  Where P′(u) vanishes (a cusp, coincident control
/// points) the direction of the first non-zero of P″, P‴ is used — the one-sided limit of the
/// tangent at an isolated zero of the speed; if all vanish, (1, 0, 0).  Never NaN for a built curve.
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
Vec3<typename C::scalar_type> unit_tangent(const C& curve, typename C::scalar_type u) noexcept {
  using T = typename C::scalar_type;
  for (int k = 1; k <= 3; ++k) {
    const Vec3<T> d = curve.derivative(u, k);
    const T n = norm(d);
    if (n > T(0) && std::isfinite(n)) return d / n;
  }
  return {T(1), T(0), T(0)};
}

/// Default threshold below which the Frenet frame counts as undefined: the sine of the angle
/// between P′ and P″ (√ε: 1.5e-8 in double, 3.5e-4 in float; rounding alone gives about ε).
template <Real T>
inline constexpr T default_straightness_tolerance = T(sizeof(T) <= 4 ? 3.5e-4 : 1.5e-8);

/// The Frenet frame at one parameter value and whether it is defined.
template <Real T>
struct FrenetSample {
  PathFrame<T> frame{};  ///< the frame; when !defined the normal is any_perpendicular(tangent)
  bool defined = false;  ///< false where the curvature vanishes (|P′ × P″| ≤ tol·|P′||P″|)
};

/// The raw Frenet frame of Eq. 3.32 at u (clamped): tangent = P′/|P′|, binormal along P′ × P″,
/// normal = binormal × tangent (towards the centre of curvature).  Undefined (defined = false) where
/// P″ is zero or parallel to P′ within `tolerance` (sine of the angle between them); the frame then
/// carries a documented stand-in normal any_perpendicular(tangent).  At a zero of P′ the tangent is
/// unit_tangent()'s fallback and the frame is reported undefined.
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
FrenetSample<typename C::scalar_type> frenet_frame(
    const C& curve, typename C::scalar_type u,
    typename C::scalar_type tolerance = default_straightness_tolerance<typename C::scalar_type>) noexcept {
  using T = typename C::scalar_type;
  FrenetSample<T> out;
  const Vec3<T> d1 = curve.derivative(u, 1), d2 = curve.derivative(u, 2);
  const T n1 = norm(d1), n2 = norm(d2);
  const Vec3<T> t = unit_tangent(curve, u);
  out.frame.tangent = t;
  const Vec3<T> b = cross(d1 / (n1 > T(0) ? n1 : T(1)), d2 / (n2 > T(0) ? n2 : T(1)));
  const T nb = norm(b);
  if (n1 > T(0) && n2 > T(0) && std::isfinite(nb) && nb > tolerance) {
    out.frame.binormal = b / nb;
    out.frame.normal = normalized(cross(out.frame.binormal, t), any_perpendicular(t));
    out.defined = true;
  } else {
    out.frame.normal = any_perpendicular(t);
    out.frame.binormal = cross(t, out.frame.normal);
  }
  return out;
}

/// Signed angle in (−π, π] that turns the unit vector a into the unit vector b about the unit
/// axis, for a and b perpendicular to it: atan2((a × b)·axis, a·b) (not acos of a dot).
template <Real T>
T signed_angle_about(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& axis) noexcept {
  return std::atan2(dot(cross(a, b), axis), dot(a, b));
}

/// Rotates v about the unit axis by angle_rad (right-hand rule), by Rodrigues' formula.
template <Real T>
Vec3<T> rotate_about(const Vec3<T>& v, const Vec3<T>& axis, T angle_rad) noexcept {
  const T c = std::cos(angle_rad), s = std::sin(angle_rad);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (T(1) - c));
}

}  // namespace inbetween
