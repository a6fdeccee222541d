#pragma once
/// A circular helix with closed-form derivatives: the standard non-polynomial curve for checking
/// arc length (exact length), Frenet frames (constant curvature and torsion) and rotation-minimising
/// frames (the normal turns against the torsion at a known rate).

#include <cmath>

#include "inbetween/curves/curve.hpp"

namespace inbetween {

/// P(u) = (radius·cos u, radius·sin u, rise·u) for u ∈ [u_begin, u_end], split into `segments`
/// equal pieces (the joints are smooth; pieces only guide arc-length and frame sampling).
/// Speed √(radius² + rise²), so the length is that times (u_end − u_begin); curvature
/// radius/(radius² + rise²); torsion rise/(radius² + rise²).  Defaults: two turns of a unit helix
/// rising 0.5 per radian (curvature 0.8, torsion 0.4).  segments ≥ 1 and u_begin ≤ u_end are the
/// caller's to keep.
template <Real T>
struct Helix {
  using point_type = Vec3<T>;  ///< the point type
  using scalar_type = T;       ///< its scalar
  T radius = 1;                       ///< distance from the z axis
  T rise = T(0.5);                    ///< z advance per radian of turn
  T u_begin = 0;                      ///< start angle (rad)
  T u_end = T(4) * pi_v<T>;           ///< end angle (rad)
  int segments = 8;                   ///< equal pieces of [u_begin, u_end]

  /// [u_begin, u_end].
  Interval<T> domain() const noexcept { return {u_begin, u_end}; }
  /// Number of equal pieces.
  int segment_count() const noexcept { return segments; }
  /// Piece i of the domain; the last piece ends exactly at u_end.
  Interval<T> segment_domain(int i) const noexcept {
    const T h = (u_end - u_begin) / T(segments);
    return {u_begin + h * T(i), i + 1 == segments ? u_end : u_begin + h * T(i + 1)};
  }
  /// P(u), u clamped into the domain.
  Vec3<T> point(T u) const noexcept { return derivative(u, 0); }
  /// d^kP/du^k for k = 0..3 (higher orders: the pattern repeats, but 0 is returned), u clamped.
  Vec3<T> derivative(T u, int k) const noexcept {
    u = domain().clamp(u);
    const T c = std::cos(u), s = std::sin(u);
    switch (k) {
      case 0: return {radius * c, radius * s, rise * u};
      case 1: return {-radius * s, radius * c, rise};
      case 2: return {-radius * c, -radius * s, T(0)};
      case 3: return {radius * s, -radius * c, T(0)};
      default: return {};
    }
  }
};

}  // namespace inbetween
