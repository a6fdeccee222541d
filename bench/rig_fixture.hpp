// The benchmark rig of issue 12, shared by bench/tracks_bench.cpp (in tree) and
// tools/bench/ozz_rig_bench.cpp (ozz-animation's SamplingJob, built out of tree by `make bench-ozz`),
// so both programs sample the same clip: J joints, each a linear-key translation and scale
// Track<Vec3<T>> and a slerp QuatTrack<T>, 30 keys per channel at frames spaced uniformly in
// [0.5, 1.5] apart, drawn from one seeded generator (seed 1212) in double and rounded to T, so the
// float and double rigs hold the same keys up to that rounding.
#pragma once

#include <algorithm>
#include <random>
#include <vector>

#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween_bench {

/// One joint of the benchmark rig: translation, rotation and scale channels with the same key frames.
template <class T>
struct RigJoint {
  inbetween::Track<inbetween::Vec3<T>> translation, scale;  ///< linear keys
  inbetween::QuatTrack<T> rotation;                         ///< slerp keys
};

/// Keys per channel of the benchmark rig.
inline constexpr int rig_keys_per_channel = 30;

/// The long clip of issue 24: 10 s at 31 keys/s, 310 keys per channel at frames 0, 1, … 309 (a
/// sampled clip, as BVH or baked glTF: every channel keyed on the same frames, so the rig's frame
/// is 1/31 s); at 1 024 joints neither its RigClip nor ozz's Animation fits in L2.
inline constexpr int rig_long_keys_per_channel = 310;

/// The benchmark rig with `joints` joints and `keys` keys per channel (seed 1212; the same draws for
/// every T).  Key frames: spaced uniformly in [0.5, 1.5] apart per channel, or, `regular`, at the
/// integers 0 … keys − 1 (the values are the same draws either way).
template <class T>
std::vector<RigJoint<T>> make_rig(int joints, int keys = rig_keys_per_channel, bool regular = false) {
  using namespace inbetween;
  std::mt19937_64 rng(1212);
  std::uniform_real_distribution<double> d(-1, 1), step(0.5, 1.5);
  std::vector<RigJoint<T>> rig;
  for (int j = 0; j < joints; ++j) {
    std::vector<TrackKey<Vec3<T>>> tk, sk;
    std::vector<QuatKey<T>> rk;
    double f = 0;
    for (int k = 0; k < keys; ++k) {
      TrackKey<Vec3<T>> t;
      t.frame = T(f);
      const double a = d(rng), b = d(rng), c = d(rng);
      t.value = {T(a), T(b), T(c)};
      t.tangent = TangentKind::linear;
      tk.push_back(t);
      TrackKey<Vec3<T>> sc = t;
      const double sa = d(rng), sb = d(rng), scc = d(rng);
      sc.value = {T(1 + 0.1 * sa), T(1 + 0.1 * sb), T(1 + 0.1 * scc)};
      sk.push_back(sc);
      QuatKey<T> r;
      r.frame = T(f);
      const double ax = d(rng), ay = d(rng), az = d(rng), ang = d(rng);
      const Quatd qd = Quatd::from_axis_angle(Vec3d{ax, ay, az + 2}, 1.5 * ang);
      r.value = Quat<T>::from_wxyz(T(qd.w), T(qd.x), T(qd.y), T(qd.z));
      r.interpolation = QuatInterpolation::slerp;
      rk.push_back(r);
      const double spacing = step(rng);
      f = regular ? double(k + 1) : f + spacing;
    }
    rig.push_back({build_track(tk).value(), build_track(sk).value(), build_quat_track(rk).value()});
  }
  return rig;
}

/// The last frame every channel of the rig reaches (playback wraps to 0 after it).
template <class T>
double rig_end(const std::vector<RigJoint<T>>& rig) {
  double end = 1e300;
  for (const auto& j : rig) end = std::min({end, double(j.translation.frames().back()), double(j.rotation.frames().back())});
  return end;
}

/// The last key frame of any channel (the clip's duration for ozz, whose keys start at 0).
template <class T>
double rig_duration(const std::vector<RigJoint<T>>& rig) {
  double duration = 0;
  for (const auto& j : rig) duration = std::max(duration, double(j.translation.frames().back()));
  return duration;
}

/// The rig's joints compiled into one RigClip (the fixture's tracks always build).
template <class T>
inbetween::RigClip<T> fixture_rig_clip(const std::vector<RigJoint<T>>& rig) {
  std::vector<inbetween::Track<inbetween::Vec3<T>>> tv, sv;
  std::vector<inbetween::QuatTrack<T>> rv;
  for (const auto& j : rig) tv.push_back(j.translation), sv.push_back(j.scale), rv.push_back(j.rotation);
  return inbetween::build_rig_clip<T>(tv, rv, sv).value();
}

}  // namespace inbetween_bench
