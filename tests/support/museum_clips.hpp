#pragma once
// Museum exhibits of compression (scene/compress.hpp): named degenerate-but-legal sampled clips.
// Every compression test that checks a contract (the error bound, round trips, the float
// sampler's agreement) loops over these, and over seeded random clips (random_clip()).

#include <cmath>
#include <string>
#include <vector>

#include "inbetween/scene/sampled_clip.hpp"
#include "random.hpp"

namespace inbetween::test {

/// A named sampled clip that stresses compression.
struct ClipExhibit {
  std::string name;
  SampledClip clip;
};

namespace museum_clip_detail {
inline SampledClip chain(std::size_t joints, std::size_t frames) {
  SampledClip c;
  for (std::size_t j = 0; j < joints; ++j) {
    c.parents.push_back(std::int32_t(j) - 1);
    c.names.push_back("j" + std::to_string(j));
  }
  c.frame_rate = 30;
  c.frames = frames;
  c.poses.resize(joints * frames);
  for (std::size_t f = 0; f < frames; ++f)
    for (std::size_t j = 1; j < joints; ++j) c.poses[f * joints + j].translation = {1, 0, 0};
  return c;
}
}  // namespace museum_clip_detail

/// The exhibits: single frame, single joint, constant tracks, antipodal neighbouring quaternions
/// (q and −q on alternate frames: the same rotation), a half turn (relative w through 0: four
/// stored components), a jump (a rest pose on frame 0), huge frame numbers, a zero scale.
inline std::vector<ClipExhibit> clip_museum() {
  using museum_clip_detail::chain;
  std::vector<ClipExhibit> out;
  {
    SampledClip c = chain(3, 1);
    c.poses[0].rotation = Quatd::from_axis_angle(Vec3d{0, 1, 0}, 0.7);
    out.push_back({"single frame", c});
  }
  {
    SampledClip c = chain(1, 40);
    for (std::size_t f = 0; f < 40; ++f) c.poses[f].translation = {0.1 * double(f), std::sin(0.2 * double(f)), 0};
    out.push_back({"single joint", c});
  }
  out.push_back({"constant tracks", chain(4, 30)});
  {
    SampledClip c = chain(2, 30);
    for (std::size_t f = 0; f < 30; ++f) {
      const Quatd q = Quatd::from_axis_angle(Vec3d{0, 0, 1}, 0.05 * double(f));
      c.poses[f * 2].rotation = f % 2 ? -q : q;
    }
    out.push_back({"antipodal neighbouring quaternions", c});
  }
  {
    SampledClip c = chain(2, 40);
    for (std::size_t f = 0; f < 40; ++f) c.poses[f * 2].rotation = Quatd::from_axis_angle(Vec3d{1, 0, 0}, 6.0 * double(f) / 39);
    out.push_back({"more than a half turn", c});
  }
  {
    SampledClip c = chain(3, 50);
    for (std::size_t f = 1; f < 50; ++f) {
      c.poses[f * 3 + 1].rotation = Quatd::from_axis_angle(Vec3d{0, 1, 0}, 1.0 + 0.01 * double(f));
      c.poses[f * 3].translation = {5, 0.01 * double(f), 0};
    }
    out.push_back({"rest pose on frame 0", c});
  }
  {
    SampledClip c = chain(2, 20);
    c.first_frame = 1e12;
    for (std::size_t f = 0; f < 20; ++f) c.poses[f * 2].translation = {0, 0, 0.3 * double(f)};
    out.push_back({"huge frame numbers", c});
  }
  {
    SampledClip c = chain(2, 20);
    for (std::size_t f = 0; f < 20; ++f) c.poses[f * 2].scale = {0, 1, double(f) / 19};
    out.push_back({"zero scale", c});
  }
  return out;
}

/// A random clip: `joints` joints in a random tree (parents before children), smooth random
/// rotations and translations plus noise, occasional scale, `frames` frames.
inline SampledClip random_clip(Random& rng, std::size_t joints, std::size_t frames) {
  SampledClip c;
  for (std::size_t j = 0; j < joints; ++j) {
    c.parents.push_back(j == 0 ? -1 : rng.integer(0, int(j) - 1));
    c.names.push_back("joint" + std::to_string(j));
  }
  c.first_frame = rng.uniform(-100.0, 100.0);
  c.frame_rate = 30;
  c.frames = frames;
  c.poses.resize(joints * frames);
  for (std::size_t j = 0; j < joints; ++j) {
    const Vec3d axis = rng.unit_vec3(), offset = rng.vec3(-2.0, 2.0), drift = rng.vec3(-0.05, 0.05);
    const Quatd rest = rng.rotation();
    const double speed = rng.uniform(0.0, 0.2), noise = rng.uniform(0.0, 0.01);
    const bool moves = rng.integer(0, 3) == 0, scaled = rng.integer(0, 5) == 0;
    for (std::size_t f = 0; f < frames; ++f) {
      JointPose<double>& p = c.poses[f * joints + j];
      p.rotation = rest * Quatd::from_axis_angle(axis, speed * double(f) + rng.uniform(-noise, noise));
      p.translation = moves ? offset + drift * double(f) + rng.vec3(-noise, noise) : offset;
      if (scaled) p.scale = Vec3d{1, 1, 1} * (1 + 0.1 * std::sin(0.1 * double(f)));
    }
  }
  return c;
}

}  // namespace inbetween::test
