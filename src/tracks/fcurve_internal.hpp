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

}  // namespace inbetween::fcurve_detail
