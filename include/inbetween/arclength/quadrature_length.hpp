#pragma once
/// Arc length LENGTH(u_a, u_b) = ∫ |dP/du| du (texts 004 Eq. 3.3) by Gauss–Legendre quadrature:
/// fixed order per curve segment, adaptive (the subdivision of Figure 3.8, corrected), and a tight
/// reference used to measure every other method.  Integration is always split at segment joints,
/// because derivatives may jump there.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "inbetween/arclength/cubic_speed.hpp"
#include "inbetween/arclength/gauss_legendre.hpp"
#include "inbetween/curves/curve.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// Options of the adaptive Gaussian integration (texts 004 "Adaptive Gaussian integration").
template <Real T>
struct AdaptiveGaussOptions {
  /// Absolute tolerance for the whole range, in length units.  Each curve segment gets the share of
  /// its parameter length, and every subdivision level halves it (ε/2ⁿ), as in the texts.  An
  /// interval is also accepted when the difference is at the rounding level (64 ulp of its length
  /// plus 64 ulp of the segment's largest speed times its width), so a tolerance below rounding
  /// cannot make the subdivision run away.
  T tolerance = T(1e-9);
  int order = 5;       ///< Gauss–Legendre nodes per interval (Figure 3.8 uses 10; 1..64)
  int min_depth = 0;   ///< levels subdivided unconditionally before the test applies
  int max_depth = 30;  ///< no interval is split more often than this (cusps, rounding)
  /// Work budget: at most this many integrand evaluations per curve segment for the subdivision
  /// (the budget of a call is this times the number of segments, shared among them).  When it
  /// runs out no interval is split further: the table builders return budget_exceeded, the
  /// length functions return the estimate reached so far (documented fallback).  Sane curves use
  /// about 1% of the default (the museum: at most 1 395 per segment); a degree-19 Lagrange curve
  /// whose speed is noisier than the tolerance used 2.6e8 evaluations before there was a budget.
  std::int64_t max_evaluations_per_segment = 100'000;
};

/// The speed |dP/du| of `curve` at u (u clamped by the curve), as √(P'·P') — the plain form, as it
/// sits in every quadrature node — falling back to math's scaled norm() when the squared norm
/// would underflow or overflow (speeds below √min ≈ 1e-154 or above √max ≈ 1e154 in double).
template <Curve C>
typename C::scalar_type speed_at(const C& curve, typename C::scalar_type u) noexcept {
  using T = typename C::scalar_type;
  const auto d = curve.derivative(u, 1);
  const T ss = squared_norm(d);
  // Fast path while the squared norm neither underflows nor overflows; otherwise the scaled norm
  // (tiny curves of subnormal extent, huge coordinates above √max).
  if (ss >= std::numeric_limits<T>::min() && ss <= std::numeric_limits<T>::max()) return std::sqrt(ss);
  return norm(d);
}

namespace detail {

/// Index of the segment whose domain contains u (the one that starts at u at a joint; the last one
/// at the end of the domain); u is clamped.  Segments are assumed ordered along the domain.
template <Curve C>
int segment_index(const C& curve, typename C::scalar_type u) noexcept {
  int lo = 0, hi = int(curve.segment_count()) - 1;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (curve.segment_domain(mid).lo <= u) lo = mid; else hi = mid - 1;
  }
  return lo;
}

/// Calls piece(i, a, b) for every segment i overlapping [ua, ub] (ua ≤ ub), with [a, b] the overlap.
template <Curve C, class Piece>
void for_each_piece(const C& curve, typename C::scalar_type ua, typename C::scalar_type ub,
                    Piece&& piece) {
  if (!(ua < ub)) return;
  const int first = segment_index(curve, ua);
  const int n = int(curve.segment_count());
  for (int i = first; i < n; ++i) {
    const auto d = curve.segment_domain(i);
    if (d.lo >= ub) break;
    const auto a = ua > d.lo ? ua : d.lo;
    const auto b = ub < d.hi ? ub : d.hi;
    if (a < b) piece(i, a, b);
  }
}

/// Parameters in (a, b) where the speed |P'| has a local minimum, found as sign changes (− to +) of
/// g(u) = P'(u)·P''(u) = ½ d|P'|²/du on `samples` + 1 evenly spaced points and refined by bisection.
/// Zero-speed points (cusps, a line that doubles back, coincident control points inside a segment)
/// are such minima; there |P'| has a kink that no polynomial quadrature rule resolves, so
/// integration splits at them.  Two minima closer than (b − a)/samples may be seen as one.
template <Curve C>
std::vector<typename C::scalar_type> speed_minima(const C& curve, typename C::scalar_type a,
                                                  typename C::scalar_type b, int samples = 32) {
  using T = typename C::scalar_type;
  std::vector<T> out;
  if (!(a < b)) return out;
  const auto g = [&curve](T u) { return T(dot(curve.derivative(u, 1), curve.derivative(u, 2))); };
  T u_prev = a, g_prev = g(a);
  for (int k = 1; k <= samples; ++k) {
    const T u = k == samples ? b : a + (b - a) * (T(k) / T(samples));
    const T gu = g(u);
    if (g_prev < T(0) && !(gu < T(0))) {
      T lo = u_prev, hi = u;
      for (int it = 0; it < 200; ++it) {
        const T mid = lo + (hi - lo) / T(2);
        if (!(lo < mid && mid < hi)) break;
        if (g(mid) < T(0)) lo = mid; else hi = mid;
      }
      if (a < hi && hi < b) out.push_back(hi);
    }
    u_prev = u;
    g_prev = gu;
  }
  return out;
}

/// Like for_each_piece, but also splits each piece at the speed minima of its segment (see
/// speed_minima), so that the integrand is smooth inside every piece.
template <Curve C, class Piece>
void for_each_smooth_piece(const C& curve, typename C::scalar_type ua, typename C::scalar_type ub,
                           Piece&& piece) {
  using T = typename C::scalar_type;
  for_each_piece(curve, ua, ub, [&](int i, T a, T b) {
    const auto d = curve.segment_domain(i);
    T start = a;
    for (T m : speed_minima(curve, d.lo, d.hi)) {
      if (m <= start || m >= b) continue;
      piece(i, start, m);
      start = m;
    }
    piece(i, start, b);
  });
}

/// Counts integrand evaluations (for cost reports) against a budget; plain struct, caller-owned.
struct EvaluationCounter {
  std::int64_t evaluations = 0;                                      ///< spent so far
  std::int64_t budget = std::numeric_limits<std::int64_t>::max();  ///< no split once this is reached
  bool exhausted = false;  ///< a split was wanted but refused for lack of budget
};

/// The budget of one call: opt.max_evaluations_per_segment × segments (saturating; ≤ 0 = none left).
template <Curve C, class R>
std::int64_t evaluation_budget(const C& curve, const AdaptiveGaussOptions<R>& opt) noexcept {
  const std::int64_t per = std::max<std::int64_t>(opt.max_evaluations_per_segment, 0);
  const std::int64_t segments = std::max<std::int64_t>(curve.segment_count(), 1);
  if (per > std::numeric_limits<std::int64_t>::max() / segments) return std::numeric_limits<std::int64_t>::max();
  return per * segments;
}

/// The recursive step of Figure 3.8, corrected: `whole` is the estimate over [a, b]; if the two
/// halves differ from it by more than `tol` (and depth allows), both halves are subdivided with
/// tol/2; otherwise leaf(a, mid, b, left, right) records the accepted halves in order.  Returns the
/// accepted length of [a, b].  An interval is also accepted when the difference is below the
/// rounding floor floor_rel·|left + right| + floor_per_width·(b − a): the first term is rounding
/// relative to the value, the second the cancellation noise of a speed computed near zero (ulp of
/// the segment's largest speed); without it a tolerance below the noise would split every interval
/// down to max_depth.
template <class R, class F, class Leaf>
R adaptive_gauss_step(F& f, R a, R b, R whole, R tol, int depth, int min_depth, int max_depth,
                      const GaussLegendreRule& rule, Leaf& leaf, EvaluationCounter& count, R floor_rel,
                      R floor_per_width) {
  const R mid = (a + b) / R(2);
  const R left = integrate_gauss_legendre<R>(f, a, mid, rule);
  const R right = integrate_gauss_legendre<R>(f, mid, b, rule);
  count.evaluations += 2 * rule.order();
  const R diff = std::fabs(whole - (left + right));
  const R floor = floor_rel * std::fabs(left + right) + floor_per_width * (b - a);
  bool splittable = a < mid && mid < b && depth < max_depth;
  const bool wanted = depth < min_depth || (diff > tol && diff > floor);
  // The two halves each evaluate their own two halves: 4·order evaluations per split.
  if (splittable && wanted && count.evaluations + 4 * std::int64_t(rule.order()) > count.budget) {
    count.exhausted = true;
    splittable = false;
  }
  if (splittable && wanted) {
    return adaptive_gauss_step(f, a, mid, left, tol / R(2), depth + 1, min_depth, max_depth, rule, leaf,
                               count, floor_rel, floor_per_width) +
           adaptive_gauss_step(f, mid, b, right, tol / R(2), depth + 1, min_depth, max_depth, rule, leaf,
                               count, floor_rel, floor_per_width);
  }
  leaf(a, mid, b, left, right);
  return left + right;
}

/// The largest speed of segment i seen at 33 evenly spaced parameters: the scale of the rounding
/// noise of any speed computed on that segment.
template <Curve C>
typename C::scalar_type segment_speed_scale(const C& curve, int i) {
  using T = typename C::scalar_type;
  const auto d = curve.segment_domain(i);
  T biggest{};
  for (int k = 0; k <= 32; ++k) {
    const T u = k == 32 ? d.hi : d.lo + d.length() * (T(k) / T(32));
    biggest = std::fmax(biggest, speed_at(curve, u));
  }
  return biggest;
}

/// Adaptive Gauss–Legendre length of one piece [a, b] of one segment with integrand f.  The
/// rounding floor is `floor_rel` (default 64 ulp of R) times the value, plus floor_rel times
/// `speed_scale` (the segment's largest speed; when negative, the largest value seen at the first
/// rule's nodes) per unit width.
template <class R, class F, class Leaf>
R adaptive_gauss_piece(F& f, R a, R b, R tol, const AdaptiveGaussOptions<R>& opt, Leaf& leaf,
                       EvaluationCounter& count,
                       R floor_rel = R(64) * std::numeric_limits<R>::epsilon(), R speed_scale = R(-1)) {
  const GaussLegendreRule rule = gauss_legendre_rule(opt.order);
  const R half = (b - a) / R(2), mid = (a + b) / R(2);
  R whole{}, biggest{};
  for (int i = 0; i < rule.order(); ++i) {
    const R v = f(mid + half * R(rule.nodes[i]));
    whole += R(rule.weights[i]) * v;
    biggest = std::fmax(biggest, std::fabs(v));
  }
  whole *= half;
  count.evaluations += rule.order();
  if (speed_scale > biggest) biggest = speed_scale;
  return adaptive_gauss_step(f, a, b, whole, tol, 0, opt.min_depth, opt.max_depth, rule, leaf, count,
                             floor_rel, floor_rel * biggest);
}

}  // namespace detail

/// LENGTH(u_a, u_b) with a fixed `order`-point Gauss–Legendre rule on each curve segment (or part
/// of one) between u_a and u_b.  Both parameters are clamped to the domain; u_b < u_a gives the
/// negative length.  Cost: order derivative evaluations per segment touched.
template <Curve C>
typename C::scalar_type gauss_length(const C& curve, typename C::scalar_type ua,
                                     typename C::scalar_type ub, int order) noexcept {
  using T = typename C::scalar_type;
  const auto dom = curve.domain();
  ua = dom.clamp(ua);
  ub = dom.clamp(ub);
  if (ub < ua) return -gauss_length(curve, ub, ua, order);
  const GaussLegendreRule rule = gauss_legendre_rule(order);
  const auto f = [&curve](T u) { return speed_at(curve, u); };
  T sum{};
  detail::for_each_piece(curve, ua, ub, [&](int, T a, T b) { sum += integrate_gauss_legendre<T>(f, a, b, rule); });
  return sum;
}

/// LENGTH(u_a, u_b) by adaptive Gaussian integration (texts 004 Figure 3.8, corrected: fields ua/ub,
/// |whole − halves| test, tolerance halved per level, and a forced minimum depth).  The initial
/// intervals are the segments split at their speed minima (detail::speed_minima), where the
/// integrand has kinks that fool the halves test.  Parameters are
/// clamped; u_b < u_a gives the negative length.  Allocates a little (the speed minima per segment).
/// Bounded work: when opt.max_evaluations_per_segment runs out, the intervals not yet accepted are
/// taken at their current Gauss estimate (documented fallback: the result is then finite but no
/// longer held to the tolerance; use ArcLength or adaptive_gauss_table to get an error instead).
template <Curve C>
typename C::scalar_type adaptive_gauss_length(const C& curve, typename C::scalar_type ua,
                                              typename C::scalar_type ub,
                                              const AdaptiveGaussOptions<typename C::scalar_type>& opt = {}) {
  using T = typename C::scalar_type;
  const auto dom = curve.domain();
  ua = dom.clamp(ua);
  ub = dom.clamp(ub);
  if (ub < ua) return -adaptive_gauss_length(curve, ub, ua, opt);
  if (!(ua < ub)) return T(0);
  auto f = [&curve](T u) { return speed_at(curve, u); };
  auto leaf = [](T, T, T, T, T) {};
  detail::EvaluationCounter count;
  count.budget = detail::evaluation_budget(curve, opt);
  T sum{};
  const T span = ub - ua;
  detail::for_each_smooth_piece(curve, ua, ub, [&](int i, T a, T b) {
    sum += detail::adaptive_gauss_piece<T>(f, a, b, opt.tolerance * ((b - a) / span), opt, leaf, count,
                                           T(64) * std::numeric_limits<T>::epsilon(),
                                           detail::segment_speed_scale(curve, i));
  });
  return sum;
}

/// The analytic integrand route (texts 004 Eqs. 3.6, 3.7, 3.16): LENGTH(u_a, u_b) of a piecewise
/// cubic curve, integrating √(Av⁴ + Bv³ + Cv² + Dv + E) of each segment's power form over its local
/// parameter v with adaptive Gaussian integration, on the segments split at their speed minima.
/// Same clamping and work budget as adaptive_gauss_length().
template <PiecewiseCubicCurve C>
typename C::scalar_type analytic_cubic_length(const C& curve, typename C::scalar_type ua,
                                              typename C::scalar_type ub,
                                              const AdaptiveGaussOptions<typename C::scalar_type>& opt = {}) noexcept {
  using T = typename C::scalar_type;
  const auto dom = curve.domain();
  ua = dom.clamp(ua);
  ub = dom.clamp(ub);
  if (ub < ua) return -analytic_cubic_length(curve, ub, ua, opt);
  if (!(ua < ub)) return T(0);
  auto leaf = [](T, T, T, T, T) {};
  detail::EvaluationCounter count;
  count.budget = detail::evaluation_budget(curve, opt);
  T sum{};
  const T span = ub - ua;
  // Split at the speed minima too (a kink of √quartic where the speed vanishes made the
  // subdivision of "straight line, doubles back" need more than 10⁶ evaluations).
  detail::for_each_smooth_piece(curve, ua, ub, [&](int i, T a, T b) {
    const auto d = curve.segment_domain(i);
    const T h = d.length();
    if (!(h > T(0))) return;
    const SpeedQuartic<T> q = speed_quartic(curve.segment_power_form(i));
    auto f = [&q](T v) { return q.speed(v); };
    sum += detail::adaptive_gauss_piece<T>(f, (a - d.lo) / h, (b - d.lo) / h,
                                           opt.tolerance * ((b - a) / span), opt, leaf, count);
  });
  return sum;
}

/// A tight reference LENGTH(u_a, u_b) for measuring the other methods: adaptive 20-point
/// Gauss–Legendre with a tolerance at the rounding level, accumulated in long double, on segments
/// split at their speed minima.  Accurate to
/// about 1e-14 relative for double curves, including cusps and zero-speed points (which only slow
/// it down).  Not meant for per-frame use.  Bounded work: 2 000 000 evaluations per segment, then
/// the estimate reached so far.
template <Curve C>
typename C::scalar_type reference_length(const C& curve, typename C::scalar_type ua,
                                         typename C::scalar_type ub) {
  using T = typename C::scalar_type;
  using R = long double;
  const auto dom = curve.domain();
  ua = dom.clamp(ua);
  ub = dom.clamp(ub);
  if (ub < ua) return -reference_length(curve, ub, ua);
  if (!(ua < ub)) return T(0);
  auto f = [&curve](R u) { return R(speed_at(curve, T(u))); };
  auto leaf = [](R, R, R, R, R) {};
  detail::EvaluationCounter count;
  // A larger budget than the default (this is the yardstick), still bounded.
  const AdaptiveGaussOptions<R> opt{
      .tolerance = 0, .order = 20, .min_depth = 1, .max_depth = 40, .max_evaluations_per_segment = 2'000'000};
  count.budget = detail::evaluation_budget(curve, opt);
  R sum{};
  detail::for_each_smooth_piece(curve, ua, ub, [&](int i, T a, T b) {
    // A tolerance of 16 ulp of the piece's length: in practice the rounding floor of the
    // integrand's own precision (32 ulp of T) is what stops the recursion.
    const R tol = R(16) * R(std::numeric_limits<T>::epsilon()) * R(gauss_length(curve, a, b, 20));
    sum += detail::adaptive_gauss_piece<R>(f, R(a), R(b), tol, opt, leaf, count,
                                           R(32) * R(std::numeric_limits<T>::epsilon()),
                                           R(detail::segment_speed_scale(curve, i)));
  });
  return T(sum);
}

}  // namespace inbetween
