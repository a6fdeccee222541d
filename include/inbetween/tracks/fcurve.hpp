#pragma once
/// Scalar animation curves with Blender's F-curve semantics (Blender 3.4): per-key interpolation of
/// the segment to the key's right (constant, linear, Bézier, Penner easings), Bézier handle types
/// recomputed as Blender recomputes them (including auto-smoothing "continuous acceleration"),
/// overshooting handles corrected, constant/linear extrapolation and Blender's F-curve modifiers
/// (fmodifier.hpp).
///
/// Blender stores and evaluates F-curves in single precision, and its results depend on that
/// rounding (key snapping, Cycles boundaries, the Bézier root finder).  A built FCurve therefore
/// keeps its keys in float and evaluates in float in Blender's order of operations; docs/tracks.md
/// lists what is reproduced and the measured agreement.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/timing/penner.hpp"
#include "inbetween/math/enum_names.hpp"
#include "inbetween/tracks/fmodifier.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

/// How the segment that starts at a key is interpolated (Blender's key "interpolation").
enum class Interpolation : std::uint8_t {
  constant,  ///< hold the key's value until the next key
  linear,    ///< straight line to the next key
  bezier,    ///< cubic Bézier through this key's right handle and the next key's left handle
  back, bounce, circ, cubic, elastic, expo, quad, quart, quint, sine,  ///< Penner easings (penner.hpp)
};

/// File and command-line names of the Interpolation enumerators, in declaration order.
inline constexpr std::array<std::string_view, 13> interpolation_names = {
    "constant", "linear", "bezier", "back", "bounce", "circ", "cubic", "elastic", "expo", "quad", "quart", "quint", "sine"};
/// The name table of Interpolation (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<Interpolation>() noexcept {
  return interpolation_names;
}

/// Easing direction stored on a key; `automatic` is Blender's "AUTO" (see automatic_direction()).
enum class KeyEasing : std::uint8_t { automatic, ease_in, ease_out, ease_in_out };

/// File and command-line names of the KeyEasing enumerators, in declaration order.
inline constexpr std::array<std::string_view, 4> key_easing_names = {"auto", "ease_in", "ease_out", "ease_in_out"};
/// The name table of KeyEasing (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<KeyEasing>() noexcept {
  return key_easing_names;
}

/// Bézier handle types (Blender's vocabulary).
enum class HandleType : std::uint8_t {
  free,          ///< kept as given
  aligned,       ///< kept collinear with the opposite handle through the key, each keeping its length
  vector,        ///< points at the neighbouring key, a third of the way
  automatic,     ///< smooth: slope from the neighbours (Blender "AUTO")
  auto_clamped,  ///< automatic, but flat at extremes and never past the neighbours' values
};

/// File and command-line names of the HandleType enumerators, in declaration order.
inline constexpr std::array<std::string_view, 5> handle_type_names = {"free", "aligned", "vector", "auto", "auto_clamped"};
/// The name table of HandleType (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<HandleType>() noexcept {
  return handle_type_names;
}

/// Value outside the keyed range (Blender's F-curve "extrapolation").
enum class Extrapolation : std::uint8_t {
  constant,  ///< the end key's value
  linear,    ///< continue along the end key's handle (Bézier/easing) or end segment (linear)
};

/// File and command-line names of the Extrapolation enumerators, in declaration order.
inline constexpr std::array<std::string_view, 2> extrapolation_names = {"constant", "linear"};
/// The name table of Extrapolation (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<Extrapolation>() noexcept {
  return extrapolation_names;
}

/// Curve-level smoothing of automatic handles (Blender's "auto_smoothing").
enum class AutoSmoothing : std::uint8_t {
  none,        ///< each automatic key on its own (Blender's classic handles)
  cont_accel,  ///< solve for continuous acceleration across runs of automatic keys
};

/// File and command-line names of the AutoSmoothing enumerators, in declaration order.
inline constexpr std::array<std::string_view, 2> auto_smoothing_names = {"none", "cont_accel"};
/// The name table of AutoSmoothing (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<AutoSmoothing>() noexcept {
  return auto_smoothing_names;
}

/// One key as authored.  Frames and values are in the curve's units; handles are absolute
/// (frame, value) points.  Handles of free and aligned sides are used as given (aligned ones
/// re-aligned); those of vector, automatic and auto_clamped sides are recomputed when the curve
/// has two keys or more (a lone key keeps its handles, as in Blender: they set its linear
/// extrapolation slope).
struct FCurveKey {
  double frame = 0;                                        ///< key time in frames
  double value = 0;                                        ///< key value
  Interpolation interpolation = Interpolation::bezier;     ///< of the segment to the right
  KeyEasing easing = KeyEasing::automatic;                 ///< for the easing interpolations
  HandleType handle_left_type = HandleType::auto_clamped;  ///< type of the left handle
  HandleType handle_right_type = HandleType::auto_clamped; ///< type of the right handle
  /// (frame, value) of the left handle; absent means (frame − 1, value), what Blender's insert() stores.
  std::optional<Vec2d> handle_left;
  /// (frame, value) of the right handle; absent means (frame + 1, value).
  std::optional<Vec2d> handle_right;
  double back = 1.70158;                                   ///< overshoot of `back` easing
  double amplitude = 0.8;                                  ///< amplitude of `elastic` (value units)
  double period = 4.1;                                     ///< period of `elastic` (frames)
};

/// A curve as authored: keys in strictly increasing frame order and curve-level settings.
struct RawFCurve {
  std::vector<FCurveKey> keys;                            ///< at least one key
  Extrapolation extrapolation = Extrapolation::constant;  ///< outside the keyed range
  AutoSmoothing auto_smoothing = AutoSmoothing::none;     ///< for automatic handles
  /// Blender's F-curve modifiers in stack order (first = top of Blender's list); fmodifier.hpp.
  std::vector<FCurveModifier> modifiers;
};

/// A built F-curve: validated keys (single precision, as Blender stores them) with their handles
/// recomputed.  Evaluation is total and noexcept.
class FCurve {
 public:
  /// One key as stored after building (single precision, handles recomputed).
  struct Key {
    float x = 0, y = 0;    ///< frame, value
    Vec2f left{}, right{}; ///< absolute handle positions
    Interpolation interpolation = Interpolation::bezier;  ///< of the segment to the right
    KeyEasing easing = KeyEasing::automatic;              ///< for the easing interpolations
    HandleType left_type = HandleType::auto_clamped;      ///< left handle type
    HandleType right_type = HandleType::auto_clamped;     ///< right handle type
    float back = 0, amplitude = 0, period = 0;            ///< easing parameters (as authored)
    bool locked = false;   ///< Blender's LOCKED auto-handle state (flat end or extreme)
  };

  /// The value at `frame` (frames are single precision, as Blender's fcurve.evaluate() takes them).
  /// Any frame is valid; NaN gives the first key's value, ±inf acts as the largest finite float.
  [[nodiscard]] float sample(float frame) const noexcept;

  /// The same value as sample(frame), found from the segment remembered in `cursor` (updated):
  /// O(1) per sample for sequential playback instead of Blender's binary search.  Near a key (within
  /// Blender's 1e-4 snap distance) the full search runs, so results are identical.
  [[nodiscard]] float sample(float frame, TrackCursor& cursor) const noexcept;

  /// Fills out[i] = sample(frames[i], cursor); the spans must have equal sizes; no allocation.
  void sample(std::span<const float> frames, std::span<float> out, TrackCursor& cursor) const noexcept;

  /// Deprecated spelling of sample() (every track type samples, docs/conventions.md); kept for one release.
  [[deprecated("use FCurve::sample")]] [[nodiscard]] float evaluate(float frame) const noexcept {
    return sample(frame);
  }
  /// Deprecated spelling of sample(frame, cursor); kept for one release.
  [[deprecated("use FCurve::sample")]] [[nodiscard]] float evaluate(float frame, TrackCursor& cursor) const noexcept {
    return sample(frame, cursor);
  }
  /// Deprecated spelling of sample(frames, out, cursor); kept for one release.
  [[deprecated("use FCurve::sample")]] void evaluate(std::span<const float> frames, std::span<float> out,
                                                     TrackCursor& cursor) const noexcept {
    sample(frames, out, cursor);
  }

  /// d value / d frame at `frame`, analytic (ours: Blender exposes no derivative).  Computed in
  /// double from the stored single-precision keys: a Bézier segment solves x(u) = frame for the
  /// Bézier parameter (after the same handle correction as sample) and returns y′(u)/x′(u) (the
  /// ratio of second derivatives where x′ vanishes, 0 when both do); linear is the chord slope,
  /// constant 0, the Penner easings their closed-form derivatives (penner_ease_velocity).  At an
  /// interior key the segment to the right counts, at the last key the segment to the left (the
  /// one-sided derivatives of the keyed range); outside the keys the extrapolation's slope (0 for
  /// constant), and with the Cycles modifier the slope of the cycled copy (negated on the
  /// backward copies of `mirror`).  Blender's 1e-4 snap of sample() to a key's value is ignored.
  /// Any other modifier stack: the chain rule through it, in double — time modifiers multiply by
  /// their own d t'/d t (Cycles ±1, Limits and Stepped 0 where they clamp or snap, else 1), value
  /// modifiers by their closed-form partial derivatives (Generator, Function, Envelope, Limits), the
  /// influence blend and its ramp over blend in/out included; Noise counts by the central difference
  /// of its turbulence over ±1/64 frame.  Where sample() jumps (Stepped, Limits edges, a range's end
  /// without blend out) the one-sided derivative of the piece holding `frame`.
  /// NaN gives 0; never NaN for a built curve.
  [[nodiscard]] double derivative(float frame) const noexcept;

  /// d² value / d frame² at `frame`, analytic, in double from the stored keys like derivative():
  /// a Bézier segment gives (y″x′ − y′x″)/x′³ at the Bézier parameter of the frame (0 where x′
  /// vanishes: a zero-length handle at a segment's end, where the curvature in frames is
  /// unbounded); linear and constant segments 0; the Penner easings their closed forms
  /// (penner_ease_acceleration).  At an interior key the segment to the right counts, at the last
  /// key the one to the left; outside the keys 0 (constant and linear extrapolation); with the
  /// Cycles modifier that of the cycled copy (a mirrored copy keeps its sign).  Any other modifier
  /// stack: the central difference of derivative() over ±1/256 frame (exact for the polynomial
  /// pieces up to O(h²); meaningless within 1/256 frame of a jump).  NaN gives 0; never NaN for a
  /// built curve.
  [[nodiscard]] double second_derivative(float frame) const noexcept;

  /// The stored keys, with recomputed handles.
  [[nodiscard]] std::span<const Key> keys() const noexcept { return keys_; }
  /// Curve-level extrapolation.
  [[nodiscard]] Extrapolation extrapolation() const noexcept { return extrapolation_; }
  /// Curve-level handle smoothing.
  [[nodiscard]] AutoSmoothing auto_smoothing() const noexcept { return smoothing_; }
  /// The modifier stack, as authored (fmodifier.hpp).
  [[nodiscard]] std::span<const FCurveModifier> modifiers() const noexcept { return modifiers_; }
  /// The Cycles modifier when it is the whole stack, unmuted, at full influence and without a frame
  /// range (the common case that the runtime, FCurveClip, folds); nullptr otherwise.
  [[nodiscard]] const FCurveCycles* simple_cycles() const noexcept { return simple_cycles_ ? &*simple_cycles_ : nullptr; }

 private:
  friend Expected<FCurve> build_fcurve(const RawFCurve& raw);
  FCurve() = default;  // only build_fcurve() makes curves: an FCurve always has ≥ 1 key
  float evaluate_impl(float frame, std::size_t* cursor) const noexcept;
  struct CycleMap {
    float t = 0;       // the frame inside (or, without cycling, outside) the keyed range
    float offset = 0;  // value added by repeat_offset
    float sign = 1;    // d t / d frame: −1 on a mirrored copy
  };
  CycleMap map_cycles(float frame) const noexcept;
  float evaluate_stack(float frame, std::size_t* cursor) const noexcept;        // fmodifier_eval.cpp
  double stack_derivative(float frame) const noexcept;                          // fmodifier_eval.cpp
  double keys_derivative(float t) const noexcept;  // d value / d t of the keys alone at (mapped) frame t
  double segment_derivative(int index, double t) const noexcept;
  double segment_second_derivative(int index, double t) const noexcept;
  double extrapolation_slope(bool before) const noexcept;
  float evaluate_keys(float t, std::size_t* cursor) const noexcept;
  float extrapolate(float t, bool before) const noexcept;
  float interpolate(float t, std::size_t* cursor) const noexcept;
  float segment_value(int index, float t) const noexcept;

  std::vector<Key> keys_;
  Extrapolation extrapolation_ = Extrapolation::constant;
  AutoSmoothing smoothing_ = AutoSmoothing::none;
  std::vector<FCurveModifier> modifiers_;
  std::optional<FCurveCycles> simple_cycles_;  // the stack is this one plain Cycles modifier
};

/// Validates `raw` (≥ 1 key; frames finite and strictly increasing, also after rounding to single
/// precision; frames, values, handles and easing parameters finite and within ±1e30, so that they
/// fit single precision) and its modifiers (fmodifier.hpp: every number finite and within ±1e30;
/// cycle counts and noise depth in 0..32767; a generator's coefficient count; envelope points in
/// increasing frame order, default_min ≠ default_max; step > 0; influence in [0, 1]; a range with
/// start ≤ end and blend in/out ≥ 0) and builds
/// the curve: handles clamped to their key's side, then recomputed as Blender's FCurve.update()
/// does.  Error locations: {"keys", i} or {"keys", i, "frame"} for a key, {"keys"} when there is
/// none, {"modifiers", i, member} for a modifier's member (e.g. {"modifiers", 1, "coefficients"}).
[[nodiscard]] Expected<FCurve> build_fcurve(const RawFCurve& raw);

/// The lower-case Blender name of each enumerator ("auto_clamped", "repeat_offset", …).
[[nodiscard]] std::string_view to_string(Interpolation v) noexcept;
[[nodiscard]] std::string_view to_string(KeyEasing v) noexcept;      ///< "auto", "ease_in", …
[[nodiscard]] std::string_view to_string(HandleType v) noexcept;     ///< "free", "auto", …
[[nodiscard]] std::string_view to_string(Extrapolation v) noexcept;  ///< "constant", "linear"
[[nodiscard]] std::string_view to_string(AutoSmoothing v) noexcept;  ///< "none", "cont_accel"
[[nodiscard]] std::string_view to_string(CycleMode v) noexcept;      ///< "none", "repeat", …

// enum_from_string<Enum>(name), the inverse of to_string(), is defined in math/enum_names.hpp.

}  // namespace inbetween
