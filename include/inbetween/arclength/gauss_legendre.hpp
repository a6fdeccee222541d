#pragma once
/// Gauss–Legendre quadrature (texts 004 Eqs. 3.13–3.15): n nodes and weights on [−1, 1], and the
/// mapped rule on any interval [a, b].  The n-point rule integrates polynomials of degree 2n − 1
/// exactly.

#include <span>

#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// The largest number of nodes available from gauss_legendre_rule().
inline constexpr int kMaxGaussLegendreOrder = 64;

/// An n-point Gauss–Legendre rule on [−1, 1]: nodes ascending in (−1, 1), positive weights that sum
/// to 2.  The spans point into storage that lives for the whole program.
struct GaussLegendreRule {
  std::span<const double> nodes;    ///< x_i, ascending, symmetric about 0
  std::span<const double> weights;  ///< w_i > 0, Σ w_i = 2
  /// Number of nodes n.
  [[nodiscard]] int order() const noexcept { return int(nodes.size()); }
};

/// The rule with `order` nodes, `order` clamped into [1, kMaxGaussLegendreOrder].  The nodes are the
/// roots of the Legendre polynomial P_n, found once (thread-safely, on first use) by Newton
/// iteration in long double and rounded to double; they agree with the 10-digit table printed in
/// texts 004 Figure 3.8 for n = 10.
[[nodiscard]] GaussLegendreRule gauss_legendre_rule(int order) noexcept;

/// ∫_a^b f(x) dx ≈ (b − a)/2 · Σ w_i f((b − a)/2 · x_i + (b + a)/2)  (Eq. 3.15).  Returns 0 when
/// a == b; b < a gives the negative of the integral over [b, a].
template <Real T, class F>
T integrate_gauss_legendre(F&& f, T a, T b, const GaussLegendreRule& rule) noexcept {
  const T half = (b - a) / T(2);
  const T mid = (b + a) / T(2);
  T sum{};
  for (int i = 0; i < rule.order(); ++i) sum += T(rule.weights[i]) * f(mid + half * T(rule.nodes[i]));
  return sum * half;
}

}  // namespace inbetween
