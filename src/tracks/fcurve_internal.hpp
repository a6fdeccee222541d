#pragma once
// Internals shared by the F-curve sources (src/tracks/fcurve_*.cpp); not installed, not public.
#include <optional>
#include <span>
#include <vector>

#include "inbetween/tracks/fcurve.hpp"

namespace inbetween::fcurve_detail {

/// Recomputes the handles of `keys` (built, single precision, handles already clamped to their
/// key's side) as Blender's FCurve.update() does: per-key handles, then continuous-acceleration
/// smoothing when `smoothing` asks for it; cycle-aware when `cycles` (the stack's leading Cycles
/// modifier, leading_cycles()) repeats forever on both sides.
void recalc_handles(std::vector<FCurve::Key>& keys, Extrapolation extrapolation, AutoSmoothing smoothing,
                    const FCurveCycles* cycles);

/// The first modifier of the stack when it is an unmuted Cycles modifier without influence or frame
/// range (Blender's BKE_fcurve_get_cycle_type looks at it for cycle-aware handles), else nullptr.
const FCurveCycles* leading_cycles(std::span<const FCurveModifier> modifiers) noexcept;

// ------------------------------------------------------------------ the modifiers' parts (fmodifier_eval.cpp)
/// Whether modifier `m` acts at frame t (outside its restricted range it is skipped).
bool in_range(const FCurveModifier& m, float t) noexcept;
/// Blender's eval_fmodifier_influence: the influence (or 1), 0 outside the range, ramped over blend in/out.
float modifier_influence(const FCurveModifier& m, float t) noexcept;
/// d modifier_influence / d t (the ramps' slopes, else 0).
double modifier_influence_slope(const FCurveModifier& m, float t) noexcept;
float limits_time(const FCurveLimits& l, float t) noexcept;                        ///< fcm_limits_time
float stepped_time(const FCurveStepped& s, float t) noexcept;                      ///< fcm_stepped_time
float generator_value(const FCurveGenerator& g, float value, float t) noexcept;    ///< fcm_generator_evaluate
float function_value(const FCurveFunction& f, float value, float t) noexcept;      ///< fcm_fn_generator_evaluate
float envelope_value(const FCurveEnvelope& e, float value, float t) noexcept;      ///< fcm_envelope_evaluate
float limits_value(const FCurveLimits& l, float value) noexcept;                   ///< fcm_limits_evaluate
float noise_value(const FCurveNoise& n, float value, float t) noexcept;            ///< fcm_noise_evaluate

/// Checks `m` (modifier `index` of the stack) as build_fcurve() documents; the error's location is
/// {"modifiers", index, member}.
std::optional<Error> check_modifier(const FCurveModifier& m, std::size_t index);

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
