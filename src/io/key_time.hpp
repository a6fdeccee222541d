#pragma once
// The rule of the readers whose key times are seconds (glTF, assimp's FBX and Collada): a range end
// t·fps within the precision of its key time t of a whole frame is that frame (docs/gltf.md, "Range").

#include <algorithm>
#include <cmath>
#include <limits>

namespace inbetween::io_detail {

/// t·fps, or the whole frame nearest to it when the two differ by less than the precision of t:
/// key times authored on frames come back as float32 (Fox.glb's 17/24 s → frame 16.9999995;
/// Collada's 1.666667 s → 39.9999989) or as six significant digits (BoxAnimated's 89/24 s written
/// 3.70833 → frame 88.99992), and the default range would lose that frame or bake every frame off by
/// that much.  Precision: the larger of 4 float32 ulp of t and 5·10⁻⁶·|t| (half a unit in the sixth
/// digit), times fps, at most 10⁻³ frame above the float32 term.
inline double whole_frame_within_key_precision(double t, double fps) {
  const double frame = t * fps;
  const double whole = std::round(frame);
  const float tf = float(t);
  const double ulp = double(std::nextafter(std::abs(tf), std::numeric_limits<float>::infinity())) - double(std::abs(tf));
  const double float_tol = 4 * ulp * fps;
  const double tol = std::max(float_tol, std::min(5e-6 * std::abs(t) * fps, float_tol + 1e-3));
  return std::abs(frame - whole) <= tol ? whole : frame;
}

}  // namespace inbetween::io_detail
