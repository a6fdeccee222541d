// Building an F-curve: validation of the authored keys (errors with their location), conversion to
// Blender's single-precision storage, then the handle recalculation (fcurve_handles.cpp).
#include "fcurve_internal.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "inbetween/math/format.hpp"

namespace inbetween {

using fcurve_detail::recalc_handles;

Expected<FCurve> build_fcurve(const RawFCurve& raw) {
  if (raw.keys.empty()) {
    return Error{ErrorCode::too_few_points, "a track needs at least one key", {"keys"}};
  }
  auto where = [](std::size_t i) { return std::vector<LocationStep>{"keys", i}; };
  FCurve curve;
  curve.keys_.reserve(raw.keys.size());
  for (std::size_t i = 0; i < raw.keys.size(); ++i) {
    const FCurveKey& k = raw.keys[i];
    if (!std::isfinite(k.frame)) return Error{ErrorCode::not_finite, "frame is not finite", where(i)};
    if (!std::isfinite(k.value)) return Error{ErrorCode::not_finite, "value is not finite", where(i)};
    const Vec2d handle_left = k.handle_left.value_or(Vec2d{k.frame - 1, k.value});
    const Vec2d handle_right = k.handle_right.value_or(Vec2d{k.frame + 1, k.value});
    if (!is_finite(handle_left) || !is_finite(handle_right)) {
      return Error{ErrorCode::not_finite, "a handle is not finite", where(i)};
    }
    if (!std::isfinite(k.back) || !std::isfinite(k.amplitude) || !std::isfinite(k.period)) {
      return Error{ErrorCode::not_finite, "back, amplitude or period is not finite", where(i)};
    }
    if (std::abs(k.frame) > 1e30 || std::abs(k.value) > 1e30) {
      return Error{ErrorCode::invalid_argument, "frame or value beyond single precision (|x| > 1e30)", where(i)};
    }
    // Handles and easing parameters are stored in float too: beyond float's range the conversion
    // is undefined (inf in practice, then NaN in the Bézier solver).
    if (std::max({std::abs(handle_left.x), std::abs(handle_left.y), std::abs(handle_right.x),
                  std::abs(handle_right.y)}) > 1e30) {
      return Error{ErrorCode::invalid_argument, "a handle is beyond single precision (|x| > 1e30)", where(i)};
    }
    if (std::max({std::abs(k.back), std::abs(k.amplitude), std::abs(k.period)}) > 1e30) {
      return Error{ErrorCode::invalid_argument, "back, amplitude or period is beyond single precision (|x| > 1e30)", where(i)};
    }
    if (i > 0) {
      const FCurveKey& p = raw.keys[i - 1];
      if (!(k.frame > p.frame)) {
        return Error{ErrorCode::keys_not_increasing,
                     "frame " + shortest_text<double>(k.frame) + " is not after the previous key's frame " +
                         shortest_text<double>(p.frame) + " (keys must be sorted by strictly increasing frame)", {"keys", i, "frame"}};
      }
      if (!(float(k.frame) > float(p.frame))) {
        return Error{ErrorCode::keys_not_increasing,
                     "frame " + shortest_text<double>(k.frame) + " rounds to the same single-precision frame as key " +
                         std::to_string(i - 1), where(i)};
      }
    }
    FCurve::Key s;
    s.x = float(k.frame);
    s.y = float(k.value);
    s.left = handle_left.cast<float>();
    s.right = handle_right.cast<float>();
    s.interpolation = k.interpolation;
    s.easing = k.easing;
    s.left_type = k.handle_left_type;
    s.right_type = k.handle_right_type;
    s.back = float(k.back);
    s.amplitude = float(k.amplitude);
    s.period = float(k.period);
    // Blender's update(): handles on the wrong side are swapped when both are, else clamped.
    if (s.left.x > s.x && s.right.x < s.x) {
      std::swap(s.left, s.right);
    } else {
      s.left.x = std::min(s.left.x, s.x);
      s.right.x = std::max(s.right.x, s.x);
    }
    curve.keys_.push_back(s);
  }
  for (std::size_t i = 0; i < raw.modifiers.size(); ++i) {
    if (auto e = fcurve_detail::check_modifier(raw.modifiers[i], i)) return std::move(*e);
  }
  curve.extrapolation_ = raw.extrapolation;
  curve.smoothing_ = raw.auto_smoothing;
  curve.modifiers_ = raw.modifiers;
  // One plain Cycles modifier is the fast path (map_cycles); any other stack runs evaluate_stack.
  if (raw.modifiers.size() == 1) {
    if (const FCurveCycles* c = fcurve_detail::leading_cycles(raw.modifiers)) curve.simple_cycles_ = *c;
  }
  recalc_handles(curve.keys_, raw.extrapolation, raw.auto_smoothing, fcurve_detail::leading_cycles(raw.modifiers));
  return curve;
}

}  // namespace inbetween
