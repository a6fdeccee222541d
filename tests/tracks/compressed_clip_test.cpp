// The .ibc format and its decoders (tracks/runtime/compressed_clip.hpp): a hand-made clip whose
// decoded values are known in closed form (linear, spacing 1: value = min + step · index at every
// sample), written and read back; every truncation and every single-byte corruption of a valid
// file is refused with a byte offset or loads into a clip that decodes to finite values — never a
// crash; the float sampler agrees with the double decoder within compressed_sample_tolerance.
#include "inbetween/tracks/runtime/compressed_clip.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace inbetween {
namespace {

// Two joints, two pieces (frames 0–4 and 5–9): joint 0 translation linear spline at spacing 1,
// rotation constant; joint 1 rotation cubic spline at spacing 2 (3 components), scale absent.
CompressedClipParts sample_parts() {
  CompressedClipParts p;
  p.parents = {-1, 0};
  p.names = {"root", "arm"};
  p.pieces = {0, 5};
  p.frames = 10;
  p.first_frame = 3;
  p.frame_rate = 24;
  p.error_bound = 0.01, p.measured_error = 0.005, p.shell = 3;
  for (std::size_t piece = 0; piece < 2; ++piece) {
    for (std::size_t j = 0; j < 2; ++j) {
      for (unsigned ch = 0; ch < 3; ++ch) {
        CompressedTrack t;
        std::vector<std::uint32_t> values;
        if (j == 0 && ch == 0) {
          t.kind = CompressedTrackKind::spline, t.degree = 1, t.spacing = 1, t.bits = 6;
          t.min = {1, -2, 0.5f, 0}, t.step = {0.25f, 0.5f, 0.125f, 0};
          for (std::uint32_t i = 0; i < 5; ++i) values.insert(values.end(), {i * 3 + std::uint32_t(piece), 40 - i, i * i});
        } else if (j == 0 && ch == 1) {
          t.kind = CompressedTrackKind::constant, t.min = {0.5f, 0.5f, 0.5f, 0.5f};
        } else if (j == 1 && ch == 1) {
          t.kind = CompressedTrackKind::spline, t.degree = 3, t.spacing = 2, t.bits = 8;
          t.min = {-0.1f, -0.1f, -0.1f, 0}, t.step = {0.001f, 0.001f, 0.001f, 0};
          t.reference = Quatf::from_wxyz(0, 1, 0, 0);
          for (std::uint32_t i = 0; i < 6; ++i) values.insert(values.end(), {i * 20, 200 - i * 7, 100});
        }
        p.tracks.push_back(t);
        p.values.push_back(values);
      }
    }
  }
  return p;
}

TEST(CompressedClip, RoundTripDecodesTheClosedForm) {
  const auto bytes = write_compressed_clip(sample_parts());
  const auto clip = load_compressed_clip(bytes);
  ASSERT_TRUE(clip) << clip.error().describe();
  EXPECT_EQ(clip->joints(), 2u);
  EXPECT_EQ(clip->frames(), 10u);
  EXPECT_EQ(clip->first_frame(), 3.0);
  EXPECT_EQ(clip->frame_rate(), 24.0);
  EXPECT_EQ(clip->names()[1], "arm");
  EXPECT_EQ(clip->parents()[1], 0);
  ASSERT_EQ(clip->pieces().size(), 2u);
  // Stored as the float not below it.
  EXPECT_GE(clip->measured_error(), 0.005);
  EXPECT_LE(clip->measured_error(), double(std::nextafter(0.005f, 1.0f)));
  EXPECT_EQ(clip->bytes().size(), bytes.size());
  std::vector<JointPose<double>> pose(2);
  for (std::size_t f = 0; f < 10; ++f) {
    decode_frame(*clip, f, pose);
    const std::size_t piece = f / 5, i = f % 5;
    // Linear at spacing 1: the control point itself, exactly (products of small dyadic floats).
    EXPECT_EQ(pose[0].translation.x, 1 + 0.25 * double(i * 3 + piece));
    EXPECT_EQ(pose[0].translation.y, -2 + 0.5 * double(40 - i));
    EXPECT_EQ(pose[0].translation.z, 0.5 + 0.125 * double(i * i));
    EXPECT_NEAR(pose[0].rotation.w, 0.5, 1e-15);
    EXPECT_EQ(pose[1].scale, (Vec3d{1, 1, 1}));
    EXPECT_NEAR(norm(Vec4d{pose[1].rotation.w, pose[1].rotation.x, pose[1].rotation.y, pose[1].rotation.z}), 1.0, 1e-12);
  }
}

TEST(CompressedClip, FloatSamplerAgreesWithTheReference) {
  const auto clip = load_compressed_clip(write_compressed_clip(sample_parts()));
  ASSERT_TRUE(clip);
  std::vector<JointPose<double>> ref(2);
  std::vector<JointPose<float>> run(2);
  for (std::size_t f = 0; f < 10; ++f) {
    decode_frame(*clip, f, ref);
    sample_compressed(*clip, clip->first_frame() + double(f), run);
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_LT(norm(ref[j].translation - run[j].translation.cast<double>()), compressed_sample_tolerance * 20);
      EXPECT_LT(angle_between(ref[j].rotation, run[j].rotation.cast<double>()), compressed_sample_tolerance);
    }
  }
  // Outside the clip: clamped to the first and last samples; NaN acts as the first.
  sample_compressed(*clip, -1e300, run);
  decode_frame(*clip, 0, ref);
  EXPECT_NEAR(run[0].translation.x, ref[0].translation.x, 1e-6);
  sample_compressed(*clip, std::nan(""), run);
  EXPECT_NEAR(run[0].translation.x, ref[0].translation.x, 1e-6);
  sample_compressed(*clip, 1e300, run);
  decode_frame(*clip, 9, ref);
  EXPECT_NEAR(run[0].translation.x, ref[0].translation.x, 1e-6);
}

// Seeded: one joint over 250 frames, a cubic translation at spacing 1 (253 control points: 22
// blocks in 2 superblocks) and a linear 4-component rotation at spacing 3, whose offsets change
// width every 12 control points (rows of 0 … 66 bits: the sampler's one-load and per-component
// paths).  At seeded fractional frames the float sampler agrees with the splines evaluated in
// double from the quantised values themselves (not through the file or its block index).
TEST(CompressedClip, SamplerAtFractionalFramesMatchesTheSplines) {
  const unsigned seed = 2411;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  CompressedClipParts p;
  p.parents = {-1};
  p.names = {"root"};
  p.frames = 250;
  p.first_frame = -7;
  p.frame_rate = 30;
  const auto random_values = [&](std::size_t controls, unsigned comps) {
    std::vector<std::uint32_t> v(controls * comps);
    for (std::size_t first = 0; first < controls; first += 12) {
      for (unsigned c = 0; c < comps; ++c) {
        const unsigned width = std::uniform_int_distribution<unsigned>(0, 22)(rng);
        const std::uint32_t base = std::uniform_int_distribution<std::uint32_t>(0, 1u << 20)(rng);
        for (std::size_t i = first; i < std::min(controls, first + 12); ++i)
          v[i * comps + c] = base + (std::uniform_int_distribution<std::uint32_t>(0, (1u << width) - 1)(rng) >> 1);
      }
    }
    return v;
  };
  CompressedTrack tr;
  tr.kind = CompressedTrackKind::spline, tr.degree = 3, tr.spacing = 1, tr.bits = 23;
  tr.min = {-3, 1, 0.25f, 0}, tr.step = {1e-6f, 2e-6f, 5e-7f, 0};
  CompressedTrack rot;
  rot.kind = CompressedTrackKind::spline, rot.components = 4, rot.degree = 1, rot.spacing = 3, rot.bits = 23;
  rot.min = {-1, -1, -1, 0.5f}, rot.step = {2e-7f, 2e-7f, 2e-7f, 1e-7f};
  rot.reference = normalized(Quatd::from_wxyz(0.9, 0.1, -0.3, 0.2)).cast<float>();
  const std::size_t tr_controls = compressed_segments(250, 1) + 3, rot_controls = compressed_segments(250, 3) + 1;
  p.tracks = {tr, rot, CompressedTrack{}};
  p.values = {random_values(tr_controls, 3), random_values(rot_controls, 4), {}};
  const auto clip = load_compressed_clip(write_compressed_clip(p));
  ASSERT_TRUE(clip) << clip.error().describe();
  // The spline of track t in double at sample x, straight from the values.
  const auto spline = [&](const CompressedTrack& t, const std::vector<std::uint32_t>& values, double x, double* out) {
    const std::size_t controls = values.size() / t.components;
    const std::size_t seg = std::min<std::size_t>(std::size_t(x / t.spacing), controls - 1 - t.degree);
    const double u = (x - double(seg * t.spacing)) / double(t.spacing);
    const auto w = t.degree == 3 ? bspline_weights(u) : linear_weights(u);
    for (unsigned c = 0; c < t.components; ++c) {
      double acc = 0;
      for (unsigned k = 0; k <= t.degree; ++k) acc += w[k] * double(values[(seg + k) * t.components + c]);
      out[c] = double(t.min[c]) + double(t.step[c]) * acc;
    }
  };
  std::vector<JointPose<float>> run(1);
  std::uniform_real_distribution<double> any(0, 249);
  for (int n = 0; n < 400; ++n) {
    const double x = n < 250 ? double(n) + (n % 2 ? 0.5 : 0.0) * (n < 249) : any(rng);
    sample_compressed(*clip, p.first_frame + x, run);
    double t[4], q[4];
    spline(tr, p.values[0], x, t);
    spline(rot, p.values[1], x, q);
    const Quatd expected = rot.reference.cast<double>() * normalized(Quatd::from_wxyz(q[3], q[0], q[1], q[2]));
    const double scale = std::max({std::abs(t[0]), std::abs(t[1]), std::abs(t[2])}) + 1;
    EXPECT_LT(norm(Vec3d{t[0], t[1], t[2]} - run[0].translation.cast<double>()), compressed_sample_tolerance * scale) << "x " << x;
    EXPECT_LT(angle_between(expected, run[0].rotation.cast<double>()), compressed_sample_tolerance) << "x " << x;
  }
}

// Seeded: 70 joints, one piece of 40 frames, so 66 rotation splines — past the sampler's chunk of
// 64 and not a multiple of its 4 lanes — mixing 3- and 4-component rotations, degrees 1 and 3,
// spacings 1 … 4 in turn, 3-component values past |v| = 1 (w = 0, normalised) and a 4-component
// track that decodes to zero (the reference itself), among translation splines and constants.
// At every frame the float sampler agrees with decode_frame on every joint (a lane stored to the
// wrong joint, or a stale weight of another spacing, shows as a whole-value difference).
TEST(CompressedClip, SamplerLanesAgreeWithTheReferenceOnEveryJoint) {
  const unsigned seed = 907;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  const std::size_t joints = 70, frames = 40;
  CompressedClipParts p;
  p.frames = frames;
  p.frame_rate = 30;
  std::size_t rotation_splines = 0;
  for (std::size_t j = 0; j < joints; ++j) {
    p.parents.push_back(std::int32_t(j) - 1);
    p.names.push_back("j" + std::to_string(j));
    for (unsigned ch = 0; ch < 3; ++ch) {
      CompressedTrack t;
      std::vector<std::uint32_t> values;
      const bool spline = (ch == 0 && j % 5 == 0) || (ch == 1 && j % 17 != 3) || (ch == 2 && j % 11 == 4);
      if (!spline) {
        if (ch == 1) t.kind = CompressedTrackKind::constant, t.min = {0.5f, -0.5f, 0.5f, 0.5f};
        p.tracks.push_back(t);
        p.values.push_back(values);
        continue;
      }
      t.kind = CompressedTrackKind::spline;
      t.components = ch == 1 && j % 3 == 0 ? 4 : 3;
      t.degree = j % 2 ? 3 : 1;
      t.spacing = 1 + std::uint32_t(j % 4);
      t.bits = 12;
      if (ch == 1) {
        ++rotation_splines;
        // |v| up to 0.8·√3 ≈ 1.39: some samples past the unit ball.
        for (unsigned c = 0; c < t.components; ++c) t.min[c] = -0.8f, t.step[c] = 1.6f / 4095.0f;
        if (j == 9) t.min = {}, t.step = {};  // 4 components, all zero: the reference
        t.reference = normalized(Quatd::from_wxyz(1, 0.1 * double(j % 5), -0.2, 0.05 * double(j % 3))).cast<float>();
      } else {
        for (unsigned c = 0; c < 3; ++c) t.min[c] = ch == 0 ? -5.0f : 0.5f, t.step[c] = ch == 0 ? 0.01f : 0.001f;
      }
      const std::size_t controls = compressed_segments(frames, t.spacing) + t.degree;
      for (std::size_t i = 0; i < controls * t.components; ++i) values.push_back(std::uniform_int_distribution<std::uint32_t>(0, 4095)(rng));
      p.tracks.push_back(t);
      p.values.push_back(values);
    }
  }
  ASSERT_EQ(rotation_splines, 66u);
  const auto clip = load_compressed_clip(write_compressed_clip(p));
  ASSERT_TRUE(clip) << clip.error().describe();
  EXPECT_EQ(clip->rotation_count(0), rotation_splines);
  std::vector<JointPose<double>> ref(joints);
  std::vector<JointPose<float>> run(joints);
  for (std::size_t f = 0; f < frames; ++f) {
    decode_frame(*clip, f, ref);
    sample_compressed(*clip, double(f), run);
    for (std::size_t j = 0; j < joints; ++j) {
      // translations ≤ 36 in size, scales ≤ 5: compressed_sample_tolerance relative to |value| + 1
      EXPECT_LT(norm(ref[j].translation - run[j].translation.cast<double>()), compressed_sample_tolerance * 37) << "frame " << f << " joint " << j;
      EXPECT_LT(norm(ref[j].scale - run[j].scale.cast<double>()), compressed_sample_tolerance * 6) << "frame " << f << " joint " << j;
      EXPECT_LT(angle_between(ref[j].rotation, run[j].rotation.cast<double>()), compressed_sample_tolerance)
          << "frame " << f << " joint " << j;
      const Quatf& q = run[j].rotation;  // unit length (angle_between alone does not see a scaled rotation)
      EXPECT_NEAR(std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z), 1.0f, 1e-6f) << "frame " << f << " joint " << j;
    }
  }
  EXPECT_NEAR(angle_between(ref[9].rotation, clip->track(0, 9, CompressedChannel::rotation).reference.cast<double>()), 0, 1e-7);
}

bool finite_pose(const JointPose<double>& p) {
  return std::isfinite(p.translation.x + p.translation.y + p.translation.z + p.rotation.w + p.rotation.x + p.rotation.y +
                       p.rotation.z + p.scale.x + p.scale.y + p.scale.z);
}

TEST(CompressedClip, TruncatedFilesAreRefusedWithAByteOffset) {
  const auto bytes = write_compressed_clip(sample_parts());
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const auto r = load_compressed_clip(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(n)));
    ASSERT_FALSE(r) << "prefix of " << n << " bytes loaded";
    EXPECT_EQ(r.error().code, ErrorCode::parse);
    EXPECT_EQ(r.error().place().rfind("byte ", 0), 0u) << r.error().describe();
  }
}

TEST(CompressedClip, CorruptBytesAreRefusedOrDecodeFinite) {
  const auto bytes = write_compressed_clip(sample_parts());
  std::size_t refused = 0;
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    for (const std::uint8_t x : {std::uint8_t(0xff), std::uint8_t(0x80), std::uint8_t(0x01)}) {
      auto corrupt = bytes;
      corrupt[at] ^= x;
      const auto r = load_compressed_clip(corrupt);
      // The layout fields (magic, version, header size, file size, joint count, the four offsets and
      // sizes) are checked exactly: any change to them is refused.
      const bool layout = at < 16 || (at >= 20 && at < 36);
      if (layout) EXPECT_FALSE(r) << "byte " << at << " ^ " << int(x);
      if (!r) {
        ++refused;
        EXPECT_EQ(r.error().place().rfind("byte ", 0), 0u) << r.error().describe();
        continue;
      }
      std::vector<JointPose<double>> pose(r->joints());
      std::vector<JointPose<float>> run(r->joints());
      for (std::size_t f = 0; f < r->frames(); ++f) {
        decode_frame(*r, f, pose);
        sample_compressed(*r, r->first_frame() + double(f), run);
        for (const auto& p : pose) ASSERT_TRUE(finite_pose(p)) << "byte " << at << " frame " << f;
      }
    }
  }
  EXPECT_GE(refused, 3u * 32u);  // at least the layout fields
}

TEST(CompressedClip, NamedFieldsInErrors) {
  auto bytes = write_compressed_clip(sample_parts());
  auto bad = bytes;
  bad[0] = 'X';
  EXPECT_EQ(load_compressed_clip(bad).error().describe(), "byte 0: magic: not an .ibc file");
  bad = bytes;
  bad[4] = 9;
  EXPECT_EQ(load_compressed_clip(bad).error().describe(), "byte 4: version: 9, this build reads version 1");
  auto parts = sample_parts();
  parts.names = {"root", "root"};  // the RawScene of a clip needs unique names
  EXPECT_NE(load_compressed_clip(write_compressed_clip(parts)).error().describe().find("names an earlier joint"),
            std::string::npos);
  parts = sample_parts();
  parts.first_frame = 1e17;  // whole frames no longer distinct
  EXPECT_EQ(load_compressed_clip(write_compressed_clip(parts)).error().place(), "byte 36");
  bad = bytes;
  bad.push_back(0);
  EXPECT_NE(load_compressed_clip(bad).error().describe().find("file size"), std::string::npos);
}

}  // namespace
}  // namespace inbetween
