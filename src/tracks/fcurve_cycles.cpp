// The Cycles modifier of an F-curve: maps a frame outside the keyed range onto the keyed range
// (repeat, repeat with offset, mirror), as Blender 3.4's fcm_cycles_time does, in float.
#include "inbetween/tracks/fcurve.hpp"
#include "fcurve_internal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace inbetween {

using Key = FCurve::Key;

namespace fcurve_detail {

CycleDecision decide_cycles(const FCurveCycles& cycles, float first_x, float first_y, float last_x, float last_y,
                            float frame) noexcept {
  float t = frame;
  float offset = 0.0f;
  float sign = 1.0f;
  int side = 0;
  CycleMode mode = CycleMode::none;
  int count = 0;
  float ofs = 0;
  if (t < first_x) {
    if (cycles.before != CycleMode::none) {
      side = -1;
      mode = cycles.before;
      count = cycles.count_before;
      ofs = first_x;
    }
  } else if (t > last_x) {
    if (cycles.after != CycleMode::none) {
      side = 1;
      mode = cycles.after;
      count = cycles.count_after;
      ofs = last_x;
    }
  }
  const float cycdx = last_x - first_x;
  const float cycdy = last_y - first_y;
  if (side == 0 || mode == CycleMode::none || cycdx == 0) return {t, offset, sign, 0, false, 0.0f};
  const float rel = t - ofs;
  const float cycle = float(side) * rel / cycdx;
  const float cyct = float(std::fmod(double(rel), double(cycdx)));
  if (!(count == 0 || !(cycle > float(count)))) return {t, offset, sign, side, false, cycle};
  if (mode == CycleMode::repeat_offset) {
    // Cycle number.  Keys very close together and a far frame overflow it (1e9 / 1.4e-45):
    // it then acts as ±max (as Track's cycle_offset does), so a zero per-cycle change stays
    // 0 (not 0·inf = NaN) and a non-zero one saturates.
    float k = side < 0 ? float(std::floor(rel / cycdx)) : float(std::ceil(rel / cycdx));
    if (std::isinf(k)) k = std::copysign(std::numeric_limits<float>::max(), k);
    offset = k * cycdy;
  }
  // |cycle| is bounded by float range; the int conversion below needs it to fit.
  const float cycle_clamped = std::min(cycle, 2.0e9f);
  if (cyct == 0.0f) {
    t = side == 1 ? last_x : first_x;
    if (mode == CycleMode::mirror && (static_cast<long long>(cycle_clamped) % 2) != 0) {
      t = side == 1 ? first_x : last_x;
      sign = -1.0f;
    }
  } else if (mode == CycleMode::mirror && (static_cast<long long>(cycle_clamped + 1) % 2) != 0) {
    t = side < 0 ? first_x - cyct : last_x - cyct;
    sign = -1.0f;
  } else {
    t = first_x + cyct;
  }
  if (t < first_x) t += cycdx;
  return {t, offset, sign, side, true, cycle};
}

}  // namespace fcurve_detail

FCurve::CycleMap FCurve::map_cycles(float frame) const noexcept {
  // ±inf acts as the largest finite frame: linear extrapolation would give 0·inf and the Cycles
  // modifier fmod(inf, ·), both NaN.
  if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<float>::max(), frame);
  if (!simple_cycles_) return {frame, 0.0f, 1.0f};
  const Key& first = keys_.front();
  const Key& last = keys_.back();
  const fcurve_detail::CycleDecision d =
      fcurve_detail::decide_cycles(*simple_cycles_, first.x, first.y, last.x, last.y, frame);
  return {d.t, d.offset, d.sign};
}

}  // namespace inbetween
