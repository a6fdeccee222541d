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
/// Scale: the computation is scale-invariant (a curve scaled by λ with gain λ·g banks like the
/// original with gain g) from subnormal to near-overflow coordinates; the lateral curvature itself
/// is ±inf where its true value exceeds T (a bend of subnormal radius), never NaN.

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
  // Scale-invariant form: c = (P″⊥ · left)/|P′|² with P′ and P″ each divided by their largest
  // component and the powers of two put back once at the end (std::ldexp), so neither |P′|²
  // underflowing (subnormal-size curves) nor P″/|P′|² overflowing turns into 0, inf·0 or NaN.
  const T s1 = std::fmax(std::abs(d1.x), std::fmax(std::abs(d1.y), std::abs(d1.z)));
  const T s2 = std::fmax(std::abs(d2.x), std::fmax(std::abs(d2.y), std::abs(d2.z)));
  if (norm(side) > std::sqrt(std::numeric_limits<T>::epsilon()) && s1 > T(0) && std::isfinite(s1) &&
      std::isfinite(s2)) {
    const Vec3<T> left = side / norm(side);
    int e1 = 0, e2 = 0, eg = 0;
    const T f1 = std::frexp(s1, &e1);  // s1 = f1·2^e1, f1 in [0.5, 1)
    const Vec3<T> u1 = d1 / s1;        // largest component ±1
    const T n1sq = dot(u1, u1);        // in [1, 3]
    T lateral_mantissa{};              // c = lateral_mantissa · 2^(e2 − 2·e1)
    if (s2 > T(0)) {
      const T f2 = std::frexp(s2, &e2);
      const Vec3<T> u2 = d2 / s2;
      const T across = dot(u2 - t * dot(u2, t), left);  // in [−√3·2, √3·2]
      lateral_mantissa = across * f2 / (f1 * f1 * n1sq);
    }
    const int exponent = e2 - 2 * e1;
    out.lateral_curvature = lateral_mantissa == T(0) ? T(0) : std::ldexp(lateral_mantissa, exponent);
    const T limit = clamp(options.max_bank_rad, T(0), pi_v<T> / T(2));
    if (lateral_mantissa != T(0) && options.gain != T(0) && std::isfinite(options.gain)) {
      // gain · c with the gain's exponent added to the same power of two (λ·gain on a λ-scaled
      // curve gives the same angle).
      const T fg = std::frexp(options.gain, &eg);
      const T beta = std::atan(std::ldexp(fg * lateral_mantissa, eg + exponent));
      if (std::isfinite(beta)) out.bank_rad = clamp(beta, -limit, limit);
    }
  }
  // Rolling up about the tangent by −β turns it towards left = up × t.
  const Vec3<T> n = perpendicular_part(rotate_about(level_up, t, -out.bank_rad), t);
  out.frame = {t, n, cross(t, n)};
  return out;
}

}  // namespace inbetween
