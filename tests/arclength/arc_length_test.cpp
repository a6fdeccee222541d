#include "inbetween/arclength/arc_length.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "inbetween/arclength/accuracy.hpp"
#include "support/museum_arclength.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// The target for the default object in double: u(s) within 1e-9 of the curve length.
constexpr double kDefaultRelTarget = 1e-9;

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
  EXPECT_EQ(r.error().code, ErrorCode::NotFinite);
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
