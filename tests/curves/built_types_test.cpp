// Built curves cannot exist empty (house style: raw → builder → built, as tests/tracks/built_types_test.cpp
// for the tracks): only their builders make them, so no curve with no segment (whose point(u) would
// read segments_[0]) or a made-up "segment from zero to zero" can be written.
#include <gtest/gtest.h>

#include <type_traits>
#include <vector>

#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"

namespace inbetween {
namespace {

static_assert(!std::is_default_constructible_v<BezierCurve<Vec3d>>);
static_assert(!std::is_default_constructible_v<BezierPath<Vec3d>>);
static_assert(!std::is_default_constructible_v<BSpline<Vec3d>>);
static_assert(!std::is_default_constructible_v<CatmullRomSpline<Vec3d>>);
static_assert(!std::is_default_constructible_v<CubicSpline<Vec3d>>);
static_assert(!std::is_default_constructible_v<HermiteSpline<Vec3d>>);
static_assert(!std::is_default_constructible_v<KochanekBartelsSpline<Vec3d>>);
static_assert(!std::is_default_constructible_v<LagrangeCurve<Vec3d>>);
static_assert(!std::is_default_constructible_v<ParabolicBlendSpline<Vec3d>>);
static_assert(!std::is_default_constructible_v<PiecewiseCubic<Vec3d>>);
static_assert(!std::is_default_constructible_v<CatmullRomSpline<double>>);
static_assert(!std::is_default_constructible_v<BSpline<Vec2f>>);
// They stay values: copied and moved like any other.
static_assert(std::is_copy_constructible_v<CatmullRomSpline<Vec3d>> && std::is_move_constructible_v<BSpline<Vec3d>>);
static_assert(std::is_copy_assignable_v<LagrangeCurve<Vec3d>> && std::is_copy_constructible_v<BezierCurve<Vec3d>>);

TEST(BuiltCurves, OnlyTheBuilderMakesThem) {
  // The static_asserts above are the test; this checks a builder still makes a usable curve.
  auto curve = build_catmull_rom(std::vector<Vec3d>{{0, 0, 0}, {1, 0, 0}});
  ASSERT_TRUE(curve.has_value());
  EXPECT_EQ(curve->point(0.0)[0], 0.0);
}

}  // namespace
}  // namespace inbetween
