// Sequential playback of keyframed tracks: with a TrackCursor the per-sample cost should not grow
// with the number of keys (the cursor moves at most one segment per sample); without it every
// sample is a binary search, O(log n).  Peers side by side: cursor, no cursor, Blender F-curve.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <optional>
#include <utility>
#include <random>
#include <span>
#include <vector>

#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/runtime/fcurve_clip.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"
#include "inbetween/tracks/track.hpp"
#include "rig_fixture.hpp"
#include "rig_lanes.hpp"

namespace {

using namespace inbetween;

Track<Vec3d> make_track(int keys) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> v(-5, 5);
  std::vector<TrackKey<Vec3d>> raw;
  for (int i = 0; i < keys; ++i) {
    TrackKey<Vec3d> k;
    k.frame = double(i);
    k.value = Vec3d{v(rng), v(rng), v(rng)};
    raw.push_back(k);
  }
  return std::move(build_track(raw)).value();
}

// Playback at 4 samples per key over the whole track, repeated.
void BM_TrackSequentialCursor(benchmark::State& state) {
  const int keys = int(state.range(0));
  const Track<Vec3d> tr = make_track(keys);
  const double step = 0.25, end = double(keys - 1);
  double t = 0;
  TrackCursor cursor;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tr.sample(t, cursor));
    t += step;
    if (t > end) t = 0;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TrackSequentialCursor)->RangeMultiplier(16)->Range(16, 1 << 20);

void BM_TrackSequentialNoCursor(benchmark::State& state) {
  const int keys = int(state.range(0));
  const Track<Vec3d> tr = make_track(keys);
  const double step = 0.25, end = double(keys - 1);
  double t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tr.sample(t));
    t += step;
    if (t > end) t = 0;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TrackSequentialNoCursor)->RangeMultiplier(16)->Range(16, 1 << 20);

// Batch form: one call fills a span of 1024 frames.
void BM_TrackBatch1024(benchmark::State& state) {
  const int keys = int(state.range(0));
  const Track<Vec3d> tr = make_track(keys);
  std::vector<double> frames(1024);
  std::vector<Vec3d> out(1024);
  double t = 0;
  TrackCursor cursor;
  for (auto _ : state) {
    for (auto& f : frames) {
      f = t;
      t += 0.25;
      if (t > double(keys - 1)) t = 0;
    }
    tr.sample(frames, out, cursor);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * 1024);
}
BENCHMARK(BM_TrackBatch1024)->RangeMultiplier(16)->Range(16, 1 << 20);

// Orientation playback: Bézier quaternion spline (six slerps per sample) with a cursor.
void BM_QuatTrackBezierCursor(benchmark::State& state) {
  const int keys = int(state.range(0));
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::vector<QuatKey<double>> raw;
  for (int i = 0; i < keys; ++i) {
    QuatKey<double> k;
    k.frame = double(i);
    k.value = normalized(Quatd::from_wxyz(g(rng), g(rng), g(rng), g(rng)));
    k.interpolation = QuatInterpolation::bezier;
    raw.push_back(k);
  }
  const QuatTrack<double> tr = std::move(build_quat_track(raw)).value();
  double t = 0;
  TrackCursor cursor;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tr.sample(t, cursor));
    t += 0.25;
    if (t > double(keys - 1)) t = 0;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QuatTrackBezierCursor)->RangeMultiplier(16)->Range(16, 1 << 16);

FCurve make_fcurve(int keys) {
  RawFCurve raw{.auto_smoothing = AutoSmoothing::cont_accel};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> v(-5, 5);
  for (int i = 0; i < keys; ++i) {
    FCurveKey k;
    k.frame = double(i);
    k.value = v(rng);
    raw.keys.push_back(k);
  }
  return std::move(build_fcurve(raw)).value();
}

// Blender-compatible F-curve with a cursor (same values as Blender's search).
void BM_FCurveSequentialCursor(benchmark::State& state) {
  const int keys = int(state.range(0));
  const FCurve c = make_fcurve(keys);
  float t = 0.125f;
  TrackCursor cursor;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.sample(t, cursor));
    t += 0.25f;
    if (t > float(keys - 1)) t = 0.125f;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FCurveSequentialCursor)->RangeMultiplier(16)->Range(16, 1 << 16);

// Blender-compatible F-curve (binary search per sample, as Blender does).
void BM_FCurveSequential(benchmark::State& state) {
  const int keys = int(state.range(0));
  RawFCurve raw{.auto_smoothing = AutoSmoothing::cont_accel};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> v(-5, 5);
  for (int i = 0; i < keys; ++i) {
    FCurveKey k;
    k.frame = double(i);
    k.value = v(rng);
    raw.keys.push_back(k);
  }
  const FCurve c = std::move(build_fcurve(raw)).value();
  float t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c.sample(t));
    t += 0.25f;
    if (t > float(keys - 1)) t = 0;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FCurveSequential)->RangeMultiplier(16)->Range(16, 1 << 16);


// ---------------------------------------------------------------- whole rigs (issue 12)
// A character rig of J joints, each with translation and scale Track<Vec3<T>> (linear keys) and a
// QuatTrack (slerp keys), 30 keys per channel at uneven frames (spacing uniform in [0.5, 1.5], so
// about 1 frame), played back sequentially, every joint's three cursors kept.  Second argument:
// calls per frame — 2 (half a key interval per call, as before) or 8 (60 Hz playback of keys
// ~7.5 Hz apart: most calls change no key).  Reported per character (one iteration); divide by J
// for a joint, compare with a game's 1 ms animation budget per frame.  Floor: a plain read of the
// same bytes the sampling touches (the two bracketing keys' frames and values of every channel,
// found with the same cursors), in the same scalar type, so runtime / floor shows how far
// sampling is from memory-bound.  BM_RigPerTrack: one Track/QuatTrack::sample per channel (the
// scalar reference API); BM_RigRuntime: the same tracks compiled by build_rig_clip, one
// sample_rig call per character.  The rig is bench/rig_fixture.hpp's make_rig, which
// tools/bench/ozz_rig_bench.cpp (`make bench-ozz`) also gives to ozz-animation's SamplingJob.
using inbetween_bench::make_rig;
using inbetween_bench::rig_end;

template <class T>
void BM_RigPerTrack(benchmark::State& state) {
  const auto rig = make_rig<T>(int(state.range(0)));
  const double end = rig_end(rig), step = 1.0 / double(state.range(1));
  std::vector<TrackCursor> cursors(rig.size() * 3);
  std::vector<Vec3<T>> t(rig.size()), sc(rig.size());
  std::vector<Quat<T>> r(rig.size());
  double frame = 0;
  for (auto _ : state) {
    for (std::size_t j = 0; j < rig.size(); ++j) {
      t[j] = rig[j].translation.sample(T(frame), cursors[3 * j]);
      r[j] = rig[j].rotation.sample(T(frame), cursors[3 * j + 1]);
      sc[j] = rig[j].scale.sample(T(frame), cursors[3 * j + 2]);
    }
    benchmark::DoNotOptimize(t.data());
    benchmark::DoNotOptimize(r.data());
    benchmark::DoNotOptimize(sc.data());
    benchmark::ClobberMemory();
    frame += step;
    if (frame > end) frame = 0;
  }
}

template <class T>
void BM_RigMemoryFloor(benchmark::State& state) {
  const auto rig = make_rig<T>(int(state.range(0)));
  const double end = rig_end(rig), step = 1.0 / double(state.range(1));
  std::vector<std::size_t> seg(rig.size() * 3, 0);
  double frame = 0;
  for (auto _ : state) {
    T acc = 0;
    const T f = T(frame);
    for (std::size_t j = 0; j < rig.size(); ++j) {
      // Same bytes as sampling: both bracketing keys' frame and value, per channel.
      const auto read = [&](std::span<const T> frames, auto values, std::size_t& i) {
        while (i + 2 < frames.size() && frames[i + 1] <= f) ++i;
        if (f < frames[i]) i = 0;
        const auto& a = values[i];
        const auto& b = values[i + 1];
        const T* pa = reinterpret_cast<const T*>(&a);
        const T* pb = reinterpret_cast<const T*>(&b);
        T sum = frames[i] + frames[i + 1];
        for (std::size_t c = 0; c < sizeof(a) / sizeof(T); ++c) sum += pa[c] + pb[c];
        return sum;
      };
      acc += read(rig[j].translation.frames(), rig[j].translation.values(), seg[3 * j]);
      acc += read(rig[j].rotation.frames(), rig[j].rotation.keys(), seg[3 * j + 1]);
      acc += read(rig[j].scale.frames(), rig[j].scale.values(), seg[3 * j + 2]);
    }
    benchmark::DoNotOptimize(acc);
    frame += step;
    if (frame > end) frame = 0;
  }
}

template <class T>
void BM_RigRuntime(benchmark::State& state) {
  const auto rig = make_rig<T>(int(state.range(0)));
  const auto clip = inbetween_bench::fixture_rig_clip(rig);
  const double end = rig_end(rig), step = 1.0 / double(state.range(1));
  RigClipCursor ctx = make_rig_clip_cursor(clip);
  std::vector<JointPose<T>> pose(rig.size());
  double frame = 0;
  for (auto _ : state) {
    sample_rig(clip, T(frame), ctx, std::span<JointPose<T>>(pose));
    benchmark::DoNotOptimize(pose.data());
    benchmark::ClobberMemory();
    frame += step;
    if (frame > end) frame = 0;
  }
}

// The same rig as Blender F-curves: 10 Bézier curves per joint (location xyz, rotation_quaternion
// wxyz, scale xyz) through the same keys (auto-clamped handles, Blender's default).  Per-curve: one
// FCurve::sample(frame, cursor) per curve (Blender's root-finding evaluation, with a cursor) and
// the quaternion normalised, as Blender does; runtime: build_fcurve_rig + sample_fcurve_rig.
// The rig's keys as 10 F-curves per joint; `frame_of(joint's key frames, i)` places key i, and
// `cycles_of(k)` gives curve k of a joint its Cycles modifier (none when it returns nullopt).
template <class FrameOf, class CyclesOf>
std::vector<FCurve> rig_fcurves(int joints, FrameOf frame_of, CyclesOf cycles_of) {
  const auto rig = make_rig<float>(joints);
  std::vector<FCurve> curves;
  for (const auto& j : rig) {
    const auto f = j.translation.frames();
    for (int k = 0; k < 10; ++k) {
      RawFCurve raw;
      for (std::size_t i = 0; i < f.size(); ++i) {
        const Vec3f t = j.translation.values()[i], s = j.scale.values()[i];
        const Quatf q = j.rotation.keys()[i];
        const float v[10] = {t.x, t.y, t.z, q.w, q.x, q.y, q.z, s.x, s.y, s.z};
        FCurveKey key;
        key.frame = frame_of(f, i);
        key.value = v[k];
        raw.keys.push_back(key);
      }
      if (const std::optional<FCurveCycles> c = cycles_of(k)) raw.modifiers = {FCurveModifier{.kind = *c}};
      curves.push_back(build_fcurve(raw).value());
    }
  }
  return curves;
}

std::vector<FCurve> make_fcurve_rig(int joints) {
  return rig_fcurves(
      joints, [](auto f, std::size_t i) { return double(f[i]); },
      [](int) { return std::optional<FCurveCycles>{}; });
}

void BM_RigFCurvePerCurve(benchmark::State& state) {
  const int joints = int(state.range(0));
  const auto curves = make_fcurve_rig(joints);
  const double end = rig_end(make_rig<float>(joints)), step = 1.0 / double(state.range(1));
  std::vector<TrackCursor> cursors(curves.size());
  std::vector<JointPose<float>> pose(static_cast<std::size_t>(joints));
  double frame = 0;
  for (auto _ : state) {
    const float f = float(frame);
    for (std::size_t j = 0; j < pose.size(); ++j) {
      float v[10];
      for (std::size_t k = 0; k < 10; ++k) v[k] = curves[10 * j + k].sample(f, cursors[10 * j + k]);
      pose[j].translation = {v[0], v[1], v[2]};
      pose[j].rotation = normalized(Quatf::from_wxyz(v[3], v[4], v[5], v[6]));
      pose[j].scale = {v[7], v[8], v[9]};
    }
    benchmark::DoNotOptimize(pose.data());
    benchmark::ClobberMemory();
    frame += step;
    if (frame > end) frame = 0;
  }
}

// Compiling 10·J curves fits every segment against FCurve::sample (seconds at 1024 joints): built
// once per rig size and kept for the repetitions.
const FCurveClip& fcurve_rig_clip(int joints) {
  static std::map<int, FCurveClip> clips;
  auto it = clips.find(joints);
  if (it == clips.end()) it = clips.emplace(joints, build_fcurve_rig(make_fcurve_rig(joints)).value()).first;
  return it->second;
}

// Sequential playback of an F-curve rig clip from frame 0 to `end` in `step`s, wrapping to 0 (one
// sample_fcurve_rig per iteration); counter pieces_per_curve.
void play_fcurve_rig(benchmark::State& state, const FCurveClip& clip, double end, double step) {
  auto ctx = make_fcurve_clip_cursor(clip);
  std::vector<JointPose<float>> pose(clip.joints());
  double frame = 0;
  for (auto _ : state) {
    sample_fcurve_rig(clip, float(frame), ctx, std::span<JointPose<float>>(pose));
    benchmark::DoNotOptimize(pose.data());
    benchmark::ClobberMemory();
    frame += step;
    if (frame > end) frame = 0;
  }
  state.counters["pieces_per_curve"] = double(clip.pieces()) / double(clip.channels());
}

void BM_RigFCurveRuntime(benchmark::State& state) {
  const int joints = int(state.range(0));
  const FCurveClip& clip = fcurve_rig_clip(joints);
  const double end = rig_end(make_rig<float>(joints)), step = 1.0 / double(state.range(1));
  play_fcurve_rig(state, clip, end, step);
  state.counters["max_fit_error"] = double(clip.max_fit_error());
}

// The same rig as walk cycles: every curve with a Cycles modifier (location x y z repeat with
// offset after the keys, as a walking root moves on; every other curve repeat; repeat before),
// played from the first key through three more copies (frames 0 … 4·end) with the same steps, so
// three quarters of the samples fold the frame into the keyed range.  Compare with
// BM_RigFCurveRuntime (the same keys without cycles, frames 0 … end).  Third argument 0: exactly
// those keys — every joint keyed at its own random frames, so every joint has its own cycle (its
// own cycle class: the worst case for the runtime, which shares one folded local frame and one
// piece stream per class); 1: each joint's key frames scaled to end at the rig's last frame, so
// all joints share one cycle, as a character's walk cycle keyed over one frame range does.
std::vector<FCurve> make_cycling_fcurve_rig(int joints, bool shared) {
  const double end = rig_end(make_rig<float>(joints));
  return rig_fcurves(
      joints,
      [&](auto f, std::size_t i) {
        const double stretch = shared ? end / double(f.back()) : 1.0;
        return i + 1 == f.size() && shared ? end : double(f[i]) * stretch;
      },
      [](int k) {
        return std::optional<FCurveCycles>{
            FCurveCycles{.before = CycleMode::repeat, .after = k < 3 ? CycleMode::repeat_offset : CycleMode::repeat}};
      });
}

void BM_RigFCurveRuntimeCyclic(benchmark::State& state) {
  const int joints = int(state.range(0));
  const bool shared = state.range(2) != 0;
  static std::map<std::pair<int, bool>, FCurveClip> clips;
  auto it = clips.find({joints, shared});
  if (it == clips.end())
    it = clips.emplace(std::pair{joints, shared}, build_fcurve_rig(make_cycling_fcurve_rig(joints, shared)).value()).first;
  const FCurveClip& clip = it->second;
  const double end = 4 * rig_end(make_rig<float>(joints)), step = 1.0 / double(state.range(1));
  play_fcurve_rig(state, clip, end, step);
  state.counters["cycle_classes"] = double(clip.cycle_classes());
}

// ---------------------------------------------------------------- which SIMD library (issue 12)
// The runtime's lane arithmetic in std::experimental::simd (rig_detail::StdSimdLanes: sample_rig's
// float kernel), in xsimd (bench/rig_lanes/) and in Highway (src/tracks/rig_lanes_hwy.cpp): static
// target (the build's baseline) and dynamic dispatch (the best target of this CPU: sample_rig's
// double kernel; also limited to AVX2, a machine without AVX-512), on the BM_RigRuntime clips.
// Everything but the lane arithmetic is shared (refresh, group loop, AoS write), so the ratio of
// two BM_RigKernel times is the kernels' difference per character.
// Counter max_abs_diff: largest difference of any pose component from sample_rig over one pass
// of the benchmark's frames (0 when bit-identical; FMA contraction makes a few ulp); the label
// names the Highway target that ran.  RigKernel::none runs everything but the lane arithmetic
// (its lanes write zeros): what no SIMD library can speed up, measured.
enum class RigKernel { none, std_simd, xsimd, hwy_static, hwy_dynamic, hwy_dynamic_avx2 };

// (whole registers of zeros, as many stores into res as StdSimdLanes makes, no loads, no arithmetic).
template <class T>
struct ZeroLanes {
  void operator()(const T*, const T*, const T*, T, std::size_t n, T (*res)[rig_group<T>]) const noexcept {
    using V = std::experimental::native_simd<T>;
    for (std::size_t s = 0; s < n; s += V::size())
      for (std::size_t r = 0; r < 10; ++r) V(T(0)).copy_to(res[r] + s, std::experimental::vector_aligned);
  }
};

template <class T, RigKernel K>
void BM_RigKernel(benchmark::State& state) {
  const auto rig = make_rig<T>(int(state.range(0)));
  const auto clip = inbetween_bench::fixture_rig_clip(rig);
  const double end = rig_end(rig), step = 1.0 / double(state.range(1));
  bench_rig::hwy_limit_to_avx2(K == RigKernel::hwy_dynamic_avx2);
  const auto sample = [&](T frame, RigClipCursor<T>& ctx, std::span<JointPose<T>> out) {
    if constexpr (K == RigKernel::none) bench_rig::sample_rig_with(clip, frame, ctx, out, ZeroLanes<T>{});
    else if constexpr (K == RigKernel::std_simd) bench_rig::sample_rig_with(clip, frame, ctx, out, rig_detail::StdSimdLanes<T>{});
    else if constexpr (K == RigKernel::xsimd) bench_rig::sample_rig_with(clip, frame, ctx, out, bench_rig::XsimdLanes<T>{});
    else if constexpr (K == RigKernel::hwy_static) bench_rig::sample_rig_with(clip, frame, ctx, out, bench_rig::HwyStaticLanes<T>{});
    else bench_rig::sample_rig_with(clip, frame, ctx, out, bench_rig::HwyDynamicLanes<T>{});
  };
  std::vector<JointPose<T>> pose(rig.size()), ref(rig.size());
  double diff = 0;
  if (K != RigKernel::none) {
    RigClipCursor ref_ctx = make_rig_clip_cursor(clip), ctx = make_rig_clip_cursor(clip);
    for (double frame = 0; frame <= end; frame += step) {
      sample_rig(clip, T(frame), ref_ctx, std::span<JointPose<T>>(ref));
      sample(T(frame), ctx, std::span<JointPose<T>>(pose));
      for (std::size_t j = 0; j < pose.size(); ++j) {
        const T* a = &pose[j].translation.x;
        const T* b = &ref[j].translation.x;
        for (std::size_t c = 0; c < sizeof(JointPose<T>) / sizeof(T); ++c) diff = std::max(diff, double(std::abs(a[c] - b[c])));
      }
    }
  }
  RigClipCursor ctx = make_rig_clip_cursor(clip);
  double frame = 0;
  for (auto _ : state) {
    sample(T(frame), ctx, std::span<JointPose<T>>(pose));
    benchmark::DoNotOptimize(pose.data());
    benchmark::ClobberMemory();
    frame += step;
    if (frame > end) frame = 0;
  }
  if (K != RigKernel::none) state.counters["max_abs_diff"] = diff;
  if constexpr (K == RigKernel::none) state.SetLabel("refresh and AoS write only");
  else if constexpr (K == RigKernel::std_simd) state.SetLabel("std::experimental::simd");
  else if constexpr (K == RigKernel::xsimd) state.SetLabel("xsimd");
  else if constexpr (K == RigKernel::hwy_static) state.SetLabel(bench_rig::hwy_static_target());
  else state.SetLabel(bench_rig::hwy_dynamic_target());
  bench_rig::hwy_limit_to_avx2(false);
}

#define RIG_ARGS ->ArgsProduct({{25, 64, 71, 551, 1024}, {2, 8}})
BENCHMARK(BM_RigPerTrack<float>) RIG_ARGS;
BENCHMARK(BM_RigPerTrack<double>) RIG_ARGS;
BENCHMARK(BM_RigMemoryFloor<float>) RIG_ARGS;
BENCHMARK(BM_RigMemoryFloor<double>) RIG_ARGS;
BENCHMARK(BM_RigRuntime<float>) RIG_ARGS;
BENCHMARK(BM_RigRuntime<double>) RIG_ARGS;
BENCHMARK(BM_RigFCurvePerCurve) RIG_ARGS;
BENCHMARK(BM_RigFCurveRuntime) RIG_ARGS;
BENCHMARK(BM_RigFCurveRuntimeCyclic)->ArgsProduct({{25, 64, 71, 551, 1024}, {2, 8}, {0, 1}});
BENCHMARK(BM_RigKernel<float, RigKernel::none>) RIG_ARGS;
BENCHMARK(BM_RigKernel<float, RigKernel::std_simd>) RIG_ARGS;
BENCHMARK(BM_RigKernel<float, RigKernel::xsimd>) RIG_ARGS;
BENCHMARK(BM_RigKernel<float, RigKernel::hwy_static>) RIG_ARGS;
BENCHMARK(BM_RigKernel<float, RigKernel::hwy_dynamic>) RIG_ARGS;
BENCHMARK(BM_RigKernel<float, RigKernel::hwy_dynamic_avx2>) RIG_ARGS;
BENCHMARK(BM_RigKernel<double, RigKernel::none>) RIG_ARGS;
BENCHMARK(BM_RigKernel<double, RigKernel::std_simd>) RIG_ARGS;
BENCHMARK(BM_RigKernel<double, RigKernel::xsimd>) RIG_ARGS;
BENCHMARK(BM_RigKernel<double, RigKernel::hwy_static>) RIG_ARGS;
BENCHMARK(BM_RigKernel<double, RigKernel::hwy_dynamic>) RIG_ARGS;
BENCHMARK(BM_RigKernel<double, RigKernel::hwy_dynamic_avx2>) RIG_ARGS;
}  // namespace

BENCHMARK_MAIN();
