#pragma once
/// Blender 3.4's F-curve modifiers (fmodifier.c): Generator, Built-in Function, Envelope, Cycles,
/// Noise, Limits and Stepped Interpolation, each with Blender's common settings (mute, influence,
/// restricted frame range with blend in/out).  A RawFCurve holds them as a list in Blender's stack
/// order (RawFCurve::modifiers); FCurve::sample runs the time parts from the last modifier to the
/// first, evaluates the keys at the resulting frame, then the value parts from the first to the
/// last, in float and in Blender's order of operations (docs/tracks.md, "F-curve modifiers").
/// Defaults are those of a modifier Blender 3.4 adds.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "inbetween/math/enum_names.hpp"

namespace inbetween {

/// Repetition mode on one side of a Cycles modifier.
enum class CycleMode : std::uint8_t {
  none,           ///< no cycling on this side
  repeat,         ///< repeat the keyed range
  repeat_offset,  ///< repeat, shifted by (last value − first value) per cycle
  mirror,         ///< alternate forwards and backwards copies
};

/// File and command-line names of the CycleMode enumerators, in declaration order.
inline constexpr std::array<std::string_view, 4> cycle_mode_names = {"none", "repeat", "repeat_offset", "mirror"};
/// The name table of CycleMode (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<CycleMode>() noexcept {
  return cycle_mode_names;
}

/// Blender's Cycles modifier: repeats the keyed range before the first and after the last key.
/// Blender disables a Cycles modifier that is not the first of the stack: it then does nothing.
struct FCurveCycles {
  CycleMode before = CycleMode::repeat;  ///< before the first key
  CycleMode after = CycleMode::repeat;   ///< after the last key
  int count_before = 0;                  ///< number of copies before; 0 = forever (0..32767)
  int count_after = 0;                   ///< number of copies after; 0 = forever (0..32767)
};

/// Form of a Generator's polynomial.
enum class GeneratorMode : std::uint8_t {
  expanded,    ///< c0 + c1·x + … + cN·x^N (coefficients c0 … cN, N ≥ 1)
  factorised,  ///< (a1·x + b1)·(a2·x + b2)·… (coefficients a1, b1, a2, b2, …)
};

/// File names of the GeneratorMode enumerators, in declaration order.
inline constexpr std::array<std::string_view, 2> generator_mode_names = {"expanded", "factorised"};
/// The name table of GeneratorMode (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<GeneratorMode>() noexcept {
  return generator_mode_names;
}

/// Blender's Generator modifier: a polynomial in the (modified) frame replaces or is added to the value.
struct FCurveGenerator {
  GeneratorMode mode = GeneratorMode::expanded;  ///< polynomial form
  bool additive = false;                         ///< add to the value instead of replacing it
  /// Expanded: c0 … cN (N = order ≥ 1, so ≥ 2 numbers); factorised: pairs (a, b) per factor (an
  /// even count ≥ 2).  Blender's new modifier: 0 + 1·x.
  std::vector<double> coefficients = {0.0, 1.0};
};

/// The function of a Built-in Function modifier.
enum class BuiltinFunction : std::uint8_t { sin, cos, tan, sqrt, ln, sinc };

/// File names of the BuiltinFunction enumerators, in declaration order (Blender's, lower case).
inline constexpr std::array<std::string_view, 6> builtin_function_names = {"sin", "cos", "tan", "sqrt", "ln", "sinc"};
/// The name table of BuiltinFunction (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<BuiltinFunction>() noexcept {
  return builtin_function_names;
}

/// Blender's Built-in Function modifier: amplitude·fn(phase_multiplier·frame + phase_offset) +
/// value_offset.  Outside a function's domain Blender writes 0 (not value_offset) when not
/// additive and leaves the value when additive: sqrt of arg ≤ 0, ln of arg ≤ 1 (sic: Blender tests
/// arg > 1), tan within FLT_EPSILON of a pole; sinc(x) = 1 for |x| < 1e-4, else sin(πx)/(πx).
struct FCurveFunction {
  BuiltinFunction function = BuiltinFunction::sin;  ///< the function
  double amplitude = 1;         ///< scale of the function's value
  double phase_multiplier = 1;  ///< scale of the frame
  double phase_offset = 0;      ///< added to the scaled frame
  double value_offset = 0;      ///< added to the scaled value
  bool additive = false;        ///< add to the value instead of replacing it
};

/// One control point of an Envelope: at `frame` the reference band maps to [min, max].
struct FCurveEnvelopePoint {
  double frame = 0;  ///< frame of the point (points strictly increasing)
  double min = 0;    ///< value the band's lower edge maps to
  double max = 0;    ///< value the band's upper edge maps to
};

/// Blender's Envelope modifier: the band [reference + default_min, reference + default_max] is
/// mapped linearly onto [min, max], interpolated linearly between control points and held before
/// the first / after the last.  Without points it does nothing.
struct FCurveEnvelope {
  double reference = 0;     ///< Blender's "reference_value"
  double default_min = -1;  ///< lower edge of the band, relative to the reference (≠ default_max)
  double default_max = 1;   ///< upper edge of the band, relative to the reference
  std::vector<FCurveEnvelopePoint> points;  ///< control points in increasing frame order
};

/// How a Noise modifier combines its noise with the value.
enum class NoiseBlend : std::uint8_t {
  replace,   ///< value + (noise − 0.5)·strength
  add,       ///< value + noise·strength
  subtract,  ///< value − noise·strength
  multiply,  ///< value·noise·strength
};

/// File names of the NoiseBlend enumerators, in declaration order (Blender's blend_type, lower case).
inline constexpr std::array<std::string_view, 4> noise_blend_names = {"replace", "add", "subtract", "multiply"};
/// The name table of NoiseBlend (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<NoiseBlend>() noexcept {
  return noise_blend_names;
}

/// Blender's Noise modifier: noise = turbulence(scale, frame − offset, phase, 0.1, depth) (Blender's
/// BLI_noise_turbulence), combined with the value as `blend` says.
struct FCurveNoise {
  NoiseBlend blend = NoiseBlend::replace;  ///< combination with the value
  double scale = 1;     ///< Blender's "scale" (noise size in frames; ≠ 0)
  double strength = 1;  ///< amplitude
  double phase = 1;     ///< the noise's y coordinate
  double offset = 0;    ///< frame offset
  int depth = 0;        ///< turbulence octaves (0..32767)
};

/// Blender's Limits modifier: the frame clamped to [min_x, max_x] before the keys are evaluated, the
/// value to [min_y, max_y] afterwards; an absent bound is off.
struct FCurveLimits {
  std::optional<double> min_x, max_x;  ///< frame bounds (Blender's use_min_x / use_max_x)
  std::optional<double> min_y, max_y;  ///< value bounds (Blender's use_min_y / use_max_y)
};

/// Blender's Stepped Interpolation modifier: the frame is snapped down (towards zero, as C's int
/// conversion does) to offset + k·step, except before `start` / after `end` when they are set.
struct FCurveStepped {
  double step = 2;                  ///< step size in frames (> 0)
  double offset = 0;                ///< frame of a step
  std::optional<double> start;      ///< no stepping before this frame (Blender's use_frame_start)
  std::optional<double> end;        ///< no stepping after this frame (Blender's use_frame_end)
};

/// The frame range a modifier is restricted to (Blender's use_restricted_range): outside
/// [start, end] the modifier does nothing, and its influence ramps linearly from 0 to full over
/// [start, start + blend_in] and back to 0 over [end − blend_out, end].
struct FModifierRange {
  double start = 0;      ///< first frame (Blender's frame_start)
  double end = 0;        ///< last frame (≥ start)
  double blend_in = 0;   ///< frames to reach full influence (≥ 0)
  double blend_out = 0;  ///< frames to fade out before `end` (≥ 0)
};

/// One modifier of an F-curve's stack: its kind and Blender's common settings.
struct FCurveModifier {
  /// The modifier's kind and its own settings.
  std::variant<FCurveGenerator, FCurveFunction, FCurveEnvelope, FCurveCycles, FCurveNoise, FCurveLimits, FCurveStepped>
      kind;
  bool mute = false;                ///< muted: does nothing
  std::optional<double> influence;  ///< Blender's use_influence with this value in [0, 1]; absent = full
  std::optional<FModifierRange> range;  ///< Blender's use_restricted_range; absent = every frame
};

/// File names of the modifier kinds ("type" in the file), in the order of FCurveModifier::kind.
inline constexpr std::array<std::string_view, 7> fmodifier_type_names = {"generator", "function", "envelope", "cycles",
                                                                          "noise",     "limits",   "stepped"};

/// The file name of `m`'s kind ("generator", "cycles", …).
[[nodiscard]] inline std::string_view type_name(const FCurveModifier& m) noexcept {
  return fmodifier_type_names[m.kind.index()];
}

}  // namespace inbetween
