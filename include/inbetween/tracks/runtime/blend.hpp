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
/// The kernel is one pass over all layers per group of native_simd<T>::size() joints, the
/// accumulators in registers (ozz-animation's BlendingJob makes a pass per layer, one for the rest
/// pose and one to normalise).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <experimental/simd>

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
namespace stdx = std::experimental;

template <Real T>
using V = stdx::native_simd<T>;

// NaN and negatives → 0, capped at blend_weight_max.
template <Real T>
inline T clean(T w) noexcept {
  return w > T(0) ? std::min(w, blend_weight_max<T>) : T(0);
}
template <class Vt, Real T>
inline Vt clean(Vt w) noexcept {
  Vt r(T(0));
  where(w > Vt(T(0)), r) = stdx::min(w, Vt(blend_weight_max<T>));
  return r;
}

// One field of G consecutive joints (indices past `last` repeat `last`).
template <Real T, class F>
inline V<T> gather(const JointPose<T>* p, std::size_t j0, std::size_t last, F field) noexcept {
  return V<T>([&](auto i) { return field(p[std::min(j0 + std::size_t(i), last)]); });
}

template <Real T>
inline V<T> load_mask(std::span<const T> mask, std::size_t j0, std::size_t n) noexcept {
  if (mask.empty()) return V<T>(T(1));
  if (n == V<T>::size()) return clean<V<T>, T>(V<T>(mask.data() + j0, stdx::element_aligned));
  return clean<V<T>, T>(V<T>([&](auto i) { return mask[std::min(j0 + std::size_t(i), j0 + n - 1)]; }));
}

// The ten fields of a pose group, structure of arrays.
template <Real T>
struct Soa {
  V<T> tx, ty, tz, qw, qx, qy, qz, sx, sy, sz;
};

template <Real T>
inline Soa<T> load(const JointPose<T>* p, std::size_t j0, std::size_t last) noexcept {
  return {gather(p, j0, last, [](const JointPose<T>& a) { return a.translation.x; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.translation.y; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.translation.z; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.rotation.w; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.rotation.x; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.rotation.y; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.rotation.z; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.scale.x; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.scale.y; }),
          gather(p, j0, last, [](const JointPose<T>& a) { return a.scale.z; })};
}

// acc += w·x, the rotation with x's sign flipped where it is off the hemisphere of ref.
template <Real T>
inline void accumulate(Soa<T>& acc, const Soa<T>& x, V<T> w, const V<T>& rw, const V<T>& rx, const V<T>& ry,
                       const V<T>& rz) noexcept {
  acc.tx += w * x.tx;
  acc.ty += w * x.ty;
  acc.tz += w * x.tz;
  acc.sx += w * x.sx;
  acc.sy += w * x.sy;
  acc.sz += w * x.sz;
  V<T> wq = w;
  const V<T> d = rw * x.qw + rx * x.qx + ry * x.qy + rz * x.qz;
  where(d < V<T>(T(0)), wq) = -w;
  acc.qw += wq * x.qw;
  acc.qx += wq * x.qx;
  acc.qy += wq * x.qy;
  acc.qz += wq * x.qz;
}

template <Real T>
void blend_group(std::span<const BlendLayer<T>> layers, std::span<const AdditiveLayer<T>> additive,
                 std::span<const JointPose<T>> rest, JointPose<T>* out, std::size_t j0, std::size_t n,
                 T threshold) noexcept {
  using W = V<T>;
  const std::size_t last = j0 + n - 1;
  const W zero(T(0));
  const Soa<T> r = load(rest.data(), j0, last);
  // The hemisphere: layer 0's rotation (the rest pose's when there is no layer).
  W hw = r.qw, hx = r.qx, hy = r.qy, hz = r.qz;
  if (!layers.empty()) {
    const JointPose<T>* p0 = layers[0].pose.data();
    hw = gather(p0, j0, last, [](const JointPose<T>& a) { return a.rotation.w; });
    hx = gather(p0, j0, last, [](const JointPose<T>& a) { return a.rotation.x; });
    hy = gather(p0, j0, last, [](const JointPose<T>& a) { return a.rotation.y; });
    hz = gather(p0, j0, last, [](const JointPose<T>& a) { return a.rotation.z; });
  }
  Soa<T> acc{zero, zero, zero, zero, zero, zero, zero, zero, zero, zero};
  W sum = zero;
  for (const BlendLayer<T>& layer : layers) {
    const W w = W(clean(layer.weight)) * load_mask(layer.mask, j0, n);
    sum += w;
    accumulate(acc, load(layer.pose.data(), j0, last), w, hw, hx, hy, hz);
  }
  const W th(threshold);
  const W rest_w = stdx::max(th - sum, zero);
  const auto none = sum == zero;  // no layer weight at all: the rest pose exactly (no rounding)
  if (stdx::any_of(rest_w > zero)) {
    accumulate(acc, r, rest_w, hw, hx, hy, hz);
    sum = stdx::max(sum, th);
  }
  const W inv = W(T(1)) / sum;
  Soa<T> o;
  o.tx = acc.tx * inv;
  o.ty = acc.ty * inv;
  o.tz = acc.tz * inv;
  o.sx = acc.sx * inv;
  o.sy = acc.sy * inv;
  o.sz = acc.sz * inv;
  const W n2 = acc.qw * acc.qw + acc.qx * acc.qx + acc.qy * acc.qy + acc.qz * acc.qz;
  // Σ w σ q has length ≥ W·(smallest dot with the hemisphere) and can vanish only for rotations a
  // half turn apart; below this the rest rotation is written instead.
  const auto degenerate = n2 < W(T(64) * std::numeric_limits<T>::min());
  const W rn = W(T(1)) / stdx::sqrt(stdx::max(n2, W(std::numeric_limits<T>::min())));
  o.qw = acc.qw * rn;
  o.qx = acc.qx * rn;
  o.qy = acc.qy * rn;
  o.qz = acc.qz * rn;
  if (stdx::any_of(degenerate)) {
    where(degenerate, o.qw) = r.qw;
    where(degenerate, o.qx) = r.qx;
    where(degenerate, o.qy) = r.qy;
    where(degenerate, o.qz) = r.qz;
  }
  if (stdx::any_of(none)) {
    where(none, o.tx) = r.tx;
    where(none, o.ty) = r.ty;
    where(none, o.tz) = r.tz;
    where(none, o.qw) = r.qw;
    where(none, o.qx) = r.qx;
    where(none, o.qy) = r.qy;
    where(none, o.qz) = r.qz;
    where(none, o.sx) = r.sx;
    where(none, o.sy) = r.sy;
    where(none, o.sz) = r.sz;
  }
  for (const AdditiveLayer<T>& layer : additive) {
    const W w = W(clean(layer.weight)) * load_mask(layer.mask, j0, n);
    const Soa<T> d = load(layer.delta.data(), j0, last);
    o.tx += w * d.tx;
    o.ty += w * d.ty;
    o.tz += w * d.tz;
    const W one(T(1));
    o.sx *= one + w * (d.sx - one);
    o.sy *= one + w * (d.sy - one);
    o.sz *= one + w * (d.sz - one);
    // nlerp(identity, Δq⁺, w), Δq⁺ with w ≥ 0.
    W ws = w;
    where(d.qw < zero, ws) = -w;
    W aw = one - w + ws * d.qw, ax = ws * d.qx, ay = ws * d.qy, az = ws * d.qz;
    const W an = one / stdx::sqrt(stdx::max(aw * aw + ax * ax + ay * ay + az * az, W(std::numeric_limits<T>::min())));
    aw *= an;
    ax *= an;
    ay *= an;
    az *= an;
    const W qw = o.qw * aw - o.qx * ax - o.qy * ay - o.qz * az;
    const W qx = o.qw * ax + o.qx * aw + o.qy * az - o.qz * ay;
    const W qy = o.qw * ay - o.qx * az + o.qy * aw + o.qz * ax;
    const W qz = o.qw * az + o.qx * ay - o.qy * ax + o.qz * aw;
    o.qw = qw;
    o.qx = qx;
    o.qy = qy;
    o.qz = qz;
  }
  for (std::size_t i = 0; i < n; ++i) {
    JointPose<T>& p = out[j0 + i];
    p.translation = {o.tx[i], o.ty[i], o.tz[i]};
    p.rotation = Quat<T>::from_wxyz(o.qw[i], o.qx[i], o.qy[i], o.qz[i]);
    p.scale = {o.sx[i], o.sy[i], o.sz[i]};
  }
}
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
  for (const BlendLayer<T>& l : layers) INBETWEEN_ASSERT(l.pose.size() == joints && (l.mask.empty() || l.mask.size() == joints));
  for (const AdditiveLayer<T>& l : additive) INBETWEEN_ASSERT(l.delta.size() == joints && (l.mask.empty() || l.mask.size() == joints));
  constexpr std::size_t G = blend_detail::V<T>::size();
  for (std::size_t j0 = 0; j0 < joints; j0 += G)
    blend_detail::blend_group<T>(layers, additive, rest, out.data(), j0, std::min(G, joints - j0), options.threshold);
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
