#pragma once
/// Camera orientation (texts 004 §3.4.2 "Camera path following", Eqs. 3.33–3.34).
///
/// Convention (docs/paths.md): right-handed world; the camera looks down its own −z axis with +y up
/// and +x to the right (the OpenGL convention).  CameraPose holds the world-space axes right, up and
/// forward (= −z of the camera); world_from_camera has columns (right, up, −forward).  The texts'
/// left-handed eye space (u, v, w) is (right, up, forward): w = COI − POS, u = w × up, v = u × w.
///
/// Degenerate but legal input has documented fallbacks, never NaN:
///   - target at the eye (zero view vector): forward = options.fallback_forward;
///   - up parallel to the view vector (the sine of the angle between them at most √ε: 1.5e-8 in
///     double, 3.5e-4 in float) or zero: options.fallback_up is used instead; if that is parallel
///     too, any_perpendicular(forward).

#include <cmath>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/paths/path_frame.hpp"

namespace inbetween {

/// A camera placement: eye position and the orthonormal right-handed axes in world space.
template <Real T>
struct CameraPose {
  Vec3<T> eye{};                        ///< camera position (texts' POS)
  Vec3<T> right{T(1), T(0), T(0)};      ///< camera +x (texts' u)
  Vec3<T> up{T(0), T(1), T(0)};         ///< camera +y (texts' v)
  Vec3<T> forward{T(0), T(0), T(-1)};   ///< view direction, camera −z (texts' w)

  /// Rotation world_from_camera: columns (right, up, −forward).
  Mat3<T> rotation_matrix() const noexcept { return Mat3<T>::from_columns(right, up, -forward); }
  /// The same rotation as a unit quaternion (canonical).
  Quat<T> rotation() const noexcept { return quat_from_matrix(rotation_matrix()); }
  /// world_from_camera as a TRS transform (unit scale).
  Transform<T> world_from_camera() const noexcept { return {eye, rotation(), {T(1), T(1), T(1)}}; }
  /// The view matrix camera_from_world = [Rᵀ  −Rᵀ eye; 0 1].
  Mat4<T> view_matrix() const noexcept {
    const Mat3<T> rt = transpose(rotation_matrix());
    const Vec3<T> t = -(rt * eye);
    Mat4<T> m;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m.m[r][c] = rt.m[r][c];
      m.m[r][3] = t[r];
    }
    return m;
  }
};

using CameraPosef = CameraPose<float>;   ///< single-precision camera pose
using CameraPosed = CameraPose<double>;  ///< double-precision camera pose

/// Options of look_at().
template <Real T>
struct LookAtOptions {
  T tilt_rad = T(0);                                   ///< roll about the view vector; + turns up towards right
  Vec3<T> fallback_forward{T(0), T(0), T(-1)};         ///< view direction when target == eye
  Vec3<T> fallback_up{T(0), T(0), T(1)};               ///< used when up is parallel to the view vector
};

/// Camera at `eye` looking at `target` with `up` as the general up direction (Eq. 3.33 with a
/// general up; Eq. 3.34 passes U(s) − P(s)).  up need not be perpendicular or unit; it only picks
/// the plane of the camera's up axis.  Fallbacks in the file comment.
template <Real T>
CameraPose<T> look_at(const Vec3<T>& eye, const Vec3<T>& target, const Vec3<T>& up = {T(0), T(1), T(0)},
                      const LookAtOptions<T>& options = {}) noexcept {
  CameraPose<T> c;
  c.eye = eye;
  c.forward = normalized(Vec3<T>(target - eye),
                         normalized(options.fallback_forward, Vec3<T>{T(0), T(0), T(-1)}));
  // Eq. 3.33: u = w × up; a right vector shorter than √ε·|up| means up ∥ w.
  const T tiny = std::sqrt(std::numeric_limits<T>::epsilon());
  Vec3<T> r = cross(c.forward, up);
  if (!(norm(r) > tiny * norm(up)) || !is_finite(r)) r = cross(c.forward, options.fallback_up);
  if (!(norm(r) > tiny * norm(options.fallback_up)) || !is_finite(r)) r = any_perpendicular(c.forward);
  c.right = normalized(r, any_perpendicular(c.forward));
  c.up = cross(c.right, c.forward);  // v = u × w
  if (options.tilt_rad != T(0) && std::isfinite(options.tilt_rad)) {
    c.up = rotate_about(c.up, c.forward, options.tilt_rad);
    c.right = cross(c.forward, c.up);
  }
  return c;
}

/// Options of look_ahead_camera().
template <Real T>
struct LookAheadOptions {
  T ahead = T(0);              ///< Δs ≥ 0: the centre of interest is P(s + Δs) (length units)
  int average_count = 1;       ///< n ≥ 1: average P(s + kΔs/n), k = 1..n, to steady the view
  Vec3<T> up{T(0), T(1), T(0)};///< general up direction
  LookAtOptions<T> look{};     ///< tilt and fallbacks
};

/// The camera at arc length s (clamped into [0, L]) on `path`, looking ahead along the same path
/// (texts: COI = P(s + Δs)).  Past the end the path is continued along its end tangent,
/// P(L) + T(L)·(s + Δs − L), so the view turns smoothly into the end tangent as s approaches L.
/// Δs = 0, or a centre of interest that coincides with the eye, looks along the unit tangent at s
/// (the Frenet w).  average_count < 1 reads as 1; a negative or NaN Δs reads as 0.
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
CameraPose<typename C::scalar_type> look_ahead_camera(const ArcLength<C>& path, typename C::scalar_type s,
                                                      const LookAheadOptions<typename C::scalar_type>& options = {}) noexcept {
  using T = typename C::scalar_type;
  const T L = path.length();
  s = std::isnan(s) ? T(0) : clamp(s, T(0), L);
  const T ahead = options.ahead > T(0) && std::isfinite(options.ahead) ? options.ahead : T(0);
  const int n = options.average_count < 1 ? 1 : options.average_count;
  const Vec3<T> eye = path.point_at_length(s);
  const Vec3<T> end = path.point_at_length(L);
  const Vec3<T> end_tangent = unit_tangent(path.curve(), path.domain().hi);
  Vec3<T> coi{};
  for (int k = 1; k <= n; ++k) {
    const T sk = s + ahead * T(k) / T(n);
    coi += sk <= L ? path.point_at_length(sk) : end + end_tangent * (sk - L);
  }
  coi = coi / T(n);
  LookAtOptions<T> look = options.look;
  look.fallback_forward = unit_tangent(path.curve(), path.u_at(s));
  return look_at(eye, coi, options.up, look);
}

/// The camera on one path looking at a point on a second path (texts: position P(s), centre of
/// interest C(s)).  Both paths are traversed by the same normalised distance: with `fraction` f in
/// [0, 1] (clamped; NaN reads as 0) the eye is P(f·L_P) and the centre of interest C(f·L_C), so
/// both move at constant speed when f does.  `up` is the general up direction (Eq. 3.33).
template <Curve CP, Curve CC>
  requires std::same_as<typename CP::point_type, Vec3<typename CP::scalar_type>> &&
           std::same_as<typename CC::point_type, typename CP::point_type>
CameraPose<typename CP::scalar_type> camera_between_paths(
    const ArcLength<CP>& position, const ArcLength<CC>& target, typename CP::scalar_type fraction,
    const Vec3<typename CP::scalar_type>& up = {0, 1, 0},
    const LookAtOptions<typename CP::scalar_type>& options = {}) noexcept {
  using T = typename CP::scalar_type;
  const T f = std::isnan(fraction) ? T(0) : clamp(fraction, T(0), T(1));
  return look_at(position.point_at_length(f * position.length()), target.point_at_length(f * target.length()), up,
                 options);
}

/// As above with an up path U (Eq. 3.34): the general up direction is U(f·L_U) − P(f·L_P).
template <Curve CP, Curve CC, Curve CU>
  requires std::same_as<typename CP::point_type, Vec3<typename CP::scalar_type>> &&
           std::same_as<typename CC::point_type, typename CP::point_type> &&
           std::same_as<typename CU::point_type, typename CP::point_type>
CameraPose<typename CP::scalar_type> camera_between_paths(
    const ArcLength<CP>& position, const ArcLength<CC>& target, const ArcLength<CU>& up_path,
    typename CP::scalar_type fraction, const LookAtOptions<typename CP::scalar_type>& options = {}) noexcept {
  using T = typename CP::scalar_type;
  const T f = std::isnan(fraction) ? T(0) : clamp(fraction, T(0), T(1));
  const Vec3<T> eye = position.point_at_length(f * position.length());
  return look_at(eye, target.point_at_length(f * target.length()),
                 Vec3<T>(up_path.point_at_length(f * up_path.length()) - eye), options);
}

}  // namespace inbetween
