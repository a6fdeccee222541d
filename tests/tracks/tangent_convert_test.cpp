// Bézier handles ↔ Hermite slopes (tracks/tangent_convert.hpp).  Sources: the identity of a cubic
// Bézier with control points at thirds and the Hermite form (docs/gltf.md); Blender's evaluation
// as reproduced by FCurve (tracks/fcurve.hpp) as the independent reference for bezier_value().
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/tangent_convert.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// Exact identities in double: a few dozen roundings of values of order 10.
constexpr double kIdentityTol = 1e-12;

TEST(TangentConvert, HermiteToBezierIsExact) {
  test::Random rng(test::seed_for(1101));
  SCOPED_TRACE(rng.trace());
  for (int round = 0; round < 200; ++round) {
    HermiteSegment h{rng.uniform(-5.0, 5.0), 0, rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0),
                     rng.uniform(-4.0, 4.0), rng.uniform(-4.0, 4.0)};
    h.frame1 = h.frame0 + rng.uniform(0.25, 20.0);
    const BezierSegment b = hermite_to_bezier(h);
    EXPECT_TRUE(handles_at_thirds(b));
    for (int i = 0; i <= 16; ++i) {
      const double f = h.frame0 + (h.frame1 - h.frame0) * i / 16.0;
      EXPECT_NEAR(bezier_value(b, f), hermite_value(h, f), kIdentityTol * 10);
    }
    // And back: the same slopes.
    const HermiteSegment back = bezier_to_hermite(b);
    EXPECT_NEAR(back.out_slope, h.out_slope, kIdentityTol * 10);
    EXPECT_NEAR(back.in_slope, h.in_slope, kIdentityTol * 10);
    EXPECT_LE(bezier_hermite_loss(b).max_error, kIdentityTol * 10);
  }
}

TEST(TangentConvert, BezierValueMatchesBlenderFCurve) {
  // FCurve evaluates in single precision as Blender does: agreement to a few float ulps of the
  // values (|v| ≤ 10: ulp 1e-6).
  constexpr double kFloatTol = 2e-5;
  test::Random rng(test::seed_for(1102));
  SCOPED_TRACE(rng.trace());
  for (int round = 0; round < 50; ++round) {
    const double x0 = 0, x1 = double(rng.integer(2, 30));
    const double y0 = rng.uniform(-5.0, 5.0), y1 = rng.uniform(-5.0, 5.0);
    BezierSegment b{{x0, y0}, {x0 + rng.uniform(0.0, 1.0) * (x1 - x0), rng.uniform(-8.0, 8.0)},
                    {x1 - rng.uniform(0.0, 1.0) * (x1 - x0), rng.uniform(-8.0, 8.0)}, {x1, y1}};
    RawFCurve raw;
    FCurveKey k0{.frame = x0, .value = y0, .handle_left_type = HandleType::free, .handle_right_type = HandleType::free,
                 .handle_left = Vec2d{x0 - 1, y0}, .handle_right = b.h0};
    FCurveKey k1{.frame = x1, .value = y1, .handle_left_type = HandleType::free, .handle_right_type = HandleType::free,
                 .handle_left = b.h1, .handle_right = Vec2d{x1 + 1, y1}};
    // Round the segment to float as the FCurve stores it.
    auto f = [](Vec2d v) { return Vec2d{double(float(v.x)), double(float(v.y))}; };
    b = {f(b.p0), f(b.h0), f(b.h1), f(b.p1)};
    k0.value = b.p0.y;
    k0.handle_right = b.h0;
    k1.value = b.p1.y;
    k1.handle_left = b.h1;
    raw.keys = {k0, k1};
    auto curve = build_fcurve(raw);
    ASSERT_TRUE(curve) << curve.error().describe();
    for (int i = 0; i <= 40; ++i) {
      const double frame = x0 + (x1 - x0) * i / 40.0;
      EXPECT_NEAR(bezier_value(b, frame), double(curve->sample(float(frame))), kFloatTol) << "frame " << frame;
    }
  }
}

TEST(TangentConvert, NonThirdHandlesLoseAndTheLossIsMeasured) {
  // An ease-in-out authored in Blender style: both handles flat, half the interval long (Blender's
  // default auto handles would be at thirds).  As a Hermite segment both slopes are 0, which is the
  // smoothstep 3u² − 2u³; the Bézier in time is steeper in the middle.
  const BezierSegment b{{0, 0}, {5, 0}, {5, 1}, {10, 1}};
  EXPECT_FALSE(handles_at_thirds(b));
  const ConversionLoss loss = bezier_hermite_loss(b);
  // Symmetric about the middle, equal at the ends and at the middle: the largest difference is
  // strictly inside each half.
  EXPECT_GT(loss.max_error, 1e-3);
  EXPECT_LT(loss.max_error, 0.2);
  std::printf("[ loss figure ] flat half-interval handles on a unit step over 10 frames: max %.6f at frame %.3f\n",
              loss.max_error, loss.at_frame);
  // Blender 3.4's correction: a handle longer than the interval is scaled back to its length,
  // along its own direction; a shorter one is kept.
  const BezierSegment over{{0, 0}, {12, 6}, {7, 1}, {10, 1}};
  const BezierSegment c = corrected(over);
  EXPECT_NEAR(c.h0.x, 10.0, kIdentityTol);
  EXPECT_NEAR(c.h0.y, 5.0, kIdentityTol);
  EXPECT_EQ(c.h1.x, 7.0);
}

TEST(TangentConvert, GltfTangentsAreSlopesTimesFps) {
  // glTF's CUBICSPLINE in seconds: p(t) = h00 v0 + h10 Δt b0 + h01 v1 + h11 Δt a1, with tangents
  // per second; the same segment in frames uses slopes per frame and Δframe = Δt·fps.
  const double fps = 24;
  const HermiteSegment frames{10, 34, 1.0, 3.0, 0.25, -0.5};
  const double dt = (frames.frame1 - frames.frame0) / fps;
  const double b0 = gltf_tangent_from_slope(frames.out_slope, fps), a1 = gltf_tangent_from_slope(frames.in_slope, fps);
  for (int i = 0; i <= 10; ++i) {
    const double u = i / 10.0, u2 = u * u, u3 = u2 * u;
    const double gltf = (2 * u3 - 3 * u2 + 1) * 1.0 + (u3 - 2 * u2 + u) * dt * b0 + (-2 * u3 + 3 * u2) * 3.0 + (u3 - u2) * dt * a1;
    EXPECT_NEAR(hermite_value(frames, frames.frame0 + u * (frames.frame1 - frames.frame0)), gltf, kIdentityTol);
  }
  EXPECT_DOUBLE_EQ(slope_from_gltf_tangent(b0, fps), frames.out_slope);
}

}  // namespace
}  // namespace inbetween
