#pragma once
// Arc-length museum: small curves meeting the Curve concept, defined here so the arc-length and
// timing tests (and the benchmark) do not depend on the curves module's concrete types, plus the
// named hard cases every arc-length test loops over: coincident control points (zero-length
// segments, zero tangents), straight lines, cusps, a curve that doubles back on itself, and a
// curve of length zero.  Exact lengths are given where a closed form exists (source in comment).

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/curves/curve.hpp"
#include "inbetween/curves/helix.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween::test {

/// A piecewise cubic in power form: segment i covers [knots[i], knots[i+1]] with local
/// v = (u − knots[i]) / (knots[i+1] − knots[i]).  Meets PiecewiseCubicCurve.
template <class P>
struct TestCubicCurve {
  using point_type = P;
  using scalar_type = scalar_of<P>;
  using T = scalar_type;

  std::vector<PowerCubic<P>> pieces;
  std::vector<T> knots;  // pieces.size() + 1, strictly increasing

  /// One Bézier segment with control points p0..p3 over [lo, hi].
  static TestCubicCurve bezier(P p0, P p1, P p2, P p3, T lo = T(0), T hi = T(1)) {
    TestCubicCurve c;
    c.pieces.push_back(power_from_bezier(p0, p1, p2, p3));
    c.knots = {lo, hi};
    return c;
  }
  /// Bézier (p0, p1, p2, p3) → power-form coefficients.
  static PowerCubic<P> power_from_bezier(P p0, P p1, P p2, P p3) {
    return {(p3 - p0) + (p1 - p2) * T(3), (p0 - p1 * T(2) + p2) * T(3), (p1 - p0) * T(3), p0};
  }
  /// Appends a Bézier segment whose parameter runs over [knots.back(), hi].
  TestCubicCurve& then_bezier(P p0, P p1, P p2, P p3, T hi) {
    pieces.push_back(power_from_bezier(p0, p1, p2, p3));
    knots.push_back(hi);
    return *this;
  }

  Interval<T> domain() const noexcept { return {knots.front(), knots.back()}; }
  int segment_count() const noexcept { return int(pieces.size()); }
  Interval<T> segment_domain(int i) const noexcept { return {knots[std::size_t(i)], knots[std::size_t(i) + 1]}; }
  PowerCubic<P> segment_power_form(int i) const noexcept { return pieces[std::size_t(i)]; }

  int index_of(T u) const noexcept {
    int i = 0;
    while (i + 1 < segment_count() && knots[std::size_t(i) + 1] <= u) ++i;
    return i;
  }
  P point(T u) const noexcept { return derivative(u, 0); }
  P derivative(T u, int k) const noexcept {
    u = domain().clamp(u);
    const int i = index_of(u);
    const T lo = knots[std::size_t(i)], h = knots[std::size_t(i) + 1] - lo;
    const T v = (u - lo) / h;
    P d = pieces[std::size_t(i)].derivative(v, k);
    for (int j = 0; j < k; ++j) d = d / h;  // chain rule: d^k/du^k = d^k/dv^k / h^k
    return d;
  }
};

/// A named museum curve with its exact length when a closed form exists.
template <Real T>
struct ArcLengthExhibit {
  std::string name;
  TestCubicCurve<Vec3<T>> curve;
  std::optional<double> exact_length;  // closed form, where known
};

/// The four-point Bézier approximation of a quarter circle of radius 1: k = 4(√2 − 1)/3.
template <Real T>
TestCubicCurve<Vec3<T>> quarter_circle_bezier() {
  const T k = T(4) * (std::sqrt(T(2)) - T(1)) / T(3);
  return TestCubicCurve<Vec3<T>>::bezier({1, 0, 0}, {1, k, 0}, {k, 1, 0}, {0, 1, 0});
}

/// Every exhibit, in a fixed order.
template <Real T>
std::vector<ArcLengthExhibit<T>> museum_arc_length_curves() {
  using V = Vec3<T>;
  using Curve3 = TestCubicCurve<V>;
  std::vector<ArcLengthExhibit<T>> m;
  // Straight line with evenly spaced control points: P(u) = P0 + u (P3 − P0); length |P3 − P0| = 3.
  m.push_back({"straight line, uniform speed", Curve3::bezier({0, 0, 0}, {1, 2, 2} , {2, 4, 4}, {3, 6, 6}),
               std::sqrt(81.0)});
  // Straight line, uneven speed (control points bunched at the end); x monotone, so length 1.
  m.push_back({"straight line, uneven speed", Curve3::bezier({0, 0, 0}, {0.9, 0, 0}, {0.95, 0, 0}, {1, 0, 0}), 1.0});
  // x(u) = 4u³ − 6u² + 3u = ((2u − 1)³ + 1)/2: a line with zero speed at u = 1/2; length 1.
  {
    Curve3 c;
    c.pieces.push_back({V{4, 0, 0}, V{-6, 0, 0}, V{3, 0, 0}, V{0, 0, 0}});
    c.knots = {0, 1};
    m.push_back({"straight line, stops at u = 1/2", c, 1.0});
  }
  // A line that doubles back: x runs 0 → beyond 0.7 → back below 0.3 → 1.
  m.push_back({"straight line, doubles back", Curve3::bezier({0, 0, 0}, {2, 0, 0}, {-1, 0, 0}, {1, 0, 0}), std::nullopt});
  // Quarter circle, Bézier approximation: compared against its own high-order quadrature.
  m.push_back({"quarter circle (Bezier approximation)", quarter_circle_bezier<T>(), std::nullopt});
  // Parabola y = x², x = 2u, u ∈ [0, 1]: length = (a/2)√(1 + 4a²) + asinh(2a)/4 with a = 2.
  {
    Curve3 c;
    c.pieces.push_back({V{0, 0, 0}, V{0, 4, 0}, V{2, 0, 0}, V{0, 0, 0}});
    c.knots = {0, 1};
    m.push_back({"parabola y = x^2, x in [0, 2]", c, 1.0 * std::sqrt(17.0) + std::asinh(4.0) / 4.0});
  }
  // Twisted cubic (u, u², 2u³/3): |P'|² = (1 + 2u²)², length over [0, 1] = 1 + 2/3 = 5/3; the
  // parameter runs over [0, 2] here (same curve at half speed), so the length stays 5/3.
  {
    Curve3 c;
    c.pieces.push_back({V{0, 0, T(2) / T(3)}, V{0, 1, 0}, V{1, 0, 0}, V{0, 0, 0}});
    c.knots = {0, 2};
    m.push_back({"helix-like twisted cubic (u, u^2, 2u^3/3)", c, 5.0 / 3.0});
  }
  // Coincident control points.
  m.push_back({"P0 = P1 (zero tangent at start)", Curve3::bezier({0, 0, 0}, {0, 0, 0}, {1, 1, 0}, {2, 0, 0}), std::nullopt});
  m.push_back({"P2 = P3 (zero tangent at end)", Curve3::bezier({0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {2, 0, 0}), std::nullopt});
  m.push_back({"P1 = P2 (interior double point)", Curve3::bezier({0, 0, 0}, {1, 1, 1}, {1, 1, 1}, {2, 0, 0}), std::nullopt});
  // All four control points coincide: a curve of length zero.
  m.push_back({"all control points coincide (length 0)", Curve3::bezier({1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}), 0.0});
  // Cusp: the classic (0,0), (1,1), (0,1), (1,0) Bézier has P'(1/2) = 0 with a turn.
  m.push_back({"cusp", Curve3::bezier({0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 0}), std::nullopt});
  // Three segments, the middle one a single point (zero-length segment), uneven knots.
  {
    Curve3 c = Curve3::bezier({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {2, 2, 0}, 0, T(0.5));
    c.then_bezier({2, 2, 0}, {2, 2, 0}, {2, 2, 0}, {2, 2, 0}, T(0.75));
    c.then_bezier({2, 2, 0}, {2, 3, 1}, {3, 3, 2}, {4, 4, 2}, T(2));
    m.push_back({"three segments, middle one zero length", c, std::nullopt});
  }
  // A smooth, strongly non-uniform 3-D curve: most of the length in a short parameter range.
  m.push_back({"fast middle (speed varies 100x)",
               Curve3::bezier({0, 0, 0}, {0.01, 0.01, 0}, {9.99, 5, 3}, {10, 5, 3}), std::nullopt});
  return m;
}

/// The exhibit whose name starts with `prefix` (the first one in museum order).
template <Real T>
ArcLengthExhibit<T> museum_arc_length_exhibit(const std::string& prefix) {
  for (auto& ex : museum_arc_length_curves<T>()) {
    if (ex.name.rfind(prefix, 0) == 0) return ex;
  }
  return {};
}

}  // namespace inbetween::test
