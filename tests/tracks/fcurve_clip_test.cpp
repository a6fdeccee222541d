// The F-curve runtime (runtime/fcurve_clip.hpp): seeded random Bézier/easing curves compiled into
// an FCurveClip agree with FCurve::sample (the scalar reference) to fcurve_runtime_tolerance of
// the value scale, forwards, backwards and with jumps; a rig of 10 curves per joint gives the
// normalised quaternion; curves with a Cycles modifier (every mode, counts, cycle-aware handles)
// agree at cycle boundaries, far from the keys and on backward seeks.  Agreement on every recorded
// Blender case: tests/io/fcurve_clip_blender_test.cpp.
#include "inbetween/tracks/runtime/fcurve_clip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

#include "support/museum_tracks.hpp"
#include "support/random.hpp"

namespace inbetween {
namespace {

// min_keys … 8 seeded keys 0.3 … 6 frames apart, values in [−5, 5], a quarter of them with a
// random interpolation (the rest Bézier), auto-clamped handles.
RawFCurve random_raw_curve(test::Random& rng, Extrapolation extrapolation, int min_keys) {
  RawFCurve raw;
  raw.extrapolation = extrapolation;
  double f = rng.uniform<double>(-10, 10);
  const int n = rng.integer(min_keys, 8);
  for (int i = 0; i < n; ++i) {
    FCurveKey k;
    k.frame = f;
    k.value = rng.uniform<double>(-5, 5);
    k.interpolation = rng.integer(0, 3) == 0 ? Interpolation(rng.integer(0, 12)) : Interpolation::bezier;
    raw.keys.push_back(k);
    f += rng.uniform<double>(0.3, 6);
  }
  return raw;
}

FCurve random_curve(test::Random& rng) {
  const Extrapolation extrapolation = rng.integer(0, 1) ? Extrapolation::linear : Extrapolation::constant;
  return build_fcurve(random_raw_curve(rng, extrapolation, 1)).value();
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
  auto ctx = make_fcurve_clip_cursor(*clip);
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

// A looping playback (frames −15 … 60, then back to −15, three times) takes each seek back to
// the start by replaying the stream from its beginning, other seeks back by searching each
// channel's pieces; both must leave the cache as a fresh context's forward consumption does, so
// every value is bit-identical to a fresh context's at the same frame (an independent path:
// consumption from −∞).
TEST(FCurveClip, LoopingPlaybackMatchesAFreshContextBitForBit) {
  test::Random rng(test::seed_for(1213));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (int i = 0; i < 30; ++i) curves.push_back(random_curve(rng));
  const auto clip = build_fcurve_clip(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  auto ctx = make_fcurve_clip_cursor(*clip);
  std::vector<float> out(curves.size()), fresh_out(curves.size());
  std::vector<float> frames;
  for (int loop = 0; loop < 3; ++loop)
    for (float t = -15; t < 60; t += 0.5f) frames.push_back(t);
  for (int i = 0; i < 50; ++i) frames.push_back(rng.uniform<float>(-20, 70));  // seeks either way
  for (const float t : frames) {
    sample_fcurves(*clip, t, ctx, std::span<float>(out));
    auto fresh = make_fcurve_clip_cursor(*clip);
    sample_fcurves(*clip, t, fresh, std::span<float>(fresh_out));
    for (std::size_t c = 0; c < curves.size(); ++c) EXPECT_EQ(out[c], fresh_out[c]) << "curve " << c << " frame " << t;
  }
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
  auto ctx = make_fcurve_clip_cursor(*clip);
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
  auto ctx = make_fcurve_clip_cursor(*clip);
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
  auto ctx = make_fcurve_clip_cursor(*clip);
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

TEST(FCurveClip, RigRefusesACountNotAMultipleOfTen) {
  RawFCurve raw;
  raw.keys.push_back(FCurveKey{.frame = 0, .value = 0});
  raw.keys.push_back(FCurveKey{.frame = 4, .value = 1});
  const FCurve plain = build_fcurve(raw).value();
  const auto r = build_fcurve_rig(std::vector<FCurve>(9, plain));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::invalid_argument);
}

// ---- The Cycles modifier through the runtime -------------------------------------------------

// A random curve with a Cycles modifier: every mode on each side (none included), counts 0–3,
// both extrapolations and smoothings, random handle types (auto and auto-clamped on both ends
// make Blender's cycle-aware handles when both counts are 0 and both modes repeat).  `integral`
// puts the keys on whole frames, as animators' walk cycles are: then the cycle boundaries
// last + k·period are exact floats and Blender's r == 0 branch is hit.
FCurve random_cycling_curve(test::Random& rng, bool integral) {
  RawFCurve raw;
  raw.extrapolation = rng.integer(0, 1) ? Extrapolation::linear : Extrapolation::constant;
  raw.auto_smoothing = rng.integer(0, 1) ? AutoSmoothing::cont_accel : AutoSmoothing::none;
  double f = integral ? double(rng.integer(-10, 10)) : rng.uniform<double>(-10, 10);
  const int n = rng.integer(2, 7);
  for (int i = 0; i < n; ++i) {
    FCurveKey k;
    k.frame = f;
    k.value = rng.uniform<double>(-5, 5);
    k.interpolation = rng.integer(0, 3) == 0 ? Interpolation(rng.integer(0, 12)) : Interpolation::bezier;
    if (rng.integer(0, 2) == 0) k.handle_left_type = k.handle_right_type = HandleType(rng.integer(2, 4));
    raw.keys.push_back(k);
    f += integral ? double(rng.integer(1, 6)) : rng.uniform<double>(0.3, 6);
  }
  FCurveCycles cy;
  cy.before = CycleMode(rng.integer(0, 3));
  cy.after = CycleMode(rng.integer(0, 3));
  if (rng.integer(0, 1)) cy.count_before = rng.integer(0, 3);
  if (rng.integer(0, 1)) cy.count_after = rng.integer(0, 3);
  raw.modifiers = {FCurveModifier{.kind = cy}};
  return build_fcurve(raw).value();
}

struct CycleCheck {
  double worst = 0;  // max(0, |runtime − FCurve::sample| − 1 ulp) / scale: what fcurve_runtime_tolerance bounds
  long samples = 0, exact = 0;  // samples, and those equal to FCurve::sample bit for bit
};

// Samples the clip at every frame in order (the context carries over: forwards, backwards, jumps)
// and checks every channel against FCurve::sample with fcurve_runtime_agrees; never NaN.
void check_frames(const FCurveClip& clip, FCurveClipCursor& ctx, const std::vector<FCurve>& curves,
                  const std::vector<float>& frames, CycleCheck& out) {
  std::vector<float> values(curves.size());
  for (const float t : frames) {
    sample_fcurves(clip, t, ctx, std::span<float>(values));
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const float ref = curves[c].sample(t);
      ASSERT_FALSE(std::isnan(values[c])) << "curve " << c << " frame " << t;
      EXPECT_TRUE(fcurve_runtime_agrees(values[c], ref, scale_of(curves[c])))
          << "curve " << c << " frame " << t << ": runtime " << values[c] << ", FCurve::sample " << ref;
      if (std::isfinite(ref) && std::isfinite(values[c])) {
        const float big = std::max(std::abs(values[c]), std::abs(ref));
        const double ulp = double(std::nextafter(big, INFINITY)) - double(big);
        out.worst = std::max(out.worst, std::max(0.0, std::abs(double(values[c]) - ref) - ulp) / scale_of(curves[c]));
      }
      out.exact += values[c] == ref;
      ++out.samples;
    }
  }
}

// Frames at and around every curve's cycle boundaries first + k·period and last + k·period
// (k = −9 … 9, in float as Blender's fmod sees them) and its snap bands, 4 float steps each side.
std::vector<float> boundary_frames(const std::vector<FCurve>& curves) {
  std::vector<float> frames;
  for (const FCurve& c : curves) {
    const float x0 = c.keys().front().x, x1 = c.keys().back().x, period = x1 - x0;
    for (int k = -9; k <= 9; ++k) {
      for (const float end : {x0, x1}) {
        for (const double d : {-1e-4, 0.0, 1e-4}) {
          float t = float(double(end) + double(k) * double(period) + d);
          for (int s = 0; s < 4; ++s) t = std::nextafter(t, -INFINITY);
          for (int s = 0; s < 9; ++s, t = std::nextafter(t, INFINITY)) frames.push_back(t);
        }
      }
    }
  }
  return frames;
}

void cycling_agreement(std::uint64_t seed, bool integral) {
  test::Random rng(test::seed_for(seed));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (int i = 0; i < 48; ++i) curves.push_back(random_cycling_curve(rng, integral));
  const auto clip = build_fcurve_clip(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  EXPECT_EQ(clip->cycling_channels(), std::size_t(std::count_if(curves.begin(), curves.end(), [](const FCurve& c) {
              return c.simple_cycles()->before != CycleMode::none || c.simple_cycles()->after != CycleMode::none;
            })));
  auto ctx = make_fcurve_clip_cursor(*clip);
  CycleCheck check;
  std::vector<float> frames;
  for (float t = -150; t < 200; t += 0.043f) frames.push_back(t);  // forwards over many copies
  for (float t = 200; t > -150; t -= 0.61f) frames.push_back(t);   // backwards
  for (int i = 0; i < 400; ++i) frames.push_back(rng.uniform<float>(-400, 400));  // random seeks
  check_frames(*clip, ctx, curves, frames, check);
  const auto boundaries = boundary_frames(curves);
  check_frames(*clip, ctx, curves, boundaries, check);
  // Far from the keys: large frames forwards and backwards (one-frame folds beyond 2^23 cycles),
  // the float extremes and ±inf (as the largest finite float), NaN (the first key's value).
  frames.clear();
  for (const float big : {1e3f, 1e4f, 1e5f, 1e6f, 1e7f, 1e8f, 1e12f, 1e20f, 3.4e38f, INFINITY})
    for (const float sign : {1.0f, -1.0f})
      for (int s = -2; s <= 2; ++s) frames.push_back(sign * big + float(s) * 0.37f);
  for (float t = 1e6f; t < 1e6f + 64; t += 0.0625f) frames.push_back(t);  // 16 frames per frame ulp there
  frames.push_back(std::numeric_limits<float>::quiet_NaN());
  check_frames(*clip, ctx, curves, frames, check);
  std::cout << "[ measured ] cycling curves (" << (integral ? "whole-frame keys" : "random keys") << ", "
            << clip->cycling_channels() << " of " << curves.size() << " cycling) vs FCurve::sample: " << check.worst
            << " of the value scale beyond 1 ulp, over " << check.samples << " samples (" << check.exact
            << " bit-identical)\n";
}

TEST(FCurveClipCycles, AgreesWithFCurveSampleOnRandomCyclingCurves) { cycling_agreement(1210, false); }

TEST(FCurveClipCycles, AgreesWithFCurveSampleOnWholeFrameCycles) { cycling_agreement(1211, true); }

TEST(FCurveClipCycles, BlendersRecordedMirrorAndOffsetExample) {
  // Measured in Blender 3.4.1 (docs: ../shared/guide/blender-fcurves.md §13): LINEAR keys (0, 0),
  // (10, 10), (20, 4), Cycles before MIRROR, after REPEAT_OFFSET.
  RawFCurve raw;
  const std::pair<double, double> keys[] = {{0.0, 0.0}, {10.0, 10.0}, {20.0, 4.0}};
  for (const auto& [x, y] : keys)
    raw.keys.push_back(FCurveKey{.frame = x, .value = y, .interpolation = Interpolation::linear});
  raw.modifiers = {FCurveModifier{.kind = FCurveCycles{.before = CycleMode::mirror, .after = CycleMode::repeat_offset}}};
  const std::vector<FCurve> curves{build_fcurve(raw).value()};
  const auto clip = build_fcurve_clip(curves);
  ASSERT_TRUE(clip);
  auto ctx = make_fcurve_clip_cursor(*clip);
  float v = 0;
  const float scale = scale_of(curves[0]);  // 10: the keys' value range
  const std::pair<float, float> recorded[] = {{-25.0f, 7.0f}, {-15.0f, 7.0f}, {-5.0f, 5.0f}, {20.0f, 4.0f},
                                              {25.0f, 9.0f},  {30.0f, 14.0f}, {40.0f, 8.0f}, {45.0f, 13.0f}};
  for (const auto& [frame, blender] : recorded) {
    sample_fcurves(*clip, frame, ctx, std::span<float>(&v, 1));
    EXPECT_NEAR(v, blender, fcurve_runtime_tolerance * scale) << "frame " << frame;
  }
}

TEST(FCurveClipCycles, WalkCycleRigAgreesAndNormalises) {
  // A rig whose 10 curves per joint all repeat (walk cycles): sample_fcurve_rig reads the same
  // values as sample_fcurves, which agree with FCurve::sample, over several copies both ways.
  test::Random rng(test::seed_for(1212));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (int j = 0; j < 3; ++j) {
    for (int k = 0; k < 10; ++k) {
      RawFCurve raw;
      for (int i = 0; i <= 24; i += 6) raw.keys.push_back(FCurveKey{.frame = double(i), .value = rng.uniform<double>(-1, 1)});
      raw.keys.back().value = raw.keys.front().value;  // a closed loop
      raw.modifiers = {FCurveModifier{.kind = FCurveCycles{.before = CycleMode::repeat, .after = k < 3 ? CycleMode::repeat_offset : CycleMode::repeat}}};
      curves.push_back(build_fcurve(raw).value());
    }
  }
  const auto clip = build_fcurve_rig(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  EXPECT_EQ(clip->cycling_channels(), curves.size());
  // Keys on the same frames, two Cycles settings (location repeats with offset): two classes,
  // each with one local frame and one piece stream for its channels of all joints.
  EXPECT_EQ(clip->cycle_classes(), 2u);
  EXPECT_EQ(clip->pieces(), curves.size() * 6);  // 4 segments (one piece each) + 2 lines: nothing unrolled
  auto ctx = make_fcurve_clip_cursor(*clip);
  std::vector<float> out(curves.size());
  std::vector<JointPose<float>> pose(3);
  for (float t = -60; t < 100; t += 0.53f) {
    sample_fcurves(*clip, t, ctx, std::span<float>(out));
    for (std::size_t c = 0; c < curves.size(); ++c)
      EXPECT_TRUE(fcurve_runtime_agrees(out[c], curves[c].sample(t), scale_of(curves[c]))) << c << " " << t;
    sample_fcurve_rig(*clip, t, ctx, std::span<JointPose<float>>(pose));
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(pose[j].translation.x, out[10 * j]);
      EXPECT_EQ(pose[j].scale.z, out[10 * j + 9]);
    }
  }
}

// ---- Runs: channels keyed together --------------------------------------------------------------

// A joint's ten curves on the same key frames (Blender keys a bone's channels together): `raw`'s
// keys with their values (and handles) scaled by 1, 0.9, … 0.1 and moved by k — the fit's pieces
// then start at the same frames, so the clip stores them as runs.
void push_joint(const RawFCurve& raw, std::vector<FCurve>& curves) {
  for (int k = 0; k < 10; ++k) {
    RawFCurve r = raw;
    const double s = 1.0 - 0.1 * k;
    for (auto& key : r.keys) {
      key.value = key.value * s + k;
      if (key.handle_left) key.handle_left->y = key.handle_left->y * s + k;
      if (key.handle_right) key.handle_right->y = key.handle_right->y * s + k;
    }
    curves.push_back(build_fcurve(r).value());
  }
}

// The run layout (pieces of channels keyed together side by side, a run that fills a SIMD group
// read in place by the evaluation, shorter ones copied lane by lane, a group read in place
// copied into the cache when one of its channels moves on alone) changes no value: a rig whose
// joints share their key frames — the museum's degenerate curves (single keys, keys 1e-4 and one
// ulp apart, huge frames, vertical handles …) and seeded random joints, every third with a Cycles
// modifier — gives, at every frame, forwards, looping back, seeking and far out, the same bits
// as each curve compiled alone (a clip of one channel: runs of one piece, nothing read in place;
// the SIMD lanes are independent, so the same float operations).
TEST(FCurveClip, RunsOfChannelsKeyedTogetherChangeNoValue) {
  test::Random rng(test::seed_for(1214));
  SCOPED_TRACE(rng.trace());
  std::vector<FCurve> curves;
  for (const auto& ex : test::museum_fcurves()) push_joint(ex.curve, curves);
  for (int j = 0; j < 12; ++j) {
    RawFCurve raw = random_raw_curve(rng, j % 2 ? Extrapolation::linear : Extrapolation::constant, 2);
    if (j % 3 == 2) {
      FCurveCycles cy;
      cy.before = CycleMode(rng.integer(1, 3));
      cy.after = CycleMode(rng.integer(1, 3));
      raw.modifiers = {FCurveModifier{.kind = cy}};
    }
    push_joint(raw, curves);
  }
  const auto clip = build_fcurve_rig(curves);
  ASSERT_TRUE(clip) << clip.error().describe();
  EXPECT_GT(clip->cycle_classes(), 0u);
  // Curves keyed together share runs: at most about 3 per joint and key (4 + 4 + 2 lanes with SSE).
  EXPECT_LE(2 * clip->runs(), clip->pieces());
  std::vector<FCurveClip> alone;
  std::vector<FCurveClipCursor> alone_ctx;
  for (const FCurve& c : curves) {
    alone.push_back(build_fcurve_clip(std::span<const FCurve>(&c, 1)).value());
    alone_ctx.push_back(make_fcurve_clip_cursor(alone.back()));
  }
  std::vector<float> frames;
  for (int loop = 0; loop < 2; ++loop)
    for (float t = -20; t < 80; t += 0.25f) frames.push_back(t);  // forwards, then back to the start
  for (float t = 80; t > -20; t -= 0.9f) frames.push_back(t);      // backwards
  for (int i = 0; i < 300; ++i) frames.push_back(rng.uniform<float>(-100, 200));  // seeks either way
  for (const float big : {1e4f, 1e7f, 1e7f + 30, 3e38f, INFINITY, -1e6f}) frames.push_back(big);
  frames.push_back(std::numeric_limits<float>::quiet_NaN());
  auto ctx = make_fcurve_clip_cursor(*clip);
  std::vector<float> out(curves.size());
  float one = 0;
  std::size_t read_in_place = 0, compared = 0;
  for (const float t : frames) {
    sample_fcurves(*clip, t, ctx, std::span<float>(out));
    read_in_place += std::size_t(std::count_if(ctx.direct.begin(), ctx.direct.end(),
                                               [](std::uint32_t d) { return d != FCurveClipCursor::no_run; }));
    for (std::size_t c = 0; c < curves.size(); ++c) {
      sample_fcurves(alone[c], t, alone_ctx[c], std::span<float>(&one, 1));
      ASSERT_FALSE(std::isnan(out[c])) << "curve " << c << " frame " << t;
      EXPECT_EQ(out[c], one) << "curve " << c << " frame " << t;
      ++compared;
    }
  }
  EXPECT_GT(read_in_place, 0u);  // the in-place path was taken
  std::cout << "[ measured ] runs: " << clip->pieces() << " pieces in " << clip->runs() << " runs, " << compared
            << " values bit-identical to the curves compiled alone, " << read_in_place
            << " SIMD groups read in place over " << frames.size() << " frames\n";
}

}  // namespace
}  // namespace inbetween
