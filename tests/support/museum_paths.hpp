#pragma once
// Path exhibits for the museum (see museum.hpp): named point lists and camera set-ups that stress
// the paths module — a straight line (no Frenet normal anywhere), a cusp, a zero-length path, a
// single point, and a camera whose up vector is parallel to its view.  The contract: degenerate
// but legal input gives a documented fallback and finite, orthonormal frames (never NaN); bad input
// (empty, NaN) gives an Error naming the index.

#include <limits>
#include <string>
#include <vector>

#include "inbetween/math/vec.hpp"

namespace inbetween::test {

/// A named polyline.
template <class T>
struct PathExhibit {
  std::string name;
  std::vector<Vec3<T>> points;
};

/// Degenerate but legal polylines.
template <class T>
std::vector<PathExhibit<T>> museum_paths() {
  using V = Vec3<T>;
  return {
      {"straight line: no Frenet normal", {V{0, 0, 0}, V{1, 1, 1}, V{2, 2, 2}, V{3, 3, 3}}},
      // Uniform Catmull-Rom: the tangent at the middle point is (P2 − P0)/2 = 0, a cusp.
      {"cusp: path turns back on itself", {V{0, 0, 0}, V{2, 1, 0}, V{0, 0, 0}}},
      {"zero-length path", {V{1, 2, 3}, V{1, 2, 3}, V{1, 2, 3}}},
      {"single point", {V{1, 2, 3}}},
      {"two points", {V{0, 0, 0}, V{0, 0, 5}}},
      {"sharp corner", {V{0, 0, 0}, V{1, 0, 0}, V{1, 1, 0}, V{1, 1, 1}}},
  };
}

/// Bad polylines: each must be rejected with an Error whose location names `bad_index`
/// (-1: the whole input, e.g. empty).
template <class T>
struct BadPathExhibit {
  std::string name;
  std::vector<Vec3<T>> points;
  int bad_index = -1;
};

/// Inputs that are not paths.
template <class T>
std::vector<BadPathExhibit<T>> museum_bad_paths() {
  using V = Vec3<T>;
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  return {
      {"empty path", {}, -1},
      {"NaN in point 2", {V{0, 0, 0}, V{1, 0, 0}, V{nan, 0, 0}, V{3, 0, 0}}, 2},
      {"infinity in point 0", {V{0, inf, 0}, V{1, 0, 0}, V{2, 0, 0}}, 0},
  };
}

/// A camera set-up: eye, target and up.
template <class T>
struct CameraExhibit {
  std::string name;
  Vec3<T> eye, target, up;
};

/// Degenerate camera set-ups (each has a documented fallback in paths/camera.hpp).
template <class T>
std::vector<CameraExhibit<T>> museum_cameras() {
  using V = Vec3<T>;
  return {
      {"up parallel to view", V{0, 0, 0}, V{0, 5, 0}, V{0, 1, 0}},
      {"up antiparallel to view", V{0, 0, 0}, V{0, -5, 0}, V{0, 1, 0}},
      {"target at the eye", V{1, 2, 3}, V{1, 2, 3}, V{0, 1, 0}},
      {"zero up", V{0, 0, 0}, V{1, 0, 0}, V{0, 0, 0}},
      {"up parallel to view and to the fallback", V{0, 0, 0}, V{0, 0, 7}, V{0, 0, 1}},
  };
}

}  // namespace inbetween::test
