#pragma once
/// Scalar helpers shared by every module: constants, the scalar concept and small numeric utilities.

#include <cmath>
#include <concepts>
#include <numbers>
#include <type_traits>

namespace inbetween {

/// The scalar types the library is instantiated for (float and double; long double for references).
template <class T>
concept Real = std::floating_point<T>;

/// π in the requested precision.
template <Real T>
inline constexpr T pi_v = std::numbers::pi_v<T>;

/// Degrees → radians.
template <Real T>
constexpr T deg_to_rad(T deg) noexcept { return deg * (pi_v<T> / T(180)); }

/// Radians → degrees.
template <Real T>
constexpr T rad_to_deg(T rad) noexcept { return rad * (T(180) / pi_v<T>); }

/// Linear blend a + (b − a)·u of two scalars; exact at u = 0 and u = 1.
template <Real T>
constexpr T lerp(T a, T b, T u) noexcept { return u == T(1) ? b : a + (b - a) * u; }

/// Clamp x into [lo, hi]; NaN stays NaN.
template <class T>
constexpr T clamp(T x, T lo, T hi) noexcept { return x < lo ? lo : (hi < x ? hi : x); }

/// Wrap an angle into (−π, π].
template <Real T>
T wrap_angle(T a_rad) noexcept {
  T r = std::remainder(a_rad, T(2) * pi_v<T>);  // in [−π, π]
  if (r <= -pi_v<T>) r += T(2) * pi_v<T>;
  return r;
}

}  // namespace inbetween
