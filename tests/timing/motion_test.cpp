#include "inbetween/timing/motion.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "inbetween/arclength/arc_length_table.hpp"
#include "inbetween/arclength/quadrature_length.hpp"
#include "inbetween/timing/cubic_bezier_timing.hpp"
#include "inbetween/timing/distance_time.hpp"
#include "support/museum_arclength.hpp"

namespace inbetween {
namespace {

// The default arc-length object's guarantee (1e-9·L) bounds every arc-length step below.
constexpr double kArcRel = 1e-9;

TEST(Motion, LinearEaseGivesEqualArcLengthStepsForEqualTimeSteps) {
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(ex.name);
    auto arc = make_arc_length(ex.curve);
    ASSERT_TRUE(arc);
    const double L = arc->length();
    const FrameRange<double> frames{.start = 10, .end = 58};
    const int steps = 48;
    double prev_s = 0;
    for (int f = 0; f <= steps; ++f) {
      const auto m = motion_at_frame(*arc, LinearEase<double>{}, frames, 10.0 + f);
      // Independent measure of where the object is: the reference integral up to its parameter.
      const double s = reference_length(ex.curve, ex.curve.domain().lo, m.u);
      EXPECT_NEAR(s, L * f / steps, kArcRel * L + 1e-300);
      if (f > 0) EXPECT_NEAR(s - prev_s, L / steps, 2 * kArcRel * L + 1e-300);
      prev_s = s;
      EXPECT_TRUE(is_finite(m.position) && is_finite(m.velocity) && is_finite(m.acceleration));
    }
  }
}

// The same in float over the museum.  Tolerance: the float arc-length object meets
// default_arc_length_tolerance<float> = 1e-5 relative (measured worst ~1e-6, arc_length_test), the
// reference integral is evaluated on the float curve in long double, so each position is within
// 2e-5·L of i·L/N (the bound ArcLength.FloatPrecisionWorksOnTheMuseum checks).
TEST(Motion, FloatLinearEaseGivesEqualArcLengthSteps) {
  constexpr double kFloatArcRel = 2e-5;
  for (const auto& ex : test::museum_arc_length_curves<float>()) {
    SCOPED_TRACE(ex.name);
    auto arc = make_arc_length(ex.curve);
    ASSERT_TRUE(arc) << arc.error().describe();
    const double L = double(arc->length());
    const FrameRange<float> frames{.start = 10, .end = 58};
    const int steps = 48;
    for (int f = 0; f <= steps; ++f) {
      const auto m = motion_at_frame(*arc, LinearEase<float>{}, frames, 10.0f + float(f));
      const double s = double(reference_length(ex.curve, ex.curve.domain().lo, m.u));
      EXPECT_NEAR(s, L * f / steps, kFloatArcRel * L + 1e-30) << f;
      EXPECT_TRUE(is_finite(m.position) && is_finite(m.velocity) && is_finite(m.acceleration)) << f;
    }
  }
}

template <class E>
void expect_speed_profile(const E& ease, const char* name) {
  SCOPED_TRACE(name);
  const auto ex = test::museum_arc_length_exhibit<double>("quarter circle");
  auto arc = make_arc_length(ex.curve);
  ASSERT_TRUE(arc);
  const double L = arc->length();
  const FrameRange<double> frames{.start = 0, .end = 100};
  for (int f = 1; f < 100; f += 7) {
    const auto m = motion_at_frame(*arc, ease, frames, double(f));
    // |velocity| = L·S'(t)/Δ: the ease's velocity profile, scaled (formula in motion.hpp).
    EXPECT_NEAR(norm(m.velocity), L * std::fabs(ease.sample(f / 100.0).velocity) / 100, 1e-12) << f;
    // Velocity and acceleration are the frame derivatives of position (central differences,
    // h = 1e-3 frames: truncation ~h²·|p'''| ≈ 1e-9, rounding ~1e-13/h).
    const double h = 1e-3;
    const auto p = motion_at_frame(*arc, ease, frames, f + h), q = motion_at_frame(*arc, ease, frames, f - h);
    const Vec3d fd_v = (p.position - q.position) / (2 * h);
    const Vec3d fd_a = (p.position - m.position * 2.0 + q.position) / (h * h);
    EXPECT_LT(norm(Vec3d(fd_v - m.velocity)), 1e-8) << f;
    EXPECT_LT(norm(Vec3d(fd_a - m.acceleration)), 1e-5) << f;  // second difference: rounding 1e-16/h²
  }
}

TEST(Motion, VelocityProfileOfEachEaseMatchesItsFormula) {
  expect_speed_profile(LinearEase<double>{}, "linear");
  expect_speed_profile(SineEase<double>{}, "sine");
  expect_speed_profile(CubicEase<double>{}, "cubic");
  expect_speed_profile(*SineAccelDecelEase<double>::make(0.3, 0.75), "sine accel/decel");
  expect_speed_profile(*ConstantAccelerationEase<double>::make(0.2, 0.7), "constant acceleration");
  expect_speed_profile(CubicBezierTiming<double>::css_ease(), "css ease");
  const std::vector<TimeDistanceVelocityKey<double>> keys = {{0, 0, 0}, {0.4, 0.5, 1.2}, {1, 1, 0}};
  expect_speed_profile(*DistanceTimeCurve<double>::from_constraints(keys), "distance-time curve");
}

TEST(Motion, WorksWithThePrecomputedTableOfTheLectureNotes) {
  // 000 §2.4 step 4 looks u up in a 1000-sample forward-difference table: the motion is then as
  // accurate as that table (~1e-7 of the length on the parabola, see docs/arclength.md).
  const auto ex = test::museum_arc_length_exhibit<double>("parabola");
  auto table = forward_difference_table(ex.curve, {.entries = 1001});
  ASSERT_TRUE(table);
  const double L = reference_length(ex.curve, 0.0, 1.0);
  for (int f = 0; f <= 10; ++f) {
    const auto m = motion_at_frame(ex.curve, *table, LinearEase<double>{}, {.start = 0, .end = 10}, double(f));
    EXPECT_NEAR(reference_length(ex.curve, 0.0, m.u), L * f / 10, 2e-7 * L) << f;
  }
}

TEST(Motion, FiveStepsAreVisibleInTheSample) {
  const auto ex = test::museum_arc_length_exhibit<double>("parabola");
  auto arc = make_arc_length(ex.curve);
  ASSERT_TRUE(arc);
  const SineEase<double> ease;
  const auto m = motion_at_frame(*arc, ease, {.start = 20, .end = 30}, 22.5);
  EXPECT_DOUBLE_EQ(m.t, 0.25);                                 // step 1
  EXPECT_DOUBLE_EQ(m.s, ease(0.25) * arc->length());           // steps 2–3
  EXPECT_DOUBLE_EQ(m.u, arc->u_at(m.s));                       // step 4
  EXPECT_EQ(m.position, ex.curve.point(m.u));                  // step 5
}

TEST(Motion, RestsOutsideTheFrameRangeAndSurvivesDegenerateInput) {
  const auto ex = test::museum_arc_length_exhibit<double>("parabola");
  auto arc = make_arc_length(ex.curve);
  ASSERT_TRUE(arc);
  const FrameRange<double> frames{.start = 0, .end = 10};
  const auto before = motion_at_frame(*arc, LinearEase<double>{}, frames, -5.0);
  EXPECT_EQ(before.position, ex.curve.point(0.0));
  EXPECT_EQ(before.velocity, Vec3d{});
  const auto after = motion_at_frame(*arc, LinearEase<double>{}, frames, 15.0);
  EXPECT_EQ(after.position, ex.curve.point(1.0));
  EXPECT_EQ(after.acceleration, Vec3d{});
  const auto nan = motion_at_frame(*arc, LinearEase<double>{}, frames, std::nan(""));
  EXPECT_EQ(nan.position, ex.curve.point(0.0));
  const auto empty = motion_at_frame(*arc, LinearEase<double>{}, {.start = 5, .end = 5}, 5.0);
  EXPECT_EQ(empty.position, ex.curve.point(1.0));
  // Museum: zero-speed points and zero-length curves give finite motion everywhere.
  for (const auto& m : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(m.name);
    auto a = make_arc_length(m.curve);
    ASSERT_TRUE(a);
    for (double f = 0; f <= 10; f += 0.25) {
      const auto s = motion_at_frame(*a, SineEase<double>{}, frames, f);
      EXPECT_TRUE(is_finite(s.position) && is_finite(s.velocity) && is_finite(s.acceleration)) << f;
    }
  }
}

}  // namespace
}  // namespace inbetween
