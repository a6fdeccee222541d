#pragma once
/// Blender objects: the local transform of an object animated by Blender actions and NLA tracks,
/// evaluated as Blender 3.4 does (docs/nla.md): strip time mapping, influence, extrapolation, the
/// five blend types and channel defaults in single precision, then the object matrix of its
/// rotation mode.  build_scene() builds one BlenderObject per object with a version-3 member;
/// Scene::sample() asks it for the object's local transform.  Evaluation is noexcept and never
/// allocates.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/tracks/fcurve.hpp"

namespace inbetween {

/// The channel values of a Blender object, in this order: location x y z, rotation_euler x y z,
/// rotation_quaternion w x y z, rotation_axis_angle angle x y z, scale x y z.
inline constexpr std::size_t blender_channel_count = 17;
/// First slot of each ActionPath in the channel values, and one past the last (index 5).
inline constexpr std::array<std::uint8_t, 6> blender_path_slots = {0, 3, 6, 10, 14, 17};

namespace nla_detail {
/// A built action: its F-curves by channel slot.
struct Action {
  /// One F-curve and the channel slot it writes.
  struct Channel {
    std::uint8_t slot = 0;  ///< index into the channel values
    FCurve curve;           ///< the F-curve
  };
  std::vector<Channel> channels;  ///< the F-curves, file order
  std::uint8_t paths = 0;    ///< bit p: the action animates ActionPath p
  std::uint32_t domain = 0;  ///< bit k: the NLA writes channel slot k for this action (a quaternion: all four)
  std::uint32_t written = 0;  ///< bit k: the action has an F-curve for slot k
  float key_start = 0, key_end = 0;  ///< Blender's calc_action_range (modifiers included)
  float range_start = 0, range_end = 0;  ///< the manual frame range, else the keys' range (new strips)
};

/// A built strip (or the active action as Blender's dummy strip), in single precision as Blender stores it.
struct Strip {
  std::uint32_t action = 0;  ///< index of the strip's action
  /// Scene frames, action frames, time scale, repetitions and the influence ramps, as Blender stores them.
  float start = 0, end = 0, actstart = 0, actend = 0, scale = 1, repeat = 1, blend_in = 0, blend_out = 0;
  float influence = 1;  ///< the constant of a fixed (user) influence
  /// Played backwards; muted; animated influence on; time mapping off (the active action unless
  /// its extrapolation is nothing); cyclic animated strip time.
  bool reverse = false, muted = false, user_influence = false, no_time_map = false, cyclic_time = false;
  NlaBlend blend = NlaBlend::replace;                        ///< blend type
  NlaExtrapolation extrapolation = NlaExtrapolation::hold;  ///< extrapolation
  std::optional<FCurve> influence_curve;  ///< animated influence
  std::optional<FCurve> time_curve;       ///< animated strip time
};
}  // namespace nla_detail

/// The actions of a scene, built once and shared by the objects that use them.
using BlenderActions = std::shared_ptr<const std::vector<nla_detail::Action>>;

/// A built Blender object's animation: evaluates its local transform at any frame.  Only
/// build_blender_object() makes one.
class BlenderObject {
 public:
  /// The 17 channel values (blender_channel_count: location, rotation_euler, rotation_quaternion,
  /// rotation_axis_angle, scale) at `frame` (single precision, Blender's evaluation time), as
  /// Blender writes them to the object: the NLA stack and active action where they animate a
  /// channel, the default (0, identity, 1) where an animated channel is not covered, the base value
  /// where nothing animates it.
  void sample_channels(float frame, std::span<float, blender_channel_count> out) const noexcept;

  /// The object's transform relative to its parent at `frame`: parent_inverse · local, where local
  /// is the matrix of the channel values in the object's rotation mode (Blender's
  /// BKE_object_to_mat4), as TRS (a negative determinant gives three negative scales, as Blender's
  /// mat4_to_size; a parent_inverse with shear loses the shear).
  [[nodiscard]] Transform<double> local_transform(double frame) const noexcept;

  /// The object's rotation mode.
  [[nodiscard]] RotationMode rotation_mode() const noexcept { return mode_; }

 private:
  friend Expected<BlenderObject> build_blender_object(const RawObject& raw, const std::vector<RawAction>& raw_actions,
                                                      const BlenderActions& actions);
  BlenderObject() = default;
  BlenderActions actions_;
  std::vector<std::vector<nla_detail::Strip>> tracks_;  // evaluated tracks (solo and mute applied), bottom to top
  std::optional<nla_detail::Strip> action_strip_;       // the active action as Blender's dummy strip
  std::optional<std::uint32_t> plain_action_;           // evaluated without NLA (Blender's special case)
  std::array<float, blender_channel_count> base_{};     // never-animated values
  std::uint32_t domain_ = 0;                            // slots the NLA writes
  bool nla_ = false;                                    // the NLA stack is evaluated
  RotationMode mode_ = RotationMode::quaternion;
  std::optional<Mat4d> parent_inverse_;
};

/// Builds every action (errors under {"actions", i, …}): names non-empty and unique, channels
/// within their property (index 0..2, 0..3 for rotation_quaternion and rotation_axis_angle), each
/// (path, index) once, every F-curve (build_fcurve), frame_range finite with start ≤ end.
[[nodiscard]] Expected<BlenderActions> build_blender_actions(const std::vector<RawAction>& raw);

/// Builds one object's Blender animation; errors are relative to the object ({"animation",
/// "tracks", t, "strips", s, "scale"}).  Checks: base values finite and matching the rotation mode,
/// constant translation/rotation/scale when animated, parent_inverse finite and invertible, actions
/// named by strips and the active action exist, strips with scale > 0, repeat > 0, finite frames,
/// action_frame_end ≥ action_frame_start, frame_end (when given) equal to Blender's
/// start + (action range) · scale · repeat within float rounding, strips of a track in time order
/// without overlap, blend_in and blend_out each in [0, the strip's length] (their sum may exceed it, as auto-blend leaves it), a
/// constant influence in [0, 1], action_influence in [0, 1], every strip F-curve, and no COMBINE
/// strip over an action whose scale keys are negative (Blender gives NaN there).
[[nodiscard]] Expected<BlenderObject> build_blender_object(const RawObject& raw, const std::vector<RawAction>& raw_actions,
                                                           const BlenderActions& actions);

}  // namespace inbetween
