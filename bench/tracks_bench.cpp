// Sequential playback of keyframed tracks: with a TrackCursor the per-sample cost should not grow
// with the number of keys (the cursor moves at most one segment per sample); without it every
// sample is a binary search, O(log n).  Peers side by side: cursor, no cursor, Blender F-curve.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

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
    benchmark::DoNotOptimize(c.evaluate(t, cursor));
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
    benchmark::DoNotOptimize(c.evaluate(t));
    t += 0.25f;
    if (t > float(keys - 1)) t = 0;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FCurveSequential)->RangeMultiplier(16)->Range(16, 1 << 16);

}  // namespace

BENCHMARK_MAIN();
