#pragma once
// Analytic test curves for the paths tests, each with closed-form derivatives.

#include <cmath>

#include "inbetween/curves/curve.hpp"
#include "inbetween/curves/helix.hpp"

namespace inbetween::test {

// The helix is inbetween::Helix (curves/helix.hpp).

/// Three pieces, C¹: u ∈ [0, 1] a quarter circle of radius 1 in the xy plane ending at the origin
/// heading +x (centre (0, 1, 0), Frenet normal +y at its end); u ∈ [1, 2] the straight segment
/// (π/2)(u − 1)·x; u ∈ [2, 3] a quarter circle in the xz plane (centre (π/2, 0, −1), Frenet normal
/// −z at its start).  Speed π/2 throughout.  The straight middle has no Frenet frame.
template <class T>
struct ArcLineArc {
  using point_type = Vec3<T>;
  using scalar_type = T;
  Interval<T> domain() const noexcept { return {T(0), T(3)}; }
  int segment_count() const noexcept { return 3; }
  Interval<T> segment_domain(int i) const noexcept { return {T(i), T(i + 1)}; }
  Vec3<T> point(T u) const noexcept { return derivative(u, 0); }
  Vec3<T> derivative(T u, int k) const noexcept {
    u = domain().clamp(u);
    const T w = pi_v<T> / 2;
    if (u < T(1)) {  // φ = w(u − 1) ∈ [−π/2, 0]: (sin φ, 1 − cos φ, 0)
      const T f = w * (u - 1), c = std::cos(f), s = std::sin(f);
      switch (k) {
        case 0: return {s, 1 - c, 0};
        case 1: return {w * c, w * s, 0};
        case 2: return {-w * w * s, w * w * c, 0};
        case 3: return {-w * w * w * c, -w * w * w * s, 0};
        default: return {};
      }
    }
    if (u < T(2)) {
      switch (k) {
        case 0: return {w * (u - 1), 0, 0};
        case 1: return {w, 0, 0};
        default: return {};
      }
    }
    const T f = w * (u - 2), c = std::cos(f), s = std::sin(f);  // (π/2 + sin φ, 0, −(1 − cos φ))
    switch (k) {
      case 0: return {w + s, 0, -(1 - c)};
      case 1: return {w * c, 0, -w * s};
      case 2: return {-w * w * s, 0, -w * w * c};
      case 3: return {-w * w * w * c, 0, w * w * w * s};
      default: return {};
    }
  }
};

/// The trefoil knot (sin u + 2 sin 2u, cos u − 2 cos 2u, −sin 3u), u ∈ [0, 2π]: closed and smooth
/// (every derivative periodic), curvature never zero, in 12 equal pieces for sampling.
template <class T>
struct Trefoil {
  using point_type = Vec3<T>;
  using scalar_type = T;
  Interval<T> domain() const noexcept { return {T(0), T(2) * pi_v<T>}; }
  int segment_count() const noexcept { return 12; }
  Interval<T> segment_domain(int i) const noexcept {
    const T w = T(2) * pi_v<T> / T(12);
    return {w * T(i), i == 11 ? T(2) * pi_v<T> : w * T(i + 1)};
  }
  Vec3<T> point(T u) const noexcept { return derivative(u, 0); }
  Vec3<T> derivative(T u, int k) const noexcept {
    u = domain().clamp(u);
    const T s1 = std::sin(u), c1 = std::cos(u), s2 = std::sin(2 * u), c2 = std::cos(2 * u), s3 = std::sin(3 * u),
            c3 = std::cos(3 * u);
    switch (k) {
      case 0: return {s1 + 2 * s2, c1 - 2 * c2, -s3};
      case 1: return {c1 + 4 * c2, -s1 + 4 * s2, -3 * c3};
      case 2: return {-s1 - 8 * s2, -c1 + 8 * c2, 9 * s3};
      case 3: return {-c1 - 16 * c2, s1 - 16 * s2, 27 * c3};
      default: return {};
    }
  }
};

/// A circle of radius 2 in the plane through the origin with normal (1, 1, 1)/√3, u ∈ [0, 2π],
/// in 8 pieces: closed, planar, constant curvature ½, no torsion.
template <class T>
struct TiltedCircle {
  using point_type = Vec3<T>;
  using scalar_type = T;
  Interval<T> domain() const noexcept { return {T(0), T(2) * pi_v<T>}; }
  int segment_count() const noexcept { return 8; }
  Interval<T> segment_domain(int i) const noexcept {
    const T w = T(2) * pi_v<T> / T(8);
    return {w * T(i), i == 7 ? T(2) * pi_v<T> : w * T(i + 1)};
  }
  Vec3<T> point(T u) const noexcept { return derivative(u, 0); }
  Vec3<T> derivative(T u, int k) const noexcept {
    u = domain().clamp(u);
    // Orthonormal a = (1, −1, 0)/√2, b = (1, 1, −2)/√6, both ⟂ (1, 1, 1).
    const Vec3<T> a = Vec3<T>{1, -1, 0} / std::sqrt(T(2)), b = Vec3<T>{1, 1, -2} / std::sqrt(T(6));
    const T c = std::cos(u), s = std::sin(u);
    switch (k) {
      case 0: return (a * c + b * s) * T(2);
      case 1: return (a * -s + b * c) * T(2);
      case 2: return (a * -c - b * s) * T(2);
      case 3: return (a * s - b * c) * T(2);
      default: return {};
    }
  }
};

}  // namespace inbetween::test
