// Issue 24, "the uncompressed RigClip gets the compact layout where it pays": sample_rig on the
// long clip of bench/rig_fixture.hpp (10 s at 31 keys/s: 310 keys per channel, every channel keyed
// on the same frames, as a sampled BVH or glTF clip is), 64 and 1 024 joints, ½ and ⅛ key interval
// per call, played forwards and wrapping to 0.  At 1 024 joints the clip is larger than L2, so the
// refresh streams it from L3 or memory: the bytes it reads per key decide the time.  Counters:
// bytes (RigClip::bytes()), raw_bytes (the keys as float32 / float64 values and frames: 3 + 4 + 3
// values and one frame per joint and key, the reference size a compact layout is measured against)
// and bytes_per_key (bytes per joint and key).  ozz-animation's SamplingJob on the same clip:
// `make bench-ozz` (tools/bench/ozz_rig_bench.cpp, BM_OzzLongClip / BM_RigClipLong), out of tree.
#include <benchmark/benchmark.h>

#include <span>
#include <vector>

#include "inbetween/tracks/runtime/rig_clip.hpp"
#include "rig_fixture.hpp"

using namespace inbetween;
using inbetween_bench::make_rig;
using inbetween_bench::rig_end;
using inbetween_bench::rig_long_keys_per_channel;

template <class T>
void BM_RigLongClip(benchmark::State& state) {
  const int joints = int(state.range(0));
  const auto rig = make_rig<T>(joints, rig_long_keys_per_channel, true);
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
  const double keys = double(joints) * rig_long_keys_per_channel;
  state.counters["bytes"] = double(clip.bytes());
  state.counters["raw_bytes"] = keys * 11 * sizeof(T);
  state.counters["bytes_per_key"] = double(clip.bytes()) / keys;
}

// Args: joints, calls per key interval (2: half a key interval per call; 8: an eighth, 60 Hz
// playback of keys 7.5 Hz apart).
#define RIG_LONG_ARGS ->ArgsProduct({{64, 1024}, {2, 8}})
BENCHMARK(BM_RigLongClip<float>) RIG_LONG_ARGS;
BENCHMARK(BM_RigLongClip<double>) RIG_LONG_ARGS;
BENCHMARK_MAIN();
