// Blender's original noise (math/blender_noise.hpp) against values recorded in Blender 3.4.1
// (tests/data/blender/noise-blender-3.4.1.json, tools/blender/record_noise.py):
//  (a) mathutils.noise.noise(p, noise_basis='BLENDER') at 2 000 seeded points over a wide range
//      (uniform, log-uniform magnitudes up to 1e10, near-integer, one huge coordinate), which
//      Blender computes as float32(2·orgBlenderNoise(p + 1) − 1), the +1 in float32;
//  (b) fcurve.evaluate(frame) of 48 F-curves with a Noise modifier (random scale, strength,
//      phase, offset, depth, every blend type), recorded with the modifier active and muted: the
//      modifier's formula applied to the muted value must give the active one.
// Both are compared bit for bit (0 float32 ulp; the brief allows 0.5); the largest difference
// found is printed.  Then properties of the function itself: range, 256-periodicity, 0.5 on the
// lattice, continuity across cell faces, and the documented fallbacks for NaN / ∞ / huge input.
#include "inbetween/math/blender_noise.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

#include "support/random.hpp"

namespace {

using inbetween::BlenderNoiseBlend;
using inbetween::BlenderNoiseParams;
using inbetween::blender_noise;
using inbetween::blender_noise_modifier;
using inbetween::blender_turbulence;

const char* const kRecordFile = INBETWEEN_SOURCE_DIR "/tests/data/blender/noise-blender-3.4.1.json";

// Agreement with Blender: bit-exact (in float32 ulps).
constexpr std::int64_t kBlenderUlps = 0;
// Continuity across a cell face: the noise's slope is bounded (8 corners, |gradient| ≤ 1, fall-off
// slope ≤ 1.5, offsets ≤ √3: |∂n/∂x| < 8·(1.5·√3 + 1) < 30), so one float32 step of a coordinate
// below 8 (≤ 2^-20) moves it by < 30·2^-20 ≈ 2.9e-5; a wrong corner or fall-off jumps by ~0.1.
constexpr float kFaceStep = 3e-5f;

nlohmann::json load_record() {
  std::ifstream in(kRecordFile);
  std::ostringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

// Distance in float32 ulps (ordered integer representation); huge when one side is NaN.
std::int64_t ulps_between(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<std::int64_t>::max();
  auto ordered = [](float f) {
    std::int32_t i;
    std::memcpy(&i, &f, sizeof i);
    return i < 0 ? std::int64_t(std::numeric_limits<std::int32_t>::min()) - i : std::int64_t(i);
  };
  const std::int64_t d = ordered(a) - ordered(b);
  return d < 0 ? -d : d;
}

float as_float(const nlohmann::json& number) { return static_cast<float>(number.get<double>()); }

BlenderNoiseBlend blend_of(const std::string& name) {
  if (name == "ADD") return BlenderNoiseBlend::add;
  if (name == "SUBTRACT") return BlenderNoiseBlend::subtract;
  if (name == "MULTIPLY") return BlenderNoiseBlend::multiply;
  EXPECT_EQ(name, "REPLACE");
  return BlenderNoiseBlend::replace;
}

TEST(BlenderNoise, MatchesMathutilsNoiseAtRecordedPoints) {
  const auto record = load_record();
  const auto& rows = record.at("mathutils");
  ASSERT_EQ(rows.size(), 2000u);  // a truncated file must not pass quietly
  std::int64_t worst = 0;
  int differing = 0;
  for (const auto& row : rows) {
    const float x = as_float(row[0]), y = as_float(row[1]), z = as_float(row[2]);
    const float recorded = as_float(row[3]);
    // mathutils: BLI_noise_generic_noise adds 1 (float32) for this basis; returns 2n − 1 in float32.
    const float n = blender_noise(x + 1.0f, y + 1.0f, z + 1.0f);
    const float r = 2.0f * n - 1.0f;
    const std::int64_t d = ulps_between(r, recorded);
    worst = std::max(worst, d);
    if (d > kBlenderUlps) {
      if (++differing <= 5)
        ADD_FAILURE() << "noise(" << x << ", " << y << ", " << z << "): 2n-1 = " << r
                      << ", Blender " << recorded << " (" << d << " ulp)";
    }
  }
  std::cout << "[ blender  ] mathutils.noise BLENDER, " << rows.size()
            << " points: largest difference " << worst << " float32 ulp\n";
  EXPECT_EQ(differing, 0);
}

TEST(BlenderNoise, NoiseModifierFormulaMatchesBlenderOnRecordedCurves) {
  const auto record = load_record();
  const auto& cases = record.at("modifier");
  ASSERT_EQ(cases.size(), 48u);
  std::int64_t worst = 0;
  int samples = 0, differing = 0, changed = 0, blends_seen = 0;
  for (const auto& c : cases) {
    const BlenderNoiseParams params{.size = as_float(c.at("scale")),
                                    .strength = as_float(c.at("strength")),
                                    .phase = as_float(c.at("phase")),
                                    .offset = as_float(c.at("offset")),
                                    .depth = c.at("depth").get<int>(),
                                    .blend = blend_of(c.at("blend_type").get<std::string>())};
    blends_seen |= 1 << int(params.blend);
    const auto& frames = c.at("frames");
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const float frame = as_float(frames[i]);
      const float curve = as_float(c.at("curve")[i]);
      const float recorded = as_float(c.at("value")[i]);
      const float value = blender_noise_modifier(curve, frame, params);
      const std::int64_t d = ulps_between(value, recorded);
      worst = std::max(worst, d);
      ++samples;
      changed += recorded != curve;
      if (d > kBlenderUlps && ++differing <= 5)
        ADD_FAILURE() << "scale " << params.size << " depth " << params.depth << " frame " << frame
                      << ": " << value << ", Blender " << recorded << " (" << d << " ulp)";
    }
  }
  std::cout << "[ blender  ] Noise F-curve modifier, " << samples
            << " samples: largest difference " << worst << " float32 ulp\n";
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(blends_seen, 0b1111);        // every blend type was recorded
  EXPECT_GT(changed, samples * 9 / 10);  // the modifier changes the value (scale 0 + multiply aside)
}

TEST(BlenderNoise, StaysInUnitIntervalAndIsPeriodic) {
  inbetween::test::Random rng(inbetween::test::seed_for(2301));
  SCOPED_TRACE(rng.trace());
  for (int i = 0; i < 2000; ++i) {
    // Offsets on a 1/1024 grid, so that x + 256 is exact and the lattice repeats bit for bit.
    const float x = float(rng.integer(-200000, 200000)) / 1024.0f;
    const float y = float(rng.integer(-200000, 200000)) / 1024.0f;
    const float z = float(rng.integer(-200000, 200000)) / 1024.0f;
    const float n = blender_noise(x, y, z);
    ASSERT_GE(n, 0.0f);
    ASSERT_LE(n, 1.0f);
    EXPECT_EQ(n, blender_noise(x + 256.0f, y, z));
    EXPECT_EQ(n, blender_noise(x, y - 256.0f, z));
    EXPECT_EQ(n, blender_noise(x, y, z + 512.0f));
    const float t = blender_turbulence(rng.uniform(0.1f, 20.0f), x, y, z, rng.integer(0, 8));
    ASSERT_GE(t, 0.0f);
    ASSERT_LE(t, 1.0f);
  }
}

TEST(BlenderNoise, IsOneHalfOnTheLatticeAndContinuousAcrossCellFaces) {
  inbetween::test::Random rng(inbetween::test::seed_for(2302));
  SCOPED_TRACE(rng.trace());
  for (int i = 0; i < 1000; ++i) {
    const float X = float(rng.integer(-7, 7)), Y = float(rng.integer(-7, 7)), Z = float(rng.integer(-7, 7));
    EXPECT_EQ(blender_noise(X, Y, Z), 0.5f);  // every corner's offset or fall-off weight is 0
    const float y = rng.uniform(-7.5f, 7.5f), z = rng.uniform(-7.5f, 7.5f);
    const float below = std::nextafter(X, -8.0f);
    EXPECT_NEAR(blender_noise(below, y, z), blender_noise(X, y, z), kFaceStep) << X << " " << y << " " << z;
    EXPECT_NEAR(blender_noise(y, std::nextafter(Y, -8.0f), z), blender_noise(y, Y, z), kFaceStep);
    EXPECT_NEAR(blender_noise(y, z, std::nextafter(Z, -8.0f)), blender_noise(y, z, Z), kFaceStep);
  }
}

TEST(BlenderNoise, NonFiniteAndHugeInputsGiveTheDocumentedFallback) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float big = std::numeric_limits<float>::max();
  for (const float bad : {nan, inf, -inf}) {
    EXPECT_EQ(blender_noise(bad, 0.3f, 0.7f), 0.5f);  // Blender: NaN
    EXPECT_EQ(blender_noise(0.3f, bad, 0.7f), 0.5f);
    EXPECT_EQ(blender_noise(0.3f, 0.7f, bad), 0.5f);
    for (const float t : {blender_turbulence(bad, 1.5f, 2.5f, 0.1f, 3), blender_turbulence(2.0f, bad, 2.5f, 0.1f, 3)}) {
      EXPECT_TRUE(t >= 0.0f && t <= 1.0f) << t;
    }
  }
  // Finite but beyond int: Blender's lattice index is INT_MIN (low byte 0), offsets are 0.
  for (const float huge : {big, -big, 2147483648.0f, -2147483904.0f, 1e20f}) {
    const float n = blender_noise(huge, 0.25f, 0.75f);
    EXPECT_TRUE(n >= 0.0f && n <= 1.0f);
    EXPECT_EQ(n, blender_noise(0.0f, 0.25f, 0.75f)) << huge;
  }
  // Size 0: Blender's hnoise is 0 for every octave. Tiny sizes overflow the scaled coordinate.
  EXPECT_EQ(blender_turbulence(0.0f, 3.5f, 1.0f, 0.1f, 4), 0.0f);
  for (const float size : {1e-38f, std::numeric_limits<float>::denorm_min(), -1e-30f}) {
    const float t = blender_turbulence(size, 3.5f, 1.0f, 0.1f, 4);
    EXPECT_TRUE(t >= 0.0f && t <= 1.0f) << size;
  }
  // Depth: negative is one octave; Blender's maximum (32767) ends once the octave weight is 0.
  EXPECT_EQ(blender_turbulence(3.0f, 4.2f, 1.0f, 0.1f, -5), blender_turbulence(3.0f, 4.2f, 1.0f, 0.1f, 0));
  const float deep = blender_turbulence(3.0f, 4.2f, 1.0f, 0.1f, 32767);
  EXPECT_TRUE(deep >= 0.0f && deep <= 1.0f);
  const float value = blender_noise_modifier(2.0f, nan, {});
  EXPECT_TRUE(std::isfinite(value));
}

TEST(BlenderNoise, TurbulenceIsTheWeightedOctaveSumOfShiftedScaledNoise) {
  // BLI_noise_turbulence written out for depth 2 (independent of the loop): octaves at size,
  // size/2, size/4 with weights 1, 1/2, 1/4, each at ((1 + x)/s, (1 + y)/s, (1 + z)/s).
  inbetween::test::Random rng(inbetween::test::seed_for(2303));
  SCOPED_TRACE(rng.trace());
  for (int i = 0; i < 200; ++i) {
    const float size = rng.uniform(0.2f, 30.0f), x = rng.uniform(-100.0f, 100.0f), y = rng.uniform(-10.0f, 10.0f);
    const float z = 0.1f;
    auto octave = [&](float s) { return blender_noise((1.0f + x) / s, (1.0f + y) / s, (1.0f + z) / s); };
    float sum = octave(size);
    sum += 0.5f * octave(size * 0.5f);
    sum += 0.25f * octave(size * 0.25f);
    EXPECT_EQ(blender_turbulence(size, x, y, z, 2), sum / 1.75f);
  }
}

}  // namespace
