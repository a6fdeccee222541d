// Issues 12 and 24: inbetween's RigClip against ozz-animation's SamplingJob on the same clips, in
// one binary: the 30-key rig of bench/ and the long clip (10 s at 31 keys/s), with bytes.  Not part
// of the CMake build (ozz is not packaged by Debian): `make bench-ozz OZZ_SRC=/path/to/ozz-animation`
// (tools/bench/bench_ozz.sh) builds ozz out of tree under build/ozz, compiles this file against it,
// runs it with JSON output, and tools/bench/write_results.py puts the tables into bench/RESULTS.md.
// The clips are bench/rig_fixture.hpp's, as in bench/tracks_bench.cpp and bench/rig_bench.cpp.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "inbetween/tracks/runtime/rig_clip.hpp"
#include "rig_fixture.hpp"
#include "ozz/animation/offline/animation_builder.h"
#include "ozz/animation/offline/raw_animation.h"
#include "ozz/animation/runtime/animation.h"
#include "ozz/animation/runtime/sampling_job.h"
#include "ozz/base/maths/simd_math.h"
#include "ozz/base/maths/soa_transform.h"

using namespace inbetween;

using inbetween_bench::make_rig;
using inbetween_bench::rig_duration;
using inbetween_bench::rig_end;
using inbetween_bench::RigJoint;

// The rig as an ozz RawAnimation (key times in frames as seconds; ozz holds the end values as we
// do), built by AnimationBuilder without keyframe optimisation.
ozz::unique_ptr<ozz::animation::Animation> make_ozz(const std::vector<RigJoint<float>>& rig) {
  ozz::animation::offline::RawAnimation raw;
  raw.duration = float(rig_duration(rig));
  raw.tracks.resize(rig.size());
  for (std::size_t j = 0; j < rig.size(); ++j) {
    auto& tr = raw.tracks[j];
    const auto f = rig[j].translation.frames();
    for (std::size_t k = 0; k < f.size(); ++k) {
      const Vec3f v = rig[j].translation.values()[k], s = rig[j].scale.values()[k];
      const Quatf q = rig[j].rotation.keys()[k];
      tr.translations.push_back({f[k], ozz::math::Float3(v.x, v.y, v.z)});
      tr.scales.push_back({f[k], ozz::math::Float3(s.x, s.y, s.z)});
      tr.rotations.push_back({f[k], ozz::math::Quaternion(q.x, q.y, q.z, q.w)});
    }
  }
  ozz::animation::offline::AnimationBuilder builder;
  return builder(raw);
}

// ozz's SamplingJob playing the rig of state.range(0) joints and `keys` keys per channel forwards,
// 1/state.range(1) key interval per call; counters: accuracy, bytes (Animation::size()).
void play_ozz(benchmark::State& state, int keys) {
  const auto rig = make_rig<float>(int(state.range(0)), keys, keys != inbetween_bench::rig_keys_per_channel);
  const auto anim = make_ozz(rig);
  const double duration = rig_duration(rig), end = rig_end(rig);
  ozz::animation::SamplingJob::Context ctx(anim->num_tracks());
  std::vector<ozz::math::SoaTransform> locals(std::size_t(anim->num_soa_tracks()));
  double frame = 0;
  for (auto _ : state) {
    ozz::animation::SamplingJob job;
    job.animation = anim.get();
    job.context = &ctx;
    job.ratio = float(frame / duration);
    job.output = ozz::make_span(locals);
    if (!job.Run()) state.SkipWithError("ozz job failed");
    benchmark::DoNotOptimize(locals.data());
    benchmark::ClobberMemory();
    frame += 1.0 / double(state.range(1));
    if (frame > end) frame = 0;
  }
  // Accuracy against the per-track API in double at 200 frames: max |Δtranslation|, rotation angle.
  const auto ref = make_rig<double>(int(state.range(0)), keys, keys != inbetween_bench::rig_keys_per_channel);
  double worst_t = 0, worst_r = 0;
  for (int i = 0; i < 200; ++i) {
    const double f = end * i / 199.0;
    ozz::animation::SamplingJob job;
    job.animation = anim.get();
    job.context = &ctx;
    job.ratio = float(f / duration);
    job.output = ozz::make_span(locals);
    job.Run();
    for (std::size_t j = 0; j < rig.size(); ++j) {
      const auto& soa = locals[j / 4];
      const int lane = int(j % 4);
      float tx[4], ty[4], tz[4], qx[4], qy[4], qz[4], qw[4];
      ozz::math::StorePtrU(soa.translation.x, tx);
      ozz::math::StorePtrU(soa.translation.y, ty);
      ozz::math::StorePtrU(soa.translation.z, tz);
      ozz::math::StorePtrU(soa.rotation.x, qx);
      ozz::math::StorePtrU(soa.rotation.y, qy);
      ozz::math::StorePtrU(soa.rotation.z, qz);
      ozz::math::StorePtrU(soa.rotation.w, qw);
      const Vec3d t = ref[j].translation.sample(f);
      const Quatd r = ref[j].rotation.sample(f);
      worst_t = std::max({worst_t, std::abs(t.x - tx[lane]), std::abs(t.y - ty[lane]), std::abs(t.z - tz[lane])});
      worst_r = std::max(worst_r, double(angle_between(r, normalized(Quatd{qw[lane], qx[lane], qy[lane], qz[lane]}))));
    }
  }
  state.counters["max_dt"] = worst_t;
  state.counters["max_drot_rad"] = worst_r;
  state.counters["bytes"] = double(anim->size());
}

// sample_rig playing the same rig (T's rounding of its keys) the same way; bytes: RigClip::bytes().
template <class T>
void play_rig_clip(benchmark::State& state, int keys) {
  const auto rig = make_rig<T>(int(state.range(0)), keys, keys != inbetween_bench::rig_keys_per_channel);
  const auto clip = inbetween_bench::fixture_rig_clip(rig);
  const double end = rig_end(rig);
  RigClipCursor ctx = make_rig_clip_cursor(clip);
  std::vector<JointPose<T>> pose(clip.joints());
  double frame = 0;
  for (auto _ : state) {
    sample_rig(clip, T(frame), ctx, std::span<JointPose<T>>(pose));
    benchmark::DoNotOptimize(pose.data());
    benchmark::ClobberMemory();
    frame += 1.0 / double(state.range(1));
    if (frame > end) frame = 0;
  }
  const auto ref = make_rig<double>(int(state.range(0)), keys, keys != inbetween_bench::rig_keys_per_channel);
  double worst_t = 0, worst_r = 0;
  for (int i = 0; i < 200; ++i) {
    const double f = end * i / 199.0;
    sample_rig(clip, T(f), ctx, std::span<JointPose<T>>(pose));
    for (std::size_t j = 0; j < pose.size(); ++j) {
      const Vec3d t = ref[j].translation.sample(f);
      const Quatd r = ref[j].rotation.sample(f);
      worst_t = std::max({worst_t, std::abs(t.x - pose[j].translation.x), std::abs(t.y - pose[j].translation.y),
                          std::abs(t.z - pose[j].translation.z)});
      const Quatd q{double(pose[j].rotation.w), double(pose[j].rotation.x), double(pose[j].rotation.y),
                    double(pose[j].rotation.z)};
      worst_r = std::max(worst_r, double(angle_between(r, normalized(q))));
    }
  }
  state.counters["max_dt"] = worst_t;
  state.counters["max_drot_rad"] = worst_r;
  state.counters["bytes"] = double(clip.bytes());
}

// The 30-key rig of bench/ (issue 12) and the long clip of issue 24 (10 s at 31 keys/s: 310 keys
// per channel on the integer frames, rig_fixture.hpp; at 1 024 joints larger than L2 on both sides).
void BM_OzzSamplingJob(benchmark::State& state) { play_ozz(state, inbetween_bench::rig_keys_per_channel); }
template <class T>
void BM_InbetweenRigClip(benchmark::State& state) {
  play_rig_clip<T>(state, inbetween_bench::rig_keys_per_channel);
}
void BM_OzzLongClip(benchmark::State& state) { play_ozz(state, inbetween_bench::rig_long_keys_per_channel); }
template <class T>
void BM_RigClipLong(benchmark::State& state) {
  play_rig_clip<T>(state, inbetween_bench::rig_long_keys_per_channel);
}

// Args: joints, calls per key interval (2: half a frame per call as bench/tracks_bench.cpp; 8: an
// eighth, i.e. 60 Hz playback of keys about 7.5 Hz apart).
#define RIG_ARGS ->ArgsProduct({{25, 64, 71, 551, 1024}, {2, 8}})
BENCHMARK(BM_OzzSamplingJob) RIG_ARGS;
BENCHMARK(BM_InbetweenRigClip<float>) RIG_ARGS;
BENCHMARK(BM_InbetweenRigClip<double>) RIG_ARGS;
#define RIG_LONG_ARGS ->ArgsProduct({{64, 1024}, {2, 8}})
BENCHMARK(BM_OzzLongClip) RIG_LONG_ARGS;
BENCHMARK(BM_RigClipLong<float>) RIG_LONG_ARGS;
BENCHMARK(BM_RigClipLong<double>) RIG_LONG_ARGS;
BENCHMARK_MAIN();
