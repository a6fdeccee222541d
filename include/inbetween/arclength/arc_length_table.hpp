#pragma once
/// A table of (u, s) pairs — parameter and arc length from the start of the curve — and the three
/// ways the texts build one: uniform forward differencing with supersampling (texts 004 §3.2.1,
/// 000 §2.4), adaptive forward differencing (Eq. 3.12, corrected) and adaptive Gaussian
/// integration (Figure 3.8, corrected).  Lookups: s(u) by direct index when the u column is uniform
/// (Eqs. 3.8–3.9) or binary search otherwise, then linear interpolation (Eq. 3.10); u(s) by binary
/// search and linear interpolation (Eq. 3.11).

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/arclength/quadrature_length.hpp"
#include "inbetween/curves/curve.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// An immutable, validated (u, s) table: u strictly increasing, s non-decreasing from s₀ = 0.
/// Lookups clamp their argument into the table's range and are noexcept.
template <Real T>
class ArcLengthTable {
 public:
  /// Builds a table from columns u (strictly increasing, finite) and s (non-decreasing, finite,
  /// s[0] = 0), at least 2 entries.  `build_evaluations` records how many curve evaluations made it
  /// (0 for a table typed in, such as the texts' Table 3.1).  Errors name the offending row.
  static Expected<ArcLengthTable> from_entries(std::span<const T> u, std::span<const T> s,
                                               std::int64_t build_evaluations = 0);

  /// Number of entries (≥ 2).
  [[nodiscard]] int size() const noexcept { return int(u_.size()); }
  /// The parameter column.
  [[nodiscard]] std::span<const T> u_values() const noexcept { return u_; }
  /// The arc-length column.
  [[nodiscard]] std::span<const T> s_values() const noexcept { return s_; }
  /// The last arc length: the length of the curve according to this table.
  [[nodiscard]] T length() const noexcept { return s_.back(); }
  /// The parameter range [u₀, u_last] covered.
  [[nodiscard]] Interval<T> domain() const noexcept { return {u_.front(), u_.back()}; }
  /// True when u is evenly spaced (to rounding), which enables the direct index of Eqs. 3.8–3.9.
  [[nodiscard]] bool is_uniform() const noexcept { return uniform_; }
  /// Curve evaluations (points or derivatives) spent building the table.
  [[nodiscard]] std::int64_t build_evaluations() const noexcept { return evaluations_; }

  /// Eq. 3.8: index of the entry whose u is nearest to u (direct calculation when uniform).
  [[nodiscard]] int nearest_index_for_u(T u) const noexcept;
  /// Eq. 3.9: index i of the interval [u_i, u_{i+1}] holding u (0 … size − 2).
  [[nodiscard]] int interval_index_for_u(T u) const noexcept;
  /// The crude estimate: s of the nearest entry (Eq. 3.8).
  [[nodiscard]] T s_nearest(T u) const noexcept { return s_[std::size_t(nearest_index_for_u(u))]; }
  /// s(u) by linear interpolation between the entries on either side (Eq. 3.10).
  [[nodiscard]] T s_at(T u) const noexcept;

  /// Index i of the interval [s_i, s_{i+1}] holding s, found by binary search; on a plateau of equal
  /// s (a zero-length piece) the last entry of the plateau.
  [[nodiscard]] int interval_index_for_s(T s) const noexcept;
  /// The crude estimate: u of the entry whose s is nearest (ties: the earlier entry).
  [[nodiscard]] T u_nearest(T s) const noexcept;
  /// u(s) by binary search and linear interpolation (Eq. 3.11); s clamped into [0, length()], and
  /// s ≤ 0 gives u₀.  Inside, on a zero-length piece (equal s) the result is the u at the end of the
  /// plateau.
  [[nodiscard]] T u_at(T s) const noexcept;

  /// LENGTH(u_a, u_b) = s(u_b) − s(u_a) from the table (negative when u_b < u_a).
  [[nodiscard]] T length_between(T ua, T ub) const noexcept { return s_at(ub) - s_at(ua); }
  /// The parameter at arc distance ds from u_a: u(s(u_a) + ds), clamped to the table.
  [[nodiscard]] T u_at_distance(T ua, T ds) const noexcept { return u_at(s_at(ua) + ds); }

 private:
  std::vector<T> u_, s_;
  T du_{};  // spacing when uniform
  bool uniform_ = false;
  std::int64_t evaluations_ = 0;
};

extern template class ArcLengthTable<float>;
extern template class ArcLengthTable<double>;

/// Options of the uniform forward-differencing table.
struct ForwardDifferenceOptions {
  int entries = 1001;   ///< table rows including both ends (≥ 2); 000 §2.4 samples 1000 intervals
  int supersample = 1;  ///< chords summed per table interval (≥ 1); 004 suggests 10
};

/// The uniform table of texts 004 §3.2.1 / 000 §2.4: entries evenly spaced in u over the whole
/// domain, each s the running sum of chord lengths |P(u_k) − P(u_{k−1})| over `supersample` chords
/// per interval.  Chord sums never exceed the true length (they underestimate it by O(h²)).
template <Curve C>
Expected<ArcLengthTable<typename C::scalar_type>> forward_difference_table(
    const C& curve, ForwardDifferenceOptions opt = {}) {
  using T = typename C::scalar_type;
  if (opt.entries < 2) {
    return Error{ErrorCode::invalid_argument, "entries is " + std::to_string(opt.entries) + ", needs at least 2", {Parameter{"entries"}}};
  }
  if (opt.supersample < 1) {
    return Error{ErrorCode::invalid_argument,
                 "supersample is " + std::to_string(opt.supersample) + ", needs at least 1", {Parameter{"supersample"}}};
  }
  const auto dom = curve.domain();
  const std::int64_t chords = std::int64_t(opt.entries - 1) * opt.supersample;
  std::vector<T> u(std::size_t(opt.entries)), s(std::size_t(opt.entries));
  auto prev = curve.point(dom.lo);
  T acc{};
  u[0] = dom.lo;
  s[0] = T(0);
  for (std::int64_t k = 1; k <= chords; ++k) {
    const T uk = k == chords ? dom.hi : dom.lo + dom.length() * (T(k) / T(chords));
    const auto p = curve.point(uk);
    acc += distance(prev, p);
    prev = p;
    if (k % opt.supersample == 0) {
      const auto row = std::size_t(k / opt.supersample);
      u[row] = uk;
      s[row] = acc;
    }
  }
  return ArcLengthTable<T>::from_entries(u, s, chords + 1);
}

/// The error of an adaptive table build that ran out of its work budget (BudgetExceeded).
Error budget_error(std::int64_t evaluations, std::int64_t per_segment, const char* method);

/// Options of adaptive forward differencing (texts 004 "Adaptive approach").
template <Real T>
struct AdaptiveForwardDifferenceOptions {
  /// Absolute tolerance ε in length units for the whole curve; each segment gets the share of its
  /// parameter length, and each subdivision level halves it (ε/2ⁿ).
  T tolerance = T(1e-6);
  int min_depth = 3;   ///< levels split unconditionally first (guards against the Figure 3.7 trap)
  int max_depth = 24;  ///< no piece is split more often than this
  /// Work budget: at most this many curve points per segment (shared among the segments); when a
  /// split is still wanted after that, the build fails with BudgetExceeded.
  std::int64_t max_evaluations_per_segment = 100'000;
};

/// Adaptive forward differencing: for each piece [a, b] compare the chord with the two half-chords,
/// | |P(a)−P(b)| − (|P(a)−P(m)| + |P(m)−P(b)|) | < ε/2ⁿ (Eq. 3.12 with the absolute value the texts
/// omit: the chord is never longer, so the printed test always passes).  Accepted pieces add rows
/// (m, s_a + |P(a)−P(m)|) and (b, s_m + |P(m)−P(b)|).  Curve segments are the initial pieces.
template <Curve C>
Expected<ArcLengthTable<typename C::scalar_type>> adaptive_forward_difference_table(
    const C& curve, const AdaptiveForwardDifferenceOptions<typename C::scalar_type>& opt = {}) {
  using T = typename C::scalar_type;
  using P = typename C::point_type;
  if (!(opt.tolerance > T(0)) || opt.min_depth < 0 || opt.max_depth < opt.min_depth) {
    return Error{ErrorCode::invalid_argument,
                 "needs tolerance > 0 and 0 <= min_depth <= max_depth", {Parameter{"options"}}};
  }
  const auto dom = curve.domain();
  std::vector<T> u{dom.lo}, s{T(0)};
  std::int64_t evals = 1;
  const T span = dom.length();
  struct Piece {
    T a, b;
    P pa, pb;
    T tol;
    int depth;
  };
  std::vector<Piece> stack;
  const std::int64_t segments = std::max<std::int64_t>(curve.segment_count(), 1);
  const std::int64_t per = std::max<std::int64_t>(opt.max_evaluations_per_segment, 0);
  const std::int64_t budget = per > std::numeric_limits<std::int64_t>::max() / segments
                                  ? std::numeric_limits<std::int64_t>::max()
                                  : per * segments;
  for (int i = int(curve.segment_count()) - 1; i >= 0; --i) {
    const auto d = curve.segment_domain(i);
    if (!(d.lo < d.hi)) continue;
    stack.push_back({d.lo, d.hi, curve.point(d.lo), curve.point(d.hi),
                     span > T(0) ? opt.tolerance * (d.length() / span) : opt.tolerance, 0});
    evals += 2;
  }
  // Depth-first, left piece first, so rows come out in increasing u.
  while (!stack.empty()) {
    const Piece pc = stack.back();
    stack.pop_back();
    const T m = (pc.a + pc.b) / T(2);
    const P pm = curve.point(m);
    ++evals;
    const T left = distance(pc.pa, pm), right = distance(pm, pc.pb);
    const T chord = distance(pc.pa, pc.pb);
    const bool splittable = pc.a < m && m < pc.b && pc.depth < opt.max_depth;
    // Rounding floor: the chords are differences of points, so they carry ulp of the coordinates.
    const T floor = T(16) * std::numeric_limits<T>::epsilon() * (norm(pc.pa) + norm(pm) + norm(pc.pb));
    const T diff = std::fabs(chord - (left + right));
    if (splittable && (pc.depth < opt.min_depth || (diff >= pc.tol && diff > floor))) {
      // Each split costs the midpoints of its two halves later.
      if (evals + 2 > budget) return budget_error(evals, opt.max_evaluations_per_segment, "adaptive forward differencing");
      stack.push_back({m, pc.b, pm, pc.pb, pc.tol / T(2), pc.depth + 1});
      stack.push_back({pc.a, m, pc.pa, pm, pc.tol / T(2), pc.depth + 1});
      continue;
    }
    const T sa = s.back();
    if (m > u.back()) { u.push_back(m); s.push_back(sa + left); }
    if (pc.b > u.back()) { u.push_back(pc.b); s.push_back(sa + left + right); }
  }
  if (u.size() < 2) { u.push_back(dom.hi); s.push_back(T(0)); }
  return ArcLengthTable<T>::from_entries(u, s, evals);
}

/// Adaptive Gaussian integration building a (u, s) table (texts 004 Figure 3.8, corrected: the
/// interval fields are ua/ub, and rows are stored instead of printed).  Each accepted interval adds
/// rows (mid, s + left) and (ub, s + left + right).  The initial intervals are the segments split at
/// their speed minima (kinks of |P'| at cusps and reversals, which fool the halves test: the
/// Figure 3.7 trap), so no interval crosses a joint or a kink.
template <Curve C>
Expected<ArcLengthTable<typename C::scalar_type>> adaptive_gauss_table(
    const C& curve, const AdaptiveGaussOptions<typename C::scalar_type>& opt = {}) {
  using T = typename C::scalar_type;
  if (!(opt.tolerance > T(0)) || opt.min_depth < 0 || opt.max_depth < opt.min_depth || opt.order < 1 ||
      opt.order > kMaxGaussLegendreOrder) {
    return Error{ErrorCode::invalid_argument,
                 "needs tolerance > 0, 0 <= min_depth <= max_depth and 1 <= order <= " +
                     std::to_string(kMaxGaussLegendreOrder), {Parameter{"options"}}};
  }
  const auto dom = curve.domain();
  std::vector<T> u{dom.lo}, s{T(0)};
  T total{};
  auto leaf = [&](T, T mid, T b, T left, T right) {
    if (mid > u.back()) { u.push_back(mid); s.push_back(total + left); }
    total += left + right;
    if (b > u.back()) { u.push_back(b); s.push_back(total); }
    else s.back() = total;
  };
  auto f = [&curve](T x) { return speed_at(curve, x); };
  detail::EvaluationCounter count;
  count.budget = detail::evaluation_budget(curve, opt);
  const T span = dom.length();
  detail::for_each_smooth_piece(curve, dom.lo, dom.hi, [&](int i, T a, T b) {
    detail::adaptive_gauss_piece<T>(f, a, b, opt.tolerance * ((b - a) / span), opt, leaf, count,
                                    T(64) * std::numeric_limits<T>::epsilon(),
                                    detail::segment_speed_scale(curve, i));
  });
  if (count.exhausted) return budget_error(count.evaluations, opt.max_evaluations_per_segment, "adaptive Gaussian integration");
  if (u.size() < 2) { u.push_back(dom.hi); s.push_back(T(0)); }
  return ArcLengthTable<T>::from_entries(u, s, count.evaluations);
}

}  // namespace inbetween
