// Scene building: the cost of build_scene's checks as the scene grows.  Name checks are one
// ordered lookup per name (they were pairwise before: 2^16 glTF weight tracks took 16 s);
// Google Benchmark fits the growth (`BigO` row: expect N log N, or N where the lookups are cheap
// beside the rest of the build).  Timings live here, not in the tests (tests/scene checks the
// messages and places of duplicate names at these sizes).
#include <benchmark/benchmark.h>

#include <string>

#include "inbetween/scene/camera_view.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"

namespace {
using namespace inbetween;

/// N scalar tracks of one key and N objects, all names distinct.
RawScene many_names(std::size_t n) {
  RawScene raw;
  for (std::size_t i = 0; i < n; ++i) {
    RawScalarTrack t;
    t.name = "t" + std::to_string(i);
    t.curve.keys.push_back(FCurveKey{.frame = 0, .value = double(i)});
    raw.tracks.push_back(std::move(t));
    RawObject o;
    o.name = "o" + std::to_string(i);
    raw.objects.push_back(std::move(o));
  }
  return raw;
}

void BM_BuildSceneNames(benchmark::State& state) {
  const RawScene raw = many_names(std::size_t(state.range(0)));
  for (auto _ : state) {
    auto built = build_scene(raw);
    benchmark::DoNotOptimize(built);
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_BuildSceneNames)->RangeMultiplier(4)->Range(1 << 9, 1 << 15)->Unit(benchmark::kMillisecond)->Complexity();

/// A hold-then-move camera view over N target names.
void BM_BuildCameraHoldTargets(benchmark::State& state) {
  RawHoldThenMove<double> hold;
  for (std::int64_t i = 0; i < state.range(0); ++i)
    hold.segments.push_back({.target = "o" + std::to_string(i), .hold_until = double(i)});
  const RawCameraViewd view{.coi = hold};
  for (auto _ : state) {
    auto built = build_camera_view(view);
    benchmark::DoNotOptimize(built);
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_BuildCameraHoldTargets)->RangeMultiplier(4)->Range(1 << 11, 1 << 17)->Unit(benchmark::kMillisecond)->Complexity();

}  // namespace

BENCHMARK_MAIN();
