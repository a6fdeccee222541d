// SegmentIndex (issue 12): the bucket lookup (find, and find_in_domain / locate_in_domain for
// clamped u) gives exactly the segment of the binary search it replaced — std::upper_bound over
// the inner breakpoints u_1 … u_{n−1}, minus one, the independent reference here — for every u
// tried: every breakpoint, its neighbours one ulp either side,
// midpoints, seeded random u inside and outside the domain, ±inf, NaN, ±max; on seeded random
// knot vectors in float and double and on adversarial ones (one huge segment among tiny ones,
// spacings from 1e-12 to 1e6, geometric growth, clusters, a domain far from 0, ranges that
// overflow or are subnormal, 1 and 2 segments); and through every piecewise-cubic family built on
// every museum point list.  Zero-length segments are not legal (builders reject breakpoints that
// do not increase: keys_not_increasing / not_finite, tested with each builder), so none appear here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "curve_test_util.hpp"
#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "inbetween/curves/segment_index.hpp"
#include "support/museum_curves.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

template <class T>
class SegmentIndexTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SegmentIndexTest, Scalars);

/// The reference: the binary search PiecewiseCubic::segment_at used before the index.
template <class T>
int binary_search_segment(const std::vector<T>& b, T u) {
  return int(std::upper_bound(b.begin() + 1, b.end() - 1, u) - b.begin()) - 1;
}

/// The parameters probed on breakpoints b: each breakpoint and its two neighbours, midpoints and
/// quarter points, seeded random u over the domain widened by a tenth on each side, and the
/// special values.
template <class T>
std::vector<T> probes(const std::vector<T>& b, test::Random& rng) {
  constexpr T inf = std::numeric_limits<T>::infinity();
  constexpr T big = std::numeric_limits<T>::max();
  std::vector<T> u{inf, -inf, std::numeric_limits<T>::quiet_NaN(), big, -big, T(0), -T(0),
                   std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::min()};
  for (std::size_t i = 0; i < b.size(); ++i) {
    u.push_back(b[i]);
    u.push_back(std::nextafter(b[i], inf));
    u.push_back(std::nextafter(b[i], -inf));
    if (i + 1 < b.size()) {
      u.push_back(b[i] + (b[i + 1] - b[i]) / T(2));
      u.push_back(b[i] + (b[i + 1] - b[i]) / T(4));
    }
  }
  const T lo = b.front(), hi = b.back(), pad = (hi - lo) / T(10);
  for (int k = 0; k < 200; ++k) u.push_back(T(rng.uniform<double>(double(lo - pad), double(hi + pad))));
  return u;
}

/// Builds the index of b and checks find() against the binary search on every probe.
template <class T>
void expect_same_as_binary_search(const std::vector<T>& b, test::Random& rng, const std::string& what) {
  SCOPED_TRACE(what + " (" + std::to_string(b.size() - 1) + " segments)");
  ASSERT_GE(b.size(), 2u);
  for (std::size_t i = 1; i < b.size(); ++i) ASSERT_LT(b[i - 1], b[i]) << "test input not increasing at " << i;
  const SegmentIndex<T> index(b);
  for (const T u : probes(b, rng)) {
    const int want = binary_search_segment(b, u);
    ASSERT_EQ(index.find(b, u), want) << "u=" << u;
    if (std::isnan(u)) continue;
    // The in-domain forms, on u clamped as PiecewiseCubic clamps it; the located frame is the
    // segment's start and T(1)/(its length), as the cursor computes them.
    const T uc = std::clamp(u, b.front(), b.back());
    const int want_clamped = binary_search_segment(b, uc);
    ASSERT_EQ(index.find_in_domain(b, uc), want_clamped) << "u=" << uc;
    const auto at = index.locate_in_domain(b, uc);
    ASSERT_EQ(at.segment, want_clamped) << "u=" << uc;
    const std::size_t i = std::size_t(want_clamped);
    ASSERT_EQ(at.lo, b[i]) << "u=" << uc;
    ASSERT_EQ(at.inv_span, T(1) / (b[i + 1] - b[i])) << "u=" << uc;
  }
}

/// Cumulative sums of `spacings` from `start`, keeping only values that increase (a spacing below
/// the ulp of the running sum is lost in T, as it would be in a user's params).
template <class T>
std::vector<T> knots_from_spacings(T start, const std::vector<double>& spacings) {
  std::vector<T> b{start};
  double x = double(start);
  for (const double h : spacings) {
    x += h;
    if (T(x) > b.back() && std::isfinite(T(x))) b.push_back(T(x));
  }
  return b;
}

TYPED_TEST(SegmentIndexTest, MatchesBinarySearchOnRandomKnots) {
  using T = TypeParam;
  test::Random rng(test::seed_for(1210));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 300; ++trial) {
    const int n = trial < 20 ? trial + 1 : rng.integer(1, 400);
    // Spacings log-uniform over a random number of decades (0: uniform knots .. 6: very uneven).
    const double decades = rng.uniform(0.0, 6.0);
    std::vector<double> h;
    for (int i = 0; i < n; ++i) h.push_back(std::pow(10.0, rng.uniform(-decades / 2, decades / 2)));
    const T start = T(rng.uniform(-100.0, 100.0));
    const std::vector<T> b = knots_from_spacings<T>(start, h);
    if (b.size() < 2) continue;
    expect_same_as_binary_search(b, rng, "trial " + std::to_string(trial));
  }
}

TYPED_TEST(SegmentIndexTest, MatchesBinarySearchOnAdversarialKnots) {
  using T = TypeParam;
  test::Random rng(test::seed_for(1211));
  SCOPED_TRACE(rng.trace());
  // One and two segments.
  expect_same_as_binary_search<T>({T(0), T(1)}, rng, "one segment");
  expect_same_as_binary_search<T>({T(-3), T(-2.5)}, rng, "one short negative segment");
  expect_same_as_binary_search<T>({T(0), T(1), T(2)}, rng, "two equal segments");
  expect_same_as_binary_search<T>({T(0), T(1e-6), T(1)}, rng, "two segments, the first tiny");
  expect_same_as_binary_search<T>({T(0), T(1) - T(1e-6), T(1)}, rng, "two segments, the second tiny");
  // One huge segment among tiny ones: all breakpoints but two fall into the first or last bucket.
  for (const int tiny : {3, 9, 50, 500}) {
    std::vector<double> h(std::size_t(tiny), 1e-3);
    h.push_back(1e6);
    h.insert(h.end(), std::size_t(tiny), 1e-3);
    expect_same_as_binary_search(knots_from_spacings<T>(T(0), h), rng, "huge segment in the middle");
    std::vector<double> g(std::size_t(tiny), 1e-3);
    g.push_back(1e6);
    expect_same_as_binary_search(knots_from_spacings<T>(T(5), g), rng, "huge segment at the end");
    g.insert(g.begin(), 1e6);
    g.pop_back();
    expect_same_as_binary_search(knots_from_spacings<T>(T(-5), g), rng, "huge segment at the start");
  }
  // Spacings spanning 1e-12 … 1e6, shuffled, and sorted up and down.
  {
    std::vector<double> h;
    for (int e = -12; e <= 6; ++e)
      for (int r = 0; r < 5; ++r) h.push_back(std::pow(10.0, e) * rng.uniform(1.0, 9.0));
    std::shuffle(h.begin(), h.end(), rng.engine());
    expect_same_as_binary_search(knots_from_spacings<T>(T(0), h), rng, "spacings 1e-12..1e6 shuffled");
    std::sort(h.begin(), h.end());
    expect_same_as_binary_search(knots_from_spacings<T>(T(0), h), rng, "spacings 1e-12..1e6 growing");
    std::reverse(h.begin(), h.end());
    expect_same_as_binary_search(knots_from_spacings<T>(T(0), h), rng, "spacings 1e6..1e-12 shrinking");
  }
  // Geometric growth by 2 (each segment as long as all before it).
  {
    std::vector<double> h;
    for (int i = 0; i < (sizeof(T) == 4 ? 100 : 900); ++i) h.push_back(std::ldexp(1.0, i));
    expect_same_as_binary_search(knots_from_spacings<T>(T(1), h), rng, "doubling spacings");
  }
  // Far from zero: consecutive representable values (one ulp apart) after 2^20 or 2^50.
  {
    std::vector<T> b{T(sizeof(T) == 4 ? 1 << 20 : 1LL << 50)};
    for (int i = 0; i < 40; ++i) b.push_back(std::nextafter(b.back(), std::numeric_limits<T>::infinity()));
    expect_same_as_binary_search(b, rng, "consecutive floats far from zero");
  }
  // Ranges that overflow T (the bucket width is 0) or are subnormal (its inverse overflows).
  {
    const T m = std::numeric_limits<T>::max();
    expect_same_as_binary_search<T>({-m, -m / 2, T(0), m / 2, m}, rng, "range overflows");
    const T d = std::numeric_limits<T>::denorm_min();
    expect_same_as_binary_search<T>({T(0), d, T(2) * d, T(5) * d}, rng, "subnormal range");
    expect_same_as_binary_search<T>({-d, T(0), d}, rng, "subnormal range around zero");
  }
  // Uniform knots (the bucket is the segment), and uniform knots with a cluster in one place.
  {
    std::vector<double> h(257, 1.0);
    expect_same_as_binary_search(knots_from_spacings<T>(T(0), h), rng, "uniform");
    h.insert(h.begin() + 100, 64, 1e-4);
    expect_same_as_binary_search(knots_from_spacings<T>(T(0), h), rng, "uniform with a cluster");
  }
}

TYPED_TEST(SegmentIndexTest, BucketCountIsTheSegmentCount) {
  // The memory bound documented in the header: one int per segment (one bucket when degenerate).
  using T = TypeParam;
  EXPECT_EQ(SegmentIndex<T>{}.bucket_count(), 1);
  EXPECT_EQ(SegmentIndex<T>(std::vector<T>{T(0), T(1)}).bucket_count(), 1);
  EXPECT_EQ(SegmentIndex<T>(std::vector<T>{T(0), T(1), T(3), T(7)}).bucket_count(), 3);
  const T m = std::numeric_limits<T>::max();
  EXPECT_EQ(SegmentIndex<T>(std::vector<T>{-m, T(0), m}).bucket_count(), 1);
}

/// Checks segment_at of a built curve against the binary search over its breakpoints; that the
/// cursor-free point(u) equals point(u, cursor) from an empty cursor (the same v = (u − u_i)·(1/h_i)),
/// and agrees with derivative(u, 0) (which divides) within piecewise_cursor_tolerance, the bound
/// derived in piecewise_cubic.hpp for those two roundings of v; and NaN in gives NaN out.
template <class C>
void expect_curve_lookup_unchanged(const Expected<C>& built, test::Random& rng, const std::string& family) {
  SCOPED_TRACE(family);
  if (!built) return;  // a clear error (tested in museum_curves_test.cpp)
  const C& c = built.value();
  using T = typename C::scalar_type;
  using P = typename C::point_type;
  const std::vector<T> b(c.breakpoints().begin(), c.breakpoints().end());
  for (const T u : probes(b, rng)) {
    ASSERT_EQ(c.segment_at(u), binary_search_segment(b, u)) << "u=" << u;
    const P p = c.point(u);
    PiecewiseCursor<T> fresh;
    const P q = c.point(u, fresh);
    if (std::isnan(u)) {
      ASSERT_FALSE(is_finite(p));
      ASSERT_FALSE(is_finite(q));
      continue;
    }
    ASSERT_EQ(p, q) << "u=" << u;
    const P want = c.derivative(u, 0);
    const PowerCubic<P> g = c.segment_power_form(c.segment_at(c.domain().clamp(u)));
    for (int k = 0; k < PointTraits<P>::dim; ++k) {
      using Tr = PointTraits<P>;
      const T scale = std::abs(Tr::get(g.a, k)) + std::abs(Tr::get(g.b, k)) + std::abs(Tr::get(g.c, k)) +
                      std::abs(Tr::get(g.d, k));
      ASSERT_LE(std::abs(Tr::get(p, k) - Tr::get(want, k)), piecewise_cursor_tolerance<T> * scale)
          << "u=" << u << " component " << k;
    }
  }
  // At a breakpoint v is exactly 0: the joint value is the segment's constant term, bit for bit.
  for (int i = 0; i < c.segment_count(); ++i) ASSERT_EQ(c.point(b[std::size_t(i)]), c.segment_power_form(i).d) << i;
}

TYPED_TEST(SegmentIndexTest, EveryPiecewiseFamilyOnEveryMuseumExhibit) {
  using T = TypeParam;
  using P = Vec3<T>;
  test::Random rng(test::seed_for(1212));
  SCOPED_TRACE(rng.trace());
  for (const auto& ex : test::museum_curve_points<T>()) {
    SCOPED_TRACE(ex.name);
    const std::vector<P>& p = ex.points;
    std::vector<P> tangents;
    for (std::size_t i = 0; i < p.size(); ++i) tangents.push_back(i + 1 < p.size() ? P(p[i + 1] - p[i]) : P{});
    expect_curve_lookup_unchanged(build_bezier_path(p), rng, "bezier-path");
    expect_curve_lookup_unchanged(build_hermite_spline(p, tangents), rng, "hermite");
    for (T alpha : {T(0), T(0.5), T(1)})
      for (bool closed : {false, true})
        expect_curve_lookup_unchanged(build_catmull_rom(p, {.alpha = alpha, .closed = closed}), rng,
                                      "catmull-rom alpha " + std::to_string(alpha) + (closed ? " closed" : ""));
    expect_curve_lookup_unchanged(build_natural_spline(p), rng, "natural");
    expect_curve_lookup_unchanged(build_closed_spline(p), rng, "closed natural");
    expect_curve_lookup_unchanged(build_clamped_spline(p, P{1, 0, 0}, P{}), rng, "clamped");
    expect_curve_lookup_unchanged(build_kochanek_bartels(p, std::vector<TcbParams<T>>{{T(0.2), T(0.5), T(-0.3)}}),
                                  rng, "kochanek-bartels");
    expect_curve_lookup_unchanged(build_parabolic_blend(p), rng, "parabolic");
    for (int degree = 1; degree <= 3; ++degree) {
      const auto spline = build_bspline(p, degree);
      if (spline) expect_curve_lookup_unchanged(to_piecewise_cubic(spline.value()), rng, "bspline " + std::to_string(degree));
    }
    const auto bezier = build_bezier(p);
    if (bezier && p.size() <= 4) expect_curve_lookup_unchanged(to_piecewise_cubic(bezier.value()), rng, "bezier");
  }
}

TYPED_TEST(SegmentIndexTest, PowerFormsOnAdversarialBreakpoints) {
  // from_power_forms (the B-spline and Bézier conversions) on the adversarial knot vectors: the
  // lookup and point(u) through the public PiecewiseCubic, with random cubic segments.
  using T = TypeParam;
  using P = Vec3<T>;
  test::Random rng(test::seed_for(1214));
  SCOPED_TRACE(rng.trace());
  std::vector<std::vector<double>> spacings{{1.0}, {1.0, 1e-6}, {1e6, 1e-3, 1e-3, 1e-3}};
  {
    std::vector<double> h(40, 1e-3);
    h.insert(h.begin() + 20, 1e6);
    spacings.push_back(h);
    std::vector<double> g;
    for (int e = -12; e <= 6; ++e) g.push_back(std::pow(10.0, e));
    std::shuffle(g.begin(), g.end(), rng.engine());
    spacings.push_back(g);
  }
  for (const auto& h : spacings) {
    const std::vector<T> b = knots_from_spacings<T>(T(rng.uniform(-10.0, 10.0)), h);
    std::vector<PowerCubic<P>> segs;
    for (std::size_t i = 0; i + 1 < b.size(); ++i) segs.push_back({rng.vec3<T>(), rng.vec3<T>(), rng.vec3<T>(), rng.vec3<T>()});
    expect_curve_lookup_unchanged(PiecewiseCubic<P>::from_power_forms(b, segs), rng,
                                  std::to_string(b.size() - 1) + " power-form segments");
  }
}

TYPED_TEST(SegmentIndexTest, SubnormalSpacingIsRejectedNotNaN) {
  // A spacing whose reciprocal overflows would give v = 0·inf = NaN at its breakpoint.
  using T = TypeParam;
  using P = Vec3<T>;
  const T d = std::numeric_limits<T>::denorm_min();
  const auto built = PiecewiseCubic<P>::from_power_forms({T(0), d, T(1)}, std::vector<PowerCubic<P>>(2));
  ASSERT_FALSE(built);
  EXPECT_EQ(built.error().code, ErrorCode::not_finite);
  EXPECT_EQ(json_pointer(built.error().location), "/breakpoints/1");
  const auto hermite = build_hermite_spline(std::vector<P>{P{}, P{1, 0, 0}, P{2, 0, 0}},
                                            std::vector<P>(3), std::vector<T>{T(0), d, T(1)});
  ASSERT_FALSE(hermite);
  EXPECT_EQ(hermite.error().code, ErrorCode::not_finite);
}

TYPED_TEST(SegmentIndexTest, CentripetalAndChordalCatmullRomThroughRandomPoints) {
  // The benchmarked case: non-uniform parameters from random points, 2 … 1025 points.
  using T = TypeParam;
  using P = Vec3<T>;
  test::Random rng(test::seed_for(1213));
  SCOPED_TRACE(rng.trace());
  for (const int n : {2, 3, 5, 16, 100, 1025}) {
    for (const T alpha : {T(0.5), T(1)}) {
      std::vector<P> p;
      for (int i = 0; i < n; ++i) p.push_back(rng.vec3<T>() * T(std::pow(10.0, rng.uniform(-3.0, 3.0))));
      expect_curve_lookup_unchanged(build_catmull_rom(p, {.alpha = alpha}), rng,
                                    std::to_string(n) + " points, alpha " + std::to_string(alpha));
    }
  }
}

}  // namespace
}  // namespace inbetween
