#pragma once
/// Homogeneous 4×4 transforms (column vectors, p' = M p, translation in the last column) and the
/// TRS transform {translation, rotation, scale} whose matrix is M = T·R·S: scale first, then
/// rotate, then translate.  Matrix products do not commute — T·R·S moves a rotated, scaled object,
/// S·R·T scales and rotates the translation too.  Name frames in variables so the order reads:
/// `world_T_body = world_T_path * path_T_body`.

#include <cmath>
#include <string>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"

namespace inbetween {

/// Translation by t: the identity with t in the last column.
template <Real T>
constexpr Mat4<T> translation_matrix(const Vec3<T>& t) noexcept {
  Mat4<T> m;
  m.m[0][3] = t.x;
  m.m[1][3] = t.y;
  m.m[2][3] = t.z;
  return m;
}

/// Scaling by s along x, y, z (negative factors mirror).
template <Real T>
constexpr Mat4<T> scaling_matrix(const Vec3<T>& s) noexcept {
  Mat4<T> m;
  m.m[0][0] = s.x;
  m.m[1][1] = s.y;
  m.m[2][2] = s.z;
  return m;
}

/// Embeds a 3×3 linear map (rotation, scale, …) in the upper-left block of a homogeneous matrix.
template <Real T>
constexpr Mat4<T> homogeneous(const Mat3<T>& linear) noexcept {
  Mat4<T> m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m.m[r][c] = linear.m[r][c];
  return m;
}

/// Rotation by angle_rad about the x axis (right-hand rule: y turns towards z).
template <Real T>
Mat4<T> rotation_x(T angle_rad) noexcept {
  const T c = std::cos(angle_rad), s = std::sin(angle_rad);
  Mat4<T> m;
  m.m[1][1] = c, m.m[1][2] = -s, m.m[2][1] = s, m.m[2][2] = c;
  return m;
}

/// Rotation by angle_rad about the y axis (z turns towards x).
template <Real T>
Mat4<T> rotation_y(T angle_rad) noexcept {
  const T c = std::cos(angle_rad), s = std::sin(angle_rad);
  Mat4<T> m;
  m.m[0][0] = c, m.m[0][2] = s, m.m[2][0] = -s, m.m[2][2] = c;
  return m;
}

/// Rotation by angle_rad about the z axis (x turns towards y) — the matrix printed in the texts.
template <Real T>
Mat4<T> rotation_z(T angle_rad) noexcept {
  const T c = std::cos(angle_rad), s = std::sin(angle_rad);
  Mat4<T> m;
  m.m[0][0] = c, m.m[0][1] = -s, m.m[1][0] = s, m.m[1][1] = c;
  return m;
}

/// Rotation by angle_rad about an arbitrary axis through the origin (normalised here; a zero axis
/// gives the identity), by Rodrigues' formula R = I + sin θ·K + (1 − cos θ)·K², with 1 − cos θ
/// written as 2 sin²(θ/2) so that small angles keep their digits.
template <Real T>
Mat4<T> rotation_about_axis(const Vec3<T>& axis, T angle_rad) noexcept {
  const T n = norm(axis);
  if (!(n > T(0)) || !std::isfinite(n)) return {};
  const Vec3<T> k = axis / n;
  const T s = std::sin(angle_rad), h = std::sin(angle_rad / T(2)), v = T(2) * h * h;
  Mat4<T> m;
  m.m[0][0] = T(1) - v * (k.y * k.y + k.z * k.z);
  m.m[1][1] = T(1) - v * (k.x * k.x + k.z * k.z);
  m.m[2][2] = T(1) - v * (k.x * k.x + k.y * k.y);
  m.m[0][1] = v * k.x * k.y - s * k.z;
  m.m[1][0] = v * k.x * k.y + s * k.z;
  m.m[0][2] = v * k.x * k.z + s * k.y;
  m.m[2][0] = v * k.x * k.z - s * k.y;
  m.m[1][2] = v * k.y * k.z - s * k.x;
  m.m[2][1] = v * k.y * k.z + s * k.x;
  return m;
}

/// Transforms a point: M·(p, 1), translation included.  M must be affine (last row 0 0 0 1); the
/// last row is not read.
template <Real T>
constexpr Vec3<T> transform_point(const Mat4<T>& m, const Vec3<T>& p) noexcept {
  return {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3],
          m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3],
          m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]};
}

/// Transforms a direction (a difference of points): M·(d, 0), translation ignored.  (Surface
/// normals transform with the inverse transpose instead; not this function.)
template <Real T>
constexpr Vec3<T> transform_direction(const Mat4<T>& m, const Vec3<T>& d) noexcept {
  return m.linear() * d;
}

/// Inverse of an affine matrix [L t; 0 1]: [L⁻¹  −L⁻¹t; 0 1].  Cheaper and closer to exact than the
/// general inverse.  A singular L gives non-finite values; check determinant(m.linear()) first.
template <Real T>
constexpr Mat4<T> affine_inverse(const Mat4<T>& m) noexcept {
  const Mat3<T> li = inverse(m.linear());
  const Vec3<T> t = li * m.translation();
  Mat4<T> o = homogeneous(li);
  o.m[0][3] = -t.x;
  o.m[1][3] = -t.y;
  o.m[2][3] = -t.z;
  return o;
}

/// A TRS transform: scale (per axis, in the object's frame), then rotate, then translate; its
/// matrix is T·R·S.  Default: the identity.
template <Real T>
struct Transform {
  Vec3<T> translation{};                 ///< applied last
  Quat<T> rotation{};                    ///< unit quaternion, applied after the scale
  Vec3<T> scale{T(1), T(1), T(1)};       ///< applied first, along the object's own axes

  /// The identity transform.
  static constexpr Transform identity() noexcept { return {}; }

  /// The matrix T·R·S.
  [[nodiscard]] Mat4<T> to_matrix() const noexcept {
    const Mat3<T> r = matrix_from_quat(rotation);
    Mat4<T> m;
    for (int row = 0; row < 3; ++row) {
      m.m[row][0] = r.m[row][0] * scale.x;
      m.m[row][1] = r.m[row][1] * scale.y;
      m.m[row][2] = r.m[row][2] * scale.z;
      m.m[row][3] = translation[row];
    }
    return m;
  }

  /// Applies the transform to a point: t + R(s ⊙ p).
  [[nodiscard]] Vec3<T> apply_to_point(const Vec3<T>& p) const noexcept {
    return translation + rotate(normalized(rotation), hadamard(scale, p));
  }
  /// Applies the transform to a direction: R(s ⊙ d), no translation.
  [[nodiscard]] Vec3<T> apply_to_direction(const Vec3<T>& d) const noexcept {
    return rotate(normalized(rotation), hadamard(scale, d));
  }

  /// Converts to another precision.
  template <Real U>
  [[nodiscard]] Transform<U> cast() const noexcept {
    return {translation.template cast<U>(), rotation.template cast<U>(), scale.template cast<U>()};
  }
};

using Transformf = Transform<float>;   ///< single-precision TRS transform
using Transformd = Transform<double>;  ///< double-precision TRS transform

/// Options of transform_from_matrix().
template <Real T>
struct DecomposeOptions {
  /// Largest accepted |ĉi·ĉj| between normalised columns of the linear part, and largest accepted
  /// deviation of the last row from (0, 0, 0, 1).  Default 1e-6 (double) / 1e-4 (float: a few
  /// products of float matrices already carry errors of several 1e-7).
  T tolerance = sizeof(T) >= 8 ? T(1e-6) : T(1e-4);
};

/// Recovers the TRS transform of an affine matrix M = T·R·S.  Translation: the last column.  Scale:
/// the lengths of the columns of the linear part.  Rotation: the columns divided by their lengths
/// (Shepperd's method).  A negative determinant (a mirror) cannot be a rotation: the x scale is
/// made negative (documented choice), so the recovered TRS reproduces M though it may differ from
/// the factors M was built from (scale (1, −1, 1) comes back as (−1, 1, 1) with a half turn about z).
/// Errors: NotFinite; Unsupported for a projective last row; InvalidArgument for a zero scale;
/// Unsupported for shear (columns not orthogonal within the tolerance) — no best fit is returned.
template <Real T>
Expected<Transform<T>> transform_from_matrix(const Mat4<T>& m, const DecomposeOptions<T>& options = {}) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(m.m[r][c])) return Error{ErrorCode::not_finite, "matrix entry is not finite"};
  const T tol = options.tolerance;
  if (std::abs(m.m[3][0]) > tol || std::abs(m.m[3][1]) > tol || std::abs(m.m[3][2]) > tol ||
      std::abs(m.m[3][3] - T(1)) > tol)
    return Error{ErrorCode::unsupported, "last row is not (0, 0, 0, 1): a projective matrix has no TRS form"};
  const Mat3<T> l = m.linear();
  Vec3<T> cols[3] = {l.column(0), l.column(1), l.column(2)};
  Vec3<T> s{norm(cols[0]), norm(cols[1]), norm(cols[2])};
  for (int c = 0; c < 3; ++c)
    if (!(s[c] > T(0)))
      return Error{ErrorCode::invalid_argument, "column " + std::to_string(c) + " is zero: zero scale has no rotation"};
  for (int c = 0; c < 3; ++c) cols[c] = cols[c] / s[c];
  const T d01 = std::abs(dot(cols[0], cols[1])), d02 = std::abs(dot(cols[0], cols[2])),
          d12 = std::abs(dot(cols[1], cols[2]));
  const T shear = std::fmax(d01, std::fmax(d02, d12));
  if (shear > tol)
    return Error{ErrorCode::unsupported,
                 "linear part has shear (largest cosine between columns " + detail::message_number(double(shear)) +
                     "): no TRS transform reproduces it"};
  if (determinant(l) < T(0)) {
    s.x = -s.x;
    cols[0] = -cols[0];
  }
  Transform<T> out;
  out.translation = m.translation();
  out.rotation = quat_from_matrix(Mat3<T>::from_columns(cols[0], cols[1], cols[2]));
  out.scale = s;
  return out;
}

/// Composition: the transform that applies b first, then a (matrix a·b).  Exact when a's scale is
/// uniform (or b's rotation keeps the axes); otherwise the product matrix has shear that no TRS
/// holds, and the result keeps R = Ra·Rb, S = Sa ⊙ Sb, t = ta + Ra(Sa ⊙ tb) — points at b's
/// origin still map exactly.  Use to_matrix() products when exactness matters.
template <Real T>
[[gnu::always_inline]] inline Transform<T> compose(const Transform<T>& a, const Transform<T>& b) noexcept {
  return {a.apply_to_point(b.translation), normalized(a.rotation * b.rotation), hadamard(a.scale, b.scale)};
}

/// Inverse transform.  Exact when the scale is uniform (S⁻¹R⁻¹ = R⁻¹S⁻¹); with non-uniform scale
/// the true inverse S⁻¹R⁻¹T⁻¹ is not a TRS and this returns R⁻¹, 1/s, −R⁻¹t/s in TRS form (use
/// affine_inverse(to_matrix()) for the exact matrix).  A zero scale component gives non-finite scale.
template <Real T>
Transform<T> inverse(const Transform<T>& x) noexcept {
  const Quat<T> ri = conjugate(normalized(x.rotation));
  const Vec3<T> si{T(1) / x.scale.x, T(1) / x.scale.y, T(1) / x.scale.z};
  return {-hadamard(si, rotate(ri, x.translation)), ri, si};
}

}  // namespace inbetween
