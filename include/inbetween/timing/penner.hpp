#pragma once
/// Robert Penner's easing family (sine, quad, cubic, quart, quint, expo, circ, back, bounce,
/// elastic × in / out / in-out) in the exact form Blender 3.4 evaluates it (BLI_easing_*), so that
/// an F-curve segment with an easing interpolation reproduces Blender's numbers.
///
/// The functions take Penner's four arguments: `time` since the segment start (0..duration),
/// `begin` value, `change` (end value − begin) and `duration` (> 0), and return the eased value.
/// Every operation is done in T in the order Blender writes it, so with T = float the results are
/// Blender's to an ulp or two of sinf/powf.  Two of Blender's forms differ from Penner's originals:
/// expo is rescaled so that it starts and ends exactly at begin and begin + change (Penner's jumps
/// by 2⁻¹⁰·change), and elastic blends its amplitude in near the end where it would otherwise
/// start with a jump (see PennerParams::amplitude).  docs/tracks.md ("Penner easing") gives each form.

#include <cmath>
#include <cstdint>

#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// The easing curves of the Penner family.
enum class EasingCurve : std::uint8_t {
  sine,     ///< quarter sine wave
  quad,     ///< u²
  cubic,    ///< u³
  quart,    ///< u⁴
  quint,    ///< u⁵
  expo,     ///< 2^(10(u−1)), rescaled to hit both ends exactly
  circ,     ///< 1 − √(1 − u²), a quarter circle
  back,     ///< cubic that first pulls back by an overshoot (PennerParams::back)
  bounce,   ///< a ball bouncing to rest (four parabolic arcs)
  elastic,  ///< a damped sine oscillation (PennerParams::amplitude, PennerParams::period)
};

/// Which end of the segment the easing acts on.
enum class EasingDirection : std::uint8_t {
  in,      ///< slow start: the curve as named
  out,     ///< slow end: the curve mirrored through the segment centre
  in_out,  ///< the "in" curve on the first half and the "out" curve on the second
};

/// Blender's "auto" easing: ease out for back, bounce and elastic, ease in for the others.
constexpr EasingDirection automatic_direction(EasingCurve curve) noexcept {
  return (curve == EasingCurve::back || curve == EasingCurve::bounce || curve == EasingCurve::elastic)
             ? EasingDirection::out
             : EasingDirection::in;
}

/// The shape parameters Blender stores on each key.  Defaults are those of a key inserted in
/// Blender (keyframe_points.insert), in frames for the period.
template <Real T>
struct PennerParams {
  /// Overshoot of `back` (Penner's s); 1.70158 gives a 10 % pull-back, 0 gives a plain cubic.
  T back = T(1.70158);
  /// Elastic amplitude, in value units.  When 0 or below |change| the oscillation is scaled to
  /// |change| and, within a quarter period of the segment end where it starts, blended from 1 to
  /// amplitude/|change| (Blender's modification); amplitude ≥ |change| gives Penner's curve.
  T amplitude = T(0.8);
  /// Elastic period, in the units of `time`; 0 means 0.3·duration (0.45·duration for in-out).
  T period = T(4.1);
};

namespace penner_detail {

template <Real T>
T bounce_out(T time, T begin, T change, T duration) noexcept {
  time /= duration;
  if (time < T(1) / T(2.75)) return change * (T(7.5625) * time * time) + begin;
  if (time < T(2) / T(2.75)) {
    time -= T(1.5) / T(2.75);
    return change * ((T(7.5625) * time) * time + T(0.75)) + begin;
  }
  if (time < T(2.5) / T(2.75)) {
    time -= T(2.25) / T(2.75);
    return change * ((T(7.5625) * time) * time + T(0.9375)) + begin;
  }
  time -= T(2.625) / T(2.75);
  return change * ((T(7.5625) * time) * time + T(0.984375)) + begin;
}

template <Real T>
T bounce_in(T time, T begin, T change, T duration) noexcept {
  return change - bounce_out(duration - time, T(0), change, duration) + begin;
}

// Blender's gain on the elastic oscillation: within |s| (a quarter period) of the phase origin the
// gain moves linearly from 1 to amplitude/|change|; elsewhere it is amplitude/|change|.
template <Real T>
T elastic_blend(T phase, T change, T duration, T amplitude, T s, T gain) noexcept {
  if (change != T(0)) {
    const T t = std::abs(s);
    if (amplitude != T(0)) {
      gain *= amplitude / std::abs(change);
    } else {
      gain = T(0);
    }
    if (std::abs(phase * duration) < t) {
      const T l = std::abs(phase * duration) / t;
      gain = (gain * l) + (T(1) - l);
    }
  }
  return gain;
}

template <Real T>
T expo_in(T time, T begin, T change, T duration) noexcept {
  constexpr T pow_min = T(0.0009765625);  // 2^-10
  const T pow_scale = T(1) / (T(1) - T(0.0009765625));
  if (time == T(0)) return begin;
  return change * (std::pow(T(2), T(10) * (time / duration - T(1))) - pow_min) * pow_scale + begin;
}

template <Real T>
T expo_out(T time, T begin, T change, T duration) noexcept {
  constexpr T pow_min = T(0.0009765625);
  const T pow_scale = T(1) / (T(1) - T(0.0009765625));
  if (time == T(0)) return begin;
  return change * (T(1) - (std::pow(T(2), T(-10) * time / duration) - pow_min) * pow_scale) + begin;
}

}  // namespace penner_detail

/// The eased value at `time` of a segment from `begin` to begin + change over `duration`.
/// time is normally in [0, duration]; values outside extrapolate the formula (back, elastic and
/// bounce are not clamped).  duration must be non-zero (callers handle a zero-length segment).
template <Real T>
T penner_ease(EasingCurve curve, EasingDirection direction, T time, T begin, T change, T duration,
              const PennerParams<T>& params = {}) noexcept {
  using std::sqrt;
  constexpr T half_pi = T(1.57079632679489661923);
  constexpr T pi = T(3.14159265358979323846);
  switch (curve) {
    case EasingCurve::back: {
      T s = params.back;
      if (direction == EasingDirection::in) {
        time /= duration;
        return change * time * time * ((s + T(1)) * time - s) + begin;
      }
      if (direction == EasingDirection::out) {
        time = time / duration - T(1);
        return change * (time * time * ((s + T(1)) * time + s) + T(1)) + begin;
      }
      s *= T(1.525);
      if ((time /= duration / T(2)) < T(1)) {
        return change / T(2) * (time * time * ((s + T(1)) * time - s)) + begin;
      }
      time -= T(2);
      return change / T(2) * (time * time * ((s + T(1)) * time + s) + T(2)) + begin;
    }
    case EasingCurve::bounce:
      if (direction == EasingDirection::in) return penner_detail::bounce_in(time, begin, change, duration);
      if (direction == EasingDirection::out) return penner_detail::bounce_out(time, begin, change, duration);
      if (time < duration / T(2)) {
        return penner_detail::bounce_in(time * T(2), T(0), change, duration) * T(0.5) + begin;
      }
      return penner_detail::bounce_out(time * T(2) - duration, T(0), change, duration) * T(0.5) +
             change * T(0.5) + begin;
    case EasingCurve::circ:
      if (direction == EasingDirection::in) {
        time /= duration;
        return -change * (sqrt(T(1) - time * time) - T(1)) + begin;
      }
      if (direction == EasingDirection::out) {
        time = time / duration - T(1);
        return change * sqrt(T(1) - time * time) + begin;
      }
      if ((time /= duration / T(2)) < T(1)) return -change / T(2) * (sqrt(T(1) - time * time) - T(1)) + begin;
      time -= T(2);
      return change / T(2) * (sqrt(T(1) - time * time) + T(1)) + begin;
    case EasingCurve::cubic:
      if (direction == EasingDirection::in) {
        time /= duration;
        return change * time * time * time + begin;
      }
      if (direction == EasingDirection::out) {
        time = time / duration - T(1);
        return change * (time * time * time + T(1)) + begin;
      }
      if ((time /= duration / T(2)) < T(1)) return change / T(2) * time * time * time + begin;
      time -= T(2);
      return change / T(2) * (time * time * time + T(2)) + begin;
    case EasingCurve::elastic: {
      T s;
      T gain = T(1);
      T amplitude = params.amplitude;
      T period = params.period;
      if (time == T(0)) return begin;
      if (direction == EasingDirection::in_out) {
        if ((time /= duration / T(2)) == T(2)) return begin + change;
        time -= T(1);
        if (period == T(0)) period = duration * (T(0.3) * T(1.5));
      } else {
        if ((time /= duration) == T(1)) return begin + change;
        time = direction == EasingDirection::in ? time - T(1) : -time;
        if (period == T(0)) period = duration * T(0.3);
      }
      if (amplitude == T(0) || amplitude < std::abs(change)) {
        s = period / T(4);
        gain = penner_detail::elastic_blend(time, change, duration, amplitude, s, gain);
        amplitude = change;
      } else {
        s = period / (T(2) * pi) * std::asin(change / amplitude);
      }
      if (direction == EasingDirection::in_out) {
        if (time < T(0)) {
          gain *= T(-0.5);
          return (gain * (amplitude * std::pow(T(2), T(10) * time) *
                          std::sin((time * duration - s) * (T(2) * pi) / period))) +
                 begin;
        }
        time = -time;
        gain *= T(0.5);
        return (gain * (amplitude * std::pow(T(2), T(10) * time) *
                        std::sin((time * duration - s) * (T(2) * pi) / period))) +
               change + begin;
      }
      const T wave =
          amplitude * std::pow(T(2), T(10) * time) * std::sin((time * duration - s) * (T(2) * pi) / period);
      if (direction == EasingDirection::in) return (-gain * wave) + begin;
      return (gain * wave) + change + begin;
    }
    case EasingCurve::expo:
      if (direction == EasingDirection::in) return penner_detail::expo_in(time, begin, change, duration);
      if (direction == EasingDirection::out) return penner_detail::expo_out(time, begin, change, duration);
      duration *= T(0.5);
      change *= T(0.5);
      if (time < duration) return penner_detail::expo_in(time, begin, change, duration);
      return penner_detail::expo_out(time - duration, begin + change, change, duration);
    case EasingCurve::quad:
      if (direction == EasingDirection::in) {
        time /= duration;
        return change * time * time + begin;
      }
      if (direction == EasingDirection::out) {
        time /= duration;
        return -change * time * (time - T(2)) + begin;
      }
      if ((time /= duration / T(2)) < T(1)) return change / T(2) * time * time + begin;
      time -= T(1);
      return -change / T(2) * (time * (time - T(2)) - T(1)) + begin;
    case EasingCurve::quart:
      if (direction == EasingDirection::in) {
        time /= duration;
        return change * time * time * time * time + begin;
      }
      if (direction == EasingDirection::out) {
        time = time / duration - T(1);
        return -change * (time * time * time * time - T(1)) + begin;
      }
      if ((time /= duration / T(2)) < T(1)) return change / T(2) * time * time * time * time + begin;
      time -= T(2);
      return -change / T(2) * (time * time * time * time - T(2)) + begin;
    case EasingCurve::quint:
      if (direction == EasingDirection::in) {
        time /= duration;
        return change * time * time * time * time * time + begin;
      }
      if (direction == EasingDirection::out) {
        time = time / duration - T(1);
        return change * (time * time * time * time * time + T(1)) + begin;
      }
      if ((time /= duration / T(2)) < T(1)) return change / T(2) * time * time * time * time * time + begin;
      time -= T(2);
      return change / T(2) * (time * time * time * time * time + T(2)) + begin;
    case EasingCurve::sine:
      if (direction == EasingDirection::in) {
        return -change * std::cos(time / duration * half_pi) + change + begin;
      }
      if (direction == EasingDirection::out) return change * std::sin(time / duration * half_pi) + begin;
      return -change / T(2) * (std::cos(pi * time / duration) - T(1)) + begin;
  }
  return begin;
}

/// The normalised easing function e(u) for u in [0, 1]: e(0) = 0, e(1) = 1 (back and elastic
/// overshoot in between).  Equal to penner_ease(curve, direction, u, 0, 1, 1, params); for elastic
/// the period is then in units of the whole segment, so pass e.g. {.amplitude = 1, .period = 0.3}.
template <Real T>
T ease_unit(EasingCurve curve, EasingDirection direction, T u, const PennerParams<T>& params = {}) noexcept {
  return penner_ease(curve, direction, u, T(0), T(1), T(1), params);
}

}  // namespace inbetween
