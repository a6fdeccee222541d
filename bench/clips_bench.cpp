// The raw CMU clips of issue 24 (Debian's assimp-testmodels: 01_01 and 01_03 in CMU's unit of
// 5.644 cm, Boxing_Toes in cm), the clips ACL 2.1 is measured on by `make bench-acl`
// (tools/bench/acl_clip_bench.cpp; ACL is not packaged, so its figures are recorded in
// bench/acl_reference.json).  `make bench` (tools/bench/write_results.py) puts this run's raw sizes,
// inbetween's compression (bench/compress_bench.cpp: BM_CompressedSample's bytes, error and
// ns_per_joint) and ACL's recorded figures side by side in the "ACL 2.1 vs inbetween compression" table.
//
// BM_ClipRaw/<clip>: read_input_file + build_scene + sample_clip, the raw clip every compressor
// starts from; counters joints, frames and raw_float32_bytes (frames × joints × 10 floats:
// translation, rotation, scale — ACL's raw size), so the table's ratios to raw are of this run.
// Each benchmark skips with a message when the clip is not installed or cannot be read.
#include <benchmark/benchmark.h>

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "inbetween/io/input.hpp"
#include "inbetween/scene/sampled_clip.hpp"
#include "inbetween/scene/scene.hpp"

namespace {
using namespace inbetween;

const std::filesystem::path kBvhDir = "/usr/share/assimp/models/BVH";
/// The clips of issue 24's table, as bench/acl_reference.json names them (file stems).
constexpr std::array<const char*, 3> kClips = {"01_01", "01_03", "Boxing_Toes"};

/// The raw clip of `stem`, read once per process, or why it cannot be.
const Expected<SampledClip>& raw_clip(const std::string& stem) {
  static std::map<std::string, Expected<SampledClip>> cache;
  auto it = cache.find(stem);
  if (it != cache.end()) return it->second;
  const std::filesystem::path file = kBvhDir / (stem + ".bvh");
  auto load = [&]() -> Expected<SampledClip> {
    if (!std::filesystem::exists(file)) return Error{ErrorCode::io, file.string() + " is not installed (Debian assimp-testmodels)"};
    Expected<RawScene> raw = read_input_file(file);
    if (!raw) return raw.error();
    Expected<Scene> scene = build_scene(*raw);
    if (!scene) return scene.error();
    return sample_clip(*scene);
  };
  return cache.emplace(stem, load()).first->second;
}

void set_clip_counters(benchmark::State& state, const SampledClip& clip) {
  state.counters["joints"] = double(clip.joints());
  state.counters["frames"] = double(clip.frames);
  state.counters["raw_float32_bytes"] = double(clip.frames * clip.joints() * 10 * sizeof(float));
}

/// The file → SampledClip step (what `inbetween compress` does before compressing).
void BM_ClipRaw(benchmark::State& state, const std::string& stem) {
  const Expected<SampledClip>& cached = raw_clip(stem);
  if (!cached) return state.SkipWithError(cached.error().message.c_str());
  const std::filesystem::path file = kBvhDir / (stem + ".bvh");
  for (auto _ : state) {
    Expected<RawScene> raw = read_input_file(file);
    Expected<Scene> scene = build_scene(*raw);
    Expected<SampledClip> clip = sample_clip(*scene);
    benchmark::DoNotOptimize(clip->poses.data());
  }
  set_clip_counters(state, *cached);
}

}  // namespace

int main(int argc, char** argv) {
  for (const char* stem : kClips) {
    benchmark::RegisterBenchmark((std::string("BM_ClipRaw/") + stem).c_str(), BM_ClipRaw, std::string(stem))
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
