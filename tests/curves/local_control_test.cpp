// local_control.hpp: the parameter ranges an authored control point moves (closed forms per
// family), and with_control_point() checked against them: outside the ranges the curve is
// unchanged, inside it moves.
#include "inbetween/curves/local_control.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "curve_test_util.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

using test::Random;

// Unaffected segments are rebuilt from the same numbers, so they agree to the last bit on most
// families; a Catmull-Rom spline with alpha > 0 evaluates them at shifted knots (u = lo + v·Δ
// rounds differently), which costs a few ulp of O(1) coordinates.
constexpr double kUnchanged = 1e-12;
// A move of 0.5 in each coordinate changes a point inside the range by far more than this.
constexpr double kChanged = 1e-9;

template <class C>
AnyCurve any(CurveKind kind, Expected<C> built) {
  EXPECT_TRUE(built.has_value()) << (built ? "" : built.error().describe());
  return AnyCurve{kind, 2, AnyCurveVariant{std::move(built).value()}};
}

std::vector<Vec3d> planar(const std::vector<Vec2d>& pts) {
  std::vector<Vec3d> out;
  for (const auto& p : pts) out.push_back({p.x, p.y, 0});
  return out;
}

const std::vector<Vec3d> kTen = planar({{0, 0}, {1, 2}, {2, 3}, {3, 1}, {4, 0}, {5, 2}, {6, 3}, {7, 1}, {8, 0}, {9, 2}});

using Ranges = std::vector<Interval<double>>;

// Closed form (the B-spline basis N_{i,p} is non-zero on [u_i, u_{i+p+1}]): a cubic B-spline with
// knots 0, 1, …, 13 on 10 points has domain [u_3, u_10] = [3, 10]; point 5 moves [5, 9], the four
// knot spans 2 … 5 (segment s is [s + 3, s + 4]); point 0 moves [3, 4] only.
TEST(LocalControl, BSplinePointMovesItsFourKnotSpans) {
  std::vector<double> knots;
  for (int k = 0; k <= 13; ++k) knots.push_back(k);
  const AnyCurve c = any(CurveKind::bspline, build_bspline(kTen, 3, knots));
  EXPECT_TRUE(has_local_control(c.kind));
  EXPECT_EQ(authored_point_count(c), 10);
  EXPECT_EQ(influence_ranges(c, 5), (Ranges{{5, 9}}));
  EXPECT_EQ(segments_in(c, influence_ranges(c, 5)), (std::vector<int>{2, 3, 4, 5}));
  EXPECT_EQ(influence_ranges(c, 0), (Ranges{{3, 4}}));
  EXPECT_EQ(segments_in(c, influence_ranges(c, 0)), (std::vector<int>{0}));
}

// Closed form: uniform Catmull-Rom, segment k = [k, k + 1]; point i enters the tangents at i − 1,
// i, i + 1, so it moves segments i − 2 … i + 1: point 4 of 10 moves [2, 6], point 0 [0, 2].
TEST(LocalControl, CatmullRomPointMovesFourSegments) {
  const AnyCurve c = any(CurveKind::catmull_rom, build_catmull_rom(kTen));
  EXPECT_EQ(influence_ranges(c, 4), (Ranges{{2, 6}}));
  EXPECT_EQ(segments_in(c, influence_ranges(c, 4)), (std::vector<int>{2, 3, 4, 5}));
  EXPECT_EQ(influence_ranges(c, 0), (Ranges{{0, 2}}));
}

// One Bézier curve, a natural spline and a Lagrange polynomial: every point moves everything.
TEST(LocalControl, GlobalFamiliesMoveTheWholeDomain) {
  const AnyCurve bezier = any(CurveKind::bezier, build_bezier(std::vector<Vec3d>(kTen.begin(), kTen.begin() + 4)));
  const AnyCurve natural = any(CurveKind::natural, build_natural_spline(kTen));
  const AnyCurve lagrange = any(CurveKind::lagrange, build_lagrange(std::vector<Vec3d>(kTen.begin(), kTen.begin() + 5)));
  for (const AnyCurve* c : {&bezier, &natural, &lagrange}) {
    SCOPED_TRACE(std::string(curve_kind_name(c->kind)));
    EXPECT_FALSE(has_local_control(c->kind));
    for (int i = 0; i < authored_point_count(*c); ++i) EXPECT_EQ(influence_ranges(*c, i), (Ranges{c->domain()}));
    EXPECT_EQ(int(segments_in(*c, {c->domain()}).size()), c->segment_count());
  }
}

// Closed curves: the range wraps past the seam and comes back as two ranges.  A periodic cubic
// B-spline on 6 points has knots 0 … 9 and domain [3, 9]; point 1 is held as points 1 and 7, whose
// bases cover [1, 5] and [7, 11]: [3, 5] and [7, 9] inside the domain.  A closed uniform
// Catmull-Rom spline on 8 points: point 0 moves segments 6, 7, 0, 1 = [0, 2] and [6, 8].
TEST(LocalControl, ClosedCurvesWrapPastTheSeam) {
  const std::vector<Vec3d> six(kTen.begin(), kTen.begin() + 6);
  const AnyCurve periodic = any(CurveKind::bspline, build_periodic_bspline(six, 3));
  EXPECT_EQ(authored_point_count(periodic), 6);
  EXPECT_EQ(periodic.control_point_count(), 9);
  EXPECT_EQ(influence_ranges(periodic, 1), (Ranges{{3, 5}, {7, 9}}));
  EXPECT_EQ(influence_ranges(periodic, 4), (Ranges{{4, 8}}));
  const std::vector<Vec3d> eight(kTen.begin(), kTen.begin() + 8);
  const AnyCurve loop = any(CurveKind::catmull_rom, build_catmull_rom(eight, {.closed = true}));
  EXPECT_EQ(influence_ranges(loop, 0), (Ranges{{0, 2}, {6, 8}}));
  EXPECT_EQ(influence_ranges(loop, 4), (Ranges{{2, 6}}));
  EXPECT_EQ(segments_in(loop, influence_ranges(loop, 0)), (std::vector<int>{0, 1, 6, 7}));
}

TEST(LocalControl, MovingAPointThatDoesNotExistIsAnError) {
  const AnyCurve c = any(CurveKind::catmull_rom, build_catmull_rom(kTen));
  for (int i : {-1, 10}) {
    const auto moved = with_control_point(c, i, Vec3d{});
    ASSERT_FALSE(moved.has_value());
    EXPECT_EQ(moved.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(moved.error().message.find("the curve has 10 (0 to 9)"), std::string::npos) << moved.error().message;
  }
  const auto nan = with_control_point(c, 2, Vec3d{std::nan(""), 0, 0});
  EXPECT_FALSE(nan.has_value());
}

// Every family, every authored point, moved by a random offset: the rebuilt curve keeps the
// family's options (same domain, same segment count), holds the new point, is unchanged on the
// segments outside influence_ranges() (compared at the same local parameter of each segment, and
// at the same u unless the knots move) and changes inside every range.
TEST(LocalControl, MovedCurveChangesOnlyInsideTheRanges) {
  Random rng(test::seed_for(2611));
  SCOPED_TRACE(rng.trace());
  std::vector<Vec3d> pts;
  for (int i = 0; i < 9; ++i) pts.push_back({double(i), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)});
  std::vector<Vec3d> tangents;
  for (int i = 0; i < 9; ++i) tangents.push_back(rng.vec3());
  std::vector<double> params{0, 0.5, 2, 2.25, 3, 4.5, 5, 6, 8};
  std::vector<Vec3d> path(pts.begin(), pts.begin() + 7);  // 3k + 1 = 7
  std::vector<TcbParams<double>> tcb(9, TcbParams<double>{.tension = 0.2, .continuity = -0.3, .bias = 0.4});
  const std::vector<AnyCurve> curves = {
      any(CurveKind::bezier, build_bezier(std::vector<Vec3d>(pts.begin(), pts.begin() + 5))),
      any(CurveKind::bezier_path, build_bezier_path(path)),
      any(CurveKind::hermite, build_hermite_spline(pts, tangents, params)),
      any(CurveKind::catmull_rom, build_catmull_rom(pts)),
      any(CurveKind::catmull_rom, build_catmull_rom(pts, {.alpha = 0.5})),
      any(CurveKind::catmull_rom, build_catmull_rom(pts, {.closed = true})),
      any(CurveKind::natural, build_natural_spline(pts, params)),
      any(CurveKind::natural, build_clamped_spline(pts, tangents[0], tangents[1])),
      any(CurveKind::kochanek_bartels, build_kochanek_bartels(pts, tcb, params)),
      any(CurveKind::parabolic, build_parabolic_blend(pts)),
      any(CurveKind::bspline, build_bspline(pts, 3)),
      any(CurveKind::bspline, build_bspline(pts, 2)),
      any(CurveKind::bspline, build_periodic_bspline(pts, 3)),
      any(CurveKind::lagrange, build_lagrange(std::vector<Vec3d>(pts.begin(), pts.begin() + 5))),
  };
  for (std::size_t ci = 0; ci < curves.size(); ++ci) {
    const AnyCurve& before = curves[ci];
    SCOPED_TRACE("curve " + std::to_string(ci) + " (" + std::string(curve_kind_name(before.kind)) + ")");
    const auto* cr = std::get_if<CatmullRomSpline<Vec3d>>(&before.curve);
    const bool knots_move = cr && cr->options().alpha > 0;
    for (int i = 0; i < authored_point_count(before); ++i) {
      SCOPED_TRACE("point " + std::to_string(i));
      const Vec3d p = before.control_point(i) + Vec3d{0.5, -0.5, 0.5};
      const auto moved = with_control_point(before, i, p);
      ASSERT_TRUE(moved.has_value()) << moved.error().describe();
      const AnyCurve& after = *moved;
      EXPECT_EQ(after.kind, before.kind);
      EXPECT_EQ(after.dimension, before.dimension);
      EXPECT_EQ(after.control_point(i), p);
      EXPECT_EQ(after.segment_count(), before.segment_count());
      if (!knots_move) EXPECT_EQ(after.domain(), before.domain());
      const auto ranges = influence_ranges(before, i);
      const auto inside = segments_in(before, ranges);
      std::vector<bool> changed(ranges.size(), false);
      for (int s = 0; s < before.segment_count(); ++s) {
        const bool in = std::find(inside.begin(), inside.end(), s) != inside.end();
        const auto d0 = before.segment_domain(s), d1 = after.segment_domain(s);
        for (int k = 0; k <= 20; ++k) {
          const double v = k / 20.0;
          const double u0 = d0.lo + v * d0.length(), u1 = d1.lo + v * d1.length();
          const double diff = test::max_abs_diff(before.segment_derivative(s, u0, 0), after.segment_derivative(s, u1, 0));
          if (!in) {
            EXPECT_LE(diff, kUnchanged) << "segment " << s << " v=" << v;
            // Inside the segment: at its ends point(u) reads the neighbour (right limit).
            if (!knots_move && k > 0 && k < 20) EXPECT_EQ(before.point(u0), after.point(u0)) << "u=" << u0;
          } else if (diff > kChanged) {
            for (std::size_t r = 0; r < ranges.size(); ++r) changed[r] = changed[r] || ranges[r].contains(u0);
          }
        }
      }
      for (std::size_t r = 0; r < ranges.size(); ++r) EXPECT_TRUE(changed[r]) << "range " << r << " did not move";
    }
  }
}

}  // namespace
}  // namespace inbetween
