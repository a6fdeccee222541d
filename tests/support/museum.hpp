#pragma once
// The museum: named degenerate-but-legal inputs that every module's tests loop over.  Each module
// adds its own exhibits below (rotations, curves, timing, tracks); a test iterates over
// `museum_*()` and checks its module's contract (finite output, documented fallback, or a clear
// error) on every exhibit.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/math/mat.hpp"
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

/// A named rotation matrix that stresses conversion code (each is exactly or nearly a rotation).
template <class T>
struct RotationMatrixExhibit {
  std::string name;
  Mat3<T> r;
};

/// Rotation matrices at the hard places of the conversions: the identity, the three half turns
/// about the coordinate axes and about a diagonal (trace −1: the quaternion's w is 0, so a
/// trace-based conversion divides by zero), an almost half turn, tiny angles, and gimbal-lock
/// poses (Tait–Bryan middle angle ±90°, proper-Euler middle angle 0 and 180°).  Built from their
/// exact entries where those are exact (0, ±1), otherwise from cos/sin in T.
template <class T>
std::vector<RotationMatrixExhibit<T>> museum_rotation_matrices() {
  using M = Mat3<T>;
  const auto rz = [](T a) {
    return M{{{std::cos(a), -std::sin(a), T(0)}, {std::sin(a), std::cos(a), T(0)}, {T(0), T(0), T(1)}}};
  };
  const auto ry = [](T a) {
    return M{{{std::cos(a), T(0), std::sin(a)}, {T(0), T(1), T(0)}, {-std::sin(a), T(0), std::cos(a)}}};
  };
  const auto rx = [](T a) {
    return M{{{T(1), T(0), T(0)}, {T(0), std::cos(a), -std::sin(a)}, {T(0), std::sin(a), std::cos(a)}}};
  };
  const T third = T(1) / T(3), two_thirds = T(2) / T(3);
  // Half turn about (1, 1, 1)/√3: R = 2 n nᵀ − I has exact-ish entries −1/3 and 2/3.
  const M half_diag{{{-third, two_thirds, two_thirds}, {two_thirds, -third, two_thirds}, {two_thirds, two_thirds, -third}}};
  const T tiny = T(16) * std::numeric_limits<T>::epsilon();
  return {
      {"identity", M{}},
      {"half turn about x", M{{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}}},
      {"half turn about y", M{{{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}},
      {"half turn about z", M{{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}}},
      {"half turn about the diagonal (1,1,1)", half_diag},
      {"almost a half turn about z", rz(pi_v<T> - T(1e-4))},
      {"a half turn in T about x then y (trace -1)", rx(pi_v<T>) * ry(T(0.3))},
      {"tiny angle about z", rz(tiny)},
      {"quarter turn about z (the texts' R(90))", M{{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}}},
      {"gimbal lock: y = +90 after x (xyz middle)", ry(pi_v<T> / 2) * rx(T(0.4))},
      {"gimbal lock: y = -90 between z and x", rz(T(0.7)) * ry(-pi_v<T> / 2) * rx(T(-1.2))},
      {"gimbal lock: exact y = +90 (entries 0, +-1)", M{{{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}}}},
      {"gimbal lock: proper zxz middle 0", rz(T(0.5)) * rz(T(0.6))},
      {"gimbal lock: proper zxz middle 180", rz(T(0.5)) * rx(pi_v<T>) * rz(T(-0.25))},
  };
}

}  // namespace inbetween::test
