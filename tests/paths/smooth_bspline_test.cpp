// Smoothing by B-spline approximation (texts 004 §3.4.3) on the texts' data set.
#include "inbetween/paths/smooth_bspline.hpp"

#include <gtest/gtest.h>

#include "support/museum_paths.hpp"

namespace inbetween {
namespace {

const std::vector<double> kY{1.6, 1.65, 1.6, 1.8, 2.1, 2.2, 2.0, 1.5, 1.3, 1.4};

// Independent implementation: scipy.interpolate.make_lsq_spline(x = 0..9, y, t, k = 3) with the
// clamped knots t = [0,0,0,0, 3, 6, 9,9,9,9] (6 control points), evaluated at x (SciPy 1.x,
// /usr/bin/python3).  Least squares by QR agrees to ~1e-15 relative; reference_tol allows 1e-12.
TEST(SmoothBSpline, MatchesSciPyLeastSquaresOnTheTextsDataSet) {
  auto s = smooth_bspline(kY, {.degree = 3, .control_points = 6});
  ASSERT_TRUE(s) << s.error().describe();
  const std::vector<double> want{1.6178071725977305, 1.5817715095846918, 1.6650342631837407, 1.8368451861176298,
                                 2.0458575531162659, 2.1583387269381724, 2.0199595923490263, 1.5824555296485587,
                                 1.2218199012727096, 1.4201105651914727};
  ASSERT_EQ(s->points.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(s->points[i], want[i], 1e-12) << i;
  EXPECT_NEAR(s->fit.rms_residual, 0.0537960723673719, 1e-12);   // SciPy, same fit
  EXPECT_NEAR(s->fit.max_residual, 0.08245552964855873, 1e-12);  // SciPy, same fit
}

TEST(SmoothBSpline, OneControlPointPerDatumInterpolatesAndALineStaysALine) {
  auto s = smooth_bspline(kY);  // square system: the curve passes through every point (Eq. 3.26)
  ASSERT_TRUE(s);
  for (std::size_t i = 0; i < kY.size(); ++i) EXPECT_NEAR(s->points[i], kY[i], 1e-12) << i;
  std::vector<Vec2d> line;
  for (int i = 0; i < 12; ++i) line.push_back({2.0 * i, 1.0 - 0.5 * i});
  auto l = smooth_bspline(line, {.degree = 3, .control_points = 5});
  ASSERT_TRUE(l);
  // Linear functions of t lie in the spline space, so the least-squares fit reproduces them.
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(distance(l->points[i], line[i]), 0.0, 1e-12) << i;
}

TEST(SmoothBSpline, BadInputNamesTheIndex) {
  for (const auto& ex : test::museum_bad_paths<double>()) {
    SCOPED_TRACE(ex.name);
    auto s = smooth_bspline(ex.points, {.degree = 2, .control_points = 3});
    ASSERT_FALSE(s);
    EXPECT_EQ(json_pointer(s.error().location), ex.bad_index < 0 ? "/points" : "/points/" + std::to_string(ex.bad_index));
  }
  auto opt = smooth_bspline(kY, {.degree = 3, .control_points = 2});
  ASSERT_FALSE(opt);
  EXPECT_EQ(json_pointer(opt.error().location), "/control_points");
}

template <class T>
class SmoothBSplineMuseum : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SmoothBSplineMuseum, Scalars);

// Degenerate but legal polylines (straight, cusp, zero length, one or two points, corner), one
// control point per point: every fit with degree + 1 ≤ points builds and is finite (never NaN);
// a single point is refused with the place "points" (it was an error without a place), a degree
// too high for the points with "control_points".
TYPED_TEST(SmoothBSplineMuseum, MuseumPathsGiveFinitePointsOrANamedError) {
  using T = TypeParam;
  for (const auto& ex : test::museum_paths<T>()) {
    SCOPED_TRACE(ex.name);
    for (int degree : {1, 2, 3}) {
      auto s = smooth_bspline(ex.points, {.degree = degree});
      const std::size_t n = ex.points.size();
      if (n < 2) {
        ASSERT_FALSE(s);
        EXPECT_EQ(json_pointer(s.error().location), "/points");
        continue;
      }
      if (std::size_t(degree) + 1 > n) {  // a degree-d spline needs d + 1 control points
        ASSERT_FALSE(s);
        EXPECT_EQ(json_pointer(s.error().location), "/control_points");
        continue;
      }
      ASSERT_TRUE(s) << s.error().describe();
      ASSERT_EQ(s->points.size(), ex.points.size());
      for (const auto& p : s->points) EXPECT_TRUE(is_finite(p));
    }
  }
}

}  // namespace
}  // namespace inbetween
