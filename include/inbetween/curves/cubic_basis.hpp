#pragma once
/// The cubic segment in matrix form P(u) = U·M·B (texts 000 §2.3, 004 App. B.5): U = [u³ u² u 1],
/// M a 4×4 basis matrix, B four geometric constraints (points or tangents).  The basis matrices of
/// Hermite, Bézier, Catmull-Rom (tension s), the uniform cubic B-spline and parabolic blending, the
/// blending functions U·M, and the conversion of a matrix-form segment into power form.

#include <array>

#include "inbetween/curves/curve.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// A 4×4 cubic basis matrix, row-major: row 0 multiplies u³, row 3 multiplies 1.
template <Real T>
using BasisMatrix = std::array<std::array<T, 4>, 4>;

/// Hermite basis; geometry B = [P0, P1, P0', P1'] (000 §2.3.1).
template <Real T>
constexpr BasisMatrix<T> hermite_basis() noexcept {
  return {{{2, -2, 1, 1}, {-3, 3, -2, -1}, {0, 0, 1, 0}, {1, 0, 0, 0}}};
}

/// Cubic Bézier basis; geometry B = [P0, P1, P2, P3] (000 §2.3.2).
template <Real T>
constexpr BasisMatrix<T> bezier_basis() noexcept {
  return {{{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}}};
}

/// Catmull-Rom basis with tension s (tangent at P_i is s·(P_{i+1} − P_{i−1}); s = 1/2 is the
/// classic spline); geometry B = [P_{i−1}, P_i, P_{i+1}, P_{i+2}], the segment runs P_i → P_{i+1}.
template <Real T>
constexpr BasisMatrix<T> catmull_rom_basis(T s = T(0.5)) noexcept {
  return {{{-s, T(2) - s, s - T(2), s},
           {T(2) * s, s - T(3), T(3) - T(2) * s, -s},
           {-s, T(0), s, T(0)},
           {T(0), T(1), T(0), T(0)}}};
}

/// Uniform cubic B-spline basis (1/6 factor included); geometry B = [P_{i−1}, P_i, P_{i+1}, P_{i+2}].
/// The segment approximates: it starts at (P_{i−1} + 4P_i + P_{i+1})/6.
template <Real T>
constexpr BasisMatrix<T> uniform_bspline_basis() noexcept {
  constexpr T k = T(1) / T(6);
  return {{{-k, T(3) * k, T(-3) * k, k},
           {T(3) * k, T(-6) * k, T(3) * k, T(0)},
           {T(-3) * k, T(0), T(3) * k, T(0)},
           {k, T(4) * k, k, T(0)}}};
}

/// Parabolic blending basis for an interior segment; geometry B = [P_{i−1}, P_i, P_{i+1}, P_{i+2}].
/// Derived from (1 − u)·Q(u) + u·R(u) with Q the parabola through P_{i−1}, P_i, P_{i+1} at
/// u = −1, 0, 1 and R the one through P_i, P_{i+1}, P_{i+2} at u = 0, 1, 2.  With uniform spacing
/// this equals catmull_rom_basis(1/2) (see docs/curves.md); only the end segments differ.
template <Real T>
constexpr BasisMatrix<T> parabolic_blend_basis() noexcept {
  // Q = P_i + u(P_{i+1} − P_{i−1})/2 + u²(P_{i−1} − 2P_i + P_{i+1})/2
  // R = P_i + u(−3P_i + 4P_{i+1} − P_{i+2})/2 + u²(P_i − 2P_{i+1} + P_{i+2})/2
  // (1−u)Q + uR = q0 + q1 u + (q2 + r1 − q1) u² + (r2 − q2) u³, written row by row below.
  constexpr T h = T(0.5);
  return {{{-h, T(3) * h, T(-3) * h, h},  // r2 − q2
           {T(2) * h, T(-5) * h, T(4) * h, -h},  // q2 + r1 − q1
           {-h, T(0), h, T(0)},  // q1
           {T(0), T(1), T(0), T(0)}}};  // q0
}

/// The blending functions U·M at u: weights of the four geometric constraints.
template <Real T>
constexpr std::array<T, 4> blending_functions(const BasisMatrix<T>& m, T u) noexcept {
  const T powers[4] = {u * u * u, u * u, u, T(1)};
  std::array<T, 4> w{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) w[c] += powers[r] * m[r][c];
  return w;
}

/// The k-th derivative (k = 0..3) of the blending functions at u.
template <Real T>
constexpr std::array<T, 4> blending_function_derivatives(const BasisMatrix<T>& m, T u, int k) noexcept {
  T powers[4] = {u * u * u, u * u, u, T(1)};
  if (k == 1) powers[0] = T(3) * u * u, powers[1] = T(2) * u, powers[2] = T(1), powers[3] = T(0);
  if (k == 2) powers[0] = T(6) * u, powers[1] = T(2), powers[2] = T(0), powers[3] = T(0);
  if (k == 3) powers[0] = T(6), powers[1] = T(0), powers[2] = T(0), powers[3] = T(0);
  if (k > 3) powers[0] = powers[1] = powers[2] = powers[3] = T(0);
  std::array<T, 4> w{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) w[c] += powers[r] * m[r][c];
  return w;
}

/// The power-form coefficients M·B of a matrix-form segment with geometry g0..g3.
template <Point P>
constexpr PowerCubic<P> power_form(const BasisMatrix<scalar_of<P>>& m, const P& g0, const P& g1,
                                   const P& g2, const P& g3) noexcept {
  const P* g[4] = {&g0, &g1, &g2, &g3};
  P row[4]{};
  for (int r = 0; r < 4; ++r) {
    P acc{};
    for (int c = 0; c < 4; ++c)
      if (m[r][c] != 0) acc = acc + *g[c] * m[r][c];
    row[r] = acc;
  }
  return {row[0], row[1], row[2], row[3]};
}

/// P(u) = U·M·B evaluated literally (blending functions times geometry), for u in [0, 1].
template <Point P>
constexpr P evaluate_matrix_form(const BasisMatrix<scalar_of<P>>& m, const P& g0, const P& g1,
                                 const P& g2, const P& g3, scalar_of<P> u) noexcept {
  const auto w = blending_functions(m, u);
  return g0 * w[0] + g1 * w[1] + g2 * w[2] + g3 * w[3];
}

/// Power form of the Hermite segment from p0 to p1 with tangents t0, t1 (dP/dv at v = 0 and 1).
template <Point P>
constexpr PowerCubic<P> hermite_power_form(const P& p0, const P& p1, const P& t0, const P& t1) noexcept {
  using T = scalar_of<P>;
  return {(p0 - p1) * T(2) + t0 + t1, (p1 - p0) * T(3) - t0 * T(2) - t1, t0, p0};
}

}  // namespace inbetween
