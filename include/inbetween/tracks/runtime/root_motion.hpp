#pragma once
/// Root motion (issue 23; docs/blending.md, "Root motion"): splits a root joint's pose into the
/// character's motion on the ground — the horizontal translation and the yaw — and the rest, left in
/// character space, so that  world = motion ∘ character  holds exactly (up to rounding).  The
/// semantics are ozz-animation 0.16's offline MotionExtractor: the project's up axis is +Y (glTF,
/// docs/scene-format.md), so the ground plane is XZ and yaw is the heading about +Y of a Y-Z-X
/// decomposition (ozz's ToEuler: the direction of the rotated +X axis in the ground plane); the
/// motion is taken relative to a reference (absolute, a rest pose, or the first frame); baking
/// moves it out of the root; looping spreads the end-to-start difference over the frames.
/// The root joint is a joint without a parent (its local transform is its world transform); the
/// other joints are relative to it and need no change, so no hierarchy is needed here (tracks
/// module, next to the rest of the runtime).

#include <cmath>
#include <cstddef>
#include <span>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween {

/// What root motion is measured from (ozz's MotionExtractor::Reference).
enum class MotionReference {
  absolute,     ///< the origin and the identity: the motion is the root's own (masked) transform
  rest,         ///< the rest pose's root transform (the `rest` argument)
  first_frame,  ///< the root's transform at the first frame: the motion starts at the identity
};

/// Which components become root motion, and how.  Defaults: ozz's (X and Z translation, yaw only,
/// baked, not looped) with the first frame as reference.
struct RootMotionOptions {
  bool x = true, y = false, z = true;            ///< translation components extracted (Y is up)
  bool yaw = true, pitch = false, roll = false;  ///< rotation angles extracted (heading about Y, then Z, then X)
  MotionReference position_reference = MotionReference::first_frame;  ///< reference of the translation
  MotionReference rotation_reference = MotionReference::first_frame;  ///< reference of the rotation
  bool bake = true;  ///< remove the motion from the root (false: the root is copied unchanged)
  bool loop = false;  ///< make the last frame's motion equal the first's (the difference spread linearly)
};

/// The character's transform in the world at one frame: translation t and rotation q, applied as
/// p_world = t + q·p_character.
template <Real T>
struct RootMotion {
  Vec3<T> translation{};  ///< world position of the character's origin
  Quat<T> rotation{};     ///< world rotation of the character (unit)
};

/// Heading, attitude and bank (radians) of q in ozz's convention, q = Ry(yaw)·Rz(pitch)·Rx(roll):
/// yaw ∈ (−π, π], pitch ∈ [−π/2, π/2], roll ∈ (−π, π].  At the poles (|pitch| within 0.8° of π/2)
/// roll is 0 and yaw takes the whole turn about the vertical, as ozz does.
template <Real T>
[[nodiscard]] Vec3<T> yaw_pitch_roll(const Quat<T>& q) noexcept {
  const T sqw = q.w * q.w, sqx = q.x * q.x, sqy = q.y * q.y, sqz = q.z * q.z;
  const T unit = sqx + sqy + sqz + sqw;
  const T test = q.x * q.y + q.z * q.w;
  if (test > T(0.499) * unit) return {T(2) * std::atan2(q.x, q.w), pi_v<T> / T(2), T(0)};
  if (test < T(-0.499) * unit) return {T(-2) * std::atan2(q.x, q.w), -pi_v<T> / T(2), T(0)};
  return {std::atan2(T(2) * (q.y * q.w - q.x * q.z), sqx - sqy - sqz + sqw), std::asin(T(2) * test / unit),
          std::atan2(T(2) * (q.x * q.w - q.y * q.z), -sqx + sqy - sqz + sqw)};
}

/// The rotation Ry(yaw)·Rz(pitch)·Rx(roll) (inverse of yaw_pitch_roll away from the poles).
template <Real T>
[[nodiscard]] Quat<T> quat_from_yaw_pitch_roll(const Vec3<T>& ypr) noexcept {
  const Quat<T> ry = Quat<T>::from_wxyz(std::cos(ypr.x / T(2)), T(0), std::sin(ypr.x / T(2)), T(0));
  const Quat<T> rz = Quat<T>::from_wxyz(std::cos(ypr.y / T(2)), T(0), T(0), std::sin(ypr.y / T(2)));
  const Quat<T> rx = Quat<T>::from_wxyz(std::cos(ypr.z / T(2)), std::sin(ypr.z / T(2)), T(0), T(0));
  return ry * rz * rx;
}

/// The reference transform of root motion for a clip whose root starts at `first` (used by
/// MotionReference::first_frame) with rest pose `rest` (used by MotionReference::rest).
template <Real T>
[[nodiscard]] RootMotion<T> root_motion_reference(const RootMotionOptions& options, const JointPose<T>& first,
                                                  const JointPose<T>& rest = {}) noexcept {
  RootMotion<T> ref;
  if (options.position_reference == MotionReference::rest) ref.translation = rest.translation;
  if (options.position_reference == MotionReference::first_frame) ref.translation = first.translation;
  if (options.rotation_reference == MotionReference::rest) ref.rotation = rest.rotation;
  if (options.rotation_reference == MotionReference::first_frame) ref.rotation = first.rotation;
  return ref;
}

/// The motion part of one root pose relative to `reference`: translation (t − t_ref) with the
/// unselected components zeroed; rotation from the selected yaw/pitch/roll of q·q_ref*.
template <Real T>
[[nodiscard]] RootMotion<T> root_motion_of(const JointPose<T>& root, const RootMotion<T>& reference,
                                           const RootMotionOptions& options) noexcept {
  const Vec3<T> d = root.translation - reference.translation;
  RootMotion<T> m;
  m.translation = {options.x ? d.x : T(0), options.y ? d.y : T(0), options.z ? d.z : T(0)};
  const Vec3<T> ypr = yaw_pitch_roll(root.rotation * conjugate(reference.rotation));
  m.rotation = quat_from_yaw_pitch_roll(Vec3<T>{options.yaw ? ypr.x : T(0), options.pitch ? ypr.y : T(0), options.roll ? ypr.z : T(0)});
  return m;
}

/// The root in character space given its world pose and the motion: q = m_q*·q_world,
/// t = m_q*·(t_world − m_t), scale unchanged; apply_root_motion undoes it.
template <Real T>
[[nodiscard]] JointPose<T> remove_root_motion(const JointPose<T>& root, const RootMotion<T>& motion) noexcept {
  JointPose<T> p = root;
  const Quat<T> inv = conjugate(motion.rotation);
  p.translation = rotate(inv, root.translation - motion.translation);
  p.rotation = inv * root.rotation;
  return p;
}

/// The root's world pose from the motion and the character-space root: t = m_t + m_q·t_c,
/// q = m_q·q_c, scale unchanged.
template <Real T>
[[nodiscard]] JointPose<T> apply_root_motion(const RootMotion<T>& motion, const JointPose<T>& root) noexcept {
  JointPose<T> p = root;
  p.translation = motion.translation + rotate(motion.rotation, root.translation);
  p.rotation = motion.rotation * root.rotation;
  return p;
}

/// Extracts root motion from a clip's root joint sampled at N frames (`root`, one pose per frame):
/// `motion` gets the motion track, `root_in_character` the root with the motion removed (a copy when
/// options.bake is false).  With options.loop the motion's end-to-start difference is spread
/// linearly over the frames (translation: t_i += (t_0 − t_N−1)·i/(N−1); rotation: q_i =
/// nlerp(1, q_0·q_N−1*, i/(N−1))·q_i, as ozz) and the bake uses the looped motion, so
/// apply_root_motion(motion[i], root_in_character[i]) gives root[i] back in every case with bake
/// (ozz bakes the translation before looping, which loses that).  Spans of equal size (asserted);
/// root_in_character may alias root.  noexcept, no allocation.
template <Real T>
void extract_root_motion(std::span<const JointPose<T>> root, const RootMotionOptions& options,
                         std::span<RootMotion<T>> motion, std::span<JointPose<T>> root_in_character,
                         const JointPose<T>& rest = {}) noexcept {
  const std::size_t n = root.size();
  INBETWEEN_ASSERT(motion.size() == n && root_in_character.size() == n);
  if (n == 0) return;
  const RootMotion<T> ref = root_motion_reference(options, root[0], rest);
  for (std::size_t i = 0; i < n; ++i) motion[i] = root_motion_of(root[i], ref, options);
  if (options.loop && n > 1) {
    const Vec3<T> dt = motion[0].translation - motion[n - 1].translation;
    Quat<T> dq = motion[0].rotation * conjugate(motion[n - 1].rotation);
    if (dq.w < T(0)) dq = -dq;
    for (std::size_t i = 0; i < n; ++i) {
      const T alpha = T(i) / T(n - 1);
      motion[i].translation = motion[i].translation + dt * alpha;
      const Quat<T> step = normalized(Quat<T>{} * (T(1) - alpha) + dq * alpha);
      motion[i].rotation = normalized(step * motion[i].rotation);
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    root_in_character[i] = options.bake ? remove_root_motion(root[i], motion[i]) : root[i];
}

}  // namespace inbetween
