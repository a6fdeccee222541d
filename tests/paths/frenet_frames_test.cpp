// Frenet frames (texts 004 §3.4.2, Eq. 3.32) and the repair of straight pieces (Fig. 3.33).
#include "inbetween/paths/frenet_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "inbetween/curves/catmull_rom.hpp"
#include "paths_test_curves.hpp"
#include "support/museum_paths.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
void expect_vec_near(const Vec3<T>& a, const Vec3<T>& b, T tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

template <class T>
void expect_orthonormal(const PathFrame<T>& f, T tol) {
  ASSERT_TRUE(is_finite(f.tangent) && is_finite(f.normal) && is_finite(f.binormal));
  EXPECT_NEAR(norm(f.tangent), T(1), tol);
  EXPECT_NEAR(norm(f.normal), T(1), tol);
  EXPECT_NEAR(dot(f.tangent, f.normal), T(0), tol);
  expect_vec_near(cross(f.tangent, f.normal), f.binormal, tol);
}

template <class T>
class FrenetTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(FrenetTyped, Scalars);

// A few rotations and sqrt/atan2 evaluations of unit vectors: roundtrip_tol (tolerances.hpp).
TYPED_TEST(FrenetTyped, HelixMatchesClosedForm) {
  using T = TypeParam;
  const T tol = T(16) * test::roundtrip_tol<T>;
  Helix<T> h;
  // Closed form for P = (a cos u, a sin u, b u): T = (−a sin u, a cos u, b)/√(a²+b²),
  // N = (−cos u, −sin u, 0), B = T × N = (b sin u, −b cos u, a)/√(a²+b²).
  const T c = std::sqrt(h.radius * h.radius + h.rise * h.rise);
  for (T u : {T(0), T(0.3), T(1.7), T(4), T(10)}) {
    SCOPED_TRACE(u);
    const FrenetSample<T> f = frenet_frame(h, u);
    ASSERT_TRUE(f.defined);
    expect_vec_near(f.frame.tangent, Vec3<T>{-h.radius * std::sin(u), h.radius * std::cos(u), h.rise} / c, tol);
    expect_vec_near(f.frame.normal, Vec3<T>{-std::cos(u), -std::sin(u), T(0)}, tol);
    expect_vec_near(f.frame.binormal, Vec3<T>{h.rise * std::sin(u), -h.rise * std::cos(u), h.radius} / c, tol);
    // Texts' left-handed (u, v, w) = (binormal, normal, tangent): u × v = −w.
    expect_vec_near(cross(f.frame.binormal, f.frame.normal), -f.frame.tangent, tol);
  }
}

TYPED_TEST(FrenetTyped, StraightMiddleIsInterpolatedFromTheBoundaryFrames) {
  using T = TypeParam;
  const T tol = T(16) * test::roundtrip_tol<T>;
  auto built = build_frenet_frames(test::ArcLineArc<T>{});
  ASSERT_TRUE(built) << built.error().describe();
  const auto& ff = *built;
  // Exactly one straight piece, located by bisection at the segment joints u = 1 and u = 2.
  ASSERT_EQ(ff.straight_pieces().size(), 1u);
  const auto& piece = ff.straight_pieces()[0];
  EXPECT_NEAR(piece.u_begin, T(1), tol);
  EXPECT_NEAR(piece.u_end, T(2), tol);
  ASSERT_TRUE(piece.has_begin && piece.has_end);
  // Boundary normals: +y (centre of the first arc), −z (centre of the second): a −90° turn about +x.
  const T r = std::sqrt(T(0.5));
  // First arc at u = 0.5 (φ = −π/4): N = (−sin φ, cos φ, 0), T = (cos φ, sin φ, 0).
  const PathFrame<T> a = ff.frame_at(T(0.5));
  expect_vec_near(a.normal, Vec3<T>{r, r, 0}, tol);
  expect_vec_near(a.tangent, Vec3<T>{r, -r, 0}, tol);
  // Straight piece: the normal turns linearly in u from +y (u = 1) to −z (u = 2) about +x.
  for (T u : {T(1.25), T(1.5), T(1.75)}) {
    SCOPED_TRACE(u);
    const T angle = -(pi_v<T> / 2) * (u - T(1));
    const PathFrame<T> f = ff.frame_at(u);
    expect_orthonormal(f, tol);
    expect_vec_near(f.tangent, Vec3<T>{1, 0, 0}, tol);
    expect_vec_near(f.normal, Vec3<T>{0, std::cos(angle), std::sin(angle)}, tol);
  }
  // Second arc at u = 2.5 (φ = π/4): N = (−sin φ, 0, −cos φ) towards the centre (π/2, 0, −1).
  expect_vec_near(ff.frame_at(T(2.5)).normal, Vec3<T>{-r, 0, -r}, tol);
}

TEST(Frenet, RawFrameIsUndefinedOnTheStraightPiece) {
  // The raw Eq. 3.32 frame: P″ = 0 on u ∈ (1, 2), so u = P′ × P″ = 0 there.
  EXPECT_FALSE(frenet_frame(test::ArcLineArc<double>{}, 1.5).defined);
  EXPECT_TRUE(frenet_frame(test::ArcLineArc<double>{}, 0.5).defined);
}

TEST(Frenet, BadOptionsAreNamed) {
  auto a = build_frenet_frames(Helix<double>{}, {.samples_per_segment = 0});
  ASSERT_FALSE(a);
  EXPECT_EQ(a.error().place(), "samples_per_segment");
  auto b = build_frenet_frames(Helix<double>{}, {.tolerance = -1.0});
  ASSERT_FALSE(b);
  EXPECT_EQ(b.error().place(), "tolerance");
}

// Museum: every degenerate polyline that builds a curve gives finite orthonormal frames.
TYPED_TEST(FrenetTyped, MuseumFramesAreFiniteAndOrthonormal) {
  using T = TypeParam;
  const T tol = T(16) * test::roundtrip_tol<T>;
  for (const auto& ex : test::museum_paths<T>()) {
    SCOPED_TRACE(ex.name);
    auto curve = build_catmull_rom(ex.points);
    if (!curve) {
      EXPECT_LT(ex.points.size(), 2u) << curve.error().describe();  // only the single point fails
      continue;
    }
    auto ff = build_frenet_frames(*curve);
    ASSERT_TRUE(ff);
    const auto dom = curve->domain();
    for (int k = 0; k <= 40; ++k) {
      const T u = dom.lo + dom.length() * T(k) / T(40);
      expect_orthonormal(ff->frame_at(u), tol);
    }
  }
}

TEST(Frenet, StraightEverywhereUsesTheDocumentedStandIn) {
  const std::vector<Vec3d> pts{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  auto curve = build_catmull_rom(pts);
  ASSERT_TRUE(curve);
  auto ff = build_frenet_frames(*curve);
  ASSERT_TRUE(ff);
  ASSERT_EQ(ff->straight_pieces().size(), 1u);
  EXPECT_FALSE(ff->straight_pieces()[0].has_begin);
  EXPECT_FALSE(ff->straight_pieces()[0].has_end);
  // any_perpendicular((1,1,1)/√3) crosses with x: (0, 1, −1)/√2.
  const Vec3d n = ff->frame_at(0.7).normal;
  const double r = std::sqrt(0.5);
  expect_vec_near(n, Vec3d{0, r, -r}, 1e-12);
}

}  // namespace
}  // namespace inbetween
