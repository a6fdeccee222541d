#pragma once
// Shared helpers for the curve tests: random points of any point type, finite-difference checks
// of derivatives, and the local-control check (move one control point, compare outside its
// predicted influence).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "inbetween/curves/curve.hpp"
#include "support/random.hpp"

namespace inbetween::test {

/// The point types every family is tested over.
using CurvePointTypes = ::testing::Types<float, double, Vec2f, Vec2d, Vec3f, Vec3d, Vec4f, Vec4d>;

/// A point with components uniform in [lo, hi).
template <Point P>
P random_point(Random& rng, double lo = -1, double hi = 1) {
  using T = scalar_of<P>;
  P p{};
  for (int i = 0; i < PointTraits<P>::dim; ++i) PointTraits<P>::set(p, i, rng.uniform<T>(T(lo), T(hi)));
  return p;
}

/// n random points.
template <Point P>
std::vector<P> random_points(Random& rng, int n, double lo = -1, double hi = 1) {
  std::vector<P> v;
  for (int i = 0; i < n; ++i) v.push_back(random_point<P>(rng, lo, hi));
  return v;
}

/// max component-wise |a − b|.
template <Point P>
double max_abs_diff(const P& a, const P& b) {
  double m = 0;
  for (int i = 0; i < PointTraits<P>::dim; ++i)
    m = std::max(m, std::abs(double(PointTraits<P>::get(a, i)) - double(PointTraits<P>::get(b, i))));
  return m;
}

/// Checks derivative(u, k), k = 1..3, against central differences of derivative(u, k − 1) at
/// random u strictly inside segments (joints excluded: derivatives may jump there).  Double only.
/// Tolerance: the central difference has truncation error h²/6·|f'''| plus rounding eps·|f|/h;
/// with h = 1e-5 both are below 1e-8 for the O(1..100) values of these curves, so 1e-6 relative
/// catches any wrong coefficient (those give O(1) errors).
template <Curve C>
void expect_derivatives_match_differences(const C& c, Random& rng, int samples = 40) {
  using T = typename C::scalar_type;
  static_assert(std::is_same_v<T, double>);
  const double h = 1e-5;
  for (int s = 0; s < samples; ++s) {
    const int seg = rng.integer(0, c.segment_count() - 1);
    const auto d = c.segment_domain(seg);
    if (d.length() < 1e-3) continue;
    const double u = rng.uniform(d.lo + 0.05 * d.length(), d.hi - 0.05 * d.length());
    for (int k = 1; k <= 3; ++k) {
      const auto fd = (c.derivative(u + h, k - 1) - c.derivative(u - h, k - 1)) / (2 * h);
      const auto an = c.derivative(u, k);
      const double scale = 1 + std::sqrt(double(squared_norm(an)));
      EXPECT_LT(max_abs_diff(fd, an), 1e-6 * scale) << "k=" << k << " u=" << u << " segment " << seg;
    }
  }
}

/// Local control: for every control point i, moving it (by `offset`) leaves the curve unchanged
/// (bitwise: the unaffected segments are rebuilt from the same inputs) at every sampled u outside
/// influence(i), and changes it somewhere inside.  `build` maps control points to a curve.
template <class Build, Point P>
void expect_local_control(Build build, const std::vector<P>& pts, const P& offset) {
  const auto before = build(pts);
  const auto dom = before.domain();
  for (int i = 0; i < int(pts.size()); ++i) {
    auto moved = pts;
    moved[i] = moved[i] + offset;
    const auto after = build(moved);
    ASSERT_EQ(after.domain(), dom);
    const auto inf = before.influence(i);
    bool changed_inside = false;
    for (int s = 0; s <= 400; ++s) {
      const auto u = dom.lo + dom.length() * scalar_of<P>(s) / scalar_of<P>(400);
      if (u < inf.lo || u > inf.hi) {
        EXPECT_EQ(after.point(u), before.point(u)) << "point " << i << " moved the curve at u=" << u;
      } else if (!(after.point(u) == before.point(u))) {
        changed_inside = true;
      }
    }
    EXPECT_TRUE(changed_inside) << "point " << i << " changed nothing inside its influence";
  }
}

/// Global control: moving any control point changes the curve inside every segment.
template <class Build, Point P>
void expect_global_control(Build build, const std::vector<P>& pts, const P& offset) {
  const auto before = build(pts);
  for (int i = 0; i < int(pts.size()); ++i) {
    auto moved = pts;
    moved[i] = moved[i] + offset;
    const auto after = build(moved);
    EXPECT_EQ(before.influence(i), before.domain());
    for (int seg = 0; seg < before.segment_count(); ++seg) {
      const auto d = before.segment_domain(seg);
      const auto u = d.lo + d.length() * scalar_of<P>(0.37);
      EXPECT_NE(after.point(u), before.point(u)) << "point " << i << " segment " << seg;
    }
  }
}

}  // namespace inbetween::test
