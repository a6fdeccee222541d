// Compression on real clips (issue 24): the CMU motion-capture clips of Debian's assimp-testmodels
// (01_01 and 01_03 in CMU's unit of 5.644 cm, Boxing_Toes in cm), the clips ACL 2.1 is measured on
// by `make bench-acl` (tools/bench/acl_clip_bench.cpp; ACL is not packaged, so its figures are
// recorded in bench/acl_reference.json).  `make bench` (tools/bench/write_results.py) puts these
// counters next to ACL's recorded figures in the "ACL 2.1 vs inbetween compression" table.
//
// BM_ClipRaw/<clip>: read_input_file + build_scene + sample_clip, the raw clip every compressor
// starts from; counters joints, frames and raw_float32_bytes (frames × joints × 10 floats:
// translation, rotation, scale — ACL's raw size), so the table's ratios to raw are of this run.
// BM_CompressClip/<clip>/<E>: compress_clip at error bound E, shell D = 3 (one iteration, one
// repetition: compression is seconds, and its time is reported, not a target); counters bytes,
// measured_error (clip_error of the double decoder, the guarantee) and runtime_error (clip_error of
// sample_compressed's float poses at the same frames, what a game sees).
// BM_SampleCompressed/<clip>/<E>/sequential|random: sample_compressed of a whole pose at the clip's
// frames in order / at seeded random frames; items = joints, so items_per_second gives ns per joint,
// the figure ACL's decompress_tracks is compared on.
// Each benchmark skips with a message when the clip is not installed or cannot be read.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <span>
#include <utility>
#include <vector>
#include <string>

#include "inbetween/io/input.hpp"
#include "inbetween/scene/compress.hpp"
#include "inbetween/scene/sampled_clip.hpp"
#include "inbetween/scene/scene.hpp"
#include "inbetween/tracks/runtime/compressed_clip.hpp"

namespace {
using namespace inbetween;

const std::filesystem::path kBvhDir = "/usr/share/assimp/models/BVH";
/// The clips of issue 24's table, as bench/acl_reference.json names them (file stems).
constexpr std::array<const char*, 3> kClips = {"01_01", "01_03", "Boxing_Toes"};
/// Issue 24's error bounds (clip units) and shell distance.
constexpr std::array<double, 2> kErrors = {0.01, 0.1};
constexpr double kShell = 3;

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

/// Compressed clips by (clip, error bound): compressed once per process (compression takes seconds).
std::map<std::pair<std::string, double>, Expected<CompressedClip>>& compressed_cache() {
  static std::map<std::pair<std::string, double>, Expected<CompressedClip>> cache;
  return cache;
}

/// The clip of `stem` compressed at `error` (from the cache, or compressed now), or why not.
const Expected<CompressedClip>& compressed(const std::string& stem, double error) {
  auto& cache = compressed_cache();
  auto it = cache.find({stem, error});
  if (it != cache.end()) return it->second;
  const Expected<SampledClip>& clip = raw_clip(stem);
  Expected<CompressedClip> c = clip ? compress_clip(*clip, {.error = error, .shell = kShell}) : Expected<CompressedClip>(clip.error());
  return cache.emplace(std::make_pair(stem, error), std::move(c)).first->second;
}

/// The float runtime's poses at the clip's frames, as a SampledClip (for clip_error).
SampledClip runtime_frames(const SampledClip& clip, const CompressedClip& c) {
  std::vector<JointPose<float>> pose(clip.joints());
  SampledClip out = clip;
  for (std::size_t f = 0; f < clip.frames; ++f) {
    sample_compressed(c, clip.first_frame + double(f), pose);
    for (std::size_t j = 0; j < clip.joints(); ++j)
      out.poses[f * clip.joints() + j] = {pose[j].translation.cast<double>(), pose[j].rotation.cast<double>(),
                                          pose[j].scale.cast<double>()};
  }
  return out;
}

void BM_CompressClip(benchmark::State& state, const std::string& stem, double error) {
  const Expected<SampledClip>& clip = raw_clip(stem);
  if (!clip) return state.SkipWithError(clip.error().message.c_str());
  std::optional<Expected<CompressedClip>> last;
  for (auto _ : state) last.emplace(compress_clip(*clip, {.error = error, .shell = kShell}));
  if (!*last) return state.SkipWithError(last->error().message.c_str());
  const CompressedClip& c = **last;
  compressed_cache().emplace(std::make_pair(stem, error), *last);  // BM_SampleCompressed's clip, when it runs later
  set_clip_counters(state, *clip);
  state.counters["bytes"] = double(c.bytes().size());
  state.counters["error_bound"] = error;
  state.counters["measured_error"] = clip_error(*clip, decompress(c), kShell).max;
  state.counters["runtime_error"] = clip_error(*clip, runtime_frames(*clip, c), kShell).max;
}

void BM_SampleCompressed(benchmark::State& state, const std::string& stem, double error, bool random) {
  const Expected<SampledClip>& clip = raw_clip(stem);
  if (!clip) return state.SkipWithError(clip.error().message.c_str());
  const Expected<CompressedClip>& c = compressed(stem, error);
  if (!c) return state.SkipWithError(c.error().message.c_str());
  std::vector<double> frames(clip->frames);
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> uni(0.0, double(clip->frames - 1));
  for (std::size_t f = 0; f < frames.size(); ++f) frames[f] = clip->first_frame + (random ? uni(rng) : double(f));
  // The output buffer moves among 16 places, one per call (as in tools/bench/acl_clip_bench.cpp):
  // the sampler's time was seen to depend on where its buffer lies.
  constexpr std::size_t kSlots = 16, kSlotStride = 5;
  std::vector<JointPose<float>> buffer(c->joints() + kSlots * kSlotStride);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::span<JointPose<float>> pose(buffer.data() + (i % kSlots) * kSlotStride, c->joints());
    sample_compressed(*c, frames[i], pose);
    benchmark::DoNotOptimize(pose.data());
    benchmark::ClobberMemory();
    if (++i == frames.size()) i = 0;
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(c->joints()));
}

}  // namespace

int main(int argc, char** argv) {
  for (const char* stem : kClips) {
    benchmark::RegisterBenchmark((std::string("BM_ClipRaw/") + stem).c_str(), BM_ClipRaw, std::string(stem))
        ->Unit(benchmark::kMillisecond);
  }
  for (const char* stem : kClips) {
    for (double e : kErrors) {
      char tag[64];
      std::snprintf(tag, sizeof tag, "%s/%g", stem, e);
      benchmark::RegisterBenchmark((std::string("BM_CompressClip/") + tag).c_str(), BM_CompressClip, std::string(stem), e)
          ->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(1);
      for (bool random : {false, true})
        benchmark::RegisterBenchmark((std::string("BM_SampleCompressed/") + tag + (random ? "/random" : "/sequential")).c_str(),
                                     BM_SampleCompressed, std::string(stem), e, random);
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
