// Parabolic blending: interpolates, C¹, interior segments equal Catmull-Rom (s = 1/2) while the end
// segments are the single end parabolas; local control.
#include <gtest/gtest.h>

#include "curve_test_util.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class ParabolicBlend : public ::testing::Test {};
TYPED_TEST_SUITE(ParabolicBlend, test::CurvePointTypes);

TYPED_TEST(ParabolicBlend, InteriorEqualsCatmullRomEndsAreParabolas) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(391));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<P>(rng, 6);
  const auto pb = build_parabolic_blend(pts).value();
  const auto cr = build_catmull_rom(pts).value();
  const T tol = T(256) * test::eps<T>;
  for (int seg = 1; seg <= 3; ++seg)
    for (T v : {T(0.2), T(0.5), T(0.8)})
      EXPECT_LT(test::max_abs_diff(pb.point(T(seg) + v), cr.point(T(seg) + v)), tol) << seg;
  // First segment: the parabola through P0, P1, P2 at u = 0, 1, 2: no cubic term, and its
  // continuation to u = 2 reaches P2.
  const auto first = pb.segment_power_form(0);
  EXPECT_EQ(first.a, P{});
  EXPECT_LT(test::max_abs_diff(first.point(T(2)), pts[2]), tol * T(4));
  for (int i = 0; i < 6; ++i) EXPECT_LT(test::max_abs_diff(pb.point(T(i)), pts[i]), tol);
  for (const auto& j : measure_continuity(pb)) EXPECT_EQ(j.c_order(), 1) << j.u;
}

TEST(ParabolicBlendDouble, LocalControlAndDerivatives) {
  test::Random rng(test::seed_for(392));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<Vec3d>(rng, 8);
  test::expect_local_control([](const std::vector<Vec3d>& p) { return build_parabolic_blend(p).value(); }, pts,
                             Vec3d{0.1, -0.1, 0.2});
  test::expect_derivatives_match_differences(build_parabolic_blend(pts).value(), rng);
}

}  // namespace
}  // namespace inbetween
