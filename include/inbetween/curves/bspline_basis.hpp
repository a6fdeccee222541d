#pragma once
/// B-spline basis functions N_{i,p}(u) and their derivatives over any non-decreasing knot vector
/// u_0 ≤ … ≤ u_m (Cox–de Boor recursion, with 0/0 taken as 0), and the standard knot vectors.
/// With n = m − p basis functions the valid parameter domain is [u_p, u_n]; there the basis is a
/// partition of unity.  Used by BSpline and by least-squares fitting (the collocation matrix).
///
///   N_{i,0}(u) = 1 if u_i ≤ u < u_{i+1}, else 0   (the last non-empty span of the domain is closed
///                                                 on the right so that N sums to 1 at u = u_n)
///   N_{i,p}(u) = (u − u_i)/(u_{i+p} − u_i) N_{i,p−1}(u) + (u_{i+p+1} − u)/(u_{i+p+1} − u_{i+1}) N_{i+1,p−1}(u)
///   N'_{i,p}(u) = p/(u_{i+p} − u_i) N_{i,p−1}(u) − p/(u_{i+p+1} − u_{i+1}) N_{i+1,p−1}(u)

#include <algorithm>
#include <span>
#include <vector>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// The knot span s with u_s ≤ u < u_{s+1} and p ≤ s ≤ n − 1 (n = knots.size() − degree − 1 basis
/// functions), u clamped into [u_p, u_n]; at u = u_n it is the last span of positive length.
/// Precondition: a valid knot vector (u_p < u_n).
template <Real T>
int bspline_span(std::span<const T> knots, int degree, T u) noexcept {
  const int n = int(knots.size()) - degree - 1;
  u = std::clamp(u, knots[degree], knots[n]);
  // Largest s in [p, n − 1] with knots[s] ≤ u and knots[s] < knots[s + 1].
  auto first = knots.begin() + degree, last = knots.begin() + n;
  int s = int(std::upper_bound(first, last, u) - knots.begin()) - 1;
  s = std::clamp(s, degree, n - 1);
  while (s > degree && !(knots[s] < knots[s + 1])) --s;
  return s;
}

/// All n basis functions' `derivative`-th derivatives (0 = values) at u, written to out
/// (out.size() must be knots.size() − degree − 1).  u is clamped into [u_p, u_n].  Derivatives of
/// order above the degree are zero.  Allocates O(m·p) scratch.
template <Real T>
void bspline_basis_all(std::span<const T> knots, int degree, T u, int derivative, std::span<T> out) {
  const int m = int(knots.size()) - 1;
  const int n = m - degree;
  INBETWEEN_ASSERT(int(out.size()) == n && degree >= 0 && n >= 1);
  std::fill(out.begin(), out.end(), T(0));
  if (derivative > degree) return;
  u = std::clamp(u, knots[degree], knots[n]);
  const int s = bspline_span(knots, degree, u);
  // level[q][j] = N_{j,q}(u) for j in [0, m − q − 1].
  auto ratio = [](T num, T den) { return den == T(0) ? T(0) : num / den; };
  std::vector<std::vector<T>> level(degree + 1);
  level[0].assign(m, T(0));
  level[0][s] = T(1);
  for (int q = 1; q <= degree; ++q) {
    level[q].assign(m - q, T(0));
    for (int j = 0; j < m - q; ++j) {
      level[q][j] = ratio(u - knots[j], knots[j + q] - knots[j]) * level[q - 1][j] +
                    ratio(knots[j + q + 1] - u, knots[j + q + 1] - knots[j + 1]) * level[q - 1][j + 1];
    }
  }
  // Differentiate `derivative` times, starting from degree p − k.
  std::vector<T> a = level[degree - derivative];
  for (int r = 1; r <= derivative; ++r) {
    const int q = degree - derivative + r;
    std::vector<T> b(m - q, T(0));
    for (int j = 0; j < m - q; ++j) {
      b[j] = T(q) * (ratio(a[j], knots[j + q] - knots[j]) - ratio(a[j + 1], knots[j + q + 1] - knots[j + 1]));
    }
    a = std::move(b);
  }
  std::copy(a.begin(), a.begin() + n, out.begin());
}

/// N_{i,p}^{(derivative)}(u) for one basis function (convenience; computes all of them).
template <Real T>
T bspline_basis(std::span<const T> knots, int degree, int i, T u, int derivative = 0) {
  const int n = int(knots.size()) - degree - 1;
  if (i < 0 || i >= n) return T(0);
  std::vector<T> all(n);
  bspline_basis_all(knots, degree, u, derivative, std::span<T>(all));
  return all[i];
}

/// Checks a knot vector for `point_count` control points of degree `degree`: size
/// point_count + degree + 1, finite, non-decreasing, no knot repeated more than degree + 1 times,
/// and a non-empty domain u_p < u_n.  Error locations: {"knots", i} or {"knots"}.
template <Real T>
Expected<void> check_knots(std::span<const T> knots, int point_count, int degree) {
  const int want = point_count + degree + 1;
  if (int(knots.size()) != want)
    return Error{ErrorCode::wrong_arity,
                 "expected " + std::to_string(want) + " knots (points + degree + 1), got " + std::to_string(knots.size()), {"knots"}};
  for (int i = 0; i < want; ++i) {
    if (!std::isfinite(knots[i]))
      return Error{ErrorCode::not_finite, "knot " + std::to_string(i) + " is not finite", {"knots", std::size_t(i)}};
    if (i > 0 && knots[i] < knots[i - 1])
      return Error{ErrorCode::keys_not_increasing,
                   "knot " + std::to_string(i) + " (" + shortest_text<double>(double(knots[i])) + ") is less than knot " +
                       std::to_string(i - 1) + " (" + shortest_text<double>(double(knots[i - 1])) + ")", {"knots", std::size_t(i)}};
  }
  int run = 1;
  for (int i = 1; i < want; ++i) {
    run = knots[i] == knots[i - 1] ? run + 1 : 1;
    if (run > degree + 1)
      return Error{ErrorCode::invalid_argument,
                   "knot " + std::to_string(i) + " repeats a value more than degree + 1 = " +
                       std::to_string(degree + 1) + " times", {"knots", std::size_t(i)}};
  }
  if (!(knots[degree] < knots[point_count]))
    return Error{ErrorCode::invalid_argument,
                 "empty parameter domain: knot " + std::to_string(degree) + " equals knot " + std::to_string(point_count), {"knots"}};
  return {};
}

/// Clamped uniform knots on [0, 1]: degree + 1 zeros, uniformly spaced interior knots, degree + 1
/// ones (the curve starts at the first and ends at the last control point).  point_count ≥ degree + 1.
template <Real T>
std::vector<T> clamped_uniform_knots(int point_count, int degree) {
  const int m = point_count + degree + 1;
  const int inner = point_count - degree;  // number of spans
  std::vector<T> k(m);
  for (int i = 0; i < m; ++i) {
    const int j = std::clamp(i - degree, 0, inner);
    k[i] = T(j) / T(inner);
  }
  return k;
}

/// Uniform (unclamped) knots 0, 1, 2, …, point_count + degree; domain [degree, point_count].
template <Real T>
std::vector<T> uniform_knots(int point_count, int degree) {
  std::vector<T> k(point_count + degree + 1);
  for (int i = 0; i < int(k.size()); ++i) k[i] = T(i);
  return k;
}

}  // namespace inbetween
