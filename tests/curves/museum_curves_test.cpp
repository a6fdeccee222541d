// Every curve family on every curve exhibit of the museum: finite values everywhere (points,
// derivatives 1..3, continuity measurements) or a clear error (message and place).
#include <gtest/gtest.h>

#include <functional>

#include "curve_test_util.hpp"
#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "support/museum_curves.hpp"

namespace inbetween {
namespace {

template <class T>
class MuseumCurves : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(MuseumCurves, Scalars);

template <class C>
void expect_finite_or_clear_error(const Expected<C>& built, const std::string& family) {
  SCOPED_TRACE(family);
  if (!built) {
    EXPECT_FALSE(built.error().message.empty());
    EXPECT_FALSE(built.error().location.empty());
    return;
  }
  const C& c = built.value();
  const auto d = c.domain();
  ASSERT_TRUE(std::isfinite(d.lo) && std::isfinite(d.hi) && d.lo < d.hi);
  for (int s = 0; s <= 100; ++s) {
    const auto u = d.lo + d.length() * scalar_of<typename C::point_type>(s) / 100;
    for (int k = 0; k <= 3; ++k) ASSERT_TRUE(is_finite(c.derivative(u, k))) << "u=" << u << " k=" << k;
  }
  for (int i = 0; i < c.segment_count(); ++i) ASSERT_GT(c.segment_domain(i).length(), 0) << i;
  for (const auto& j : measure_continuity(c))
    for (int k = 0; k < 4; ++k) ASSERT_TRUE(std::isfinite(j.jump[k]) && std::isfinite(j.tangent_angle_rad));
  for (int i = 0; i < c.control_point_count(); ++i) {
    const auto inf = c.influence(i);
    ASSERT_TRUE(inf.lo <= inf.hi && d.contains(inf.lo) && d.contains(inf.hi)) << i;
  }
}

TYPED_TEST(MuseumCurves, EveryFamilyGivesFiniteResultsOrAClearError) {
  using T = TypeParam;
  using P = Vec3<T>;
  for (const auto& ex : test::museum_curve_points<T>()) {
    SCOPED_TRACE(ex.name);
    const std::vector<P>& p = ex.points;
    std::vector<P> tangents;
    for (std::size_t i = 0; i < p.size(); ++i) tangents.push_back(i + 1 < p.size() ? P(p[i + 1] - p[i]) : P{});
    expect_finite_or_clear_error(build_bezier(p), "bezier");
    expect_finite_or_clear_error(build_bezier_path(p), "bezier-path");
    expect_finite_or_clear_error(build_hermite_spline(p, tangents), "hermite");
    for (T alpha : {T(0), T(0.5), T(1)})
      for (bool closed : {false, true})
        expect_finite_or_clear_error(build_catmull_rom(p, {.alpha = alpha, .closed = closed}),
                                     "catmull-rom alpha " + std::to_string(alpha) + (closed ? " closed" : ""));
    expect_finite_or_clear_error(build_natural_spline(p), "natural");
    expect_finite_or_clear_error(build_clamped_spline(p, P{1, 0, 0}, P{}), "clamped");
    expect_finite_or_clear_error(build_kochanek_bartels(p, std::vector<TcbParams<T>>{{T(0.2), T(0.5), T(-0.3)}}),
                                 "kochanek-bartels");
    expect_finite_or_clear_error(build_parabolic_blend(p), "parabolic");
    for (int degree = 1; degree <= 3; ++degree) {
      expect_finite_or_clear_error(build_bspline(p, degree), "bspline " + std::to_string(degree));
      expect_finite_or_clear_error(build_periodic_bspline(p, degree), "periodic bspline " + std::to_string(degree));
    }
    expect_finite_or_clear_error(build_lagrange(p), "lagrange");
  }
}

// Finite inputs whose built coefficients overflow (coordinates near the largest double, points
// whose chordal spacing is subnormal, Lagrange params 1e-300 apart) used to build curves that
// evaluated to NaN (`curve sample` printed -nan with exit 0).  Each family now either reports
// not_finite naming the place or evaluates finitely everywhere.
TEST(MuseumCurvesDouble, OverflowingCoefficientsAreAClearError) {
  const double M = 1e308;
  const std::vector<double> huge{0, M, -M};
  const std::vector<double> huge_tangents{M, -M, M};
  const std::vector<Vec2d> subnormal{{0, 0}, {1e-320, 0}, {2e-320, 0}};
  int errors = 0;
  auto check = [&](const auto& built, const std::string& family) {
    SCOPED_TRACE(family);
    if (!built) {
      EXPECT_EQ(built.error().code, ErrorCode::not_finite) << built.error().describe();
      EXPECT_FALSE(built.error().location.empty());
      ++errors;
      return;
    }
    const auto d = built->domain();
    for (int s = 0; s <= 64; ++s) ASSERT_TRUE(is_finite(built->point(d.lo + d.length() * s / 64))) << s;
  };
  check(build_hermite_spline<double>(std::vector<double>{0, 1, 2}, huge_tangents), "hermite");
  check(build_catmull_rom<double>(huge), "catmull-rom");
  check(build_catmull_rom<Vec2d>(subnormal, {.alpha = 1}), "catmull-rom chordal, subnormal spacing");
  check(build_natural_spline<double>(huge), "natural");
  check(build_kochanek_bartels<double>(std::vector<double>{0, 1, 2}, std::vector<TcbParams<double>>{{-1e308, 0, 0}}),
        "kochanek-bartels tension -1e308");
  check(build_parabolic_blend<double>(huge), "parabolic");
  check(build_bezier_path<double>(std::vector<double>{M, -M, M, -M}), "bezier-path");
  check(build_lagrange<double>(std::vector<double>{0, 1, 0}, std::vector<double>{0, 1e-300, 2e-300}), "lagrange");
  // Each of these overflowed before the check (measured with `curve sample`), so each is an error.
  EXPECT_EQ(errors, 8);
}

TEST(MuseumCurvesDouble, CoincidentPointsFallBackAsDocumented) {
  // All points coincident, centripetal: every span would be 0; the documented fallback makes all
  // spans 1 (uniform knots) and the curve is the constant point.
  const std::vector<Vec3d> same(4, Vec3d{2, -1, 0.5});
  const auto c = build_catmull_rom(same, {.alpha = 0.5}).value();
  EXPECT_EQ(c.domain(), (Interval<double>{0, 3}));
  EXPECT_EQ(c.point(1.7), same[0]);
  EXPECT_EQ(c.derivative(1.7, 1), Vec3d{});
  // One zero-length span among spans of length 1: its knot span is 1e-6 (10⁻⁶ × the largest).
  const std::vector<Vec3d> gap{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const auto g = build_catmull_rom(gap, {.alpha = 0.5}).value();
  // The span is stored as breakpoints 1 and 1 + 1e-6, so its length carries their rounding (ulp of 1).
  EXPECT_NEAR(g.segment_domain(1).length(), 1e-6, 4 * std::numeric_limits<double>::epsilon());
  EXPECT_LT(test::max_abs_diff(g.point(g.segment_domain(1).lo + 5e-7), Vec3d{1, 0, 0}), 1e-6);
}

}  // namespace
}  // namespace inbetween
