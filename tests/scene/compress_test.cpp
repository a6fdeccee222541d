// Error-bounded compression (scene/compress.hpp): on seeded random clips and the museum of
// degenerate clips, the measured virtual-vertex error of both decoders (decompress, the double
// reference; sample_float, the runtime's float sampler) is at most the requested error — the
// guarantee, checked by clip_error, an implementation independent of the compressor's own search.
#include "inbetween/scene/compress.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace inbetween
