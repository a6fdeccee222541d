// The closed-form helix: derivatives agree with central differences, and curvature and torsion
// computed from the derivatives equal the closed forms r/(r² + c²) and c/(r² + c²).
#include <gtest/gtest.h>

#include <cmath>

#include "inbetween/curves/helix.hpp"

namespace inbetween {
namespace {

static_assert(Curve<Helix<double>>);
static_assert(Curve<Helix<float>>);

TEST(Helix, DerivativesAgreeWithCentralDifferences) {
  const Helix<double> h{.radius = 2, .rise = 0.3, .u_begin = -1, .u_end = 9, .segments = 4};
  // Central difference error is O(step²)·|P'''| ≈ 1e-8 for step 1e-4; rounding ~1e-16/1e-4.
  const double step = 1e-4, tol = 1e-7;
  for (double u = -0.5; u < 8.5; u += 0.37) {
    for (int k = 1; k <= 3; ++k) {
      const Vec3d fd = (h.derivative(u + step, k - 1) - h.derivative(u - step, k - 1)) / (2 * step);
      const Vec3d d = h.derivative(u, k);
      EXPECT_NEAR(d.x, fd.x, tol) << "u=" << u << " k=" << k;
      EXPECT_NEAR(d.y, fd.y, tol);
      EXPECT_NEAR(d.z, fd.z, tol);
    }
  }
}

TEST(Helix, CurvatureAndTorsionMatchTheClosedForm) {
  const Helix<double> h{.radius = 1.5, .rise = 0.4};
  const double denom = 1.5 * 1.5 + 0.4 * 0.4;
  for (double u = 0.1; u < 12; u += 1.3) {
    const Vec3d d1 = h.derivative(u, 1), d2 = h.derivative(u, 2), d3 = h.derivative(u, 3);
    const Vec3d c = cross(d1, d2);
    // κ = |P' × P''|/|P'|³, τ = (P' × P'')·P'''/|P' × P''|² (standard Frenet–Serret formulas).
    EXPECT_NEAR(norm(c) / std::pow(norm(d1), 3), 1.5 / denom, 1e-14);
    EXPECT_NEAR(dot(c, d3) / squared_norm(c), 0.4 / denom, 1e-14);
  }
  // Segments tile the domain exactly.
  EXPECT_EQ(h.segment_domain(0).lo, h.u_begin);
  EXPECT_EQ(h.segment_domain(h.segment_count() - 1).hi, h.u_end);
  // Parameters are clamped.
  EXPECT_EQ(h.point(-1.0), h.point(0.0));
}

}  // namespace
}  // namespace inbetween
