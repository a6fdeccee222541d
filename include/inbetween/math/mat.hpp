#pragma once
/// Square matrices Mat3 and Mat4, row-major, acting on column vectors (v' = M v).
/// Default-constructed matrices are the identity.

#include <cmath>

#include "inbetween/math/vec.hpp"

namespace inbetween {

/// 3×3 matrix, row-major storage m[row][col]; identity by default.
template <Real T>
struct Mat3 {
  T m[3][3] = {{T(1), T(0), T(0)}, {T(0), T(1), T(0)}, {T(0), T(0), T(1)}};  ///< elements m[row][col]
  using scalar_type = T;          ///< the element type
  static constexpr int size = 3;  ///< rows (= columns)

  /// Element at (row, col).
  constexpr T& operator()(int r, int c) noexcept { return m[r][c]; }
  constexpr const T& operator()(int r, int c) const noexcept { return m[r][c]; }
  /// The identity.
  static constexpr Mat3 identity() noexcept { return {}; }
  /// All zeros.
  static constexpr Mat3 zero() noexcept { return {{{T(0), T(0), T(0)}, {T(0), T(0), T(0)}, {T(0), T(0), T(0)}}}; }
  /// From nine numbers in row-major order.
  static constexpr Mat3 from_rows(const Vec3<T>& r0, const Vec3<T>& r1, const Vec3<T>& r2) noexcept {
    return {{{r0.x, r0.y, r0.z}, {r1.x, r1.y, r1.z}, {r2.x, r2.y, r2.z}}};
  }
  /// From three column vectors (for a rotation: the images of the x, y, z axes).
  static constexpr Mat3 from_columns(const Vec3<T>& c0, const Vec3<T>& c1, const Vec3<T>& c2) noexcept {
    return {{{c0.x, c1.x, c2.x}, {c0.y, c1.y, c2.y}, {c0.z, c1.z, c2.z}}};
  }
  /// Column c as a vector.
  constexpr Vec3<T> column(int c) const noexcept { return {m[0][c], m[1][c], m[2][c]}; }
  /// Row r as a vector.
  constexpr Vec3<T> row(int r) const noexcept { return {m[r][0], m[r][1], m[r][2]}; }
  /// Converts to another precision.
  template <Real U>
  constexpr Mat3<U> cast() const noexcept {
    Mat3<U> o;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) o.m[r][c] = U(m[r][c]);
    return o;
  }
  /// Exact element-wise equality (use a tolerance for computed values).
  friend constexpr bool operator==(const Mat3& a, const Mat3& b) noexcept {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (a.m[r][c] != b.m[r][c]) return false;
    return true;
  }
};

/// 4×4 matrix, row-major storage m[row][col]; identity by default.  Homogeneous transforms keep
/// the translation in the last column.
template <Real T>
struct Mat4 {
  T m[4][4] = {{T(1), T(0), T(0), T(0)}, {T(0), T(1), T(0), T(0)}, {T(0), T(0), T(1), T(0)},
               {T(0), T(0), T(0), T(1)}};  ///< elements m[row][col]; identity by default
  using scalar_type = T;          ///< the element type
  static constexpr int size = 4;  ///< rows (= columns)

  /// Element at (row, col).
  constexpr T& operator()(int r, int c) noexcept { return m[r][c]; }
  constexpr const T& operator()(int r, int c) const noexcept { return m[r][c]; }
  /// The identity matrix (also the default value).
  static constexpr Mat4 identity() noexcept { return {}; }
  /// The all-zero matrix.
  static constexpr Mat4 zero() noexcept {
    Mat4 o;
    for (auto& row : o.m)
      for (auto& e : row) e = T(0);
    return o;
  }
  /// Column c as a vector.
  constexpr Vec4<T> column(int c) const noexcept { return {m[0][c], m[1][c], m[2][c], m[3][c]}; }
  /// Row r as a vector.
  constexpr Vec4<T> row(int r) const noexcept { return {m[r][0], m[r][1], m[r][2], m[r][3]}; }
  /// The upper-left 3×3 block (rotation·scale part of an affine transform).
  constexpr Mat3<T> linear() const noexcept {
    Mat3<T> o;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) o.m[r][c] = m[r][c];
    return o;
  }
  /// The translation column of an affine transform.
  constexpr Vec3<T> translation() const noexcept { return {m[0][3], m[1][3], m[2][3]}; }
  /// Converts to another precision.
  template <Real U>
  constexpr Mat4<U> cast() const noexcept {
    Mat4<U> o;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) o.m[r][c] = U(m[r][c]);
    return o;
  }
  /// Exact element-wise equality (use a tolerance for computed values).
  friend constexpr bool operator==(const Mat4& a, const Mat4& b) noexcept {
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        if (a.m[r][c] != b.m[r][c]) return false;
    return true;
  }
};

/// Precision aliases: f = float, d = double.
using Mat3f = Mat3<float>;
using Mat3d = Mat3<double>;
using Mat4f = Mat4<float>;
using Mat4d = Mat4<double>;

#define INBETWEEN_MAT_OPS(M, V)                                                                    \
  /** Matrix product a·b (b is applied first to a column vector). */                               \
  template <Real T>                                                                                \
  constexpr M<T> operator*(const M<T>& a, const M<T>& b) noexcept {                                \
    M<T> o = M<T>::zero();                                                                         \
    for (int r = 0; r < M<T>::size; ++r)                                                           \
      for (int k = 0; k < M<T>::size; ++k)                                                         \
        for (int c = 0; c < M<T>::size; ++c) o.m[r][c] += a.m[r][k] * b.m[k][c];                   \
    return o;                                                                                      \
  }                                                                                                \
  /** Matrix–vector product M v. */                                                                \
  template <Real T>                                                                                \
  constexpr V<T> operator*(const M<T>& a, const V<T>& v) noexcept {                                \
    V<T> o{};                                                                                      \
    for (int r = 0; r < M<T>::size; ++r)                                                           \
      for (int c = 0; c < M<T>::size; ++c) o[r] += a.m[r][c] * v[c];                               \
    return o;                                                                                      \
  }                                                                                                \
  /** Element-wise sum (used to show why matrices must not be lerped). */                          \
  template <Real T>                                                                                \
  constexpr M<T> operator+(M<T> a, const M<T>& b) noexcept {                                       \
    for (int r = 0; r < M<T>::size; ++r)                                                           \
      for (int c = 0; c < M<T>::size; ++c) a.m[r][c] += b.m[r][c];                                 \
    return a;                                                                                      \
  }                                                                                                \
  template <Real T>                                                                                \
  constexpr M<T> operator-(M<T> a, const M<T>& b) noexcept {                                       \
    for (int r = 0; r < M<T>::size; ++r)                                                           \
      for (int c = 0; c < M<T>::size; ++c) a.m[r][c] -= b.m[r][c];                                 \
    return a;                                                                                      \
  }                                                                                                \
  /** Element-wise scaling. */                                                                     \
  template <Real T>                                                                                \
  constexpr M<T> operator*(M<T> a, T s) noexcept {                                                 \
    for (int r = 0; r < M<T>::size; ++r)                                                           \
      for (int c = 0; c < M<T>::size; ++c) a.m[r][c] *= s;                                         \
    return a;                                                                                      \
  }                                                                                                \
  template <Real T>                                                                                \
  constexpr M<T> operator*(T s, const M<T>& a) noexcept { return a * s; }                          \
  /** Transpose. */                                                                                \
  template <Real T>                                                                                \
  constexpr M<T> transpose(const M<T>& a) noexcept {                                               \
    M<T> o;                                                                                        \
    for (int r = 0; r < M<T>::size; ++r)                                                           \
      for (int c = 0; c < M<T>::size; ++c) o.m[r][c] = a.m[c][r];                                  \
    return o;                                                                                      \
  }                                                                                                \
  /** Largest absolute element-wise difference. */                                                 \
  template <Real T>                                                                                \
  T max_abs_diff(const M<T>& a, const M<T>& b) noexcept {                                          \
    T d{};                                                                                         \
    for (int r = 0; r < M<T>::size; ++r)                                                           \
      for (int c = 0; c < M<T>::size; ++c) d = std::fmax(d, std::abs(a.m[r][c] - b.m[r][c]));      \
    return d;                                                                                      \
  }

INBETWEEN_MAT_OPS(Mat3, Vec3)
INBETWEEN_MAT_OPS(Mat4, Vec4)
#undef INBETWEEN_MAT_OPS

/// Determinant of a 3×3 matrix.
template <Real T>
constexpr T determinant(const Mat3<T>& a) noexcept {
  return a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
         a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
         a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
}

/// Inverse of a 3×3 matrix by the adjugate.  A singular matrix (|det| below the smallest normal
/// number) has no inverse: the result then holds non-finite values; check determinant() first.
template <Real T>
constexpr Mat3<T> inverse(const Mat3<T>& a) noexcept {
  const T det = determinant(a);
  const T inv = T(1) / det;
  Mat3<T> o;
  o.m[0][0] = (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) * inv;
  o.m[0][1] = (a.m[0][2] * a.m[2][1] - a.m[0][1] * a.m[2][2]) * inv;
  o.m[0][2] = (a.m[0][1] * a.m[1][2] - a.m[0][2] * a.m[1][1]) * inv;
  o.m[1][0] = (a.m[1][2] * a.m[2][0] - a.m[1][0] * a.m[2][2]) * inv;
  o.m[1][1] = (a.m[0][0] * a.m[2][2] - a.m[0][2] * a.m[2][0]) * inv;
  o.m[1][2] = (a.m[0][2] * a.m[1][0] - a.m[0][0] * a.m[1][2]) * inv;
  o.m[2][0] = (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]) * inv;
  o.m[2][1] = (a.m[0][1] * a.m[2][0] - a.m[0][0] * a.m[2][1]) * inv;
  o.m[2][2] = (a.m[0][0] * a.m[1][1] - a.m[0][1] * a.m[1][0]) * inv;
  return o;
}

/// Determinant of a 4×4 matrix (cofactor expansion via 2×2 minors).
template <Real T>
constexpr T determinant(const Mat4<T>& a) noexcept {
  const auto& m = a.m;
  const T s0 = m[0][0] * m[1][1] - m[1][0] * m[0][1], s1 = m[0][0] * m[1][2] - m[1][0] * m[0][2];
  const T s2 = m[0][0] * m[1][3] - m[1][0] * m[0][3], s3 = m[0][1] * m[1][2] - m[1][1] * m[0][2];
  const T s4 = m[0][1] * m[1][3] - m[1][1] * m[0][3], s5 = m[0][2] * m[1][3] - m[1][2] * m[0][3];
  const T c5 = m[2][2] * m[3][3] - m[3][2] * m[2][3], c4 = m[2][1] * m[3][3] - m[3][1] * m[2][3];
  const T c3 = m[2][1] * m[3][2] - m[3][1] * m[2][2], c2 = m[2][0] * m[3][3] - m[3][0] * m[2][3];
  const T c1 = m[2][0] * m[3][2] - m[3][0] * m[2][2], c0 = m[2][0] * m[3][1] - m[3][0] * m[2][1];
  return s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0;
}

/// General inverse of a 4×4 matrix (Laplace expansion by 2×2 minors).  Singular input gives
/// non-finite values; check determinant() first.  For rigid or TRS transforms prefer
/// Transform::inverse() or affine_inverse(), which are cheaper and exact in structure.
template <Real T>
constexpr Mat4<T> inverse(const Mat4<T>& a) noexcept {
  const auto& m = a.m;
  const T s0 = m[0][0] * m[1][1] - m[1][0] * m[0][1], s1 = m[0][0] * m[1][2] - m[1][0] * m[0][2];
  const T s2 = m[0][0] * m[1][3] - m[1][0] * m[0][3], s3 = m[0][1] * m[1][2] - m[1][1] * m[0][2];
  const T s4 = m[0][1] * m[1][3] - m[1][1] * m[0][3], s5 = m[0][2] * m[1][3] - m[1][2] * m[0][3];
  const T c5 = m[2][2] * m[3][3] - m[3][2] * m[2][3], c4 = m[2][1] * m[3][3] - m[3][1] * m[2][3];
  const T c3 = m[2][1] * m[3][2] - m[3][1] * m[2][2], c2 = m[2][0] * m[3][3] - m[3][0] * m[2][3];
  const T c1 = m[2][0] * m[3][2] - m[3][0] * m[2][2], c0 = m[2][0] * m[3][1] - m[3][0] * m[2][1];
  const T inv = T(1) / (s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0);
  Mat4<T> o;
  o.m[0][0] = (m[1][1] * c5 - m[1][2] * c4 + m[1][3] * c3) * inv;
  o.m[0][1] = (-m[0][1] * c5 + m[0][2] * c4 - m[0][3] * c3) * inv;
  o.m[0][2] = (m[3][1] * s5 - m[3][2] * s4 + m[3][3] * s3) * inv;
  o.m[0][3] = (-m[2][1] * s5 + m[2][2] * s4 - m[2][3] * s3) * inv;
  o.m[1][0] = (-m[1][0] * c5 + m[1][2] * c2 - m[1][3] * c1) * inv;
  o.m[1][1] = (m[0][0] * c5 - m[0][2] * c2 + m[0][3] * c1) * inv;
  o.m[1][2] = (-m[3][0] * s5 + m[3][2] * s2 - m[3][3] * s1) * inv;
  o.m[1][3] = (m[2][0] * s5 - m[2][2] * s2 + m[2][3] * s1) * inv;
  o.m[2][0] = (m[1][0] * c4 - m[1][1] * c2 + m[1][3] * c0) * inv;
  o.m[2][1] = (-m[0][0] * c4 + m[0][1] * c2 - m[0][3] * c0) * inv;
  o.m[2][2] = (m[3][0] * s4 - m[3][1] * s2 + m[3][3] * s0) * inv;
  o.m[2][3] = (-m[2][0] * s4 + m[2][1] * s2 - m[2][3] * s0) * inv;
  o.m[3][0] = (-m[1][0] * c3 + m[1][1] * c1 - m[1][2] * c0) * inv;
  o.m[3][1] = (m[0][0] * c3 - m[0][1] * c1 + m[0][2] * c0) * inv;
  o.m[3][2] = (-m[3][0] * s3 + m[3][1] * s1 - m[3][2] * s0) * inv;
  o.m[3][3] = (m[2][0] * s3 - m[2][1] * s1 + m[2][2] * s0) * inv;
  return o;
}

}  // namespace inbetween
