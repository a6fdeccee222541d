// Banking into turns (texts 004 §3.4.2): closed forms on a circle and a line.
#include "inbetween/paths/banking.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "inbetween/curves/catmull_rom.hpp"
#include "paths_test_curves.hpp"
#include "support/museum_paths.hpp"

namespace inbetween {
namespace {

// Circle of radius R in the ground plane, P(u) = (R cos u, 0, −R sin u): at u = 0 it is at (R, 0, 0)
// heading −z, and the centre (the origin) lies to the left (left = up × T = y × (−z) = −x).
struct GroundCircle {
  using point_type = Vec3d;
  using scalar_type = double;
  double r = 2;
  Interval<double> domain() const noexcept { return {0, 2 * pi_v<double>}; }
  int segment_count() const noexcept { return 1; }
  Interval<double> segment_domain(int) const noexcept { return domain(); }
  Vec3d point(double u) const noexcept { return derivative(u, 0); }
  Vec3d derivative(double u, int k) const noexcept {
    const double c = std::cos(u), s = std::sin(u);
    switch (k) {
      case 0: return {r * c, 0, -r * s};
      case 1: return {-r * s, 0, -r * c};
      case 2: return {-r * c, 0, r * s};
      default: return {r * s, 0, r * c};
    }
  }
};

TEST(Banking, CoordinatedTurnOnACircle) {
  // Speed v = 3, g = 9.81, R = 2: tan β = v²/(gR) (coordinated turn), lateral curvature 1/R.
  const double v = 3, g = 9.81, R = 2;
  const double beta = std::atan(v * v / (g * R));
  const Banking<double> b = banking(GroundCircle{R}, 0.0, {.gain = v * v / g});
  EXPECT_NEAR(b.lateral_curvature, 1 / R, 1e-15);
  EXPECT_NEAR(b.bank_rad, beta, 1e-15);
  // Up rolls towards the centre (−x): (−sin β, cos β, 0).
  EXPECT_NEAR(b.frame.normal.x, -std::sin(beta), 1e-15);
  EXPECT_NEAR(b.frame.normal.y, std::cos(beta), 1e-15);
  EXPECT_NEAR(b.frame.normal.z, 0.0, 1e-15);
  EXPECT_NEAR(determinant(b.frame.matrix()), 1.0, 1e-15);
  // Negative gain leans out of the turn; the clamp holds the largest angle.
  EXPECT_NEAR(banking(GroundCircle{R}, 0.0, {.gain = -v * v / g}).bank_rad, -beta, 1e-15);
  EXPECT_NEAR(banking(GroundCircle{R}, 0.0, {.gain = 1e6, .max_bank_rad = 0.5}).bank_rad, 0.5, 0.0);
}

// Issue 9, defect 7b: banking on a curve at subnormal scale returned NaN (25 of 1880 calls in the
// issue's sweep): |P'|² underflows while P″/|P'|² overflows.  Closed form for the scale: the curve
// λ·C with gain λ·g banks exactly like C with gain g (curvature scales as 1/λ, gain·curvature is
// invariant), and its lateral curvature is 1/(λR) (±inf only where that exceeds double).  The
// comparison allows for the precision a subnormal coordinate still has (denorm_min / |coordinate|).
TEST(Banking, ScaleInvariantDownToSubnormalAndUpToHugeCurves) {
  const double R = 2, g = 0.7;
  int calls = 0, nan_fields = 0;
  double worst = 0;
  for (const double lambda : {1.0, 1e-150, 1e-300, 1e-308, 1e-310, 1e-315, 1e-320, 1e150, 1e300, 1e307}) {
    SCOPED_TRACE(lambda);
    const GroundCircle small{R * lambda};
    for (int i = 0; i < 64; ++i) {
      const double u = 2 * pi_v<double> * (i + 0.5) / 64;
      const Banking<double> ref = banking(GroundCircle{R}, u, {.gain = g});
      const Banking<double> b = banking(small, u, {.gain = g * lambda});
      ++calls;
      const double fields[] = {b.lateral_curvature, b.bank_rad, b.frame.tangent.x, b.frame.tangent.y,
                               b.frame.tangent.z, b.frame.normal.x, b.frame.normal.y, b.frame.normal.z,
                               b.frame.binormal.x, b.frame.binormal.y, b.frame.binormal.z};
      bool any_nan = false;
      for (double f : fields) any_nan = any_nan || std::isnan(f);
      if (any_nan) ++nan_fields;
      EXPECT_FALSE(any_nan) << "u = " << u;
      // Relative precision of the smallest coordinate that matters (|cos u|, |sin u| ≥ sin(π/64)).
      const double coord = R * lambda * std::sin(pi_v<double> / 64);
      const double tol = std::fmax(1e-14, 64 * std::numeric_limits<double>::denorm_min() / coord);
      EXPECT_NEAR(b.bank_rad, ref.bank_rad, tol) << "u = " << u;
      if (!std::isnan(b.bank_rad)) worst = std::fmax(worst, std::fabs(b.bank_rad - ref.bank_rad) / tol);
      const double expect_c = 1 / (R * lambda);
      if (std::isfinite(expect_c)) EXPECT_NEAR(b.lateral_curvature, expect_c, tol * expect_c) << "u = " << u;
      else EXPECT_EQ(b.lateral_curvature, expect_c) << "u = " << u;
    }
  }
  std::printf("[ measured ] banking at scales 1e-320 .. 1e307: %d calls, %d with a NaN field, worst bank error %.3g of its tolerance\n",
              calls, nan_fields, worst);
}

// P(u) = (ε u, u², 0) (climbing) or (ε u, 0, −u²) (turning left for +y up) near u = 0: |P'| = ε
// is tiny while P″ = 2 is not, so the curvature 2/ε² overflows for ε = 1e-160.
struct SlowParabola {
  using point_type = Vec3d;
  using scalar_type = double;
  double eps = 1;
  bool climbing = true;
  Interval<double> domain() const noexcept { return {-1, 1}; }
  int segment_count() const noexcept { return 1; }
  Interval<double> segment_domain(int) const noexcept { return domain(); }
  Vec3d point(double u) const noexcept { return derivative(u, 0); }
  Vec3d derivative(double u, int k) const noexcept {
    const double a = k == 0 ? u * u : (k == 1 ? 2 * u : (k == 2 ? 2 : 0));
    const double x = k == 0 ? eps * u : (k == 1 ? eps : 0);
    return climbing ? Vec3d{x, a, 0} : Vec3d{x, 0, -a};
  }
};

TEST(Banking, OverflowingCurvatureIsZeroWhenVerticalAndSaturatesWhenLateral) {
  // Closed forms at u = 0: tangent +x, left = y × x = −z.  Climbing: κN = (0, 2/ε², 0) is vertical,
  // lateral curvature 0, no bank (the old code gave inf·0 = NaN).  Turning: κN = (0, 0, −2/ε²),
  // lateral curvature +2/ε² → +inf past double, bank at the clamp π/3.
  for (const double eps : {1.0, 1e-100, 1e-160, 1e-170}) {
    SCOPED_TRACE(eps);
    const Banking<double> climb = banking(SlowParabola{eps, true}, 0.0, {.gain = 1});
    EXPECT_EQ(climb.lateral_curvature, 0.0);
    EXPECT_EQ(climb.bank_rad, 0.0);
    const Banking<double> turn = banking(SlowParabola{eps, false}, 0.0, {.gain = 1});
    EXPECT_EQ(turn.lateral_curvature, 2 / (eps * eps));
    EXPECT_NEAR(turn.bank_rad, std::fmin(std::atan(2 / (eps * eps)), pi_v<double> / 3), 1e-15);
  }
}

TEST(Banking, HorizontalTurnBanksLineAndVerticalTurnDoNot) {
  // ArcLineArc with up = +z: the first arc lies in the horizontal xy plane (radius 1), the middle is
  // straight, the second arc lies in the vertical xz plane.
  const test::ArcLineArc<double> c;
  const BankingOptions<double> up_z{.up = {0, 0, 1}, .gain = 1.0};
  // u = 0.5 (φ = −π/4): T = (√½, −√½, 0), κN = N = (√½, √½, 0), left = z × T = (√½, √½, 0):
  // lateral curvature +1 (a left turn), β = atan(1) = π/4.
  const Banking<double> first = banking(c, 0.5, up_z);
  EXPECT_NEAR(first.lateral_curvature, 1.0, 1e-14);
  EXPECT_NEAR(first.bank_rad, pi_v<double> / 4, 1e-14);
  EXPECT_EQ(banking(c, 1.5, up_z).bank_rad, 0.0);  // straight: κN = 0
  // u = 2.5 (φ = π/4): T = (√½, 0, −√½), left ∝ z × T = (0, √½, 0), κN = (−√½, 0, −√½): c = 0.
  EXPECT_NEAR(banking(c, 2.5, up_z).bank_rad, 0.0, 1e-15);
}

TEST(Banking, MuseumPathsAreFinite) {
  for (const auto& ex : test::museum_paths<double>()) {
    SCOPED_TRACE(ex.name);
    auto curve = build_catmull_rom(ex.points);
    if (!curve) {
      EXPECT_LT(ex.points.size(), 2u) << curve.error().describe();  // only the single point has no curve
      continue;
    }
    const auto dom = curve->domain();
    for (int k = 0; k <= 20; ++k) {
      const Banking<double> b = banking(*curve, dom.lo + dom.length() * k / 20.0, {.gain = 5.0});
      EXPECT_TRUE(std::isfinite(b.bank_rad));
      EXPECT_TRUE(is_finite(b.frame.normal) && is_finite(b.frame.binormal));
      EXPECT_NEAR(determinant(b.frame.matrix()), 1.0, 1e-12);
    }
  }
  // Travel straight up (tangent ∥ up): no horizontal plane, β = 0.
  const std::vector<Vec3d> vertical{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}};
  auto c = build_catmull_rom(vertical);
  ASSERT_TRUE(c);
  EXPECT_EQ(banking(*c, 0.5).bank_rad, 0.0);
}

}  // namespace
}  // namespace inbetween
