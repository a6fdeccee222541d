#include "inbetween/arclength/arc_length_table.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "inbetween/arclength/accuracy.hpp"
#include "support/museum_arclength.hpp"

namespace inbetween {
namespace {

// Texts 004 Table 3.1: u = 0, 0.05, …, 1 and the printed arc lengths G.
std::vector<double> table31_u() {
  std::vector<double> u;
  for (int i = 0; i <= 20; ++i) u.push_back(0.05 * i);
  return u;
}
const std::vector<double> kTable31S = {0.000, 0.080, 0.150, 0.230, 0.320, 0.400, 0.500, 0.600, 0.720, 0.800, 0.860,
                                       0.900, 0.920, 0.932, 0.944, 0.959, 0.972, 0.984, 0.994, 0.998, 1.000};

// The worked numbers are a handful of double operations on 3-digit data: 8 ulp of 1.
constexpr double kWorkedTol = 8 * 2.220446049250313e-16;

TEST(ArcLengthTable, ReproducesTable31WorkedNumbers) {
  const auto u = table31_u();
  auto t = ArcLengthTable<double>::from_entries(u, kTable31S);
  ASSERT_TRUE(t) << t.error().describe();
  EXPECT_TRUE(t->is_uniform());
  EXPECT_EQ(t->nearest_index_for_u(0.73), 15);    // Eq. 3.8
  EXPECT_EQ(t->interval_index_for_u(0.73), 14);   // Eq. 3.9
  EXPECT_DOUBLE_EQ(t->s_nearest(0.73), 0.959);    // "a crude approximation … 0.959"
  EXPECT_NEAR(t->s_at(0.73), 0.953, kWorkedTol);  // Eq. 3.10
  EXPECT_DOUBLE_EQ(t->u_nearest(0.75), 0.40);     // "the closest arc length is 0.72 … 0.40"
  EXPECT_NEAR(t->u_at(0.75), 0.41875, kWorkedTol);  // Eq. 3.11
  // Problem 1 by the table: LENGTH(0.25, 0.5) = G[10] − G[5]; problem 2: u at 0.35 from u = 0.25.
  EXPECT_NEAR(t->length_between(0.25, 0.5), 0.46, kWorkedTol);
  EXPECT_NEAR(t->u_at_distance(0.25, 0.35), 0.40 + (0.03 / 0.08) * 0.05, kWorkedTol);
}

// The same worked numbers in float.  Source of the tolerance: the table's inputs are the printed
// 3-digit values rounded to float (½ ulp each) and the lookups are a handful of float operations,
// so 8 ulp of 1 in float, as kWorkedTol is in double.
TEST(ArcLengthTable, ReproducesTable31WorkedNumbersInFloat) {
  constexpr float kWorkedTolF = 8 * std::numeric_limits<float>::epsilon();
  std::vector<float> u, s;
  for (int i = 0; i <= 20; ++i) u.push_back(0.05f * float(i)), s.push_back(float(kTable31S[std::size_t(i)]));
  auto t = ArcLengthTable<float>::from_entries(u, s);
  ASSERT_TRUE(t) << t.error().describe();
  EXPECT_EQ(t->interval_index_for_u(0.73f), 14);
  EXPECT_NEAR(t->s_at(0.73f), 0.953f, kWorkedTolF);      // Eq. 3.10
  EXPECT_NEAR(t->u_at(0.75f), 0.41875f, kWorkedTolF);    // Eq. 3.11
  EXPECT_NEAR(t->length_between(0.25f, 0.5f), 0.46f, kWorkedTolF);
  // A float forward-difference table of the museum's uniform straight line (length 9): chords of a
  // line are exact up to float rounding of the 20 summed chord lengths, 20·eps·9.
  const auto ex = test::museum_arc_length_exhibit<float>("straight line, uniform");
  auto line = forward_difference_table(ex.curve, {.entries = 21});
  ASSERT_TRUE(line);
  EXPECT_NEAR(line->length(), *ex.exact_length, 20 * std::numeric_limits<float>::epsilon() * 9);
  EXPECT_NEAR(line->s_at(0.73f), 0.73f * 9, 20 * std::numeric_limits<float>::epsilon() * 9);
}

TEST(ArcLengthTable, LookupsAtRowsAndOutsideTheRangeClamp) {
  auto t = ArcLengthTable<double>::from_entries(table31_u(), kTable31S);
  ASSERT_TRUE(t);
  for (int i = 0; i <= 20; ++i) {
    EXPECT_NEAR(t->s_at(0.05 * i), kTable31S[std::size_t(i)], kWorkedTol) << i;
    EXPECT_NEAR(t->u_at(kTable31S[std::size_t(i)]), 0.05 * i, kWorkedTol) << i;
  }
  EXPECT_EQ(t->s_at(-3.0), 0.0);
  EXPECT_EQ(t->s_at(7.0), 1.0);
  EXPECT_EQ(t->u_at(-1.0), 0.0);
  EXPECT_EQ(t->u_at(2.0), 1.0);
  EXPECT_EQ(t->u_at(std::nan("")), 0.0);
  EXPECT_EQ(t->s_at(std::nan("")), 0.0);
}

TEST(ArcLengthTable, RejectsBadTablesNamingTheRow) {
  std::vector<double> u = {0, 0.5, 0.4, 1}, s = {0, 0.1, 0.2, 0.3};
  auto bad_u = ArcLengthTable<double>::from_entries(u, s);
  ASSERT_FALSE(bad_u);
  EXPECT_EQ(bad_u.error().code, ErrorCode::keys_not_increasing);
  EXPECT_EQ(bad_u.error().place(), "row 2");
  u = {0, 0.3, 0.6, 1};
  s = {0, 0.2, 0.1, 0.3};
  auto bad_s = ArcLengthTable<double>::from_entries(u, s);
  ASSERT_FALSE(bad_s);
  EXPECT_EQ(bad_s.error().code, ErrorCode::not_monotone);
  EXPECT_EQ(bad_s.error().place(), "row 2");
  std::vector<double> one = {0};
  EXPECT_EQ(ArcLengthTable<double>::from_entries(one, one).error().code, ErrorCode::too_few_points);
  s = {0.1, 0.2, 0.3, 0.4};
  EXPECT_EQ(ArcLengthTable<double>::from_entries(u, s).error().place(), "row 0");
  s = {0, std::nan(""), 0.3, 0.4};
  EXPECT_EQ(ArcLengthTable<double>::from_entries(u, s).error().code, ErrorCode::not_finite);
}

TEST(ArcLengthTable, NonUniformTableUsesBinarySearch) {
  const std::vector<double> u = {0, 0.1, 0.5, 1}, s = {0, 1, 1, 3};  // plateau: zero-length piece
  auto t = ArcLengthTable<double>::from_entries(u, s);
  ASSERT_TRUE(t);
  EXPECT_FALSE(t->is_uniform());
  EXPECT_EQ(t->interval_index_for_u(0.3), 1);
  EXPECT_DOUBLE_EQ(t->s_at(0.3), 1.0);
  EXPECT_DOUBLE_EQ(t->s_at(0.75), 2.0);
  EXPECT_DOUBLE_EQ(t->u_at(1.0), 0.5);  // documented: the end of the plateau
  EXPECT_DOUBLE_EQ(t->u_at(0.5), 0.05);
  EXPECT_EQ(t->nearest_index_for_u(0.29), 1);
  EXPECT_EQ(t->nearest_index_for_u(0.31), 2);
}

TEST(ForwardDifferenceTable, IsExactOnAUniformLineAndRejectsBadOptions) {
  const auto ex = test::museum_arc_length_exhibit<double>("straight line, uniform");
  auto t = forward_difference_table(ex.curve, {.entries = 21});
  ASSERT_TRUE(t);
  EXPECT_TRUE(t->is_uniform());
  EXPECT_EQ(t->build_evaluations(), 21);
  EXPECT_NEAR(t->length(), *ex.exact_length, 1e-14 * 9);  // chords of a straight line are exact
  EXPECT_NEAR(t->s_at(0.73), 0.73 * 9, 1e-13);
  EXPECT_FALSE(forward_difference_table(ex.curve, {.entries = 1}));
  EXPECT_FALSE(forward_difference_table(ex.curve, {.entries = 5, .supersample = 0}));
}

TEST(ForwardDifferenceTable, ChordSumsUnderestimateAndSupersamplingCutsTheErrorQuadratically) {
  const auto ex = test::museum_arc_length_exhibit<double>("parabola");
  const double exact = *ex.exact_length;
  auto coarse = forward_difference_table(ex.curve, {.entries = 101});
  auto fine = forward_difference_table(ex.curve, {.entries = 101, .supersample = 10});
  ASSERT_TRUE(coarse && fine);
  EXPECT_EQ(fine->build_evaluations(), 1001);
  const double e1 = exact - coarse->length(), e10 = exact - fine->length();
  EXPECT_GT(e1, 0.0);  // a polygon inscribed in a curve is never longer than the curve
  EXPECT_GT(e10, 0.0);
  // Chord error is O(h²): ten times as many chords gives ~1/100 of the error (between 1/80 and 1/120).
  EXPECT_GT(e1 / e10, 80.0);
  EXPECT_LT(e1 / e10, 120.0);
}

TEST(AdaptiveForwardDifference, ErrorShrinksWithToleranceAndAdaptsToTheCurve) {
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(ex.name);
    // The line that doubles back is the Figure 3.7 trap: see the next test.
    if (ex.name.find("doubles back") != std::string::npos) continue;
    double previous = 1e300;
    for (double tol : {1e-3, 1e-5, 1e-7}) {
      auto t = adaptive_forward_difference_table(ex.curve, {.tolerance = tol});
      ASSERT_TRUE(t) << t.error().describe();
      const auto acc = measure_arc_length_accuracy(ex.curve, *t, 33);
      EXPECT_TRUE(std::isfinite(acc.worst_relative()));
      // Measured: the length error stays below 2·ε on these exhibits (the accepted half-chords are
      // about 4× better than the chord test that accepted them).
      EXPECT_LE(acc.length_error, 2 * tol);
      EXPECT_LE(acc.length_error, previous + 1e-15);
      previous = acc.length_error;
    }
  }
}

TEST(AdaptiveForwardDifference, TheFigure37TrapAndTheForcedDepthThatAvoidsIt) {
  // On a straight line that doubles back, any piece whose two ends and midpoint lie in order along
  // the line gives chord = half-chords exactly, whatever the tolerance, although the curve
  // overshoots between the samples (texts 004 Figure 3.7).  Only the forced depth bounds the loss:
  // the missed overshoot is quadratic in the piece width, so 3 more forced levels cut it by ~64.
  const auto ex = test::museum_arc_length_exhibit<double>("straight line, doubles back");
  auto shallow = adaptive_forward_difference_table(ex.curve, {.tolerance = 1e-7, .min_depth = 3});
  auto deep = adaptive_forward_difference_table(ex.curve, {.tolerance = 1e-7, .min_depth = 6});
  ASSERT_TRUE(shallow && deep);
  const double L = reference_length(ex.curve, 0.0, 1.0);
  const double e3 = L - shallow->length(), e6 = L - deep->length();
  EXPECT_GT(e3, 1e-3);  // measured 0.019: an overshoot is missed outright
  EXPECT_GT(e6, 0.0);
  EXPECT_LT(e6, e3 / 50);  // measured 2.4e-5
}

TEST(AdaptiveForwardDifference, PlacesRowsWhereTheCurveBendsNotWhereItIsFast) {
  // "Fast middle" runs nearly straight and fast through the middle and bends slowly at both ends:
  // the chord test puts its rows at the bends.
  const auto ex = test::museum_arc_length_exhibit<double>("fast middle");
  auto t = adaptive_forward_difference_table(ex.curve, {.tolerance = 1e-6});
  ASSERT_TRUE(t);
  int middle = 0, ends = 0;
  for (double u : t->u_values()) {
    if (std::fabs(u - 0.5) < 0.125) ++middle;
    if (u < 0.125 || u > 0.875) ++ends;
  }
  EXPECT_GT(ends, 2 * middle);
  EXPECT_FALSE(adaptive_forward_difference_table(ex.curve, {.tolerance = 0}));
  EXPECT_FALSE(adaptive_forward_difference_table(ex.curve, {.tolerance = 1e-3, .min_depth = 5, .max_depth = 2}));
}

TEST(AdaptiveGaussTable, MeetsItsToleranceOnEveryExhibit) {
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(ex.name);
    for (int order : {5, 10}) {
      auto t = adaptive_gauss_table(ex.curve, {.tolerance = 1e-8, .order = order, .min_depth = 1});
      ASSERT_TRUE(t) << t.error().describe();
      const auto acc = measure_arc_length_accuracy(ex.curve, *t, 33);
      EXPECT_LE(acc.length_error, 1e-8);  // the table's own rows are quadrature-accurate
      EXPECT_TRUE(std::isfinite(acc.max_u_error));
    }
  }
  EXPECT_FALSE(adaptive_gauss_table(test::quarter_circle_bezier<double>(), {.tolerance = 1e-8, .order = 0}));
}

}  // namespace
}  // namespace inbetween
