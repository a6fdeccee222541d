#pragma once
/// Banking into turns (texts 004 §3.4.2, end of "Use of the Frenet frame"): the horizontal part of
/// the curvature vector says which way a path turns and how sharply; an object can roll into the
/// turn by an angle that grows with it (or away from it, the roller-coaster effect, with a negative
/// gain).
///
/// With unit tangent T, global up U and curvature vector κN = (P″ − (P″·T)T)/|P′|², the lateral
/// curvature is c = κN · L, where L = (U × T)/|U × T| points to the left of travel (for travel
/// along +x with +y up, left is −z).  Only the component of κN along L counts, so climbing and
/// diving (curvature in the vertical plane) do not bank.  The bank angle is
///   β = atan(gain · c), clamped into [−max_bank_rad, max_bank_rad],
/// and β > 0 rolls the object's up vector towards the left, into a left turn.  With
/// gain = v²/g (speed squared over gravity, in length units) β is the angle of a coordinated turn:
/// tan β = v²κ/g, the roll at which the rider feels the apparent weight straight down.
/// Fallbacks: travel parallel to U (no horizontal plane to turn in) and a zero P′ give β = 0.

#include <cmath>
#include <limits>

#include "inbetween/paths/path_frame.hpp"

namespace inbetween {

/// Options of banking().
template <Real T>
struct BankingOptions {
  Vec3<T> up{T(0), T(1), T(0)};     ///< global up (normalised here; zero reads as +y)
  T gain = T(1);                    ///< length units: β = atan(gain · lateral curvature); v²/g for a coordinated turn
  T max_bank_rad = pi_v<T> / T(3);  ///< largest |β|, in [0, π/2]
};

/// The bank at one parameter value.
template <Real T>
struct Banking {
  T lateral_curvature{};  ///< c = κN · left, 1/length; > 0 turning left
  T bank_rad{};           ///< β, > 0 rolls up towards the left
  PathFrame<T> frame{};   ///< tangent, banked up as the normal, binormal = tangent × normal
};

/// The bank of `curve` at u (clamped).  Never NaN for a built curve and finite options.
template <Curve C>
  requires std::same_as<typename C::point_type, Vec3<typename C::scalar_type>>
Banking<typename C::scalar_type> banking(const C& curve, typename C::scalar_type u,
                                         const BankingOptions<typename C::scalar_type>& options = {}) noexcept {
  using T = typename C::scalar_type;
  Banking<T> out;
  const Vec3<T> up = normalized(options.up, Vec3<T>{T(0), T(1), T(0)});
  const Vec3<T> t = unit_tangent(curve, u);
  const Vec3<T> level_up = perpendicular_part(up, t);
  const Vec3<T> side = cross(up, t);
  const Vec3<T> d1 = curve.derivative(u, 1), d2 = curve.derivative(u, 2);
  const T speed2 = dot(d1, d1);
  if (norm(side) > std::sqrt(std::numeric_limits<T>::epsilon()) && speed2 > T(0) && std::isfinite(speed2)) {
    const Vec3<T> left = side / norm(side);
    const Vec3<T> kappa = (d2 - t * dot(d2, t)) / speed2;
    out.lateral_curvature = dot(kappa, left);
    const T limit = clamp(options.max_bank_rad, T(0), pi_v<T> / T(2));
    const T beta = std::atan(options.gain * out.lateral_curvature);
    if (std::isfinite(beta)) out.bank_rad = clamp(beta, -limit, limit);
  }
  // Rolling up about the tangent by −β turns it towards left = up × t.
  const Vec3<T> n = perpendicular_part(rotate_about(level_up, t, -out.bank_rad), t);
  out.frame = {t, n, cross(t, n)};
  return out;
}

}  // namespace inbetween
