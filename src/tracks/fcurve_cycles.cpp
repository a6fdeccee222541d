// The Cycles modifier of an F-curve: maps a frame outside the keyed range onto the keyed range
// (repeat, repeat with offset, mirror), as Blender 3.4's fcm_cycles_time does, in float.
#include "inbetween/tracks/fcurve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace inbetween {

using Key = FCurve::Key;

FCurve::CycleMap FCurve::map_cycles(float frame) const noexcept {
  // ±inf acts as the largest finite frame: linear extrapolation would give 0·inf and the Cycles
  // modifier fmod(inf, ·), both NaN.
  if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<float>::max(), frame);
  float t = frame;
  float offset = 0.0f;
  float sign = 1.0f;
  if (cycles_) {
    const Key& first = keys_.front();
    const Key& last = keys_.back();
    int side = 0;
    CycleMode mode = CycleMode::none;
    int count = 0;
    float ofs = 0;
    if (t < first.x) {
      if (cycles_->before != CycleMode::none) {
        side = -1;
        mode = cycles_->before;
        count = cycles_->count_before;
        ofs = first.x;
      }
    } else if (t > last.x) {
      if (cycles_->after != CycleMode::none) {
        side = 1;
        mode = cycles_->after;
        count = cycles_->count_after;
        ofs = last.x;
      }
    }
    const float cycdx = last.x - first.x;
    const float cycdy = last.y - first.y;
    if (side != 0 && mode != CycleMode::none && cycdx != 0) {
      const float rel = t - ofs;
      const float cycle = float(side) * rel / cycdx;
      const float cyct = float(std::fmod(double(rel), double(cycdx)));
      if (count == 0 || !(cycle > float(count))) {
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
          t = side == 1 ? last.x : first.x;
          if (mode == CycleMode::mirror && (static_cast<long long>(cycle_clamped) % 2) != 0) {
            t = side == 1 ? first.x : last.x;
            sign = -1.0f;
          }
        } else if (mode == CycleMode::mirror && (static_cast<long long>(cycle_clamped + 1) % 2) != 0) {
          t = side < 0 ? first.x - cyct : last.x - cyct;
          sign = -1.0f;
        } else {
          t = first.x + cyct;
        }
        if (t < first.x) t += cycdx;
      }
    }
  }
  return {t, offset, sign};
}

}  // namespace inbetween
