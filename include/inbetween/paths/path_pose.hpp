#pragma once
/// Position and orientation of an object moving along a path at a given animation frame: the
/// position from p = P(U(S(t))) (timing/motion.hpp: normalised time t, ease S, arc length U) and the
/// orientation from any frame field along the curve (RotationMinimizingFrames, FrenetFrames, or
/// anything with frame_at(u)) evaluated at the same u.

#include "inbetween/math/transform.hpp"
#include "inbetween/paths/path_frame.hpp"
#include "inbetween/timing/motion.hpp"

namespace inbetween {

/// Anything that answers frame_at(u) with a PathFrame.
template <class F, class T>
concept PathFrameField = requires(const F& f, T u) {
  { f.frame_at(u) } -> std::same_as<PathFrame<T>>;
};

/// Where an object is and how it is turned at one animation frame.
template <Real T>
struct PathPose {
  Vec3<T> position{};     ///< P(u)
  PathFrame<T> frame{};   ///< orientation: tangent, normal, binormal at u
  T t{};                  ///< normalised time
  T s{};                  ///< arc length travelled
  T u{};                  ///< curve parameter

  /// world_from_object as a TRS transform: the object's x axis along the tangent, y along the
  /// normal, z along the binormal, origin at the position.
  Transform<T> transform() const noexcept { return {position, frame.rotation(), {T(1), T(1), T(1)}}; }
};

/// The pose at `frame_number` (see motion_at_frame for clamping outside the frame range).
template <Curve C, class A, class E, class F>
  requires ArcLengthParameterisation<A, typename C::scalar_type> &&
           DistanceTimeFunction<E, typename C::scalar_type> && PathFrameField<F, typename C::scalar_type>
PathPose<typename C::scalar_type> pose_at_frame(const C& curve, const A& arc, const E& ease, const F& frames,
                                                FrameRange<typename C::scalar_type> range,
                                                typename C::scalar_type frame_number) noexcept {
  const auto m = motion_at_frame(curve, arc, ease, range, frame_number);
  return {m.position, frames.frame_at(m.u), m.t, m.s, m.u};
}

}  // namespace inbetween
