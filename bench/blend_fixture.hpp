// The blending benchmark's poses (issue 23), shared by bench/blend_bench.cpp (in tree) and
// tools/bench/ozz_blend_bench.cpp (ozz-animation's BlendingJob, built out of tree by `make
// bench-ozz`), so both blend the same numbers: `layers` poses of `joints` joints (translations in
// [−1, 1]³, rotations about random axes by up to 1.5 rad as the rig fixture's keys, scales
// 1 ± 0.1), a rest pose of the same kind, layer weights 0.6, 0.4, 0.3, 0.2, …, and a per-joint mask
// in [0, 1] on every layer but the first (a full-body layer under masked ones); seed 2323, drawn in
// double and rounded to T.
#pragma once

#include <random>
#include <vector>

#include "inbetween/tracks/runtime/blend.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween_bench {

/// The blending benchmark's inputs.
template <class T>
struct BlendPoses {
  std::vector<std::vector<inbetween::JointPose<T>>> layers;  ///< one pose per layer
  std::vector<std::vector<T>> masks;                          ///< per layer; empty for layer 0
  std::vector<T> weights;                                     ///< per layer
  std::vector<inbetween::JointPose<T>> rest;                  ///< the rest pose
};

/// `layers` poses of `joints` joints as described at the top of this file.
template <class T>
BlendPoses<T> make_blend_poses(int layers, int joints) {
  using namespace inbetween;
  std::mt19937_64 rng(2323);
  std::uniform_real_distribution<double> d(-1, 1), u(0, 1);
  const auto pose = [&] {
    std::vector<JointPose<T>> p;
    for (int j = 0; j < joints; ++j) {
      const double ax = d(rng), ay = d(rng), az = d(rng), ang = d(rng);
      const Quatd q = Quatd::from_axis_angle(Vec3d{ax, ay, az + 2}, 1.5 * ang);
      JointPose<T> jp;
      jp.translation = {T(d(rng)), T(d(rng)), T(d(rng))};
      jp.rotation = Quat<T>::from_wxyz(T(q.w), T(q.x), T(q.y), T(q.z));
      jp.scale = {T(1 + 0.1 * d(rng)), T(1 + 0.1 * d(rng)), T(1 + 0.1 * d(rng))};
      p.push_back(jp);
    }
    return p;
  };
  BlendPoses<T> b;
  b.rest = pose();
  for (int l = 0; l < layers; ++l) {
    b.layers.push_back(pose());
    b.weights.push_back(l == 0 ? T(0.6) : l == 1 ? T(0.4) : l == 2 ? T(0.3) : T(0.2));
    std::vector<T> mask;
    if (l > 0)
      for (int j = 0; j < joints; ++j) mask.push_back(T(u(rng)));
    b.masks.push_back(mask);
  }
  return b;
}

/// The same poses as PoseBlocks (the SoA layout), converted once, with the layers pointing into
/// them: what a blend on PoseBlocks reads.  Not copyable or movable (the layers hold spans of it).
struct BlendPosesSoA {
  std::vector<std::vector<inbetween::PoseBlock>> poses;  ///< per layer
  std::vector<std::vector<float>> masks;                 ///< per layer (empty: unmasked)
  std::vector<inbetween::BlendLayerSoA> layers;          ///< spans of poses and masks
  std::vector<inbetween::PoseBlock> rest, out;           ///< rest pose; output buffer

  explicit BlendPosesSoA(const BlendPoses<float>& b) {
    using namespace inbetween;
    const std::size_t blocks = pose_blocks(b.rest.size());
    poses.assign(b.layers.size(), std::vector<PoseBlock>(blocks));
    masks.resize(b.layers.size());
    for (std::size_t l = 0; l < b.layers.size(); ++l) {
      to_pose_blocks(b.layers[l], poses[l]);
      if (!b.masks[l].empty()) masks[l].resize(blocks * pose_block_joints), to_mask_blocks(b.masks[l], masks[l]);
      layers.push_back({poses[l], b.weights[l], masks[l]});
    }
    rest.resize(blocks);
    out.resize(blocks);
    to_pose_blocks(b.rest, rest);
  }
  BlendPosesSoA(const BlendPosesSoA&) = delete;
  BlendPosesSoA& operator=(const BlendPosesSoA&) = delete;
};

}  // namespace inbetween_bench
