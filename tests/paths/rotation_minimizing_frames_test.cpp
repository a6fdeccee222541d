// Rotation-minimising frames by double reflection (Wang et al. 2008).
#include "inbetween/paths/rotation_minimizing_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "inbetween/curves/catmull_rom.hpp"
#include "paths_test_curves.hpp"
#include "support/museum_paths.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
class RmfTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(RmfTyped, Scalars);

// Helix with a = 1, b = 1/2: torsion τ = b/(a² + b²) = 0.4, speed √1.25.  An RMF normal r written
// as cos θ N + sin θ B has r′ ∥ T only if θ′(s) = −τ (from the Frenet–Serret equations), so
// starting at r = N the RMF normal is N rotated by θ = −τ s about T — a closed form.
TEST(Rmf, HelixNormalTurnsAgainstTheTorsion) {
  Helix<double> h;
  auto rmf = build_rotation_minimizing_frames(h, {.samples_per_segment = 32});
  ASSERT_TRUE(rmf);
  const double tau = 0.4, speed = std::sqrt(1.25);
  // Double reflection has global error O(h⁴).  Measured over two turns (u step 0.0371): 1.85e-6
  // with 8 samples per segment, 7.2e-9 with 32 — the factor 256 of fourth order.  The bound is
  // the 8-sample figure divided by 4⁴ = 256, rounded up.
  constexpr double kAngleTol = 1e-8;
  for (double u : {0.0, 0.5, 3.0, 7.3, 12.0, 4 * pi_v<double>}) {
    SCOPED_TRACE(u);
    const PathFrame<double> f = rmf->frame_at(u);
    const FrenetSample<double> fr = frenet_frame(h, u);
    const double theta = signed_angle_about(fr.frame.normal, f.normal, f.tangent);
    EXPECT_NEAR(wrap_angle(theta + tau * speed * u), 0.0, kAngleTol);
  }
}

// Zero twist: the frame's angular velocity ω satisfies dN/ds = ω × N, and ω·T = (dN/ds)·B.  For the
// RMF that is 0; for the Frenet frame it is the torsion 0.4 (closed form above).  Central
// differences with step δ = 1e-4 have truncation error O(δ²) ≈ 1e-8 times the third derivative.
TEST(Rmf, HasNoTwistWhereFrenetTwistsByTheTorsion) {
  Helix<double> h;
  auto rmf = build_rotation_minimizing_frames(h);
  ASSERT_TRUE(rmf);
  const double speed = std::sqrt(1.25), delta = 1e-4;
  // O(δ²) ≈ 1e-8 differencing error times |N‴| ≲ 1, plus the method's own twist (measured at most
  // 2.9e-9 over two turns with the default 32 samples per segment).
  constexpr double kTwistTol = 1e-8;
  for (double u = 0.3; u < 12.0; u += 0.77) {
    SCOPED_TRACE(u);
    const PathFrame<double> f = rmf->frame_at(u);
    const Vec3d dn = (rmf->frame_at(u + delta).normal - rmf->frame_at(u - delta).normal) / (2 * delta * speed);
    EXPECT_NEAR(dot(dn, f.binormal), 0.0, kTwistTol);
    const Vec3d dnf = (frenet_frame(h, u + delta).frame.normal - frenet_frame(h, u - delta).frame.normal) /
                      (2 * delta * speed);
    EXPECT_NEAR(dot(dnf, frenet_frame(h, u).frame.binormal), 0.4, kTwistTol);
  }
}

// Fourth-order convergence tells the double reflection method apart from the cheaper projection
// method (drop the second reflection; third order in angle): halving h must divide the largest
// normal-angle error by about 2⁴ = 16.  Measured 16.0 from 4 to 8 samples per segment (projection
// alone: 7.8).
TEST(Rmf, ErrorConvergesAtFourthOrder) {
  Helix<double> h;
  auto max_error = [&](int samples) {
    auto rmf = build_rotation_minimizing_frames(h, {.samples_per_segment = samples});
    double e = 0;
    for (double u = 0.01; u < 4 * pi_v<double>; u += 0.0371) {
      const PathFrame<double> f = rmf->frame_at(u);
      const double theta = signed_angle_about(frenet_frame(h, u).frame.normal, f.normal, f.tangent);
      e = std::max(e, std::abs(wrap_angle(theta + 0.4 * std::sqrt(1.25) * u)));
    }
    return e;
  };
  const double ratio = max_error(4) / max_error(8);
  EXPECT_GT(ratio, 13.0);
  EXPECT_LT(ratio, 19.0);
}

// On a planar curve the binormal of an RMF started in the plane stays the plane normal, so the
// normal equals the Frenet normal up to sign (the sign flips at inflections).
TYPED_TEST(RmfTyped, PlanarCurveMatchesFrenetUpToSign) {
  using T = TypeParam;
  const T tol = T(64) * test::roundtrip_tol<T>;
  const std::vector<Vec3<T>> pts{{0, 0, 0}, {1, 2, 0}, {2, -1, 0}, {3, 1, 0}, {5, 0, 0}};
  auto curve = build_catmull_rom(pts, {.alpha = T(0.5)});
  ASSERT_TRUE(curve);
  auto rmf = build_rotation_minimizing_frames(*curve);
  ASSERT_TRUE(rmf);
  const auto dom = curve->domain();
  int compared = 0;
  for (int k = 0; k <= 100; ++k) {
    const T u = dom.lo + dom.length() * T(k) / T(100);
    const FrenetSample<T> fr = frenet_frame(*curve, u, T(1e-3));
    if (!fr.defined) continue;
    ++compared;
    const PathFrame<T> f = rmf->frame_at(u);
    EXPECT_NEAR(std::abs(dot(f.normal, fr.frame.normal)), T(1), tol) << "u=" << u;
    EXPECT_NEAR(std::abs(f.binormal.z), T(1), tol) << "u=" << u;
  }
  EXPECT_GT(compared, 80);
}

TEST(Rmf, InitialNormalIsProjectedOffTheTangent) {
  Helix<double> h;
  // At u = 0 the tangent is (0, 1, 0.5)/√1.25; (0, 0, 1) minus its tangent part, normalised, is
  // (0, −0.5, 1)/√1.25.
  auto rmf = build_rotation_minimizing_frames(h, {.initial_normal = Vec3d{0, 0, 1}});
  ASSERT_TRUE(rmf);
  const Vec3d n = rmf->frame_at(0.0).normal;
  const double c = std::sqrt(1.25);
  EXPECT_NEAR(n.x, 0.0, 1e-15);
  EXPECT_NEAR(n.y, -0.5 / c, 1e-15);
  EXPECT_NEAR(n.z, 1.0 / c, 1e-15);
  auto bad = build_rotation_minimizing_frames(h, {.initial_normal = Vec3d{std::nan(""), 0, 0}});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().place(), "initial_normal");
}

// Straight middle: the RMF does not turn at all there (no rotation needed); the Frenet repair turns.
TEST(Rmf, StraightMiddleKeepsTheNormal) {
  auto rmf = build_rotation_minimizing_frames(test::ArcLineArc<double>{});
  ASSERT_TRUE(rmf);
  const Vec3d a = rmf->frame_at(1.0).normal, b = rmf->frame_at(2.0).normal;
  EXPECT_NEAR(distance(a, b), 0.0, 1e-12);  // a straight line is a pure translation of the frame
  // In the xy plane (first arc) the RMF normal stays in the plane: it is the Frenet normal +y.
  EXPECT_NEAR(a.y, 1.0, 1e-9);
}

// Museum: finite orthonormal frames for every degenerate curve; random initial normals.
TYPED_TEST(RmfTyped, MuseumFramesAreFiniteAndOrthonormal) {
  using T = TypeParam;
  const T tol = T(16) * test::roundtrip_tol<T>;
  test::Random rng(test::seed_for(41));
  SCOPED_TRACE(rng.trace());
  for (const auto& ex : test::museum_paths<T>()) {
    SCOPED_TRACE(ex.name);
    auto curve = build_catmull_rom(ex.points);
    if (!curve) {
      EXPECT_LT(ex.points.size(), 2u) << curve.error().describe();  // only the single point has no curve
      continue;
    }
    auto rmf = build_rotation_minimizing_frames(*curve, {.initial_normal = rng.unit_vec3<T>()});
    ASSERT_TRUE(rmf);
    const auto dom = curve->domain();
    for (int k = 0; k <= 40; ++k) {
      const PathFrame<T> f = rmf->frame_at(dom.lo + dom.length() * T(k) / T(40));
      ASSERT_TRUE(is_finite(f.tangent) && is_finite(f.normal) && is_finite(f.binormal));
      EXPECT_NEAR(norm(f.normal), T(1), tol);
      EXPECT_NEAR(dot(f.normal, f.tangent), T(0), tol);
      EXPECT_NEAR(determinant(f.matrix()), T(1), tol);
    }
  }
}

// ---- closed curves: the closing twist distributed linearly in arc length.

// The plain RMF's closing angle on the trefoil is its holonomy: with θ′ = −τ (above), the end
// normal is the start normal turned by −∫τ ds, so the angle from end to start is wrap(∫τ ds).
// The total torsion is integrated here independently (composite Simpson on 20000 panels of
// τ|P′| = (P′ × P″)·P‴ / |P′ × P″|² · |P′|... in u, closed-form derivatives).
double trefoil_total_torsion() {
  test::Trefoil<double> k;
  const int n = 20000;
  const double a = 0, b = 2 * pi_v<double>, h = (b - a) / n;
  auto f = [&](double u) {
    const Vec3d d1 = k.derivative(u, 1), d2 = k.derivative(u, 2), d3 = k.derivative(u, 3);
    const Vec3d c = cross(d1, d2);
    return dot(c, d3) / dot(c, c) * norm(d1);
  };
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
  return sum * h / 3;
}

// Double reflection's angle error is O(h⁴) (ErrorConvergesAtFourthOrder); on the trefoil with the
// default 32 samples per piece the closing angle (2.2250406390) agrees with the holonomy
// (2.2250406424) to 3.4e-9 (measured); the bound is that rounded up to 1e-8.
constexpr double kClosingAngleTol = 1e-8;

TEST(RmfClosed, PlainClosingAngleIsTheTrefoilsTotalTorsion) {
  auto plain = build_rotation_minimizing_frames(test::Trefoil<double>{}, {.closing = RmfClosing::none});
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->closing_twist_rate(), 0.0);
  const PathFrame<double> f0 = plain->frame_at(0), f1 = plain->frame_at(2 * pi_v<double>);
  const double phi = signed_angle_about(f1.normal, f0.normal, f0.tangent);
  const double expected = wrap_angle(trefoil_total_torsion());
  EXPECT_GT(std::abs(expected), 0.1);  // a real twist to distribute
  EXPECT_NEAR(wrap_angle(phi - expected), 0.0, kClosingAngleTol);
  // automatic distributes exactly that angle over the length.
  auto closed = build_rotation_minimizing_frames(test::Trefoil<double>{});
  ASSERT_TRUE(closed);
  EXPECT_NEAR(wrap_angle(closed->closing_twist_rate() * closed->length() - expected), 0.0, kClosingAngleTol);
}

template <class T>
class RmfClosedTyped : public ::testing::Test {};
TYPED_TEST_SUITE(RmfClosedTyped, Scalars);

// The frame at the end equals the frame at the start (automatic on closed curves), and the twist
// rate ω·T = (dN/ds)·B is the constant φ/L everywhere (central differences, as in
// HasNoTwistWhereFrenetTwistsByTheTorsion).
TYPED_TEST(RmfClosedTyped, EndFrameMatchesStartAndTwistRateIsConstant) {
  using T = TypeParam;
  // End = start: the closing rotation is applied exactly (cos/sin of φ, a few roundings of unit
  // vectors) — roundtrip_tol; measured ≤ 3.3e-16 (double) and 2.3e-7 (float).
  const T frame_tol = test::roundtrip_tol<T>;
  auto check = [&](const auto& curve, const char* name) {
    SCOPED_TRACE(name);
    auto rmf = build_rotation_minimizing_frames(curve);
    ASSERT_TRUE(rmf) << rmf.error().describe();
    const T hi = curve.domain().hi;
    const PathFrame<T> f0 = rmf->frame_at(T(0)), f1 = rmf->frame_at(hi);
    EXPECT_LE(norm(f1.tangent - f0.tangent), frame_tol);
    EXPECT_LE(norm(f1.normal - f0.normal), frame_tol);
    EXPECT_LE(norm(f1.binormal - f0.binormal), frame_tol);
    if constexpr (std::is_same_v<T, double>) {
      // δ = 1e-4: O(δ²) differencing error plus the RMF's own twist error; measured at most 5.5e-9
      // (trefoil, rate 0.0772 per length unit) and 5.2e-13 (circle); bound 5e-8.
      const double delta = 1e-4, rate = rmf->closing_twist_rate();
      for (double u = 0.05; u < hi - 0.05; u += 0.137) {
        const PathFrame<double> f = rmf->frame_at(u);
        const double speed = norm(curve.derivative(u, 1));
        const Vec3d dn = (rmf->frame_at(u + delta).normal - rmf->frame_at(u - delta).normal) / (2 * delta * speed);
        EXPECT_NEAR(dot(dn, f.binormal), rate, 5e-8) << "u = " << u;
      }
    }
  };
  check(test::Trefoil<T>{}, "trefoil");
  check(test::TiltedCircle<T>{}, "circle");
  // A planar circle has no holonomy: nothing to distribute (up to the method's error).
  auto circle = build_rotation_minimizing_frames(test::TiltedCircle<T>{});
  ASSERT_TRUE(circle);
  // Measured 9.1e-16 (double), 5.3e-7 (float: rounding over 257 steps).
  const T circle_tol = std::is_same_v<T, float> ? test::roundtrip_tol<T> : T(kClosingAngleTol);
  EXPECT_NEAR(circle->closing_twist_rate() * circle->length(), T(0), circle_tol);
}

TEST(RmfClosed, OpenCurvesAreLeftAloneAndDistributeNeedsAClosedCurve) {
  Helix<double> h;  // two turns with pitch: open
  auto automatic = build_rotation_minimizing_frames(h);
  auto none = build_rotation_minimizing_frames(h, {.closing = RmfClosing::none});
  ASSERT_TRUE(automatic && none);
  EXPECT_EQ(automatic->closing_twist_rate(), 0.0);
  for (double u : {0.0, 1.0, 7.0, 4 * pi_v<double>}) EXPECT_EQ(automatic->frame_at(u).normal, none->frame_at(u).normal);
  auto forced = build_rotation_minimizing_frames(h, {.closing = RmfClosing::distribute});
  ASSERT_FALSE(forced);
  EXPECT_EQ(forced.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(forced.error().place(), "closing");
}

}  // namespace
}  // namespace inbetween
