#pragma once
/// The analytic arc-length integrand of a cubic segment (texts 004 Eqs. 3.3–3.7, 3.16): for
/// P(v) = a v³ + b v² + c v + d, |dP/dv|² = A v⁴ + B v³ + C v² + D v + E with, summed over the
/// coordinates (any dimension, the texts print the 2-D case),
///   A = 9 a·a,  B = 12 a·b,  C = 6 a·c + 4 b·b,  D = 4 b·c,  E = c·c.

#include <cmath>

#include "inbetween/curves/curve.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// The quartic A v⁴ + B v³ + C v² + D v + E = |dP/dv|² of a power-form cubic.
template <Real T>
struct SpeedQuartic {
  T A{}, B{}, C{}, D{}, E{};  ///< coefficients of v⁴ … v⁰ (Eq. 3.7)

  /// |dP/dv|² at v, by Horner's rule; may come out slightly negative by rounding where the speed
  /// is zero (cusps, coincident control points).
  constexpr T squared_speed(T v) const noexcept { return (((A * v + B) * v + C) * v + D) * v + E; }
  /// |dP/dv| at v: the square root of squared_speed(v), with rounding below zero read as 0 (never
  /// NaN).  Where the speed is near zero this loses about half the digits compared with
  /// norm(cubic.derivative(v, 1)), because the quartic is a sum of large terms that cancel.
  T speed(T v) const noexcept {
    const T q = squared_speed(v);
    return q > T(0) ? std::sqrt(q) : T(0);
  }
};

/// The integrand coefficients of Eq. 3.7 (extended from 2-D to any dimension) of a power-form cubic.
template <Point P>
constexpr SpeedQuartic<scalar_of<P>> speed_quartic(const PowerCubic<P>& cubic) noexcept {
  using T = scalar_of<P>;
  return {T(9) * dot(cubic.a, cubic.a), T(12) * dot(cubic.a, cubic.b),
          T(6) * dot(cubic.a, cubic.c) + T(4) * dot(cubic.b, cubic.b), T(4) * dot(cubic.b, cubic.c),
          dot(cubic.c, cubic.c)};
}

}  // namespace inbetween
