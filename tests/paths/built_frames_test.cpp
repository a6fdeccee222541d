// Frames along a curve are built types (house style, as tests/tracks/built_types_test.cpp): only
// build() makes them, so FrenetFrames and RotationMinimizingFrames with no curve and no samples
// cannot be written.
#include <gtest/gtest.h>

#include <type_traits>
#include <vector>

#include "inbetween/curves/any_curve.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/helix.hpp"
#include "inbetween/paths/frenet_frames.hpp"
#include "inbetween/paths/rotation_minimizing_frames.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

static_assert(!std::is_default_constructible_v<FrenetFrames<CatmullRomSpline<Vec3d>>>);
static_assert(!std::is_default_constructible_v<RotationMinimizingFrames<CatmullRomSpline<Vec3d>>>);
static_assert(!std::is_default_constructible_v<FrenetFrames<AnyCurve>>);
static_assert(!std::is_default_constructible_v<RotationMinimizingFrames<AnyCurve>>);
// Even over a curve that is itself default-constructible (a value type such as Helix).
static_assert(!std::is_default_constructible_v<FrenetFrames<Helix<double>>>);
static_assert(!std::is_default_constructible_v<RotationMinimizingFrames<Helix<double>>>);
static_assert(std::is_copy_constructible_v<FrenetFrames<AnyCurve>> &&
              std::is_move_constructible_v<RotationMinimizingFrames<AnyCurve>>);

TEST(BuiltFrames, OnlyTheBuilderMakesThem) {
  auto curve = build_catmull_rom(std::vector<Vec3d>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
  ASSERT_TRUE(curve.has_value());
  auto rmf = build_rotation_minimizing_frames(*curve);
  ASSERT_TRUE(rmf.has_value());
  // A unit tangent (by construction): the built frames are usable.
  EXPECT_NEAR(norm(rmf->frame_at(0.5).tangent), 1.0, test::few_ulp<double>);
}

}  // namespace
}  // namespace inbetween
