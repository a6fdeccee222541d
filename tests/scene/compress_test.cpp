// Error-bounded compression (scene/compress.hpp): on seeded random clips and the museum of
// degenerate clips, the measured virtual-vertex error of both decoders (decompress, the double
// reference; sample_float, the runtime's float sampler) is at most the requested error — the
// guarantee, checked by clip_error, an implementation independent of the compressor's own search.
#include "inbetween/scene/compress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../support/museum_clips.hpp"

namespace inbetween {
namespace {

void expect_bounded(const SampledClip& clip, const CompressOptions& options, const std::string& what) {
  SCOPED_TRACE(what);
  const auto compressed = compress_clip(clip, options);
  ASSERT_TRUE(compressed) << compressed.error().describe();
  const ClipError reference = clip_error(clip, decompress(*compressed), options.shell);
  const ClipError runtime = clip_error(clip, sample_float(*compressed), options.shell);
  EXPECT_LE(reference.max, options.error) << "frame " << reference.frame << " joint " << reference.joint;
  EXPECT_LE(runtime.max, options.error) << "frame " << runtime.frame << " joint " << runtime.joint;
  // The header records the larger of the two, rounded up to float.
  EXPECT_GE(compressed->measured_error(), std::max(reference.max, runtime.max));
  EXPECT_LE(compressed->measured_error(), options.error * (1 + 1e-6));
  // The bytes read back to the same clip.
  const auto again = load_compressed_clip(std::vector<std::uint8_t>(compressed->bytes().begin(), compressed->bytes().end()));
  ASSERT_TRUE(again) << again.error().describe();
  EXPECT_EQ(clip_error(decompress(*compressed), decompress(*again), options.shell).max, 0.0);
}

TEST(CompressClip, RandomClipsStayWithinTheBound) {
  test::Random rng(test::seed_for(2411));
  SCOPED_TRACE(rng.trace());
  for (int i = 0; i < 6; ++i) {
    const std::size_t joints = std::size_t(rng.integer(1, 7)), frames = std::size_t(rng.integer(2, 60));
    const SampledClip clip = test::random_clip(rng, joints, frames);
    const CompressOptions options{.error = std::exp(rng.uniform(std::log(1e-4), std::log(0.2))), .shell = rng.uniform(0.0, 5.0)};
    expect_bounded(clip, options, "clip " + std::to_string(i) + ": " + std::to_string(joints) + " joints, " +
                                      std::to_string(frames) + " frames, E " + std::to_string(options.error));
  }
}

TEST(CompressClip, MuseumClipsStayWithinTheBound) {
  for (const auto& exhibit : test::clip_museum()) {
    for (const double e : {1e-3, 0.05}) expect_bounded(exhibit.clip, {.error = e, .shell = 3}, exhibit.name);
  }
}

TEST(CompressClip, ConstantClipsStoreNoStream) {
  // Nothing moves: every track absent or constant, the stream only its padding.
  const auto compressed = compress_clip(test::clip_museum()[2].clip, {.error = 1e-3});
  ASSERT_TRUE(compressed);
  for (const CompressedTrack& t : compressed->tracks()) EXPECT_NE(t.kind, CompressedTrackKind::spline);
  EXPECT_EQ(compressed->measured_error(), 0.0);
}

TEST(CompressClip, AJumpCutsAPiece) {
  const auto compressed = compress_clip(test::clip_museum()[5].clip, {.error = 1e-3});
  ASSERT_TRUE(compressed);
  ASSERT_EQ(compressed->pieces().size(), 2u);
  EXPECT_EQ(compressed->pieces()[1], 1u);
}

TEST(CompressClip, LooserBoundsGiveSmallerFiles) {
  test::Random rng(test::seed_for(77));
  SCOPED_TRACE(rng.trace());
  const SampledClip clip = test::random_clip(rng, 5, 60);
  const auto tight = compress_clip(clip, {.error = 1e-4}), loose = compress_clip(clip, {.error = 1e-1});
  ASSERT_TRUE(tight && loose);
  EXPECT_LT(loose->bytes().size(), tight->bytes().size());
}

TEST(CompressClip, BadOptionsAndPosesAreNamed) {
  const SampledClip clip = test::clip_museum()[1].clip;
  for (const double e : {0.0, -1.0, std::nan(""), double(INFINITY)}) {
    const auto r = compress_clip(clip, {.error = e});
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().place(), "error");
  }
  const auto shell = compress_clip(clip, {.shell = -1});
  ASSERT_FALSE(shell);
  EXPECT_EQ(shell.error().place(), "shell");
  SampledClip bad = clip;
  bad.poses[7].translation.y = std::nan("");
  const auto r = compress_clip(bad);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::not_finite);
  EXPECT_EQ(r.error().place(), "/frames/7/joints/0");
}

// The spline's error at each of `frames` samples for rounded control points `q` of t (decode_frame's
// segment and basis), the largest |error| — an evaluation independent of the trellis.
double worst_sample_error(const std::vector<double>& t, const std::vector<std::uint32_t>& q, std::size_t frames, std::uint32_t h,
                          unsigned degree) {
  double worst = 0;
  for (std::size_t f = 0; f < frames; ++f) {
    const std::size_t seg = std::min<std::size_t>(f / h, t.size() - 1 - degree);
    const double u = double(f - seg * h) / double(h);
    const auto w = degree == 3 ? bspline_weights(u) : linear_weights(u);
    double e = 0;
    for (unsigned k = 0; k <= degree; ++k) e += w[k] * (double(q[seg + k]) - t[seg + k]);
    worst = std::max(worst, std::abs(e));
  }
  return worst;
}

// Seeded: on small splines (10 control points) the trellis's largest sample error equals the
// best of every floor/ceiling choice, enumerated; on long ones it is never above rounding each
// control point to nearest (one of the choices it weighs) and, for cubic splines on these random
// fractions, below 0.9 of it (measured: 0.69–0.79 on this seed).
TEST(CompressClip, JointRoundingIsTheBestFloorOrCeilingChoice) {
  const unsigned seed = 5113;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(0, 1000);
  for (unsigned degree : {1u, 3u}) {
    for (std::uint32_t h : {1u, 2u, 3u}) {
      if (degree == 1 && h == 1) continue;  // the samples themselves: nothing to trade
      SCOPED_TRACE("degree " + std::to_string(degree) + " spacing " + std::to_string(h));
      const std::size_t frames = 1 + h * (10 - degree);  // 10 control points
      std::vector<double> t(std::size_t(compressed_segments(frames, h)) + degree);
      ASSERT_EQ(t.size(), 10u);
      for (double& v : t) v = value(rng);
      std::vector<std::uint32_t> q(t.size()), best(t.size());
      round_controls_jointly(t, frames, h, degree, q);
      double brute = 1e300;
      for (std::uint32_t m = 0; m < (1u << t.size()); ++m) {
        for (std::size_t i = 0; i < t.size(); ++i) best[i] = std::uint32_t(std::floor(t[i])) + ((m >> i) & 1u);
        brute = std::min(brute, worst_sample_error(t, best, frames, h, degree));
      }
      for (std::size_t i = 0; i < t.size(); ++i) EXPECT_TRUE(q[i] == std::uint32_t(std::floor(t[i])) || q[i] == std::uint32_t(std::floor(t[i])) + 1);
      EXPECT_NEAR(worst_sample_error(t, q, frames, h, degree), brute, 1e-12);
      // Long: against rounding to nearest.
      const std::size_t long_frames = 3000;
      std::vector<double> tl(std::size_t(compressed_segments(long_frames, h)) + degree);
      for (double& v : tl) v = value(rng);
      std::vector<std::uint32_t> ql(tl.size()), nearest(tl.size());
      round_controls_jointly(tl, long_frames, h, degree, ql);
      for (std::size_t i = 0; i < tl.size(); ++i) nearest[i] = std::uint32_t(std::lround(tl[i]));
      const double joint = worst_sample_error(tl, ql, long_frames, h, degree), rounded = worst_sample_error(tl, nearest, long_frames, h, degree);
      EXPECT_LE(joint, rounded);
      // Cubic: no sample is a control point itself, so the choice pays (linear samples at the knots are).
      if (degree == 3) EXPECT_LT(joint, 0.9 * rounded) << joint << " vs " << rounded;
    }
  }
}

}  // namespace
}  // namespace inbetween
