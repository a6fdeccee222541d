// Issue 12: inbetween's RigClip against ozz-animation's SamplingJob on the same clip, in one
// binary.  Not part of the CMake build (ozz is not packaged by Debian): bench/RESULTS.md says how
// to build ozz out of tree and compile this file against it.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <span>
#include <vector>

#include "inbetween/tracks/runtime/rig_clip.hpp"
#include "ozz/animation/offline/animation_builder.h"
#include "ozz/animation/offline/raw_animation.h"
#include "ozz/animation/runtime/animation.h"
#include "ozz/animation/runtime/sampling_job.h"
#include "ozz/base/maths/simd_math.h"
#include "ozz/base/maths/soa_transform.h"

using namespace inbetween;

// The rig of bench/tracks_bench.cpp (make_rig): same seed and draws, built in T.
template <class T>
struct Rig {
  std::vector<Track<Vec3<T>>> t, s;
  std::vector<QuatTrack<T>> r;
  double end = 1e300, duration = 0;
};
template <class T>
Rig<T> make_rig(int joints) {
  std::mt19937_64 rng(1212);
  std::uniform_real_distribution<double> d(-1, 1), step(0.5, 1.5);
  Rig<T> rig;
  for (int j = 0; j < joints; ++j) {
    std::vector<TrackKey<Vec3<T>>> tk, sk;
    std::vector<QuatKey<T>> rk;
    double f = 0;
    for (int k = 0; k < 30; ++k) {
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
      r.value = Quat<T>{T(qd.w), T(qd.x), T(qd.y), T(qd.z)};
      r.interpolation = QuatInterpolation::slerp;
      rk.push_back(r);
      f += step(rng);
    }
    rig.t.push_back(*build_track(tk));
    rig.s.push_back(*build_track(sk));
    rig.r.push_back(*build_quat_track(rk));
    rig.end = std::min({rig.end, double(rig.t.back().frames().back())});
    rig.duration = std::max(rig.duration, double(rig.t.back().frames().back()));
  }
  return rig;
}

ozz::unique_ptr<ozz::animation::Animation> make_ozz(const Rig<float>& rig) {
  ozz::animation::offline::RawAnimation raw;
  raw.duration = float(rig.duration);
  raw.tracks.resize(rig.t.size());
  for (std::size_t j = 0; j < rig.t.size(); ++j) {
    auto& tr = raw.tracks[j];
    const auto f = rig.t[j].frames();
    for (std::size_t k = 0; k < f.size(); ++k) {
      const Vec3f v = rig.t[j].values()[k], s = rig.s[j].values()[k];
      const Quatf q = rig.r[j].keys()[k];
      tr.translations.push_back({f[k], ozz::math::Float3(v.x, v.y, v.z)});
      tr.scales.push_back({f[k], ozz::math::Float3(s.x, s.y, s.z)});
      tr.rotations.push_back({f[k], ozz::math::Quaternion(q.x, q.y, q.z, q.w)});
    }
  }
  ozz::animation::offline::AnimationBuilder builder;
  return builder(raw);
}

void BM_OzzSamplingJob(benchmark::State& state) {
  const auto rig = make_rig<float>(int(state.range(0)));
  const auto anim = make_ozz(rig);
  ozz::animation::SamplingJob::Context ctx(anim->num_tracks());
  std::vector<ozz::math::SoaTransform> locals(std::size_t(anim->num_soa_tracks()));
  double frame = 0;
  for (auto _ : state) {
    ozz::animation::SamplingJob job;
    job.animation = anim.get();
    job.context = &ctx;
    job.ratio = float(frame / rig.duration);
    job.output = ozz::make_span(locals);
    if (!job.Run()) state.SkipWithError("ozz job failed");
    benchmark::DoNotOptimize(locals.data());
    benchmark::ClobberMemory();
    frame += 1.0 / double(state.range(1));
    if (frame > rig.end) frame = 0;
  }
  // Accuracy against the per-track API in double at 200 frames: max |Δtranslation|, rotation angle.
  const auto ref = make_rig<double>(int(state.range(0)));
  double worst_t = 0, worst_r = 0;
  for (int i = 0; i < 200; ++i) {
    const double f = rig.end * i / 199.0;
    ozz::animation::SamplingJob job;
    job.animation = anim.get();
    job.context = &ctx;
    job.ratio = float(f / rig.duration);
    job.output = ozz::make_span(locals);
    job.Run();
    for (std::size_t j = 0; j < rig.t.size(); ++j) {
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
      const Vec3d t = ref.t[j].sample(f);
      const Quatd r = ref.r[j].sample(f);
      worst_t = std::max({worst_t, std::abs(t.x - tx[lane]), std::abs(t.y - ty[lane]), std::abs(t.z - tz[lane])});
      worst_r = std::max(worst_r, double(angle_between(r, normalized(Quatd{qw[lane], qx[lane], qy[lane], qz[lane]}))));
    }
  }
  state.counters["max_dt"] = worst_t;
  state.counters["max_drot_rad"] = worst_r;
}

template <class T>
void BM_InbetweenRigClip(benchmark::State& state) {
  const auto rig = make_rig<T>(int(state.range(0)));
  const auto clip = build_rig_clip<T>(rig.t, rig.r, rig.s).value();
  RigContext ctx = make_rig_context(clip);
  std::vector<JointPose<T>> pose(clip.joints());
  double frame = 0;
  for (auto _ : state) {
    sample_rig(clip, T(frame), ctx, std::span<JointPose<T>>(pose));
    benchmark::DoNotOptimize(pose.data());
    benchmark::ClobberMemory();
    frame += 1.0 / double(state.range(1));
    if (frame > rig.end) frame = 0;
  }
  const auto ref = make_rig<double>(int(state.range(0)));
  double worst_t = 0, worst_r = 0;
  for (int i = 0; i < 200; ++i) {
    const double f = rig.end * i / 199.0;
    sample_rig(clip, T(f), ctx, std::span<JointPose<T>>(pose));
    for (std::size_t j = 0; j < pose.size(); ++j) {
      const Vec3d t = ref.t[j].sample(f);
      const Quatd r = ref.r[j].sample(f);
      worst_t = std::max({worst_t, std::abs(t.x - pose[j].translation.x), std::abs(t.y - pose[j].translation.y),
                          std::abs(t.z - pose[j].translation.z)});
      const Quatd q{double(pose[j].rotation.w), double(pose[j].rotation.x), double(pose[j].rotation.y),
                    double(pose[j].rotation.z)};
      worst_r = std::max(worst_r, double(angle_between(r, normalized(q))));
    }
  }
  state.counters["max_dt"] = worst_t;
  state.counters["max_drot_rad"] = worst_r;
}

// Args: joints, calls per key interval (2: half a frame per call as bench/tracks_bench.cpp; 8: an
// eighth, i.e. 60 Hz playback of keys about 7.5 Hz apart).
#define RIG_ARGS ->ArgsProduct({{25, 64, 71, 551, 1024}, {2, 8}})
BENCHMARK(BM_OzzSamplingJob) RIG_ARGS;
BENCHMARK(BM_InbetweenRigClip<float>) RIG_ARGS;
BENCHMARK(BM_InbetweenRigClip<double>) RIG_ARGS;
BENCHMARK_MAIN();
