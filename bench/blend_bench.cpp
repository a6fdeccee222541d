// Issue 23's blending runtime (include/inbetween/tracks/runtime/blend.hpp): blend_poses on
// bench/blend_fixture.hpp's poses (2 and 4 layers, masked, 64 and 1 024 joints — the same poses
// tools/bench/ozz_blend_bench.cpp gives ozz-animation's BlendingJob), and the whole character
// update at 71 joints against the 1 ms per frame engines budget for all animation: sample two
// clips with sample_rig (bench/rig_fixture.hpp's 71-joint rig at two phases, two cursors), blend
// them with a crossfade weight and an upper-body mask, and take the root motion out of the result
// (BM_CharacterUpdateSoA: the same through PoseBlocks, converting the sampled records).
#include <benchmark/benchmark.h>

#include <span>
#include <vector>

#include "blend_fixture.hpp"
#include "inbetween/tracks/runtime/blend.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"
#include "inbetween/tracks/runtime/root_motion.hpp"
#include "rig_fixture.hpp"

using namespace inbetween;

namespace {

// Args: joints, layers.
template <class T>
void BM_BlendPoses(benchmark::State& state) {
  const auto b = inbetween_bench::make_blend_poses<T>(int(state.range(1)), int(state.range(0)));
  std::vector<BlendLayer<T>> layers;
  for (std::size_t l = 0; l < b.layers.size(); ++l) layers.push_back({b.layers[l], b.weights[l], b.masks[l]});
  std::vector<JointPose<T>> out(b.rest.size());
  for (auto _ : state) {
    blend_poses<T>(layers, {}, b.rest, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_joint"] = benchmark::Counter(double(state.iterations()) * double(out.size()),
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The same blend on PoseBlocks (the SoA overload; float only), converted once before timing.
// Args: joints, layers.
void BM_BlendPosesSoA(benchmark::State& state) {
  const auto b = inbetween_bench::make_blend_poses<float>(int(state.range(1)), int(state.range(0)));
  inbetween_bench::BlendPosesSoA soa(b);
  for (auto _ : state) {
    blend_poses(soa.layers, {}, soa.rest, soa.out);
    benchmark::DoNotOptimize(soa.out.data());
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_joint"] = benchmark::Counter(double(state.iterations()) * double(b.rest.size()),
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The conversions around the SoA path for a caller whose sampler writes JointPose records:
// to_pose_blocks of one pose (Arg 0: joints) or from_pose_blocks of one pose (Arg 1).  A blend of L
// layers from JointPose records through PoseBlocks costs L + 1 to_pose_blocks (layers, rest; the rest
// can be converted once) and one from_pose_blocks on top of BM_BlendPosesSoA.
void BM_PoseBlockConversion(benchmark::State& state) {
  const auto b = inbetween_bench::make_blend_poses<float>(1, int(state.range(0)));
  std::vector<PoseBlock> blocks(pose_blocks(b.rest.size()));
  std::vector<JointPose<float>> back(b.rest.size());
  to_pose_blocks(b.rest, blocks);
  const bool to = state.range(1) == 0;
  for (auto _ : state) {
    if (to) to_pose_blocks(b.rest, blocks);
    else from_pose_blocks(blocks, back);
    benchmark::DoNotOptimize(blocks.data());
    benchmark::DoNotOptimize(back.data());
    benchmark::ClobberMemory();
  }
  state.SetLabel(to ? "to_pose_blocks" : "from_pose_blocks");
}

// Arg: joints (71: the CMU skeleton's size class).  One iteration = one character's frame.
template <class T>
void BM_CharacterUpdate(benchmark::State& state) {
  const auto rig = inbetween_bench::make_rig<T>(int(state.range(0)));
  const auto clip = inbetween_bench::fixture_rig_clip(rig);
  const double end = inbetween_bench::rig_end(rig);
  RigClipCursor<T> ca = make_rig_clip_cursor(clip), cb = make_rig_clip_cursor(clip);
  const std::size_t n = clip.joints();
  std::vector<JointPose<T>> a(n), b(n), rest(n), out(n);
  std::vector<T> upper(n);
  for (std::size_t j = 0; j < n; ++j) upper[j] = j < n / 2 ? T(0) : T(1);  // second clip on the upper half only
  const RootMotionOptions options;
  const RootMotion<T> reference{};
  double frame = 0;
  for (auto _ : state) {
    sample_rig(clip, T(frame), ca, std::span<JointPose<T>>(a));
    sample_rig(clip, T(std::fmod(frame + 7.5, end)), cb, std::span<JointPose<T>>(b));
    const T w = crossfade_weight(T(std::fmod(frame, 10.0)), T(10));
    const BlendLayer<T> layers[2] = {{a, T(1) - w}, {b, w, upper}};
    blend_poses<T>(layers, {}, rest, out);
    const RootMotion<T> motion = root_motion_of(out[0], reference, options);
    out[0] = remove_root_motion(out[0], motion);
    benchmark::DoNotOptimize(out.data());
    benchmark::DoNotOptimize(motion);
    benchmark::ClobberMemory();
    frame += 0.5;  // 60 Hz playback of a 30 fps clip
    if (frame > end) frame = 0;
  }
}

// The character update through PoseBlocks, float, for a caller of sample_rig (which writes
// JointPose records): sample two clips, convert both poses to blocks, blend on blocks, convert back,
// take the root motion out.  The mask and the rest pose are converted once, outside the loop.
void BM_CharacterUpdateSoA(benchmark::State& state) {
  using T = float;
  const auto rig = inbetween_bench::make_rig<T>(int(state.range(0)));
  const auto clip = inbetween_bench::fixture_rig_clip(rig);
  const double end = inbetween_bench::rig_end(rig);
  RigClipCursor<T> ca = make_rig_clip_cursor(clip), cb = make_rig_clip_cursor(clip);
  const std::size_t n = clip.joints(), blocks = pose_blocks(n);
  std::vector<JointPose<T>> a(n), b(n), rest(n), out(n);
  std::vector<PoseBlock> sa(blocks), sb(blocks), srest(blocks), sout(blocks);
  std::vector<T> upper(n), supper(blocks * pose_block_joints);
  for (std::size_t j = 0; j < n; ++j) upper[j] = j < n / 2 ? T(0) : T(1);
  to_mask_blocks(upper, supper);
  to_pose_blocks(rest, srest);
  const RootMotionOptions options;
  const RootMotion<T> reference{};
  double frame = 0;
  for (auto _ : state) {
    sample_rig(clip, T(frame), ca, std::span<JointPose<T>>(a));
    sample_rig(clip, T(std::fmod(frame + 7.5, end)), cb, std::span<JointPose<T>>(b));
    to_pose_blocks(a, sa);
    to_pose_blocks(b, sb);
    const T w = crossfade_weight(T(std::fmod(frame, 10.0)), T(10));
    const BlendLayerSoA layers[2] = {{sa, T(1) - w}, {sb, w, supper}};
    blend_poses(layers, {}, srest, sout);
    from_pose_blocks(sout, out);
    const RootMotion<T> motion = root_motion_of(out[0], reference, options);
    out[0] = remove_root_motion(out[0], motion);
    benchmark::DoNotOptimize(out.data());
    benchmark::DoNotOptimize(motion);
    benchmark::ClobberMemory();
    frame += 0.5;
    if (frame > end) frame = 0;
  }
}

}  // namespace

BENCHMARK(BM_BlendPoses<float>)->ArgsProduct({{64, 1024}, {2, 4}});
BENCHMARK(BM_BlendPoses<double>)->ArgsProduct({{64, 1024}, {2, 4}});
BENCHMARK(BM_BlendPosesSoA)->ArgsProduct({{64, 1024}, {2, 4}});
BENCHMARK(BM_PoseBlockConversion)->ArgsProduct({{64, 1024}, {0, 1}});
BENCHMARK(BM_CharacterUpdate<float>)->Arg(71);
BENCHMARK(BM_CharacterUpdate<double>)->Arg(71);
BENCHMARK(BM_CharacterUpdateSoA)->Arg(71);
BENCHMARK_MAIN();
