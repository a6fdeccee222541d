// Kochanek–Bartels: zero parameters reproduce Catmull-Rom; continuity ≠ 0 breaks C¹ and G¹ at
// that key only; tension 1 flattens tangents to zero; local control.
#include <gtest/gtest.h>

#include "curve_test_util.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class P>
class KochanekBartels : public ::testing::Test {};
TYPED_TEST_SUITE(KochanekBartels, test::CurvePointTypes);

TYPED_TEST(KochanekBartels, ZeroParametersAreCatmullRom) {
  using P = TypeParam;
  using T = scalar_of<P>;
  test::Random rng(test::seed_for(381));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<P>(rng, 7);
  const auto kb = build_kochanek_bartels(pts, std::vector<TcbParams<T>>{{}}).value();
  const auto cr = build_catmull_rom(pts).value();
  for (int s = 0; s <= 60; ++s) {
    const T u = T(6) * T(s) / T(60);
    EXPECT_LT(test::max_abs_diff(kb.point(u), cr.point(u)), T(256) * test::eps<T>);
  }
}

TEST(KochanekBartelsDouble, ContinuityParameterMakesACornerAtItsKeyOnly) {
  test::Random rng(test::seed_for(382));
  SCOPED_TRACE(rng.trace());
  const auto pts = test::random_points<Vec2d>(rng, 6);
  std::vector<TcbParams<double>> keys(6);
  keys[2].continuity = 0.7;
  keys[4].tension = 1;  // zero tangent at key 4: C¹ but the tangent direction is undefined
  const auto c = build_kochanek_bartels(pts, keys).value();
  const auto joints = measure_continuity(c);
  for (const auto& j : joints) {
    if (j.u == 2) {
      EXPECT_EQ(j.c_order(), 0);
      EXPECT_FALSE(j.g1);
    } else {
      EXPECT_GE(j.c_order(), 1) << j.u;
    }
  }
  EXPECT_EQ(c.derivative(4.0, 1), Vec2d{});
  test::expect_local_control([&](const std::vector<Vec2d>& p) { return build_kochanek_bartels(p, keys).value(); }, pts,
                             Vec2d{0.3, 0.1});
  test::expect_derivatives_match_differences(c, rng);
  EXPECT_FALSE(build_kochanek_bartels(pts, std::vector<TcbParams<double>>(3)).has_value());
}

}  // namespace
}  // namespace inbetween
