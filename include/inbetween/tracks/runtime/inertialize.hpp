#pragma once
/// Inertialization (David Bollo, "Inertialization: High-Performance Animation Transitions in
/// Gears of War", GDC 2018; docs/blending.md): at the switch from a source to a target pose,
/// record per joint the offset source − target (translation and scale as vectors, rotation as the
/// rotation vector of q_source · q_target*) and its velocity (from the previous frame of both), then
/// play the target alone plus that offset decayed to zero by a quintic over the blend time.  The
/// output equals the source at the switch and moves with the source's velocity there (C¹); after
/// the blend time it is the target.  Bollo decays the offset's magnitude along its direction; here
/// every component of the offset vectors decays with its own quintic, so the velocity is continuous
/// in every direction, not only along the offset (docs/blending.md says why).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween {

/// Bollo's quintic decay of one scalar offset: x(t) = A t⁵ + B t⁴ + C t³ + a0/2 t² + v0 t + x0 on
/// [0, t1] and 0 after, with x(0) = x0, x'(0) = v0, x(t1) = x'(t1) = x''(t1) = 0.  t1 is the blend
/// time, shortened to −5·x0/v0 when the velocity already heads to zero faster (Bollo's guard
/// against overshoot); a0 = max(0, (−8 v0 t1 − 20 x0)/t1²) for x0 ≥ 0 (mirrored for x0 < 0).
template <Real T>
struct QuinticDecay {
  T x0 = T(0), v0 = T(0), a0 = T(0), t1 = T(0), a = T(0), b = T(0), c = T(0);  ///< the coefficients

  /// The decay of offset x0 moving at v0 (per unit of t) over blend_time (> 0; a non-positive or NaN
  /// blend time gives no decay at all: value 0 everywhere).
  [[nodiscard]] static QuinticDecay make(T x0, T v0, T blend_time) noexcept {
    QuinticDecay q;
    if (!(blend_time > T(0)) || !std::isfinite(x0) || !std::isfinite(v0)) return q;
    const T s = x0 < T(0) ? T(-1) : T(1);  // mirror so that the offset is ≥ 0
    const T x = s * x0, v = s * v0;
    T t1 = blend_time;
    if (v < T(0) && x > T(0)) t1 = std::min(t1, T(-5) * x / v);
    if (!(t1 > T(0))) return q;
    const T a0 = std::max(T(0), (T(-8) * v * t1 - T(20) * x) / (t1 * t1));
    const T t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
    q.x0 = x0;
    q.v0 = v0;
    q.a0 = s * a0;
    q.t1 = t1;
    q.a = s * (-(a0 * t2 + T(6) * v * t1 + T(12) * x) / (T(2) * t5));
    q.b = s * ((T(3) * a0 * t2 + T(16) * v * t1 + T(30) * x) / (T(2) * t4));
    q.c = s * (-(T(3) * a0 * t2 + T(12) * v * t1 + T(20) * x) / (T(2) * t3));
    return q;
  }
  /// x(t); t ≤ 0 gives x0 (before the switch the offset is held), t ≥ t1 gives 0.
  [[nodiscard]] T value(T t) const noexcept {
    if (!(t < t1)) return T(0);
    t = std::max(t, T(0));
    return (((((a * t + b) * t + c) * t + a0 / T(2)) * t + v0) * t) + x0;
  }
  /// x'(t) (0 for t ≥ t1, v0 for t ≤ 0).
  [[nodiscard]] T velocity(T t) const noexcept {
    if (!(t < t1)) return T(0);
    t = std::max(t, T(0));
    return (((T(5) * a * t + T(4) * b) * t + T(3) * c) * t + a0) * t + v0;
  }
  /// x''(t) (0 for t ≥ t1).
  [[nodiscard]] T acceleration(T t) const noexcept {
    if (!(t < t1)) return T(0);
    t = std::max(t, T(0));
    return ((T(20) * a * t + T(12) * b) * t + T(6) * c) * t + a0;
  }
};

/// One joint's offset at a switch: offsets source − target and their velocities (per unit of the
/// time the caller passes to inertialize_begin's dt).
template <Real T>
struct JointOffset {
  Vec3<T> translation{};           ///< t_source − t_target
  Vec3<T> translation_velocity{};  ///< its rate of change at the switch
  Vec3<T> rotation{};              ///< rotation vector (axis × angle, |r| ≤ π) of q_source · q_target*
  Vec3<T> rotation_velocity{};     ///< its rate of change at the switch
  Vec3<T> scale{};                 ///< s_source − s_target
  Vec3<T> scale_velocity{};        ///< its rate of change at the switch
};

/// Records the offsets at a switch: the source and target poses at the switch and one step `dt`
/// (> 0, finite; asserted) before it.  All spans of equal size (asserted).  noexcept, no allocation.
template <Real T>
void inertialize_begin(std::span<const JointPose<T>> source_prev, std::span<const JointPose<T>> source,
                       std::span<const JointPose<T>> target_prev, std::span<const JointPose<T>> target, T dt,
                       std::span<JointOffset<T>> offsets) noexcept {
  const std::size_t n = source.size();
  INBETWEEN_ASSERT(source_prev.size() == n && target_prev.size() == n && target.size() == n && offsets.size() == n);
  INBETWEEN_ASSERT(dt > T(0) && std::isfinite(dt));
  const auto rot = [](const Quat<T>& s, const Quat<T>& t) { return rotation_vector_from_quat(s * conjugate(t)); };
  for (std::size_t j = 0; j < n; ++j) {
    JointOffset<T>& o = offsets[j];
    o.translation = source[j].translation - target[j].translation;
    o.translation_velocity = (o.translation - (source_prev[j].translation - target_prev[j].translation)) / dt;
    o.scale = source[j].scale - target[j].scale;
    o.scale_velocity = (o.scale - (source_prev[j].scale - target_prev[j].scale)) / dt;
    o.rotation = rot(source[j].rotation, target[j].rotation);
    const Vec3<T> before = rot(source_prev[j].rotation, target_prev[j].rotation);
    // The rotation vector jumps where the angle passes π; take the difference on the short side
    // (r and r − 2π·r/|r| are the same rotation).
    Vec3<T> step = o.rotation - before;
    const T len = norm(o.rotation);
    if (len > T(0) && norm(step) > pi_v<T>) {
      const Vec3<T> alt = o.rotation - (T(2) * pi_v<T> / len) * o.rotation - before;
      if (norm(alt) < norm(step)) step = alt;
    }
    o.rotation_velocity = step / dt;
  }
}

/// The target pose plus the offsets decayed to time `t` after the switch (QuinticDecay per
/// component over blend_time): translation and scale add, rotation is exp(r(t)) · q_target.  At
/// t = 0 that is the source pose; for t ≥ blend_time it is the target.  Spans of equal size
/// (asserted); out may alias target.  noexcept, no allocation.
template <Real T>
void inertialize(std::span<const JointOffset<T>> offsets, T t, T blend_time, std::span<const JointPose<T>> target,
                 std::span<JointPose<T>> out) noexcept {
  const std::size_t n = target.size();
  INBETWEEN_ASSERT(offsets.size() == n && out.size() == n);
  const auto decay = [&](const Vec3<T>& x, const Vec3<T>& v) {
    return Vec3<T>{QuinticDecay<T>::make(x.x, v.x, blend_time).value(t), QuinticDecay<T>::make(x.y, v.y, blend_time).value(t),
                   QuinticDecay<T>::make(x.z, v.z, blend_time).value(t)};
  };
  for (std::size_t j = 0; j < n; ++j) {
    const JointOffset<T>& o = offsets[j];
    JointPose<T> p = target[j];
    p.translation = p.translation + decay(o.translation, o.translation_velocity);
    p.scale = p.scale + decay(o.scale, o.scale_velocity);
    p.rotation = quat_from_rotation_vector(decay(o.rotation, o.rotation_velocity)) * p.rotation;
    out[j] = p;
  }
}

}  // namespace inbetween
