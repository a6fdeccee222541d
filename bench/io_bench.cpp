// Reading real files (issue 20, "Speed"): CMU motion capture 01_03.bvh (Debian assimp-testmodels,
// 4 511 frames, 31 joints, 3.4 MB) read and baked in world space, every frame and every joint's
// 10 columns (translation, rotation, scale), the way `inbetween bake` does it: read_input_file +
// build_scene + Scene::sample into one preallocated row.  The peer is three.js's BVHLoader +
// AnimationMixer + matrixWorld.decompose doing the same work in Node
// (tools/bench/bvh_threejs.mjs); `make bench` (tools/bench/write_results.py) puts the two side by
// side in bench/RESULTS.md against the target of ≥ 10×.  The parts (read, build, sample)
// are timed alone so the table can say where the time goes.  Each benchmark skips with a message
// when the clip is not installed or no BVH reader answers (read_input_file's Unsupported).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "inbetween/io/input.hpp"
#include "inbetween/scene/scene.hpp"

namespace {
using namespace inbetween;

const std::filesystem::path kClip = "/usr/share/assimp/models/BVH/01_03.bvh";

/// Why the clip cannot be benchmarked, or nothing when it can.
std::optional<std::string> unavailable() {
  if (!std::filesystem::exists(kClip)) return kClip.string() + " is not installed (Debian assimp-testmodels)";
  Expected<RawScene> raw = read_input_file(kClip);
  if (!raw) return "read_input_file: " + raw.error().message;
  if (!build_scene(*raw)) return "build_scene failed on " + kClip.string();
  return std::nullopt;
}

void set_counters(benchmark::State& state, const Scene& scene) {
  state.counters["frames"] = scene.range_end() - scene.range_start() + 1;
  state.counters["joints"] = double(scene.objects().size());
  state.counters["columns"] = double(scene.columns().size());
}

/// Samples every frame of the default range into `row` (the bake loop without the text output).
void bake_world(const Scene& scene, std::vector<double>& row) {
  for (double f = scene.range_start(); f <= scene.range_end(); f += 1) {
    scene.sample(f, row);
    benchmark::DoNotOptimize(row.data());
    benchmark::ClobberMemory();
  }
}

/// The whole job: file → RawScene → Scene → every frame's world TRS of every joint.
void BM_BvhReadBakeWorld(benchmark::State& state) {
  if (auto why = unavailable()) return state.SkipWithError(why->c_str());
  std::optional<Scene> last;
  for (auto _ : state) {
    Expected<RawScene> raw = read_input_file(kClip);
    Expected<Scene> scene = build_scene(*raw);
    std::vector<double> row(scene->columns().size());
    bake_world(*scene, row);
    last.emplace(std::move(*scene));
  }
  set_counters(state, *last);
}
BENCHMARK(BM_BvhReadBakeWorld)->Unit(benchmark::kMillisecond);

/// Part 1: read_input_file alone (text → RawScene, one key per frame and channel).
void BM_BvhRead(benchmark::State& state) {
  if (auto why = unavailable()) return state.SkipWithError(why->c_str());
  for (auto _ : state) {
    Expected<RawScene> raw = read_input_file(kClip);
    benchmark::DoNotOptimize(raw);
  }
}
BENCHMARK(BM_BvhRead)->Unit(benchmark::kMillisecond);

/// Part 2: build_scene alone (checks and built tracks).
void BM_BvhBuild(benchmark::State& state) {
  if (auto why = unavailable()) return state.SkipWithError(why->c_str());
  const RawScene raw = *read_input_file(kClip);
  for (auto _ : state) {
    Expected<Scene> scene = build_scene(raw);
    benchmark::DoNotOptimize(scene);
  }
}
BENCHMARK(BM_BvhBuild)->Unit(benchmark::kMillisecond);

/// Part 3: sampling every frame's world transforms from a built scene.
void BM_BvhSampleWorld(benchmark::State& state) {
  if (auto why = unavailable()) return state.SkipWithError(why->c_str());
  const Scene scene = *build_scene(*read_input_file(kClip));
  std::vector<double> row(scene.columns().size());
  for (auto _ : state) bake_world(scene, row);
  set_counters(state, scene);
}
BENCHMARK(BM_BvhSampleWorld)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
