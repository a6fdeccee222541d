#include "inbetween/arclength/arc_length.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <type_traits>
#include <vector>

#include "inbetween/arclength/accuracy.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "support/museum_arclength.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// The target for the default object in double: u(s) within 1e-9 of the curve length.
constexpr double kDefaultRelTarget = 1e-9;

// Counts the derivative and point evaluations made through it (the work of an arc-length method).
template <class C>
struct CountingCurve {
  using point_type = typename C::point_type;
  using scalar_type = typename C::scalar_type;
  C curve;
  std::int64_t* calls;
  Interval<scalar_type> domain() const noexcept { return curve.domain(); }
  int segment_count() const noexcept { return curve.segment_count(); }
  Interval<scalar_type> segment_domain(int i) const noexcept { return curve.segment_domain(i); }
  point_type point(scalar_type u) const noexcept { return ++*calls, curve.point(u); }
  point_type derivative(scalar_type u, int k) const noexcept { return ++*calls, curve.derivative(u, k); }
};

// Issue 9, defect 5: a 20-point Lagrange curve made `curve info` run 57 s and take 1.55 GB: the
// speed of a degree-19 polynomial evaluated in Newton form carries rounding noise larger than the
// per-interval tolerance, so adaptive integration split every interval down to depth 30.  Every
// adaptive method now has a work budget (max_evaluations_per_segment × segments); the test asserts
// on the evaluation count, not on time.  The count may exceed the budget only by the fixed work
// around the adaptive loop: the speed-minima search (33 samples + 200 bisection steps for each of
// up to 32 minima, 2 derivatives each: 12 866), the speed-scale probe (33), the initial estimate
// (order 10) and, per piece (≤ 33), its first rule (10) plus the halves of the pending recursion
// frames (2 × 10 × 31): 33 × 630 = 20 790 — 33 709 in all, rounded up to 50 000.
// Reference length, independent of quadrature: for a 1-D curve ∫|P'| is the total variation,
// Σ |P(r_{k+1}) − P(r_k)| over the zeros r_k of P' (found by bisection on sign changes).
constexpr std::int64_t kBudgetPerSegment = 100'000;   // the default of every adaptive method
constexpr std::int64_t kBudgetOverhead = 50'000;      // derived above

LagrangeCurve<double> pathological_lagrange() {
  std::vector<double> pts;
  for (int i = 0; i < 20; ++i) pts.push_back(i % 2 == 0 ? 9 : -9);  // 133 bytes as a curve file
  return build_lagrange(pts).value();
}

double total_variation(const LagrangeCurve<double>& c) {
  const auto d = c.domain();
  std::vector<double> stops{d.lo};
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    double lo = d.lo + d.length() * i / n, hi = d.lo + d.length() * (i + 1) / n;
    if ((c.derivative(lo, 1) < 0) == (c.derivative(hi, 1) < 0)) continue;
    for (int it = 0; it < 200 && lo < hi; ++it) {
      const double mid = lo + (hi - lo) / 2;
      if (!(lo < mid && mid < hi)) break;
      if ((c.derivative(mid, 1) < 0) == (c.derivative(lo, 1) < 0)) lo = mid; else hi = mid;
    }
    stops.push_back(lo);
  }
  stops.push_back(d.hi);
  long double sum = 0;
  for (std::size_t k = 1; k < stops.size(); ++k) sum += std::fabs((long double)c.point(stops[k]) - c.point(stops[k - 1]));
  return double(sum);
}

TEST(ArcLength, PathologicalLagrangeStaysWithinTheWorkBudget) {
  const LagrangeCurve<double> lagrange = pathological_lagrange();
  const double exact = total_variation(lagrange);
  std::printf("[ measured ] 20-point Lagrange (+-9 alternating): total variation %.17g\n", exact);
  const std::int64_t bound = kBudgetPerSegment * lagrange.segment_count() + kBudgetOverhead;
  std::int64_t calls = 0;
  auto arc = make_arc_length(CountingCurve<LagrangeCurve<double>>{lagrange, &calls});
  std::printf("[ measured ] ArcLength::build: %lld evaluations (bound %lld), %s\n", (long long)calls, (long long)bound,
              arc ? "built" : arc.error().describe().c_str());
  EXPECT_LE(calls, bound);
  if (arc) EXPECT_NEAR(arc->length(), exact, 1e-9 * exact);
  // The plain adaptive length and the forward-difference table: same budget.
  calls = 0;
  const double fallback = adaptive_gauss_length(CountingCurve<LagrangeCurve<double>>{lagrange, &calls},
                                                lagrange.domain().lo, lagrange.domain().hi,
                                                AdaptiveGaussOptions<double>{.tolerance = 1e-11 * exact, .order = 10});
  std::printf("[ measured ] adaptive_gauss_length: %lld evaluations, relative error %.3g\n", (long long)calls,
              std::fabs(fallback - exact) / exact);
  EXPECT_LE(calls, bound);
  // Stops here within budget (no min_depth), accepting intervals at the rounding floor of the
  // noisy speed: 1.5e-9 relative, the same before and after the budget existed.
  EXPECT_NEAR(fallback, exact, 1e-8 * exact);
  // The fallback itself: a budget of 2 000 per segment runs out; the estimate stays finite.
  calls = 0;
  const double starved = adaptive_gauss_length(
      CountingCurve<LagrangeCurve<double>>{lagrange, &calls}, lagrange.domain().lo, lagrange.domain().hi,
      AdaptiveGaussOptions<double>{.tolerance = 1e-13 * exact, .order = 10, .min_depth = 6,
                                   .max_evaluations_per_segment = 2'000});
  std::printf("[ measured ] adaptive_gauss_length with 2000 evaluations per segment: %lld evaluations, relative error %.3g\n",
              (long long)calls, std::fabs(starved - exact) / exact);
  EXPECT_LE(calls, 2'000 + kBudgetOverhead);
  EXPECT_TRUE(std::isfinite(starved));
  calls = 0;
  auto fd = adaptive_forward_difference_table(CountingCurve<LagrangeCurve<double>>{lagrange, &calls},
                                              AdaptiveForwardDifferenceOptions<double>{.tolerance = 1e-9 * exact,
                                                                                       .max_depth = 40});
  std::printf("[ measured ] adaptive_forward_difference_table: %lld evaluations, %s\n", (long long)calls,
              fd ? "built" : fd.error().describe().c_str());
  EXPECT_LE(calls, bound);
}

TEST(ArcLength, PathologicalLagrangeStaysWithinTheWorkBudgetInFloatToo) {
  std::vector<float> pts;
  for (int i = 0; i < 20; ++i) pts.push_back(i % 2 == 0 ? 9.0f : -9.0f);
  const auto lagrange = build_lagrange(pts).value();
  std::int64_t calls = 0;
  auto arc = make_arc_length(CountingCurve<LagrangeCurve<float>>{lagrange, &calls});
  std::printf("[ measured ] ArcLength::build (float): %lld evaluations, %s\n", (long long)calls,
              arc ? "built" : arc.error().describe().c_str());
  EXPECT_LE(calls, kBudgetPerSegment + kBudgetOverhead);
}

TEST(ArcLength, MuseumCurvesUseAFractionOfTheBudget) {
  std::int64_t worst = 0;
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    std::int64_t calls = 0;
    using Curve = std::decay_t<decltype(ex.curve)>;
    auto arc = make_arc_length(CountingCurve<Curve>{ex.curve, &calls});
    ASSERT_TRUE(arc) << ex.name << ": " << arc.error().describe();
    worst = std::max(worst, calls / std::max(1, ex.curve.segment_count()));
  }
  std::printf("[ measured ] museum curves: at most %lld evaluations per segment for ArcLength::build\n", (long long)worst);
  EXPECT_LE(worst, kBudgetPerSegment / 10);
}

TEST(ArcLength, DefaultMeetsOneNanoLengthOnEveryMuseumCurve) {
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(ex.name);
    auto arc = make_arc_length(ex.curve);
    ASSERT_TRUE(arc) << arc.error().describe();
    const auto acc = measure_arc_length_accuracy(ex.curve, *arc, 65);
    const double L = acc.reference_length;
    EXPECT_LE(acc.length_error, kDefaultRelTarget * L);
    EXPECT_LE(acc.max_s_error, kDefaultRelTarget * L);
    EXPECT_LE(acc.max_u_error, kDefaultRelTarget * L);
    if (ex.exact_length) EXPECT_NEAR(arc->length(), *ex.exact_length, kDefaultRelTarget * L + 1e-300);
  }
}

TEST(ArcLength, DefaultMeetsTheTargetOnTheGenericHelix) {
  const Helix<double> h{.radius = 2, .rise = 0.3, .u_begin = -1, .u_end = 9, .segments = 4};
  auto arc = make_arc_length(h);
  ASSERT_TRUE(arc);
  const double exact = std::sqrt(4 + 0.09) * 10;  // √(r² + c²)·(hi − lo)
  EXPECT_NEAR(arc->length(), exact, kDefaultRelTarget * exact);
  // On a helix s is linear in u, so u(s) has a closed form: lo + s/√(r² + c²).
  for (double s = 0; s <= exact; s += exact / 37) {
    EXPECT_NEAR(arc->u_at(s), -1 + s / std::sqrt(4.09), 1e-12);
  }
}

TEST(ArcLength, InverseComposedWithForwardIsTheIdentity) {
  test::Random rng(test::seed_for(7));
  SCOPED_TRACE(rng.trace());
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(ex.name);
    auto arc = make_arc_length(ex.curve);
    ASSERT_TRUE(arc);
    const auto d = ex.curve.domain();
    const double L = arc->length();
    for (int k = 0; k < 50; ++k) {
      // s(u(s)) = s for every s: the round trip in the arc-length direction is always defined.
      const double s = rng.uniform(0.0, L);
      EXPECT_NEAR(arc->s_at(arc->u_at(s)), s, 1e-12 * (L + 1));
      // u(s(u)) = u wherever the speed is not zero (else u is not determined by s).
      const double u = rng.uniform(d.lo, d.hi);
      if (speed_at(ex.curve, u) > 1e-3 * (L + 1)) EXPECT_NEAR(arc->u_at(arc->s_at(u)), u, 1e-9);
    }
  }
}

TEST(ArcLength, PointAtLengthOnAStraightLineIsEvenlySpaced) {
  // Uneven-speed line from (0,0,0) to (1,0,0): point_at_length(s) = (s, 0, 0) (closed form).
  const auto ex = test::museum_arc_length_exhibit<double>("straight line, uneven speed");
  auto arc = make_arc_length(ex.curve);
  ASSERT_TRUE(arc);
  for (int i = 0; i <= 20; ++i) {
    const Vec3d p = arc->point_at_length(i / 20.0);
    EXPECT_NEAR(p.x, i / 20.0, 1e-12);
    EXPECT_EQ(p.y, 0.0);
  }
}

TEST(ArcLength, ClampsAndHandlesNaNAndZeroLength) {
  const auto ex = test::museum_arc_length_exhibit<double>("parabola");
  auto arc = make_arc_length(ex.curve);
  ASSERT_TRUE(arc);
  EXPECT_EQ(arc->u_at(-1.0), 0.0);
  EXPECT_EQ(arc->u_at(100.0), 1.0);
  EXPECT_EQ(arc->u_at(std::nan("")), 0.0);
  EXPECT_EQ(arc->s_at(-4.0), 0.0);
  EXPECT_EQ(arc->s_at(4.0), arc->length());
  EXPECT_EQ(arc->s_at(std::nan("")), 0.0);
  EXPECT_NEAR(arc->length_between(0.25, 0.75), reference_length(ex.curve, 0.25, 0.75), 1e-12);
  EXPECT_NEAR(arc->length_between(0.75, 0.25), -reference_length(ex.curve, 0.25, 0.75), 1e-12);
  const double u = arc->u_at_distance(0.25, 1.0);
  EXPECT_NEAR(reference_length(ex.curve, 0.25, u), 1.0, 1e-12);

  const auto zero = test::museum_arc_length_exhibit<double>("all control points coincide");
  auto z = make_arc_length(zero.curve);
  ASSERT_TRUE(z);
  EXPECT_EQ(z->length(), 0.0);
  EXPECT_EQ(z->u_at(0.5), 0.0);
  EXPECT_EQ(z->s_at(0.5), 0.0);
  const Vec3d p = z->point_at_length(0.3);
  EXPECT_EQ(p, (Vec3d{1, 2, 3}));
}

TEST(ArcLength, ZeroLengthSegmentAnswersItsEnd) {
  // Segment 2 of this exhibit is a single point over u ∈ [0.5, 0.75]: s is flat there, and u_at of
  // that s answers the end of the plateau (documented), from which the motion continues.
  const auto ex = test::museum_arc_length_exhibit<double>("three segments");
  auto arc = make_arc_length(ex.curve);
  ASSERT_TRUE(arc);
  const double s_joint = arc->s_at(0.5);
  EXPECT_DOUBLE_EQ(arc->s_at(0.6), s_joint);
  EXPECT_DOUBLE_EQ(arc->s_at(0.75), s_joint);
  EXPECT_DOUBLE_EQ(arc->u_at(s_joint), 0.75);
  EXPECT_GT(arc->u_at(s_joint + 1e-9), 0.75);
  EXPECT_LT(arc->u_at(s_joint - 1e-9), 0.5);
}

TEST(ArcLength, RejectsBadOptionsAndNonFiniteCurves) {
  const auto c = test::quarter_circle_bezier<double>();
  EXPECT_FALSE(make_arc_length(c, {.relative_tolerance = 0}));
  EXPECT_FALSE(make_arc_length(c, {.order = 0}));
  EXPECT_FALSE(make_arc_length(c, {.min_depth = 4, .max_depth = 3}));
  auto bad = c;
  bad.pieces[0].a.x = std::numeric_limits<double>::infinity();
  auto r = make_arc_length(bad);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::not_finite);
}

TEST(ArcLength, FloatPrecisionWorksOnTheMuseum) {
  for (const auto& ex : test::museum_arc_length_curves<float>()) {
    SCOPED_TRACE(ex.name);
    auto arc = make_arc_length(ex.curve);
    ASSERT_TRUE(arc) << arc.error().describe();
    const auto acc = measure_arc_length_accuracy(ex.curve, *arc, 33);
    // float: table tolerance 1e-5 relative and speeds rounded to float; measured worst is ~1e-6.
    EXPECT_LE(acc.worst_relative(), 2e-5f);
  }
}

}  // namespace
}  // namespace inbetween

namespace inbetween {
namespace {

TEST(ArcLength, InverseIsAccurateRightAtZeroSpeedPoints) {
  // Distances just around the places where P' = 0: the Newton step is replaced by bisection there.
  for (const char* name : {"P0 = P1", "P2 = P3", "P1 = P2", "cusp", "straight line, stops", "straight line, doubles"}) {
    SCOPED_TRACE(name);
    const auto ex = test::museum_arc_length_exhibit<double>(name);
    auto arc = make_arc_length(ex.curve);
    ASSERT_TRUE(arc);
    const double L = arc->length();
    std::vector<double> targets = {0, 1e-12 * L, 1e-6 * L, L - 1e-6 * L, L - 1e-12 * L, L};
    for (double m : detail::speed_minima(ex.curve, 0.0, 1.0)) {
      const double sm = reference_length(ex.curve, 0.0, m);
      for (double d : {-1e-6, -1e-10, 0.0, 1e-10, 1e-6}) targets.push_back(sm + d * L);
    }
    for (double s : targets) {
      const double u = arc->u_at(s);
      EXPECT_NEAR(reference_length(ex.curve, 0.0, u), std::clamp(s, 0.0, L), 1e-13 * L) << s;
    }
  }
}

}  // namespace
}  // namespace inbetween

namespace inbetween {
namespace {

TEST(ArcLength, UniformArcLengthParametersAreEvenlySpacedAlongTheCurve) {
  const auto ex = test::museum_arc_length_exhibit<double>("fast middle");
  auto arc = make_arc_length(ex.curve);
  ASSERT_TRUE(arc);
  std::vector<double> u(11);
  uniform_arc_length_parameters(*arc, std::span<double>(u));
  const double L = arc->length();
  EXPECT_EQ(u.front(), 0.0);
  EXPECT_EQ(u.back(), 1.0);
  for (std::size_t i = 0; i < u.size(); ++i) {
    EXPECT_NEAR(reference_length(ex.curve, 0.0, u[i]), L * double(i) / 10, 1e-12 * L) << i;
  }
  std::vector<double> one(1);
  uniform_arc_length_parameters(*arc, std::span<double>(one));
  EXPECT_EQ(one[0], 0.0);
}

}  // namespace
}  // namespace inbetween
