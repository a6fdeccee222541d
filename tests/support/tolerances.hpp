#pragma once
// Named tolerances.  Each one says where it comes from; tests use these names, never bare numbers.

#include <limits>

namespace inbetween::test {

/// Machine epsilon of T.
template <class T>
inline constexpr T eps = std::numeric_limits<T>::epsilon();

/// A few units in the last place of a value of magnitude ~1: for results of a handful of
/// correctly rounded operations (products of unit quaternions, rotations of unit vectors).
template <class T>
inline constexpr T few_ulp = T(8) * std::numeric_limits<T>::epsilon();

/// Round trips through two or three conversions (each a few ulp, with sqrt/atan2 in between):
/// 64 ulp leaves room for error growth while still catching any formula that loses digits, which
/// shows up as errors of order √eps (1e-8 in double, 3e-4 in float).
template <class T>
inline constexpr T roundtrip_tol = T(64) * std::numeric_limits<T>::epsilon();

/// Agreement with an independent implementation evaluated in double (SciPy, Eigen) for values of
/// magnitude ~1.
inline constexpr double reference_tol = 1e-12;

}  // namespace inbetween::test
