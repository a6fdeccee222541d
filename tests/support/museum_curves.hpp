#pragma once
// Curve exhibits for the museum (see museum.hpp): named point lists that stress the curve
// builders — too few points, coincident points, zero-length spans, collinear and back-tracking
// points, extreme magnitudes.  Every curve family is built on every exhibit; the contract is a
// curve that evaluates to finite values everywhere, or an Error with a message and a place.

#include <string>
#include <vector>

#include "inbetween/math/vec.hpp"

namespace inbetween::test {

/// A named list of control points.
template <class T>
struct CurvePointsExhibit {
  std::string name;
  std::vector<Vec3<T>> points;
};

/// The curve exhibits, in precision T.
template <class T>
std::vector<CurvePointsExhibit<T>> museum_curve_points() {
  using V = Vec3<T>;
  const T big = T(sizeof(T) == 4 ? 1e15 : 1e150), small = T(sizeof(T) == 4 ? 1e-15 : 1e-150);
  return {
      {"one point", {V{1, 2, 3}}},
      {"two points", {V{0, 0, 0}, V{1, 2, 3}}},
      {"two coincident points", {V{1, 1, 1}, V{1, 1, 1}}},
      {"all five points coincident", std::vector<V>(5, V{2, -1, T(0.5)})},
      {"zero-length span in the middle", {V{0, 0, 0}, V{1, 0, 0}, V{1, 0, 0}, V{2, 1, 0}, V{3, 0, 0}}},
      {"zero-length span at the start", {V{0, 0, 0}, V{0, 0, 0}, V{1, 1, 0}, V{2, 0, 0}}},
      {"zero-length span at the end", {V{0, 0, 0}, V{1, 1, 0}, V{2, 0, 0}, V{2, 0, 0}}},
      {"collinear, equally spaced", {V{0, 0, 0}, V{1, 2, 0}, V{2, 4, 0}, V{3, 6, 0}, V{4, 8, 0}}},
      {"collinear, back and forth", {V{0, 0, 0}, V{1, 0, 0}, V{T(0.5), 0, 0}, V{2, 0, 0}, V{0, 0, 0}}},
      {"three points", {V{0, 0, 0}, V{1, 1, 0}, V{2, 0, 1}}},
      {"seven points (3k + 1)", {V{0, 0, 0}, V{1, 1, 0}, V{2, 1, 0}, V{3, 0, 0}, V{4, -1, 0}, V{5, -1, 0}, V{6, 0, 0}}},
      {"nearly coincident pair", {V{0, 0, 0}, V{1, 0, 0}, V{T(1) + T(1e-6) * std::numeric_limits<T>::epsilon(), 0, 0}, V{2, 1, 0}}},
      {"huge coordinates", {V{big, 0, 0}, V{0, big, 0}, V{-big, 0, big}, V{0, -big, 0}}},
      {"tiny coordinates", {V{small, 0, 0}, V{0, small, 0}, V{-small, 0, small}, V{0, -small, 0}}},
  };
}

}  // namespace inbetween::test
