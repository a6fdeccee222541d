#pragma once
// Internals shared by the F-curve sources (src/tracks/fcurve_*.cpp); not installed, not public.
#include <optional>
#include <vector>

#include "inbetween/tracks/fcurve.hpp"

namespace inbetween::fcurve_detail {

/// Recomputes the handles of `keys` (built, single precision, handles already clamped to their
/// key's side) as Blender's FCurve.update() does: per-key handles, then continuous-acceleration
/// smoothing when `smoothing` asks for it; cycle-aware when `cycles` repeats forever on both sides.
void recalc_handles(std::vector<FCurve::Key>& keys, Extrapolation extrapolation, AutoSmoothing smoothing,
                    const std::optional<FCurveCycles>& cycles);

/// Blender 3.4's Cycles time mapping (fcm_cycles_time, in float, in its order of operations) of
/// `frame` for keys first (x, y) … last (x, y), with the decisions it took: the FCurve's
/// map_cycles and the runtime's cycle folding (fcurve_clip.cpp) both call it, so they agree.
struct CycleDecision {
  float t = 0;       ///< the frame inside the keyed range (unchanged when not cycled)
  float offset = 0;  ///< value added by repeat_offset
  float sign = 1;    ///< d t / d frame: −1 on a mirrored copy
  int side = 0;      ///< −1 before the first key, +1 after the last (with a mode other than none), 0 otherwise
  bool cycled = false;  ///< side ≠ 0 and within the side's cycle count
  float cycle = 0;   ///< Blender's cycle number side·(frame − end key)/period (when side ≠ 0)
};
/// See CycleDecision.
CycleDecision decide_cycles(const FCurveCycles& cycles, float first_x, float first_y, float last_x, float last_y,
                            float frame) noexcept;

}  // namespace inbetween::fcurve_detail
