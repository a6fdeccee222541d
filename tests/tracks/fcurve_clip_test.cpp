// The F-curve runtime (runtime/fcurve_clip.hpp): seeded random Bézier/easing curves compiled into
// an FCurveClip agree with FCurve::sample (the scalar reference) to fcurve_runtime_tolerance of
// the value scale, forwards, backwards and with jumps; a rig of 10 curves per joint gives the
// normalised quaternion; what the runtime cannot sample is refused with its place.  Agreement on
// every recorded Blender case: tests/io/fcurve_clip_blender_test.cpp.
#include "inbetween/tracks/runtime/fcurve_clip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "support/random.hpp"

namespace inbetween {
namespace {

FCurve random_curve(test::Random& rng) {
  RawFCurve raw;
  raw.extrapolation = rng.integer(0, 1) ? Extrapolation::linear : Extrapolation::constant;
  double f = rng.uniform<double>(-10, 10);
  const int n = rng.integer(1, 8);
  for (int i = 0; i < n; ++i) {
    FCurveKey k;
    k.frame = f;
    k.value = rng.uniform<double>(-5, 5);
    k.interpolation = rng.integer(0, 3) == 0 ? Interpolation(rng.integer(0, 12)) : Interpolation::bezier;
    raw.keys.push_back(k);
    f += rng.uniform<double>(0.3, 6);
  }
  return build_fcurve(raw).value();
}

float scale_of(const FCurve& c) {
  float lo = c.keys()[0].y, hi = lo, big = std::abs(lo);
  for (const auto& k : c.keys())
    for (const float v : {k.y, k.left.y, k.right.y}) lo = std::min(lo, v), hi = std::max(hi, v), big = std::max(big, std::abs(v));
  const float s = std::max(hi - lo, 8.0f * std::numeric_limits<float>::epsilon() * big / FCurveClipOptions{}.tolerance);
  return s > 0 ? s : 1.0f;
}

TEST(FCurveClip, AgreesWithFCurveSampleOnRandomCurves) {
  test::Random rng(test::seed_for(1204));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (int i = 0; i < 40; ++i) curves.push_back(random_curve(rng));
  const auto clip = build_fcurve_clip(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  EXPECT_LE(clip->max_fit_error(), fcurve_runtime_tolerance);
  auto ctx = make_fcurve_context(*clip);
  std::vector<float> out(curves.size());
  std::vector<float> frames;
  for (float t = -15; t < 60; t += 0.037f) frames.push_back(t);
  for (float t = 60; t > -15; t -= 0.71f) frames.push_back(t);
  for (int i = 0; i < 200; ++i) frames.push_back(rng.uniform<float>(-20, 70));
  frames.push_back(std::numeric_limits<float>::quiet_NaN());  // reads as the first value
  double worst = 0;
  for (const float t : frames) {
    sample_fcurves(*clip, t, ctx, std::span<float>(out));
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const float ref = curves[c].sample(t);
      const double err = std::abs(double(out[c]) - ref) / scale_of(curves[c]);
      worst = std::max(worst, err);
      EXPECT_LE(err, fcurve_runtime_tolerance) << "curve " << c << " frame " << t;
    }
  }
  std::cout << "[ measured ] FCurveClip vs FCurve::sample on random curves: " << worst << " of the value scale, "
            << clip->pieces() << " pieces\n";
}

TEST(FCurveClip, AgreesAtBlendersSnapBandEdges) {
  // Blender answers a key's own value within 1e-4 frames of it (|t − x| ≤ 1e-4 in float); the
  // runtime folds those bands into its pieces (u clamped to ∓1), so the frames just inside and
  // just outside every band edge, and the keys themselves, are where a wrong band shows.
  test::Random rng(test::seed_for(1205));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (int i = 0; i < 40; ++i) curves.push_back(random_curve(rng));
  const auto clip = build_fcurve_clip(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  auto ctx = make_fcurve_context(*clip);
  std::vector<float> out(curves.size());
  double worst = 0;
  std::size_t probes = 0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (const auto& key : curves[c].keys()) {
      for (const double d : {-1e-4, 0.0, 1e-4}) {
        float t = float(double(key.x) + d);
        for (int s = 0; s < 3; ++s) t = std::nextafter(t, -INFINITY);
        for (int s = 0; s < 7; ++s, t = std::nextafter(t, INFINITY)) {
          sample_fcurves(*clip, t, ctx, std::span<float>(out));
          const double err = std::abs(double(out[c]) - curves[c].sample(t)) / scale_of(curves[c]);
          worst = std::max(worst, err);
          ++probes;
          EXPECT_LE(err, fcurve_runtime_tolerance) << "curve " << c << " frame " << t;
        }
      }
    }
  }
  std::cout << "[ measured ] FCurveClip at snap-band edges: " << worst << " of the value scale over " << probes
            << " frames\n";
}

TEST(FCurveClip, AutoClampedBezierSegmentsTakeOnePieceEach) {
  // The speed of the runtime rests on this (bench/RESULTS.md, the F-curve rig): Bézier keys with
  // Blender's default auto-clamped handles, 30 keys spaced uniformly in [0.5, 1.5] frames, values
  // in [−1, 1] as the benchmark rig's, fit one degree-9 piece per segment (the benchmark measured
  // exactly 31 pieces per curve, 29 segments and 2 extrapolation lines, on all 10240 curves).  A
  // tenth more is allowed for an unlucky seed; a fit of lower order needs 1.6–2.8× (degree 5–8).
  test::Random rng(test::seed_for(1206));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (int c = 0; c < 50; ++c) {
    RawFCurve raw;
    double f = 0;
    for (int i = 0; i < 30; ++i) {
      FCurveKey k;
      k.frame = f;
      k.value = rng.uniform<double>(-1, 1);
      raw.keys.push_back(k);
      f += rng.uniform<double>(0.5, 1.5);
    }
    curves.push_back(build_fcurve(raw).value());
  }
  const auto clip = build_fcurve_clip(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  const std::size_t one_each = curves.size() * 31;
  EXPECT_LE(clip->pieces(), one_each + one_each / 10);
  EXPECT_LE(clip->max_fit_error(), FCurveClipOptions{}.tolerance);
  std::cout << "[ measured ] auto-clamped rig curves: " << clip->pieces() << " pieces for " << one_each
            << " (one per segment), fit error " << clip->max_fit_error() << "\n";
}

TEST(FCurveClip, RigNormalisesTheQuaternion) {
  // One joint: location (1, 2, 3), quaternion curves (w, x, y, z) = (2, 0, 0, 2) → normalised
  // (√½, 0, 0, √½); scale (1, 1, 1).  Single-key curves: constant values (closed form).
  const double v[10] = {1, 2, 3, 2, 0, 0, 2, 1, 1, 1};
  std::vector<FCurve> curves;
  for (const double x : v) {
    RawFCurve raw;
    raw.keys.push_back(FCurveKey{.frame = 0, .value = x});
    curves.push_back(build_fcurve(raw).value());
  }
  const auto clip = build_fcurve_rig(curves);
  ASSERT_TRUE(clip);
  auto ctx = make_fcurve_context(*clip);
  std::vector<JointPose<float>> pose(1);
  sample_fcurve_rig(*clip, 5.0f, ctx, std::span<JointPose<float>>(pose));
  EXPECT_EQ(pose[0].translation.y, 2.0f);
  EXPECT_NEAR(pose[0].rotation.w, std::sqrt(0.5f), 1e-7f);
  EXPECT_NEAR(pose[0].rotation.z, std::sqrt(0.5f), 1e-7f);
  EXPECT_EQ(pose[0].rotation.x, 0.0f);
}

TEST(FCurveClip, RigChannelsAreTheCurvesInOrder) {
  // A 3-joint rig of random curves: sample_fcurves gives curve c at out[c], and each joint's pose
  // reads its own ten curves (translation = curves 10j..10j+2, scale = 10j+7..10j+9), against
  // FCurve::sample to fcurve_runtime_tolerance of each curve's value scale.
  test::Random rng(test::seed_for(1207));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (int i = 0; i < 30; ++i) curves.push_back(random_curve(rng));
  const auto clip = build_fcurve_rig(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  ASSERT_EQ(clip->joints(), 3u);
  auto ctx = make_fcurve_context(*clip);
  std::vector<float> out(curves.size());
  std::vector<JointPose<float>> pose(3);
  for (float t = -12; t < 50; t += 0.53f) {
    sample_fcurves(*clip, t, ctx, std::span<float>(out));
    for (std::size_t c = 0; c < curves.size(); ++c)
      EXPECT_LE(std::abs(out[c] - curves[c].sample(t)) / scale_of(curves[c]), fcurve_runtime_tolerance) << c << " " << t;
    sample_fcurve_rig(*clip, t, ctx, std::span<JointPose<float>>(pose));
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(pose[j].translation.x, out[10 * j]);
      EXPECT_EQ(pose[j].translation.z, out[10 * j + 2]);
      EXPECT_EQ(pose[j].scale.x, out[10 * j + 7]);
      EXPECT_EQ(pose[j].scale.z, out[10 * j + 9]);
    }
  }
}

TEST(FCurveClip, RefusesWhatItCannotSampleWithThePlace) {
  RawFCurve raw;
  raw.keys.push_back(FCurveKey{.frame = 0, .value = 0});
  raw.keys.push_back(FCurveKey{.frame = 4, .value = 1});
  const FCurve plain = build_fcurve(raw).value();
  raw.cycles = FCurveCycles{};
  const FCurve cycled = build_fcurve(raw).value();
  const std::vector<FCurve> curves{plain, cycled};
  const auto e = build_fcurve_clip(curves);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::Unsupported);
  EXPECT_EQ(json_pointer(e.error().location), "/curves/1");
  const auto r = build_fcurve_rig(std::vector<FCurve>(9, plain));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::InvalidArgument);
}

}  // namespace
}  // namespace inbetween
