// PiecewiseCubic's cursor (issue 12): point(u, cursor) and the batch points(u, out, cursor) agree
// with point(u) within piecewise_cursor_tolerance (a rounding bound derived in the header), on
// sweeps forwards, backwards and at random, on every museum point list, at the breakpoints and
// outside the domain; the batch form equals the single form value for value; neither allocates.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "curve_test_util.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "support/counting_new.hpp"
#include "support/museum_curves.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class PiecewiseCursorTest : public ::testing::Test {};
TYPED_TEST_SUITE(PiecewiseCursorTest, test::CurvePointTypes);

/// Checks point(u, cursor) against point(u) with the header's bound for the segment at u.
template <class P>
void expect_cursor_agrees(const PiecewiseCubic<P>& c, scalar_of<P> u, PiecewiseCursor<scalar_of<P>>& cursor) {
  using T = scalar_of<P>;
  const P got = c.point(u, cursor);
  const P want = c.point(u);
  const PowerCubic<P> g = c.segment_power_form(c.segment_at(c.domain().clamp(u)));
  for (int k = 0; k < PointTraits<P>::dim; ++k) {
    using Tr = PointTraits<P>;
    const T scale = std::abs(Tr::get(g.a, k)) + std::abs(Tr::get(g.b, k)) + std::abs(Tr::get(g.c, k)) +
                    std::abs(Tr::get(g.d, k));
    ASSERT_LE(std::abs(Tr::get(got, k) - Tr::get(want, k)), piecewise_cursor_tolerance<T> * scale)
        << "u=" << u << " component " << k;
  }
}

TYPED_TEST(PiecewiseCursorTest, AgreesWithPointOnSweepsAndJumps) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(1201));
  SCOPED_TRACE(rng.trace());
  for (const T alpha : {T(0), T(0.5), T(1)}) {
    const auto c = build_catmull_rom(test::random_points<P>(rng, 9), {.alpha = alpha}).value();
    const Interval<T> dom = c.domain();
    PiecewiseCursor<T> cursor;
    for (int k = -8; k <= 8 * 64 + 8; ++k) expect_cursor_agrees<P>(c, dom.lo + (dom.hi - dom.lo) * T(k) / T(512), cursor);
    for (int k = 8 * 64; k >= 0; --k) expect_cursor_agrees<P>(c, dom.lo + (dom.hi - dom.lo) * T(k) / T(512), cursor);
    for (int n = 0; n < 500; ++n) expect_cursor_agrees<P>(c, rng.uniform<T>(dom.lo - T(1), dom.hi + T(1)), cursor);
    for (const T b : c.breakpoints()) {
      expect_cursor_agrees<P>(c, b, cursor);
      expect_cursor_agrees<P>(c, std::nextafter(b, dom.lo - T(1)), cursor);
    }
  }
}

TEST(PiecewiseCursorDouble, MuseumCurvesStayFiniteAndAgree) {
  for (const auto& ex : test::museum_curve_points<double>()) {
    SCOPED_TRACE(ex.name);
    const auto built = build_catmull_rom(ex.points, {.alpha = 0.5});
    if (!built) continue;  // too few points: the builder's error (tested in catmull_rom_test.cpp)
    const auto& c = built.value();
    PiecewiseCursor<double> cursor;
    const Interval<double> dom = c.domain();
    for (int k = -2; k <= 130; ++k) {
      const double u = dom.lo + (dom.hi - dom.lo) * k / 128.0;
      ASSERT_TRUE(is_finite(c.point(u, cursor)));
      expect_cursor_agrees<Vec3d>(c, u, cursor);
    }
  }
}

TEST(PiecewiseCursorDouble, NanGivesNanAndDoesNotPoisonTheCursor) {
  test::Random rng(test::seed_for(1202));
  SCOPED_TRACE(rng.trace());
  const auto c = build_catmull_rom(test::random_points<Vec3d>(rng, 5)).value();
  PiecewiseCursor<double> cursor;
  (void)c.point(1.5, cursor);
  EXPECT_FALSE(is_finite(c.point(std::nan(""), cursor)));  // as point(NaN)
  EXPECT_EQ(c.point(1.5, cursor), c.point(1.5, cursor));
  expect_cursor_agrees<Vec3d>(c, 1.5, cursor);
}

TEST(PiecewiseCursorDouble, CursorOfAnotherCurveIsRefilled) {
  test::Random rng(test::seed_for(1203));
  SCOPED_TRACE(rng.trace());
  const auto a = build_catmull_rom(test::random_points<Vec3d>(rng, 5)).value();
  const auto b = build_catmull_rom(test::random_points<Vec3d>(rng, 5)).value();
  PiecewiseCursor<double> cursor;
  (void)a.point(1.5, cursor);
  expect_cursor_agrees<Vec3d>(b, 1.5, cursor);  // same segment index and domain, other curve
}

TYPED_TEST(PiecewiseCursorTest, BatchEqualsSingleFormAndNeverAllocates) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(1204));
  SCOPED_TRACE(rng.trace());
  const auto c = build_catmull_rom(test::random_points<P>(rng, 12), {.alpha = T(0.5)}).value();
  const Interval<T> dom = c.domain();
  std::vector<T> u(1000);
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = dom.lo + (dom.hi - dom.lo) * T(k) / T(999);
  // A sorted sweep, then shuffled parameters with some outside the domain.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      for (T& x : u) x = rng.uniform<T>(dom.lo - T(0.5), dom.hi + T(0.5));
    }
    std::vector<P> out(u.size());
    PiecewiseCursor<T> batch_cursor, single_cursor;
    EXPECT_EQ(test::allocations_in([&] { c.points(u, out, batch_cursor); }), 0);
    long allocations = 0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      P single{};
      allocations += test::allocations_in([&] { single = c.point(u[k], single_cursor); });
      ASSERT_EQ(out[k], single) << "k=" << k << " u=" << u[k];
      expect_cursor_agrees<P>(c, u[k], single_cursor);
    }
    EXPECT_EQ(allocations, 0);
  }
}

TYPED_TEST(PiecewiseCursorTest, CursorFreeQueriesNeverAllocate) {
  // point(u), segment_at(u) and derivative(u, k) read the SegmentIndex built with the curve: no
  // allocation per query, also in a crowded bucket (many tiny segments next to a huge one) and
  // for u outside the domain, ±inf and NaN.
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(1205));
  SCOPED_TRACE(rng.trace());
  std::vector<T> params{T(0)};
  for (int i = 0; i < 20; ++i) params.push_back(params.back() + T(1e-3));
  params.push_back(params.back() + T(1e3));
  const std::vector<P> points = test::random_points<P>(rng, int(params.size()));
  const std::vector<P> tangents = test::random_points<P>(rng, int(params.size()));
  const auto c = build_hermite_spline(points, tangents, params).value();
  const Interval<T> dom = c.domain();
  std::vector<T> u{std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity(),
                   std::numeric_limits<T>::quiet_NaN()};
  for (int k = 0; k < 500; ++k) u.push_back(rng.uniform<T>(dom.lo - T(1), dom.lo + T(0.05)));
  for (int k = 0; k < 500; ++k) u.push_back(rng.uniform<T>(dom.lo, dom.hi + T(1)));
  long allocations = 0;
  P sink{};
  for (const T x : u) {
    allocations += test::allocations_in([&] {
      sink = sink + c.point(x) * T(0);
      sink = sink + c.derivative(x, 1) * T(0);
      (void)c.segment_at(x);
    });
  }
  EXPECT_EQ(allocations, 0);
}

}  // namespace
}  // namespace inbetween
