// Issue 24, "Sample in place": sample_compressed (tracks/runtime/compressed_clip.hpp) on the CMU
// clips of Debian's assimp-testmodels, compressed at E = 0.01 and 0.1 (D = 3), one call per
// character per frame: time per joint (the ns_per_joint counter), sequential frames (a playback
// step of one frame) and random frames (a fixed pseudo-random sequence over the clip).  ACL 2.1's
// decompression of the same clips is measured by `make bench-acl` (tools/bench/), 16–20 ns per
// joint on this machine (bench/RESULTS.md).  Also: the compression itself (BM_CompressClip).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "inbetween/io/input.hpp"
#include "inbetween/scene/compress.hpp"

namespace {

using namespace inbetween;

const char* const kClips[] = {"01_01", "01_03", "Boxing_Toes"};
const double kErrors[] = {0.01, 0.1};

const SampledClip* sampled(const std::string& name) {
  static std::map<std::string, std::unique_ptr<SampledClip>> cache;
  auto& slot = cache[name];
  if (!slot) {
    const auto raw = read_input_file("/usr/share/assimp/models/BVH/" + name + ".bvh");
    if (!raw) return nullptr;
    const auto scene = build_scene(*raw);
    if (!scene) return nullptr;
    auto clip = sample_clip(*scene);
    if (!clip) return nullptr;
    slot = std::make_unique<SampledClip>(std::move(*clip));
  }
  return slot.get();
}

const CompressedClip* compressed(const std::string& name, double error) {
  static std::map<std::pair<std::string, double>, std::unique_ptr<CompressedClip>> cache;
  auto& slot = cache[{name, error}];
  if (!slot) {
    const SampledClip* clip = sampled(name);
    if (!clip) return nullptr;
    auto c = compress_clip(*clip, {.error = error, .shell = 3});
    if (!c) return nullptr;
    slot = std::make_unique<CompressedClip>(std::move(*c));
  }
  return slot.get();
}

void BM_CompressedSample(benchmark::State& state, std::string name, double error, bool random) {
  const CompressedClip* clip = compressed(name, error);
  if (!clip) {
    state.SkipWithError("clip not found (Debian assimp-testmodels)");
    return;
  }
  std::vector<JointPose<float>> local(clip->joints());
  std::vector<double> frames(4096);
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> any(clip->first_frame(), clip->first_frame() + double(clip->frames() - 1));
  for (std::size_t i = 0; i < frames.size(); ++i)
    frames[i] = random ? any(rng) : clip->first_frame() + double(i % clip->frames());
  std::size_t i = 0;
  for (auto _ : state) {
    sample_compressed(*clip, frames[i++ & 4095], local);
    benchmark::DoNotOptimize(local.data());
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_joint"] = benchmark::Counter(double(state.iterations()) * double(clip->joints()),
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["bytes"] = double(clip->bytes().size());
  state.counters["error"] = clip->measured_error();
}

void BM_CompressClip(benchmark::State& state, std::string name, double error) {
  const SampledClip* clip = sampled(name);
  if (!clip) {
    state.SkipWithError("clip not found (Debian assimp-testmodels)");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(compress_clip(*clip, {.error = error, .shell = 3}));
}

[[maybe_unused]] const bool kRegistered = [] {
  for (const char* name : kClips) {
    for (const double e : kErrors) {
      const std::string tag = std::string(name) + "/E=" + (e == 0.01 ? "0.01" : "0.1");
      benchmark::RegisterBenchmark(("BM_CompressedSample/" + tag + "/sequential").c_str(), BM_CompressedSample, name, e, false);
      benchmark::RegisterBenchmark(("BM_CompressedSample/" + tag + "/random").c_str(), BM_CompressedSample, name, e, true);
    }
  }
  benchmark::RegisterBenchmark("BM_CompressClip/01_01/E=0.01", BM_CompressClip, "01_01", 0.01)
      ->Unit(benchmark::kSecond)
      ->Iterations(1);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
