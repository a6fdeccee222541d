// Banking into turns (texts 004 §3.4.2): closed forms on a circle and a line.
#include "inbetween/paths/banking.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
