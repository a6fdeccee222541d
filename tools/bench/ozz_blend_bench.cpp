// Issue 23: inbetween's blend_poses against ozz-animation 0.16's BlendingJob on the same poses, in
// one binary.  Not part of the CMake build (ozz is not packaged by Debian): `make bench-ozz
// OZZ_SRC=/path/to/ozz-animation` (tools/bench/bench_ozz.sh, its last block) compiles this file
// against the ozz libraries that script builds, runs it with JSON output to
// build/ozz/ozz_blend_bench.json, and tools/bench/write_results.py puts the table into
// bench/RESULTS.md.  The poses are bench/blend_fixture.hpp's (as bench/blend_bench.cpp): 2 or 4
// layers, every layer but the first masked per joint, the rest pose below the threshold, float.
// ozz reads SoA transforms (what its SamplingJob writes); inbetween reads JointPose spans (what
// sample_rig writes) and, in BM_InbetweenBlendSoA, PoseBlocks (its SoA layout, 8 joints per block):
// each converted once before timing.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "blend_fixture.hpp"
#include "inbetween/tracks/runtime/blend.hpp"
#include "ozz/animation/runtime/blending_job.h"
#include "ozz/base/maths/simd_math.h"
#include "ozz/base/maths/soa_transform.h"
#include "ozz/base/span.h"

using namespace inbetween;
using inbetween_bench::make_blend_poses;

namespace {

// J poses as ⌈J/4⌉ SoA transforms (the padding lanes repeat the last joint).
std::vector<ozz::math::SoaTransform> to_soa(const std::vector<JointPose<float>>& p) {
  std::vector<ozz::math::SoaTransform> out((p.size() + 3) / 4);
  for (std::size_t g = 0; g < out.size(); ++g) {
    const auto at = [&](std::size_t i) -> const JointPose<float>& { return p[std::min(4 * g + i, p.size() - 1)]; };
    const auto load = [&](auto f) { return ozz::math::simd_float4::Load(f(at(0)), f(at(1)), f(at(2)), f(at(3))); };
    auto& s = out[g];
    s.translation.x = load([](const JointPose<float>& a) { return a.translation.x; });
    s.translation.y = load([](const JointPose<float>& a) { return a.translation.y; });
    s.translation.z = load([](const JointPose<float>& a) { return a.translation.z; });
    s.rotation.x = load([](const JointPose<float>& a) { return a.rotation.x; });
    s.rotation.y = load([](const JointPose<float>& a) { return a.rotation.y; });
    s.rotation.z = load([](const JointPose<float>& a) { return a.rotation.z; });
    s.rotation.w = load([](const JointPose<float>& a) { return a.rotation.w; });
    s.scale.x = load([](const JointPose<float>& a) { return a.scale.x; });
    s.scale.y = load([](const JointPose<float>& a) { return a.scale.y; });
    s.scale.z = load([](const JointPose<float>& a) { return a.scale.z; });
  }
  return out;
}

std::vector<ozz::math::SimdFloat4> to_soa(const std::vector<float>& m) {
  std::vector<ozz::math::SimdFloat4> out((m.size() + 3) / 4);
  for (std::size_t g = 0; g < out.size(); ++g) {
    const auto at = [&](std::size_t i) { return m[std::min(4 * g + i, m.size() - 1)]; };
    out[g] = ozz::math::simd_float4::Load(at(0), at(1), at(2), at(3));
  }
  return out;
}

float lane(ozz::math::SimdFloat4 v, std::size_t i) {
  alignas(16) float f[4];
  ozz::math::StorePtr(v, f);
  return f[i];
}

}  // namespace

// Args: joints, layers.
void BM_OzzBlendingJob(benchmark::State& state) {
  const auto b = make_blend_poses<float>(int(state.range(1)), int(state.range(0)));
  std::vector<std::vector<ozz::math::SoaTransform>> poses;
  std::vector<std::vector<ozz::math::SimdFloat4>> masks;
  for (std::size_t l = 0; l < b.layers.size(); ++l) poses.push_back(to_soa(b.layers[l])), masks.push_back(to_soa(b.masks[l]));
  const auto rest = to_soa(b.rest);
  std::vector<ozz::math::SoaTransform> out(rest.size());
  std::vector<ozz::animation::BlendingJob::Layer> layers(b.layers.size());
  for (std::size_t l = 0; l < layers.size(); ++l) {
    layers[l].weight = b.weights[l];
    layers[l].transform = ozz::make_span(poses[l]);
    if (!masks[l].empty()) layers[l].joint_weights = ozz::make_span(masks[l]);
  }
  ozz::animation::BlendingJob job;
  job.layers = ozz::make_span(layers);
  job.rest_pose = ozz::make_span(rest);
  job.output = ozz::make_span(out);
  if (!job.Validate()) {
    state.SkipWithError("BlendingJob::Validate failed");
    return;
  }
  for (auto _ : state) {
    job.Run();
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  // Agreement with inbetween on these poses (ozz normalises with an estimated reciprocal square
  // root, ~1e-3 relative before its Newton step, so this is not a correctness check of either).
  std::vector<JointPose<float>> ours(b.rest.size());
  std::vector<BlendLayer<float>> ls;
  for (std::size_t l = 0; l < b.layers.size(); ++l) ls.push_back({b.layers[l], b.weights[l], b.masks[l]});
  blend_poses<float>(ls, {}, b.rest, ours);
  double worst_t = 0, worst_r = 0;
  for (std::size_t j = 0; j < ours.size(); ++j) {
    const auto& s = out[j / 4];
    const std::size_t i = j % 4;
    worst_t = std::max({worst_t, double(std::abs(lane(s.translation.x, i) - ours[j].translation.x)),
                        double(std::abs(lane(s.translation.y, i) - ours[j].translation.y)),
                        double(std::abs(lane(s.translation.z, i) - ours[j].translation.z))});
    const Quatf q = Quatf::from_wxyz(lane(s.rotation.w, i), lane(s.rotation.x, i), lane(s.rotation.y, i), lane(s.rotation.z, i));
    worst_r = std::max(worst_r, double(angle_between(normalized(q), ours[j].rotation)));
  }
  state.counters["vs_inbetween_dt"] = worst_t;
  state.counters["vs_inbetween_drot_rad"] = worst_r;
}

template <class T>
void BM_InbetweenBlend(benchmark::State& state) {
  const auto b = make_blend_poses<T>(int(state.range(1)), int(state.range(0)));
  std::vector<BlendLayer<T>> layers;
  for (std::size_t l = 0; l < b.layers.size(); ++l) layers.push_back({b.layers[l], b.weights[l], b.masks[l]});
  std::vector<JointPose<T>> out(b.rest.size());
  for (auto _ : state) {
    blend_poses<T>(layers, {}, b.rest, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
}

// The same blend on PoseBlocks (inbetween's SoA layout: 8 joints per block, the peer's layout
// idea with the AVX2 width), converted once before timing as ozz's SoaTransforms are.
void BM_InbetweenBlendSoA(benchmark::State& state) {
  const auto b = make_blend_poses<float>(int(state.range(1)), int(state.range(0)));
  inbetween_bench::BlendPosesSoA blocks(b);
  for (auto _ : state) {
    blend_poses(blocks.layers, {}, blocks.rest, blocks.out);
    benchmark::DoNotOptimize(blocks.out.data());
    benchmark::ClobberMemory();
  }
  // Same result as the JointPose overload (bit for bit on full groups of 8: the fixture's sizes).
  std::vector<JointPose<float>> soa(b.rest.size()), aos(b.rest.size());
  from_pose_blocks(blocks.out, soa);
  std::vector<BlendLayer<float>> ls;
  for (std::size_t l = 0; l < b.layers.size(); ++l) ls.push_back({b.layers[l], b.weights[l], b.masks[l]});
  blend_poses<float>(ls, {}, b.rest, aos);
  double unequal = 0;  // values that differ from the JointPose overload's (expected: none)
  for (std::size_t j = 0; j < aos.size(); ++j) {
    const float* x = &soa[j].translation.x;
    const float* y = &aos[j].translation.x;
    for (int k = 0; k < 10; ++k) unequal += x[k] != y[k] ? 1 : 0;
  }
  state.counters["vs_aos_unequal_values"] = unequal;
}

#define BLEND_ARGS ->ArgsProduct({{64, 1024}, {2, 4}})
BENCHMARK(BM_OzzBlendingJob) BLEND_ARGS;
BENCHMARK(BM_InbetweenBlend<float>) BLEND_ARGS;
BENCHMARK(BM_InbetweenBlendSoA) BLEND_ARGS;
BENCHMARK(BM_InbetweenBlend<double>) BLEND_ARGS;
BENCHMARK_MAIN();
