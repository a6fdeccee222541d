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
  EXPECT_EQ(bad.error().where, "initial_normal");
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

}  // namespace
}  // namespace inbetween
