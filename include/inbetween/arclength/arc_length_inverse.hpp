#pragma once
/// ArcLengthInverse<C>: u(s) from a piecewise polynomial approximation of the inverse, built once
/// from an ArcLength, so that a query is a bucket lookup and one Clenshaw sum — no quadrature, no
/// Newton iteration (issue 12: "u(s) at the cost of a point").
///
/// How: every table interval [s_i, s_{i+1}] of the ArcLength (adaptive Gauss rows) gets a Chebyshev
/// interpolant of degree 8 of u(s) through ArcLength::u_at at the Chebyshev nodes.  The interpolant
/// is then checked at 2·9 + 1 points spread over the piece (ends and the points between nodes):
/// the reference length from the start to the answered u must be within fit_tolerance of s
/// (ArcLength::s_at, itself accurate to the table tolerance, 1e-11·L by default).  A piece that
/// fails is halved in s and refitted, down to 2^-6 of the table interval; a piece that still fails
/// (next to a cusp, where u(s) has a square-root singularity) is marked, and its queries are
/// answered by ArcLength::u_at (Newton on the Gauss table, the reference) — so every answer keeps
/// ArcLength's 1e-9·L guarantee.  Pieces are found through a uniform bucket index over [0, L].

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/math/assert.hpp"

namespace inbetween {

/// Options of ArcLengthInverse::build.
template <Real T>
struct ArcLengthInverseOptions {
  /// Allowed |s(u(s)) − s| relative to the length at the check points: 1e-10 in double (ten times
  /// inside ArcLength's 1e-9·L guarantee), 64·ε in float.
  T relative_tolerance = sizeof(T) <= 4 ? T(64) * std::numeric_limits<T>::epsilon() : T(1e-10);
  int max_halvings = 6;  ///< ≥ 0: how often a piece that fails the check may be halved in s
};

/// Piecewise Chebyshev approximation of the inverse arc-length function u(s) of one curve (keeps a
/// copy of the ArcLength for the marked pieces).  Immutable after build; queries are noexcept, do
/// not allocate and clamp s into [0, L].
template <Curve C>
class ArcLengthInverse {
 public:
  using T = typename C::scalar_type;  ///< scalar type

  /// Degree of the Chebyshev interpolant on every piece.
  static constexpr int degree = 8;

  /// Builds the pieces from `arc` (copied).  Errors: options out of range (InvalidArgument).
  static Expected<ArcLengthInverse> build(ArcLength<C> arc, const ArcLengthInverseOptions<T>& opt = {}) {
    if (!(opt.relative_tolerance > T(0)) || opt.max_halvings < 0 || opt.max_halvings > 30) {
      return Error{ErrorCode::invalid_argument, "needs relative_tolerance > 0 and 0 <= max_halvings <= 30", {Parameter{"options"}}};
    }
    ArcLengthInverse inv(std::move(arc));
    const ArcLength<C>& a = inv.arc_;
    inv.length_ = a.length();
    inv.u_lo_ = a.domain().lo;
    inv.u_hi_ = a.domain().hi;
    inv.tolerance_ = opt.relative_tolerance * (inv.length_ > T(0) ? inv.length_ : T(1));
    const auto su = a.table().s_values();
    for (std::size_t i = 0; i + 1 < su.size(); ++i) {
      if (!(su[i + 1] > su[i])) continue;  // a zero-length piece: the next piece answers its s
      inv.fit(su[i], su[i + 1], opt.max_halvings);
    }
    inv.index();
    return inv;
  }

  /// Total length L the pieces cover.
  [[nodiscard]] T length() const noexcept { return length_; }
  /// Number of polynomial pieces.
  [[nodiscard]] std::size_t pieces() const noexcept { return s_lo_.size(); }
  /// Pieces answered by ArcLength::u_at because their fit failed the check (cusps).
  [[nodiscard]] std::size_t fallback_pieces() const noexcept {
    return std::size_t(std::count(exact_.begin(), exact_.end(), std::uint8_t(1)));
  }
  /// The largest |s(u(s)) − s| seen at the check points of the fitted pieces (length units,
  /// measured with ArcLength::s_at); at most the tolerance.
  [[nodiscard]] T max_checked_error() const noexcept { return max_checked_; }
  /// The ArcLength behind the pieces.
  [[nodiscard]] const ArcLength<C>& arc_length() const noexcept { return arc_; }

  /// u(s), s clamped into [0, L] (NaN reads as 0); u₀ for a curve of length zero.
  [[nodiscard]] T u_at(T s) const noexcept {
    if (!(s > T(0)) || s_lo_.empty()) return u_lo_;
    if (!(s < length_)) return u_hi_;
    const std::size_t p = piece_for(s);
    if (exact_[p]) return arc_.u_at(s);
    return eval(p, s);
  }

  /// u(s_k) for every s_k (each clamped as u_at does); u_out.size() must equal s.size().
  /// Does not allocate.
  void u_at(std::span<const T> s, std::span<T> u_out) const noexcept {
    INBETWEEN_ASSERT(s.size() == u_out.size());
    for (std::size_t k = 0; k < s.size(); ++k) u_out[k] = u_at(s[k]);
  }

 private:
  explicit ArcLengthInverse(ArcLength<C> arc) : arc_(std::move(arc)) {}

  // Chebyshev nodes x_j = cos(π(j + ½)/(n)) on [−1, 1], n = degree + 1.
  static std::array<T, degree + 1> nodes() noexcept {
    std::array<T, degree + 1> x{};
    for (int j = 0; j <= degree; ++j)
      x[j] = T(std::cos(std::numbers::pi * (double(j) + 0.5) / double(degree + 1)));
    return x;
  }

  // Clenshaw sum of Σ c_k T_k(x).
  static T clenshaw(const T* c, T x) noexcept {
    T b1 = T(0), b2 = T(0);
    const T x2 = x + x;
    for (int k = degree; k >= 1; --k) {
      const T b0 = c[k] + x2 * b1 - b2;
      b2 = b1;
      b1 = b0;
    }
    return c[0] + x * b1 - b2;
  }

  T eval(std::size_t p, T s) const noexcept {
    const T x = (s - s_mid_[p]) * s_inv_half_[p];  // in [−1, 1]
    const T u = clenshaw(&coef_[p * (degree + 1)], std::clamp(x, T(-1), T(1)));
    return std::clamp(u, u_lo_, u_hi_);
  }

  std::size_t piece_for(T s) const noexcept {
    std::size_t b = std::min(std::size_t(s * bucket_scale_), bucket_.size() - 1);
    std::size_t p = bucket_[b];
    while (p + 1 < s_lo_.size() && s_lo_[p + 1] <= s) ++p;
    return p;
  }

  void fit(T sa, T sb, int halvings_left) {
    const ArcLength<C>& arc = arc_;
    static const std::array<T, degree + 1> x = nodes();
    const T mid = T(0.5) * (sa + sb), half = T(0.5) * (sb - sa);
    std::array<T, degree + 1> uj{};
    for (int j = 0; j <= degree; ++j) uj[j] = arc.u_at(mid + half * x[j]);
    std::array<T, degree + 1> c{};
    for (int k = 0; k <= degree; ++k) {
      T sum = T(0);
      for (int j = 0; j <= degree; ++j)
        sum += uj[j] * T(std::cos(std::numbers::pi * double(k) * (double(j) + 0.5) / double(degree + 1)));
      c[k] = sum * T(2) / T(degree + 1);
    }
    c[0] *= T(0.5);
    // Check: the ends and the points halfway between neighbouring nodes.
    T worst = T(0);
    const int checks = 2 * (degree + 1);
    for (int m = 0; m <= checks; ++m) {
      const T xm = T(std::cos(std::numbers::pi * double(m) / double(checks)));
      const T s = mid + half * xm;
      const T u = std::clamp(clenshaw(c.data(), xm), u_lo_, u_hi_);
      worst = std::max(worst, std::fabs(arc.s_at(u) - s));
    }
    if (!(worst <= tolerance_) && halvings_left > 0) {
      fit(sa, mid, halvings_left - 1);
      fit(mid, sb, halvings_left - 1);
      return;
    }
    const bool exact = !(worst <= tolerance_);
    if (!exact) max_checked_ = std::max(max_checked_, worst);
    exact_.push_back(exact ? 1 : 0);
    s_lo_.push_back(sa);
    s_mid_.push_back(mid);
    s_inv_half_.push_back(T(1) / half);
    coef_.insert(coef_.end(), c.begin(), c.end());
  }

  // Bucket k covers [k·L/B, (k + 1)·L/B) and holds the piece containing its start.
  void index() {
    if (s_lo_.empty()) return;
    const std::size_t buckets = 2 * s_lo_.size();
    bucket_scale_ = T(buckets) / length_;
    bucket_.assign(buckets, 0);
    std::size_t p = 0;
    for (std::size_t k = 0; k < buckets; ++k) {
      const T s = T(k) / bucket_scale_;
      while (p + 1 < s_lo_.size() && s_lo_[p + 1] <= s) ++p;
      bucket_[k] = std::uint32_t(p);
    }
  }

  ArcLength<C> arc_;
  T length_ = T(0), u_lo_ = T(0), u_hi_ = T(0), tolerance_ = T(0), max_checked_ = T(0), bucket_scale_ = T(0);
  std::vector<T> s_lo_, s_mid_, s_inv_half_, coef_;
  std::vector<std::uint32_t> bucket_;
  std::vector<std::uint8_t> exact_;  // 1: the piece is answered by arc_.u_at
};

/// Builds the inverse of `arc` (copied): ArcLengthInverse<C>::build(arc, opt).
template <Curve C>
Expected<ArcLengthInverse<C>> make_arc_length_inverse(ArcLength<C> arc,
                                                      const ArcLengthInverseOptions<typename C::scalar_type>& opt = {}) {
  return ArcLengthInverse<C>::build(std::move(arc), opt);
}

}  // namespace inbetween
