#pragma once
/// Blending of sampled poses (issue 23, "Blending runtime"; docs/blending.md): N layers of
/// JointPose<T> spans — what sample_rig() writes — with per-layer weights and per-joint masks,
/// additive layers on top, and a rest pose where the layers' summed weight is too small.  One call
/// for a whole character into a caller-owned span; noexcept, no allocation.
///
/// Per joint j, with w_l = clean(weight_l)·clean(mask_l[j]) (clean: NaN and negatives → 0, capped at
/// blend_weight_max):
///   W = Σ w_l;  if W < threshold the rest pose enters with weight threshold − W (W = threshold);
///   translation = Σ w_l t_l / W,  scale = Σ w_l s_l / W;
///   rotation = normalise(Σ w_l σ_l q_l), σ_l = ±1 chosen so that σ_l q_l is on the hemisphere of
///   layer 0's q (dot ≥ 0) — the rest pose too; where that sum has (almost) no length the rest
///   rotation is written; where W = 0 (no layer weight at all) the rest pose is copied exactly.
/// Then each additive layer a with w = clean(weight_a)·clean(mask_a[j]) (a delta pose, see
/// additive_delta): t += w·Δt;  q = q · normalise((1 − w)·1 + w·Δq⁺) (Δq⁺: Δq with w ≥ 0);
/// s ⊙= 1 + w·(Δs − 1).
/// One pass over the joints with every layer in registers (ozz-animation's BlendingJob makes a pass
/// per layer, one for the rest pose and one to normalise): float joints in groups of 8 through
/// src/tracks/blend_kernel.cpp (AoS records transposed to fields, AVX-512/AVX2/SSE2 chosen at run
/// time; rotation normalised by rsqrt + one Newton step, within 2 ulp), the rest joint by joint
/// (docs/blending.md, "Speed").  A second overload takes PoseBlocks (8 joints as structure of
/// arrays, float) and runs the same kernel without the transposes (below, "Structure-of-arrays").

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <limits>
#include <span>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween {

/// Largest weight or mask value blend_poses uses; larger ones (and +∞) are capped to it, so that
/// Σ w·x stays finite for finite poses.
template <Real T>
inline constexpr T blend_weight_max = T(1e6);

/// One blended layer: a sampled pose, its weight and an optional per-joint mask.
template <Real T>
struct BlendLayer {
  std::span<const JointPose<T>> pose;  ///< one pose per joint (size = the character's joints)
  T weight = T(1);                     ///< layer weight ≥ 0; NaN and negatives count as 0 (not an error)
  std::span<const T> mask{};           ///< per-joint factor, usually in [0, 1]; empty = 1 everywhere; NaN/negative → 0
};

/// One additive layer: a delta pose (additive_delta of a pose against its reference), its weight
/// and an optional per-joint mask.
template <Real T>
struct AdditiveLayer {
  std::span<const JointPose<T>> delta;  ///< one delta per joint (size = the character's joints)
  T weight = T(1);                      ///< 0 = no effect, 1 = the full delta; NaN and negatives count as 0
  std::span<const T> mask{};            ///< per-joint factor; empty = 1 everywhere; NaN/negative → 0
};

/// Most BlendLayers one blend_poses call takes (asserted; nest calls for more).
inline constexpr std::size_t blend_max_layers = 16;

/// Options of blend_poses.
template <Real T>
struct BlendOptions {
  /// Where a joint's summed layer weight W is below this (> 0, finite), the rest pose is blended in
  /// with weight threshold − W (ozz-animation's BlendingJob::threshold, same default 0.1): no
  /// layer → the rest pose; a fading layer slides into it continuously.
  T threshold = T(0.1);
};

/// The delta of `pose` relative to `reference` that an AdditiveLayer adds back: Δt = t − t_ref,
/// Δq = q_ref* · q (so q = q_ref · Δq), Δs = s / s_ref per axis (a zero reference scale gives 1:
/// that axis is not scaled).  The delta of the reference itself is the identity.  Spans of equal
/// size (asserted); out may alias pose.
template <Real T>
void additive_delta(std::span<const JointPose<T>> pose, std::span<const JointPose<T>> reference,
                    std::span<JointPose<T>> out) noexcept {
  INBETWEEN_ASSERT(pose.size() == reference.size() && out.size() == pose.size());
  const auto ratio = [](T s, T r) { return r != T(0) ? s / r : T(1); };
  for (std::size_t j = 0; j < pose.size(); ++j) {
    const JointPose<T>& p = pose[j];
    const JointPose<T>& r = reference[j];
    JointPose<T> d;
    d.translation = p.translation - r.translation;
    d.rotation = conjugate(r.rotation) * p.rotation;
    d.scale = {ratio(p.scale.x, r.scale.x), ratio(p.scale.y, r.scale.y), ratio(p.scale.z, r.scale.z)};
    out[j] = d;
  }
}

namespace blend_detail {

// NaN and negatives → 0, capped at blend_weight_max.
template <Real T>
[[gnu::always_inline]] inline T clean(T w) noexcept {
  return w > T(0) ? std::min(w, blend_weight_max<T>) : T(0);
}

// Four lanes of T (a GCC/Clang vector: SSE for float, two SSE registers for double unless AVX).
template <Real T>
using V4 [[gnu::vector_size(4 * sizeof(T))]] = T;
template <Real T>
using I4 [[gnu::vector_size(4 * sizeof(T))]] = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;

// A JointPose is ten consecutive T: translation 0–2, rotation (w x y z) 3–6, scale 7–9.  Three
// unaligned 4-lane loads at 0, 3 and 6 cover it (lane 3 of the first and lane 0 of the third are
// the rotation's w and z, ignored there).
template <Real T>
[[gnu::always_inline]] inline V4<T> load4(const T* p) noexcept {
  V4<T> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <Real T>
[[gnu::always_inline]] inline void store4(T* p, V4<T> v) noexcept {
  std::memcpy(p, &v, sizeof v);
}
// The sum of the four lanes, in every lane.
template <Real T>
[[gnu::always_inline]] inline V4<T> hsum(V4<T> v) noexcept {
  v += __builtin_shufflevector(v, v, 1, 0, 3, 2);
  return v + __builtin_shufflevector(v, v, 2, 3, 0, 1);
}
// w with the sign of d flipped in (copysign-like: w ≥ 0, so w·sign(d) with sign(−0) = −).
template <Real T>
[[gnu::always_inline]] inline V4<T> signed_by(V4<T> w, V4<T> d) noexcept {
  using S = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
  const I4<T> sign = I4<T>{} + std::numeric_limits<S>::min();
  return reinterpret_cast<V4<T>>(reinterpret_cast<I4<T>>(w) ^ (reinterpret_cast<I4<T>>(d) & sign));
}

template <Real T>
inline const T* fields(const JointPose<T>& p) noexcept {
  return &p.translation.x;
}
template <Real T>
inline T* fields(JointPose<T>& p) noexcept {
  return &p.translation.x;
}

// The additive layers on one blended joint.
template <Real T>
[[gnu::always_inline]] inline void apply_additive(std::span<const AdditiveLayer<T>> additive, JointPose<T>& out,
                                                  std::size_t j) noexcept {
  for (const AdditiveLayer<T>& layer : additive) {
    const T w = clean(layer.weight) * (layer.mask.empty() ? T(1) : clean(layer.mask[j]));
    const JointPose<T>& d = layer.delta[j];
    out.translation = out.translation + d.translation * w;
    out.scale = {out.scale.x * (T(1) + w * (d.scale.x - T(1))), out.scale.y * (T(1) + w * (d.scale.y - T(1))),
                 out.scale.z * (T(1) + w * (d.scale.z - T(1)))};
    const Quat<T> dq = d.rotation.w < T(0) ? -d.rotation : d.rotation;  // Δq⁺
    const Quat<T> a = Quat<T>{} * (T(1) - w) + dq * w;
    out.rotation = out.rotation * (a / std::sqrt(std::max(dot(a, a), std::numeric_limits<T>::min())));
  }
}

// One joint: every layer, the rest pose, the normalisation and the additive layers, in registers.
template <Real T>
[[gnu::always_inline]] inline void blend_joint(std::span<const BlendLayer<T>> layers, const T* clean_weight,
                                               std::span<const AdditiveLayer<T>> additive,
                                               const JointPose<T>& rest, JointPose<T>& out, std::size_t j,
                                               T threshold) noexcept {
  if constexpr (sizeof(T) == 8) {
    // double: plain scalar code (GCC splits 4-lane double vectors into SSE2 pairs badly: 5× slower).
    const Quat<T> h = layers.empty() ? rest.rotation : layers[0].pose[j].rotation;
    Vec3<T> at{}, as{};
    Quat<T> aq{T(0), T(0), T(0), T(0)};
    T sum = 0;
    const auto add = [&](const JointPose<T>& x, T w) {
      sum += w;
      at = at + x.translation * w;
      as = as + x.scale * w;
      aq = aq + x.rotation * (dot(x.rotation, h) < T(0) ? -w : w);
    };
    for (std::size_t l = 0; l < layers.size(); ++l) {
      const BlendLayer<T>& layer = layers[l];
      add(layer.pose[j], layer.mask.empty() ? clean_weight[l] : clean_weight[l] * clean(layer.mask[j]));
    }
    if (sum == T(0)) {
      out = rest;
    } else {
      if (sum < threshold) add(rest, threshold - sum);
      const T n2 = dot(aq, aq);
      out.translation = at / sum;
      out.scale = as / sum;
      out.rotation = n2 >= T(64) * std::numeric_limits<T>::min() ? aq / std::sqrt(n2) : rest.rotation;
    }
  } else {
  using W = V4<T>;
  const T* r = fields(rest);
  const W h = load4<T>(layers.empty() ? r + 3 : fields(layers[0].pose[j]) + 3);  // the hemisphere
  W at{}, aq{}, as{}, sum{};
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const BlendLayer<T>& layer = layers[l];
    const T w = layer.mask.empty() ? clean_weight[l] : clean_weight[l] * clean(layer.mask[j]);
    const W wv = W{} + w;
    const T* x = fields(layer.pose[j]);
    const W q = load4<T>(x + 3);
    sum += wv;
    at += wv * load4<T>(x);
    as += wv * load4<T>(x + 6);
    aq += signed_by<T>(wv, hsum<T>(q * h)) * q;
  }
  const bool none = sum[0] == T(0);
  if (sum[0] < threshold) {
    const W wv = W{} + (threshold - sum[0]);
    const W q = load4<T>(r + 3);
    at += wv * load4<T>(r);
    as += wv * load4<T>(r + 6);
    aq += signed_by<T>(wv, hsum<T>(q * h)) * q;
    sum = W{} + threshold;
  }
  const W inv = W{} + T(1) / sum[0];
  const W n2 = hsum<T>(aq * aq);
  T* o = fields(out);
  if (none) {
    out = rest;
  } else {
    store4<T>(o, at * inv);
    store4<T>(o + 6, as * inv);
    // Σ w σ q can vanish only for rotations a half turn apart: then the rest rotation.
    if (n2[0] >= T(64) * std::numeric_limits<T>::min()) store4<T>(o + 3, aq * (W{} + T(1) / std::sqrt(n2[0])));
    else store4<T>(o + 3, load4<T>(r + 3));
  }
  }
  apply_additive<T>(additive, out, j);
}
/// blend_poses<float>'s kernel for `groups` full groups of 8 joints from joint 0, without the
/// additive layers (src/tracks/blend_kernel.cpp; AVX-512/AVX2/SSE2 chosen by the CPU).
void blend_groups8(const BlendLayer<float>* layers, std::size_t layer_count, const float* clean_weight,
                   const JointPose<float>* rest, JointPose<float>* out, std::size_t groups, float threshold) noexcept;
}  // namespace blend_detail

/// Blends `layers` (then `additive`) joint by joint into `out`, as described at the top of this
/// header.  Every pose span, every non-empty mask and `out` have rest.size() elements (asserted: a
/// wrong size is a programming error); options.threshold is finite and > 0 (asserted).  Finite
/// poses and any weights (NaN, negative, ∞ included) give a finite pose.  No layer at all writes the
/// rest pose.  `out` must not alias an input.  noexcept, no allocation.
template <Real T>
void blend_poses(std::span<const BlendLayer<T>> layers, std::span<const AdditiveLayer<T>> additive,
                 std::span<const JointPose<T>> rest, std::span<JointPose<T>> out,
                 const BlendOptions<T>& options = {}) noexcept {
  const std::size_t joints = rest.size();
  INBETWEEN_ASSERT(out.size() == joints);
  INBETWEEN_ASSERT(options.threshold > T(0) && options.threshold <= blend_weight_max<T>);
  for ([[maybe_unused]] const BlendLayer<T>& l : layers) INBETWEEN_ASSERT(l.pose.size() == joints && (l.mask.empty() || l.mask.size() == joints));
  for ([[maybe_unused]] const AdditiveLayer<T>& l : additive) INBETWEEN_ASSERT(l.delta.size() == joints && (l.mask.empty() || l.mask.size() == joints));
  static_assert(sizeof(JointPose<T>) == 10 * sizeof(T), "JointPose<T> is ten consecutive T");
  // The layers' weights cleaned once (at most 16 layers on this stack buffer; more in chunks is
  // not supported: asserted).
  INBETWEEN_ASSERT(layers.size() <= blend_max_layers);
  T clean_weight[blend_max_layers];
  for (std::size_t l = 0; l < layers.size(); ++l) clean_weight[l] = blend_detail::clean(layers[l].weight);
  std::size_t j = 0;
  if constexpr (std::is_same_v<T, float>) {
    // Groups of 8 joints through the transposing kernel (src/tracks/blend_kernel.cpp), the rest and
    // the additive layers joint by joint.
    const std::size_t groups = joints / 8;
    blend_detail::blend_groups8(layers.data(), layers.size(), clean_weight, rest.data(), out.data(), groups,
                                options.threshold);
    if (!additive.empty())
      for (std::size_t k = 0; k < 8 * groups; ++k) blend_detail::apply_additive<T>(additive, out[k], k);
    j = 8 * groups;
  }
  for (; j < joints; ++j)
    blend_detail::blend_joint<T>(layers, clean_weight, additive, rest[j], out[j], j, options.threshold);
}

// ---- Structure-of-arrays poses (docs/blending.md, "SoA poses") ----------------------------------

/// Joints in one PoseBlock: one 256-bit vector (AVX2) of floats per field.
inline constexpr std::size_t pose_block_joints = 8;

/// Eight joints' poses as structure of arrays — the layout blend_poses' SIMD kernel computes in, so
/// a blend of PoseBlock spans needs no transposition (ozz-animation's SoaTransform is the same idea
/// with 4 joints).  Joint j of a pose is lane j % 8 of block j / 8; a pose of J joints is
/// pose_blocks(J) blocks, the lanes past J are padding (any finite values: to_pose_blocks writes the
/// identity pose there).  32-byte aligned, 320 bytes.
struct alignas(32) PoseBlock {
  float tx[pose_block_joints];  ///< translation x of the eight joints
  float ty[pose_block_joints];  ///< translation y
  float tz[pose_block_joints];  ///< translation z
  float qw[pose_block_joints];  ///< rotation w (unit quaternions, either sign)
  float qx[pose_block_joints];  ///< rotation x
  float qy[pose_block_joints];  ///< rotation y
  float qz[pose_block_joints];  ///< rotation z
  float sx[pose_block_joints];  ///< scale x
  float sy[pose_block_joints];  ///< scale y
  float sz[pose_block_joints];  ///< scale z
};

/// Blocks holding `joints` joints: ⌈joints / 8⌉.
[[nodiscard]] constexpr std::size_t pose_blocks(std::size_t joints) noexcept {
  return (joints + pose_block_joints - 1) / pose_block_joints;
}

/// One blended layer of PoseBlocks (the SoA form of BlendLayer<float>).
struct BlendLayerSoA {
  std::span<const PoseBlock> pose;  ///< the layer's pose (size = the rest pose's block count)
  float weight = 1.0f;              ///< as BlendLayer::weight: NaN and negatives count as 0
  std::span<const float> mask{};    ///< empty = 1 everywhere, else 8 · blocks floats, joint j at [j] (padding: any value)
};

/// One additive layer of PoseBlocks (the SoA form of AdditiveLayer<float>).
struct AdditiveLayerSoA {
  std::span<const PoseBlock> delta;  ///< the delta pose (additive_delta, then to_pose_blocks)
  float weight = 1.0f;               ///< as AdditiveLayer::weight
  std::span<const float> mask{};     ///< empty = 1 everywhere, else 8 · blocks floats
};

namespace blend_detail {
/// Full groups of 8 JointPose records ↔ PoseBlocks, by the blend kernel's 4×4 transposes
/// (src/tracks/blend_kernel.cpp, same CPU dispatch).
void records_to_blocks8(const JointPose<float>* pose, PoseBlock* out, std::size_t groups) noexcept;
void blocks_to_records8(const PoseBlock* blocks, JointPose<float>* out, std::size_t groups) noexcept;
}  // namespace blend_detail

/// `pose` (J joints) into pose_blocks(J) blocks (out.size(), asserted); the padding lanes get the
/// identity pose.  Full groups of 8 by SIMD transposes, the last partial one joint by joint.
/// noexcept, no allocation.
inline void to_pose_blocks(std::span<const JointPose<float>> pose, std::span<PoseBlock> out) noexcept {
  INBETWEEN_ASSERT(out.size() == pose_blocks(pose.size()));
  static_assert(sizeof(JointPose<float>) == 10 * sizeof(float), "JointPose<float> is ten consecutive floats");
  const std::size_t full = pose.size() / pose_block_joints;
  blend_detail::records_to_blocks8(pose.data(), out.data(), full);
  for (std::size_t b = full; b < out.size(); ++b) {
    PoseBlock& o = out[b];
    for (std::size_t i = 0; i < pose_block_joints; ++i) {
      const std::size_t j = b * pose_block_joints + i;
      const JointPose<float> p = j < pose.size() ? pose[j] : JointPose<float>{};
      o.tx[i] = p.translation.x, o.ty[i] = p.translation.y, o.tz[i] = p.translation.z;
      o.qw[i] = p.rotation.w, o.qx[i] = p.rotation.x, o.qy[i] = p.rotation.y, o.qz[i] = p.rotation.z;
      o.sx[i] = p.scale.x, o.sy[i] = p.scale.y, o.sz[i] = p.scale.z;
    }
  }
}

/// The first out.size() joints of `blocks` as JointPose records (out.size() ≤ 8 · blocks.size(),
/// asserted).  Full groups of 8 by SIMD transposes, the rest joint by joint.  noexcept, no allocation.
inline void from_pose_blocks(std::span<const PoseBlock> blocks, std::span<JointPose<float>> out) noexcept {
  INBETWEEN_ASSERT(out.size() <= blocks.size() * pose_block_joints);
  const std::size_t full = out.size() / pose_block_joints;
  blend_detail::blocks_to_records8(blocks.data(), out.data(), full);
  for (std::size_t j = full * pose_block_joints; j < out.size(); ++j) {
    const PoseBlock& b = blocks[j / pose_block_joints];
    const std::size_t i = j % pose_block_joints;
    out[j].translation = {b.tx[i], b.ty[i], b.tz[i]};
    out[j].rotation = Quat<float>::from_wxyz(b.qw[i], b.qx[i], b.qy[i], b.qz[i]);
    out[j].scale = {b.sx[i], b.sy[i], b.sz[i]};
  }
}

/// A per-joint mask of J floats as the 8 · pose_blocks(J) floats a SoA layer takes (padding 0).
inline void to_mask_blocks(std::span<const float> mask, std::span<float> out) noexcept {
  INBETWEEN_ASSERT(out.size() == pose_blocks(mask.size()) * pose_block_joints);
  std::size_t j = 0;
  for (; j < mask.size(); ++j) out[j] = mask[j];
  for (; j < out.size(); ++j) out[j] = 0.0f;
}

namespace blend_detail {
/// blend_poses' SoA kernel over `blocks` blocks, additive layers included (src/tracks/blend_kernel.cpp;
/// AVX-512/AVX2/SSE2 chosen on the first call by the CPU).
void blend_blocks8(const BlendLayerSoA* layers, std::size_t layer_count, const float* clean_weight,
                   const AdditiveLayerSoA* additive, std::size_t additive_count, const PoseBlock* rest,
                   PoseBlock* out, std::size_t blocks, float threshold) noexcept;
}  // namespace blend_detail

/// blend_poses on PoseBlock spans: the same formulas as the JointPose overload (top of this
/// header), every block through the 8-lane kernel — no conversion, full-width loads and stores.  On
/// the joints of full groups of 8 without additive layers the result equals the JointPose
/// overload's bit for bit (same kernel arithmetic); the last partial group and the additive layers
/// are computed in 8 lanes here and joint by joint there (within a few ulp, tests/tracks/blend_test.cpp).
/// Every pose span and `out` have rest.size() blocks, every non-empty mask 8 · rest.size() floats
/// (asserted); padding lanes are computed like joints (finite in, finite out) and carry no meaning.
/// `out` must not alias an input.  noexcept, no allocation.
inline void blend_poses(std::span<const BlendLayerSoA> layers, std::span<const AdditiveLayerSoA> additive,
                        std::span<const PoseBlock> rest, std::span<PoseBlock> out,
                        const BlendOptions<float>& options = {}) noexcept {
  const std::size_t blocks = rest.size();
  INBETWEEN_ASSERT(out.size() == blocks);
  INBETWEEN_ASSERT(options.threshold > 0.0f && options.threshold <= blend_weight_max<float>);
  INBETWEEN_ASSERT(layers.size() <= blend_max_layers);
  for ([[maybe_unused]] const BlendLayerSoA& l : layers)
    INBETWEEN_ASSERT(l.pose.size() == blocks && (l.mask.empty() || l.mask.size() == blocks * pose_block_joints));
  for ([[maybe_unused]] const AdditiveLayerSoA& l : additive)
    INBETWEEN_ASSERT(l.delta.size() == blocks && (l.mask.empty() || l.mask.size() == blocks * pose_block_joints));
  float clean_weight[blend_max_layers];
  for (std::size_t l = 0; l < layers.size(); ++l) clean_weight[l] = blend_detail::clean(layers[l].weight);
  blend_detail::blend_blocks8(layers.data(), layers.size(), clean_weight, additive.data(), additive.size(),
                              rest.data(), out.data(), blocks, options.threshold);
}

/// The target's weight of a crossfade `t` seconds (or frames) after it started over `duration`
/// (> 0): smoothstep 3u² − 2u³ of u = t/duration clamped to [0, 1] — 0 before the start, 1 after
/// the end, zero slope at both ends.  The source's weight is 1 minus it (two BlendLayers).  A
/// non-positive or NaN duration is an instant switch (1 for t ≥ 0, else 0); NaN t gives 0.
template <Real T>
[[nodiscard]] T crossfade_weight(T t, T duration) noexcept {
  if (!(duration > T(0))) return t >= T(0) ? T(1) : T(0);
  const T u = std::clamp(t / duration, T(0), T(1));
  if (!(u == u)) return T(0);
  return u * u * (T(3) - T(2) * u);
}

}  // namespace inbetween
