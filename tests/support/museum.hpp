#pragma once
// The museum: named degenerate-but-legal inputs that every module's tests loop over.  Each module
// adds its own exhibits below (rotations, curves, timing, tracks); a test iterates over
// `museum_*()` and checks its module's contract (finite output, documented fallback, or a clear
// error) on every exhibit.

#include <limits>
#include <string>
#include <vector>

#include "inbetween/math/quat.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween::test {

/// A named pair of unit quaternions that stresses interpolation and conversion code.
template <class T>
struct QuatPairExhibit {
  std::string name;
  Quat<T> a, b;
};

/// Pairs of rotations: identical, nearly identical, antipodal (same rotation, opposite sign),
/// nearly antipodal, opposite rotations (180° apart), tiny angles, and the gimbal-lock poses.
template <class T>
std::vector<QuatPairExhibit<T>> museum_quat_pairs() {
  using Q = Quat<T>;
  const Q id{};
  const Q qx = Q::from_axis_angle(Vec3<T>{1, 0, 0}, T(0.7));
  const Q tiny = Q::from_axis_angle(Vec3<T>{0, 1, 0}, T(16) * std::numeric_limits<T>::epsilon());
  const Q half_turn = Q::from_axis_angle(Vec3<T>{0, 0, 1}, pi_v<T>);
  const Q near_half = Q::from_axis_angle(Vec3<T>{0, 0, 1}, pi_v<T> - T(1e-5));
  const Q pitch90 = Q::from_axis_angle(Vec3<T>{0, 1, 0}, pi_v<T> / 2);
  return {
      {"identical identity", id, id},
      {"identical general", qx, qx},
      {"nearly identical", qx, normalized(qx * tiny)},
      {"antipodal (same rotation, opposite sign)", qx, -qx},
      {"nearly antipodal", qx, normalized(-(qx * tiny))},
      {"half turn from identity", id, half_turn},
      {"almost a half turn", id, near_half},
      {"tiny angle from identity", id, tiny},
      {"gimbal lock pitch +90", id, pitch90},
      {"gimbal lock pitch -90", pitch90, conjugate(pitch90)},
  };
}

}  // namespace inbetween::test
