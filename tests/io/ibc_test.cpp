// The .ibc file through the shared reader (io/ibc.hpp, io/input.hpp): the RawScene a compressed
// clip becomes, built and sampled like any clip, reproduces the reference decoder at every frame
// (keys at every frame: equal to rounding of the scene's normalisation); a corrupt file is an
// error naming the byte, through read_input_file too.
#include "inbetween/io/ibc.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "inbetween/io/input.hpp"
#include "inbetween/scene/compress.hpp"
#include "../support/museum_clips.hpp"

namespace inbetween {
namespace {

// Rounding of a normalised quaternion and a composed chain of a few joints (double).
constexpr double raw_scene_tolerance = 1e-12;

std::filesystem::path write_bytes(const std::string& name, std::span<const std::uint8_t> bytes) {
  const auto path = std::filesystem::temp_directory_path() / ("inbetween_ibc_test_" + std::to_string(::getpid()) + name);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  return path;
}

TEST(IbcFile, ReadInputFileGivesTheDecompressedClip) {
  test::Random rng(test::seed_for(24));
  SCOPED_TRACE(rng.trace());
  for (const auto& exhibit : test::clip_museum()) {
    SCOPED_TRACE(exhibit.name);
    const auto compressed = compress_clip(exhibit.clip, {.error = 0.01});
    ASSERT_TRUE(compressed) << compressed.error().describe();
    const auto path = write_bytes(".ibc", compressed->bytes());
    EXPECT_EQ(input_format(path), InputFormat::ibc);
    const auto raw = read_input_file(path);
    std::filesystem::remove(path);
    ASSERT_TRUE(raw) << raw.error().describe();
    const auto scene = build_scene(*raw);
    ASSERT_TRUE(scene) << scene.error().describe();
    const auto sampled = sample_clip(*scene);
    ASSERT_TRUE(sampled) << sampled.error().describe();
    const SampledClip reference = decompress(*compressed);
    ASSERT_EQ(sampled->frames, reference.frames);
    ASSERT_EQ(sampled->names, reference.names);
    EXPECT_EQ(sampled->first_frame, reference.first_frame);
    EXPECT_LE(clip_error(reference, *sampled, 3).max, raw_scene_tolerance);
  }
}

TEST(IbcFile, MagicWithoutExtensionAndCorruptFiles) {
  const auto compressed = compress_clip(test::clip_museum()[1].clip, {.error = 0.01});
  ASSERT_TRUE(compressed);
  const auto path = write_bytes(".clip", compressed->bytes());
  EXPECT_EQ(input_format(path), InputFormat::ibc);
  std::filesystem::remove(path);
  std::vector<std::uint8_t> truncated(compressed->bytes().begin(), compressed->bytes().end() - 3);
  const auto bad = write_bytes("_bad.ibc", truncated);
  const auto raw = read_input_file(bad);
  std::filesystem::remove(bad);
  ASSERT_FALSE(raw);
  EXPECT_EQ(raw.error().describe().rfind("byte 8: file size", 0), 0u) << raw.error().describe();
}

}  // namespace
}  // namespace inbetween
