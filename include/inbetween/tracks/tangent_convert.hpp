#pragma once
/// Tangent conventions: a Blender F-curve Bézier segment (keys and absolute handles in
/// (frame, value)) ↔ a cubic Hermite segment (key values and slopes), the form of glTF's
/// CUBICSPLINE sampler.  A Bézier segment whose time handles sit at thirds of the interval is
/// exactly a Hermite segment with slope = handle's value offset / handle's frame offset; any other
/// segment is a cubic in the Bézier parameter but not in time, and converting it loses accuracy —
/// bezier_hermite_loss() measures how much.  glTF stores tangents as derivatives per second (its
/// sampler multiplies them by the key interval in seconds): gltf_tangent = slope per frame × fps.
/// docs/gltf.md derives the formulas.

#include "inbetween/math/vec.hpp"

namespace inbetween {

/// One Bézier segment of an F-curve: key p0, its right handle h0, the next key's left handle h1,
/// the next key p1, all absolute (frame, value) points, p0.x < p1.x.
struct BezierSegment {
  Vec2d p0{};  ///< start key (frame, value)
  Vec2d h0{};  ///< right handle of the start key
  Vec2d h1{};  ///< left handle of the end key
  Vec2d p1{};  ///< end key
};

/// One cubic Hermite segment: value(frame) between two keys with the slopes (value per frame)
/// leaving the first key and arriving at the second.
struct HermiteSegment {
  double frame0 = 0;     ///< start frame
  double frame1 = 1;     ///< end frame (> frame0)
  double value0 = 0;     ///< value at frame0
  double value1 = 0;     ///< value at frame1
  double out_slope = 0;  ///< d value / d frame leaving frame0
  double in_slope = 0;   ///< d value / d frame arriving at frame1
};

/// Blender 3.4's handle correction (BKE_fcurve_correct_bezpart): a handle whose frame length
/// exceeds the interval is scaled back to the interval's length (the pair may still make x(u) turn
/// back; bezier_value() then takes the first root); handles on the wrong side of their key are
/// first pulled onto the key's frame.
[[nodiscard]] BezierSegment corrected(const BezierSegment& seg) noexcept;

/// The Hermite segment with the same keys and the slopes of the (corrected) handles.  Exact (the
/// same function of frame) when handles_at_thirds(); otherwise the closest Hermite in slope.  A
/// handle with zero frame length (vertical) gives the chord slope, documented fallback.
[[nodiscard]] HermiteSegment bezier_to_hermite(const BezierSegment& seg) noexcept;

/// The Bézier segment with handles at thirds of the interval: h0 = p0 + (h/3, out·h/3), h1 = p1 −
/// (h/3, in·h/3).  Exact: bezier_value(hermite_to_bezier(s), f) = hermite_value(s, f).
[[nodiscard]] BezierSegment hermite_to_bezier(const HermiteSegment& seg) noexcept;

/// True when both (corrected) handles' frame offsets are h/3 within `relative_tolerance`·h.
[[nodiscard]] bool handles_at_thirds(const BezierSegment& seg, double relative_tolerance = 1e-9) noexcept;

/// The Hermite segment's value at `frame` (clamped to [frame0, frame1]).
[[nodiscard]] double hermite_value(const HermiteSegment& seg, double frame) noexcept;

/// The (corrected) Bézier segment's value at `frame` (clamped to the keys' frames): solves
/// x(u) = frame for the Bézier parameter by bisection in double (the first root when x(u) is not
/// monotone), then returns y(u).
[[nodiscard]] double bezier_value(const BezierSegment& seg, double frame) noexcept;

/// Largest |bezier_value − hermite_value(bezier_to_hermite)| over the segment and where it occurs.
struct ConversionLoss {
  double max_error = 0;  ///< value units
  double at_frame = 0;   ///< frame of the largest error
};

/// Measures the loss of bezier_to_hermite() on `samples` + 1 evenly spaced frames (≥ 2 samples).
[[nodiscard]] ConversionLoss bezier_hermite_loss(const BezierSegment& seg, int samples = 1024) noexcept;

/// glTF CUBICSPLINE tangent (value per second) of a slope in value per frame.
[[nodiscard]] constexpr double gltf_tangent_from_slope(double slope_per_frame, double fps) noexcept {
  return slope_per_frame * fps;
}
/// Slope per frame of a glTF CUBICSPLINE tangent (value per second); fps > 0.
[[nodiscard]] constexpr double slope_from_gltf_tangent(double tangent_per_second, double fps) noexcept {
  return tangent_per_second / fps;
}

}  // namespace inbetween
