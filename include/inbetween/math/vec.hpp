#pragma once
/// Fixed-size vectors Vec2, Vec3, Vec4 over float or double, and the PointTraits that let curves,
/// tracks and arc-length code treat scalars and vectors alike.

#include <cmath>
#include <cstddef>
#include <limits>

#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// 2-D vector (x, y); zero-initialised.
template <Real T>
struct Vec2 {
  T x{}, y{};  ///< components
  using scalar_type = T;            ///< the component type
  static constexpr int size = 2;    ///< number of components
  /// Component i (0..1); any other i gives y (no check).
  constexpr T& operator[](int i) noexcept { return i == 0 ? x : y; }
  constexpr const T& operator[](int i) const noexcept { return i == 0 ? x : y; }
  /// Converts to another precision.
  template <Real U>
  constexpr Vec2<U> cast() const noexcept { return {U(x), U(y)}; }
  /// Exact component-wise equality (use a tolerance for computed values).
  friend constexpr bool operator==(const Vec2&, const Vec2&) = default;
};

/// 3-D vector (x, y, z); zero-initialised.  Points and directions share this type; Mat4 and
/// Transform say which one they mean (transform_point vs transform_direction).
template <Real T>
struct Vec3 {
  T x{}, y{}, z{};  ///< components
  using scalar_type = T;            ///< the component type
  static constexpr int size = 3;    ///< number of components
  /// Component i (0..2); any other i gives z (no check).
  constexpr T& operator[](int i) noexcept { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr const T& operator[](int i) const noexcept { return i == 0 ? x : (i == 1 ? y : z); }
  /// Converts to another precision.
  template <Real U>
  constexpr Vec3<U> cast() const noexcept { return {U(x), U(y), U(z)}; }
  /// Exact component-wise equality (use a tolerance for computed values).
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

/// 4-D vector (x, y, z, w); zero-initialised.  Also the homogeneous form of a Vec3.
template <Real T>
struct Vec4 {
  T x{}, y{}, z{}, w{};  ///< components
  using scalar_type = T;            ///< the component type
  static constexpr int size = 4;    ///< number of components
  /// Component i (0..3); any other i gives w (no check).
  constexpr T& operator[](int i) noexcept { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
  constexpr const T& operator[](int i) const noexcept {
    return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w));
  }
  /// Converts to another precision.
  template <Real U>
  constexpr Vec4<U> cast() const noexcept { return {U(x), U(y), U(z), U(w)}; }
  /// Exact component-wise equality (use a tolerance for computed values).
  friend constexpr bool operator==(const Vec4&, const Vec4&) = default;
};

/// Precision aliases: f = float, d = double.
using Vec2f = Vec2<float>;
using Vec2d = Vec2<double>;
using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;
using Vec4f = Vec4<float>;
using Vec4d = Vec4<double>;

// ---------------------------------------------------------------- element-wise arithmetic
#define INBETWEEN_VEC_OPS(V)                                                                       \
  template <Real T>                                                                                \
  constexpr V<T> operator+(V<T> a, const V<T>& b) noexcept {                                       \
    for (int i = 0; i < V<T>::size; ++i) a[i] += b[i];                                             \
    return a;                                                                                      \
  }                                                                                                \
  template <Real T>                                                                                \
  constexpr V<T> operator-(V<T> a, const V<T>& b) noexcept {                                       \
    for (int i = 0; i < V<T>::size; ++i) a[i] -= b[i];                                             \
    return a;                                                                                      \
  }                                                                                                \
  template <Real T>                                                                                \
  constexpr V<T> operator-(V<T> a) noexcept {                                                      \
    for (int i = 0; i < V<T>::size; ++i) a[i] = -a[i];                                             \
    return a;                                                                                      \
  }                                                                                                \
  template <Real T>                                                                                \
  constexpr V<T> operator*(V<T> a, T s) noexcept {                                                 \
    for (int i = 0; i < V<T>::size; ++i) a[i] *= s;                                                \
    return a;                                                                                      \
  }                                                                                                \
  template <Real T>                                                                                \
  constexpr V<T> operator*(T s, V<T> a) noexcept { return a * s; }                                 \
  template <Real T>                                                                                \
  constexpr V<T> operator/(V<T> a, T s) noexcept {                                                 \
    for (int i = 0; i < V<T>::size; ++i) a[i] /= s;                                               \
    return a;                                                                                      \
  }                                                                                                \
  template <Real T>                                                                                \
  constexpr V<T>& operator+=(V<T>& a, const V<T>& b) noexcept { return a = a + b; }                \
  template <Real T>                                                                                \
  constexpr V<T>& operator-=(V<T>& a, const V<T>& b) noexcept { return a = a - b; }                \
  template <Real T>                                                                                \
  constexpr V<T>& operator*=(V<T>& a, T s) noexcept { return a = a * s; }                          \
  template <Real T>                                                                                \
  constexpr V<T>& operator/=(V<T>& a, T s) noexcept { return a = a / s; }                          \
  /** Dot product. */                                                                              \
  template <Real T>                                                                                \
  constexpr T dot(const V<T>& a, const V<T>& b) noexcept {                                         \
    T s{};                                                                                         \
    for (int i = 0; i < V<T>::size; ++i) s += a[i] * b[i];                                         \
    return s;                                                                                      \
  }                                                                                                \
  /** Component-wise product. */                                                                   \
  template <Real T>                                                                                \
  constexpr V<T> hadamard(V<T> a, const V<T>& b) noexcept {                                        \
    for (int i = 0; i < V<T>::size; ++i) a[i] *= b[i];                                             \
    return a;                                                                                      \
  }                                                                                                \
  /** True when every component is finite. */                                                     \
  template <Real T>                                                                                \
  bool is_finite(const V<T>& a) noexcept {                                                         \
    for (int i = 0; i < V<T>::size; ++i)                                                           \
      if (!std::isfinite(a[i])) return false;                                                      \
    return true;                                                                                   \
  }

INBETWEEN_VEC_OPS(Vec2)
INBETWEEN_VEC_OPS(Vec3)
INBETWEEN_VEC_OPS(Vec4)
#undef INBETWEEN_VEC_OPS

/// Cross product a × b (right-handed).
template <Real T>
constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// 2-D cross product (the z of the 3-D cross product).
template <Real T>
constexpr T cross(const Vec2<T>& a, const Vec2<T>& b) noexcept { return a.x * b.y - a.y * b.x; }

// ---------------------------------------------------------------- PointTraits
/// How generic code sees a point type P: its scalar, its dimension and its components.
/// Specialised for the Real scalars (dimension 1) and Vec2/3/4.
template <class P>
struct PointTraits;

/// A bare scalar is a 1-D point.
template <Real T>
struct PointTraits<T> {
  using scalar = T;              ///< the scalar type
  static constexpr int dim = 1;  ///< number of components
  /// Component i (only 0).
  static constexpr T get(const T& p, int) noexcept { return p; }
  /// Sets component i (only 0).
  static constexpr void set(T& p, int, T v) noexcept { p = v; }
};

#define INBETWEEN_POINT_TRAITS(V)                                                                  \
  template <Real T>                                                                                \
  struct PointTraits<V<T>> {                                                                       \
    using scalar = T;                                                                              \
    static constexpr int dim = V<T>::size;                                                         \
    static constexpr T get(const V<T>& p, int i) noexcept { return p[i]; }                         \
    static constexpr void set(V<T>& p, int i, T v) noexcept { p[i] = v; }                          \
  };
INBETWEEN_POINT_TRAITS(Vec2)
INBETWEEN_POINT_TRAITS(Vec3)
INBETWEEN_POINT_TRAITS(Vec4)
#undef INBETWEEN_POINT_TRAITS

/// A point type usable by the generic curve code: a Real or a Vec2/3/4.
template <class P>
concept Point = requires { typename PointTraits<P>::scalar; };

/// The scalar of a point type.
template <Point P>
using scalar_of = typename PointTraits<P>::scalar;

/// Dot product of two scalars (so generic code can write dot(a, b) for any Point).
template <Real T>
constexpr T dot(T a, T b) noexcept { return a * b; }

/// True for a finite scalar.
template <Real T>
bool is_finite(T a) noexcept { return std::isfinite(a); }

/// Squared Euclidean norm.
template <Point P>
constexpr scalar_of<P> squared_norm(const P& a) noexcept { return dot(a, a); }

namespace vec_detail {
/// norm()'s rare path (a sum of squares that overflows or underflows): the components scaled by the
/// power of two 2^-e nearest below the largest |component|, so that every step is the plain path's
/// times an exact power of two and a point scaled by 2^k gets exactly 2^k times its norm (paths on
/// huge and tiny meshes are the same bits scaled).  Kept out of line so the common path inlines.
template <Point P>
[[gnu::noinline]] scalar_of<P> norm_scaled(const P& a) noexcept {
  using T = scalar_of<P>;
  T big{};
  for (int i = 0; i < PointTraits<P>::dim; ++i) {
    // std::fmax's value (a NaN component is skipped) without its library call.
    const T c = std::abs(PointTraits<P>::get(a, i));
    if (c > big) big = c;
  }
  if (big == T(0) || !std::isfinite(big)) return big;
  const int e = std::ilogb(big);
  T s{};
  for (int i = 0; i < PointTraits<P>::dim; ++i) {
    const T c = std::ldexp(PointTraits<P>::get(a, i), -e);
    s += c * c;
  }
  return std::ldexp(std::sqrt(s), e);
}
}  // namespace vec_detail

/// Euclidean norm, computed without overflow or underflow for any finite input.
template <Point P>
[[gnu::always_inline]] inline scalar_of<P> norm(const P& a) noexcept {
  using T = scalar_of<P>;
  if constexpr (PointTraits<P>::dim == 1) {
    return std::abs(a);
  } else {
    // The plain √(Σc²) where the sum of squares can neither have overflowed nor lost digits to
    // underflow (a square's underflow error, below the smallest subnormal, is then under ε² of the
    // sum): the common case, one rounding fewer than the scaled form and a fraction of its time
    // (compose() of every joint of a skeleton, every frame).  Otherwise the scaled form.
    const T sum = squared_norm(a);
    constexpr T kLeast = std::numeric_limits<T>::min() / std::numeric_limits<T>::epsilon();
    if (sum >= kLeast && sum <= std::numeric_limits<T>::max()) [[likely]] return std::sqrt(sum);
    return vec_detail::norm_scaled(a);
  }
}

/// Largest |component| of a point (0 for the zero point).
template <Point P>
scalar_of<P> max_abs_component(const P& a) noexcept {
  scalar_of<P> big{};
  for (int i = 0; i < PointTraits<P>::dim; ++i) big = std::fmax(big, std::abs(PointTraits<P>::get(a, i)));
  return big;
}

/// a · 2^e, component by component (std::ldexp: exact unless a component over- or underflows, when
/// it becomes ±inf or rounds towards 0).  The tool of scaled evaluations near the ends of the range.
template <Point P>
P scale_by_pow2(P a, int e) noexcept {
  for (int i = 0; i < PointTraits<P>::dim; ++i) PointTraits<P>::set(a, i, std::ldexp(PointTraits<P>::get(a, i), e));
  return a;
}

/// Distance between two points.
template <Point P>
scalar_of<P> distance(const P& a, const P& b) noexcept { return norm(P(b - a)); }

/// a / |a|; returns `fallback` when |a| is zero or not finite (documented degenerate case).
template <Point P>
P normalized(const P& a, const P& fallback) noexcept {
  const auto n = norm(a);
  if (!(n > 0) || !std::isfinite(n)) return fallback;
  return a / n;
}

/// Linear blend a + (b − a)·u of two points; exact at u = 0 and u = 1.
template <Point P>
constexpr P lerp(const P& a, const P& b, scalar_of<P> u) noexcept
  requires(!Real<P>)
{
  if (u == scalar_of<P>(1)) return b;
  return a + (b - a) * u;
}

}  // namespace inbetween
