#pragma once
/// Motion along a path: p = P(U(S(t))) (texts 004 §3.2.2, 000 §2.4).  The five steps of 000 §2.4
/// for a frame f between a start and an end frame:
///   1. t = (f − start)/(end − start), normalised time;
///   2. s = S(t), normalised distance from a distance-time function (ease);
///   3. s_actual = s · L, with L the curve's length;
///   4. u = U(s_actual) from the arc-length object;
///   5. p = P(u).
/// Velocity and acceleration are per frame: v = T̂ · L·S'(t)/Δ and
/// a = T̂ · L·S''(t)/Δ² + κN · (L·S'(t)/Δ)², with Δ = end − start, T̂ the unit tangent and
/// κN = dT̂/ds = (P'' − (P''·T̂)T̂)/|P'|² the curvature vector.

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/curves/curve.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/timing/ease.hpp"

namespace inbetween {

/// The frames over which the whole path is traversed; end > start.
template <Real T>
struct FrameRange {
  T start{};   ///< frame at which the object is at the start of the curve (t = 0)
  T end{1};    ///< frame at which it arrives at the end (t = 1)
};

/// Position, velocity and acceleration of an object moving along a path, and the intermediate
/// values of the five steps.
template <Point P>
struct PathMotionSample {
  using T = scalar_of<P>;  ///< the scalar of P
  P position{};      ///< P(u)
  P velocity{};      ///< dp/dframe
  P acceleration{};  ///< d²p/dframe²
  T t{};             ///< normalised time (step 1)
  T s{};             ///< arc length travelled, in length units (step 3)
  T u{};             ///< curve parameter (step 4)
};

/// Anything that answers the arc-length queries motion needs: length() and u_at(s) (ArcLength,
/// ArcLengthTable).
template <class A, class T>
concept ArcLengthParameterisation = requires(const A& a, T s) {
  { a.length() } -> std::convertible_to<T>;
  { a.u_at(s) } -> std::convertible_to<T>;
};

/// The motion at `frame` along `curve`, measured by `arc`, timed by `ease`, between frames.start
/// and frames.end.  Outside the frame range the object rests at the nearest end (velocity and
/// acceleration zero); an empty or reversed range (end ≤ start) places it at the start before
/// `end` and at the end from `end` on, at rest.  Where the curve's speed is zero (a cusp or
/// coincident control points) the tangent is taken along P'' (the one-sided limit) and the
/// curvature term is dropped; when P'' is zero too the direction is zero.  Never NaN for a built
/// curve and finite ease values; a NaN frame reads as a frame before the start.
template <Curve C, class A, class E>
  requires ArcLengthParameterisation<A, typename C::scalar_type> &&
           DistanceTimeFunction<E, typename C::scalar_type>
PathMotionSample<typename C::point_type> motion_at_frame(const C& curve, const A& arc, const E& ease,
                                                         FrameRange<typename C::scalar_type> frames,
                                                         typename C::scalar_type frame) noexcept {
  using T = typename C::scalar_type;
  using P = typename C::point_type;
  PathMotionSample<P> out;
  const T span = frames.end - frames.start;
  bool moving = span > T(0);
  T t;
  if (!moving) {
    t = frame >= frames.end ? T(1) : T(0);
  } else {
    t = (frame - frames.start) / span;  // step 1
    if (!(t >= T(0))) {                   // before the start (or NaN): at rest at the start
      t = T(0);
      moving = false;
    } else if (t > T(1)) {                // after the end: at rest at the end
      t = T(1);
      moving = false;
    }
  }
  const EaseSample<T> e = ease.sample(t);  // step 2
  const T L = T(arc.length());
  out.t = t;
  out.s = e.s * L;                 // step 3
  out.u = T(arc.u_at(out.s));      // step 4
  out.position = curve.point(out.u);  // step 5
  if (!moving) return out;
  const P d1 = curve.derivative(out.u, 1);
  const P d2 = curve.derivative(out.u, 2);
  const T speed = norm(d1);
  const T ds_dframe = L * e.velocity / span;
  const T dds_dframe2 = L * e.acceleration / (span * span);
  if (speed > T(0) && std::isfinite(speed)) {
    const P tangent = d1 / speed;
    const P curvature = (d2 - tangent * dot(d2, tangent)) / (speed * speed);
    out.velocity = tangent * ds_dframe;
    out.acceleration = tangent * dds_dframe2 + curvature * (ds_dframe * ds_dframe);
  } else {
    const P tangent = normalized(d2, P{});
    out.velocity = tangent * ds_dframe;
    out.acceleration = tangent * dds_dframe2;
  }
  return out;
}

/// The same with the curve taken from the arc-length object.
template <Curve C, class E>
  requires DistanceTimeFunction<E, typename C::scalar_type>
PathMotionSample<typename C::point_type> motion_at_frame(const ArcLength<C>& arc, const E& ease,
                                                         FrameRange<typename C::scalar_type> frames,
                                                         typename C::scalar_type frame) noexcept {
  return motion_at_frame(arc.curve(), arc, ease, frames, frame);
}

}  // namespace inbetween
