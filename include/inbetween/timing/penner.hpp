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

#include <string_view>
#include <span>
#include <array>
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <limits>

#include "inbetween/math/scalar.hpp"
#include "inbetween/math/enum_names.hpp"

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

/// File names of the EasingCurve enumerators, in declaration order.
inline constexpr std::array<std::string_view, 10> easing_curve_names = {"sine", "quad", "cubic", "quart", "quint", "expo", "circ", "back", "bounce", "elastic"};
/// The name table of EasingCurve (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<EasingCurve>() noexcept {
  return easing_curve_names;
}
/// The file name of v, from the table above (enum_from_string<EasingCurve> parses it back).
[[nodiscard]] inline std::string_view to_string(EasingCurve v) noexcept { return enum_name(v); }

/// Which end of the segment the easing acts on.
enum class EasingDirection : std::uint8_t {
  in,      ///< slow start: the curve as named
  out,     ///< slow end: the curve mirrored through the segment centre
  in_out,  ///< the "in" curve on the first half and the "out" curve on the second
};

/// File names of the EasingDirection enumerators, in declaration order.
inline constexpr std::array<std::string_view, 3> easing_direction_names = {"in", "out", "in_out"};
/// The name table of EasingDirection (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<EasingDirection>() noexcept {
  return easing_direction_names;
}
/// The file name of v, from the table above (enum_from_string<EasingDirection> parses it back).
[[nodiscard]] inline std::string_view to_string(EasingDirection v) noexcept { return enum_name(v); }

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

namespace penner_detail {

template <Real T>
T bounce_out_velocity(T time, T change, T duration) noexcept {
  // d/dtime of bounce_out: each arc is change·(7.5625·(u − a)² + c) with u = time/duration.
  const T u = time / duration;
  T a;
  if (u < T(1) / T(2.75)) a = T(0);
  else if (u < T(2) / T(2.75)) a = T(1.5) / T(2.75);
  else if (u < T(2.5) / T(2.75)) a = T(2.25) / T(2.75);
  else a = T(2.625) / T(2.75);
  return change * T(2) * T(7.5625) * (u - a) / duration;
}

template <Real T>
T expo_in_velocity(T time, T change, T duration) noexcept {
  const T pow_scale = T(1) / (T(1) - T(0.0009765625));
  return change * pow_scale * T(10) * std::log(T(2)) / duration * std::pow(T(2), T(10) * (time / duration - T(1)));
}

template <Real T>
T expo_out_velocity(T time, T change, T duration) noexcept {
  const T pow_scale = T(1) / (T(1) - T(0.0009765625));
  return change * pow_scale * T(10) * std::log(T(2)) / duration * std::pow(T(2), T(-10) * time / duration);
}

/// x/√(1 − x²), the slope of the circle arcs, with 1 − x² floored at ε² so that the vertical end
/// gives a large finite slope instead of infinity.
template <Real T>
T circ_slope(T x) noexcept {
  const T eps = std::numeric_limits<T>::epsilon();
  return x / std::sqrt(std::max(T(1) - x * x, eps * eps));
}

/// The elastic curve's set-up shared by its derivatives: Blender's amplitude blend near the start
/// (gain(x), piecewise linear, and its slope dgain), the amplitude and period in force, the wave's
/// variable x with dx/dtime, and the phase shift s.
template <Real T>
struct ElasticSetup {
  T gain, dgain, amplitude, period, x, dx_dtime, s;
};

/// ElasticSetup for penner_ease_velocity / penner_ease_acceleration (d = duration ≠ 0).
template <Real T>
ElasticSetup<T> elastic_setup(EasingDirection direction, T time, T change, T d, const PennerParams<T>& params) noexcept {
  constexpr T pi = T(3.14159265358979323846);
  T gain = T(1), dgain = T(0);  // gain and d gain / d x
  T amplitude = params.amplitude;
  T period = params.period;
  T x, dx_dtime;
  if (direction == EasingDirection::in_out) {
    x = time / (d / T(2)) - T(1);
    dx_dtime = T(2) / d;
    if (period == T(0)) period = d * (T(0.3) * T(1.5));
  } else {
    x = time / d;
    x = direction == EasingDirection::in ? x - T(1) : -x;
    dx_dtime = (direction == EasingDirection::in ? T(1) : T(-1)) / d;
    if (period == T(0)) period = d * T(0.3);
  }
  T s;
  if (amplitude == T(0) || amplitude < std::abs(change)) {
    s = period / T(4);
    if (change != T(0)) {
      const T g = amplitude != T(0) ? amplitude / std::abs(change) : T(0);
      gain = g;
      const T t = std::abs(s);
      if (std::abs(x * d) < t) {
        const T l = std::abs(x * d) / t;
        gain = g * l + (T(1) - l);
        dgain = (g - T(1)) * (x < T(0) ? T(-1) : T(1)) * d / t;
      }
    }
    amplitude = change;
  } else {
    s = period / (T(2) * pi) * std::asin(change / amplitude);
  }
  return {gain, dgain, amplitude, period, x, dx_dtime, s};
}

}  // namespace penner_detail

/// d/dtime of penner_ease(curve, direction, time, begin, change, duration, params): the closed-form
/// derivative of each formula above, branch for branch (ours: Blender exposes no derivative).
/// Inside a branch it is exact; at a branch boundary (in-out midpoint, bounce arcs) it is the
/// derivative of the branch penner_ease takes there.  circ's slope is unbounded where the circle is
/// vertical (u = 1 for in, u = 0 for out, the in-out midpoint); there it is large but finite (1 − u²
/// floored at ε²).  elastic includes Blender's amplitude blend near its start, and at time = 0 and
/// at the end (where penner_ease returns begin and begin + change exactly) gives the slope of the
/// formula.  duration must be non-zero.
template <Real T>
T penner_ease_velocity(EasingCurve curve, EasingDirection direction, T time, T change, T duration,
                       const PennerParams<T>& params = {}) noexcept {
  constexpr T half_pi = T(1.57079632679489661923);
  constexpr T pi = T(3.14159265358979323846);
  const T d = duration;
  switch (curve) {
    case EasingCurve::back: {
      T s = params.back;
      if (direction == EasingDirection::in) {
        const T u = time / d;
        return change * (T(3) * (s + T(1)) * u * u - T(2) * s * u) / d;
      }
      if (direction == EasingDirection::out) {
        const T w = time / d - T(1);
        return change * (T(3) * (s + T(1)) * w * w + T(2) * s * w) / d;
      }
      s *= T(1.525);
      T x = time / (d / T(2));
      if (x < T(1)) return change / T(2) * (T(3) * (s + T(1)) * x * x - T(2) * s * x) * T(2) / d;
      x -= T(2);
      return change / T(2) * (T(3) * (s + T(1)) * x * x + T(2) * s * x) * T(2) / d;
    }
    case EasingCurve::bounce:
      if (direction == EasingDirection::in) return penner_detail::bounce_out_velocity(d - time, change, d);
      if (direction == EasingDirection::out) return penner_detail::bounce_out_velocity(time, change, d);
      if (time < d / T(2)) return penner_detail::bounce_out_velocity(d - time * T(2), change, d);
      return penner_detail::bounce_out_velocity(time * T(2) - d, change, d);
    case EasingCurve::circ: {
      if (direction == EasingDirection::in) return change * penner_detail::circ_slope(time / d) / d;
      if (direction == EasingDirection::out) return -change * penner_detail::circ_slope(time / d - T(1)) / d;
      T x = time / (d / T(2));
      if (x < T(1)) return change / T(2) * penner_detail::circ_slope(x) * T(2) / d;
      x -= T(2);
      return -change / T(2) * penner_detail::circ_slope(x) * T(2) / d;
    }
    case EasingCurve::cubic:
    case EasingCurve::quad:
    case EasingCurve::quart:
    case EasingCurve::quint: {
      const int n = curve == EasingCurve::quad ? 2 : curve == EasingCurve::cubic ? 3 : curve == EasingCurve::quart ? 4 : 5;
      const auto ipow = [](T v, int k) { T r = T(1); for (int i = 0; i < k; ++i) r *= v; return r; };
      // in: c·uⁿ; out: c·(1 − (1 − u)ⁿ) (each form above is this, written Penner's way); in-out:
      // the in form on x = 2u < 1 and the out form on the second half, each of half the change.
      if (direction == EasingDirection::in) return change * T(n) * ipow(time / d, n - 1) / d;
      if (direction == EasingDirection::out) return change * T(n) * ipow(T(1) - time / d, n - 1) / d;
      const T x = time / (d / T(2));
      if (x < T(1)) return change / T(2) * T(n) * ipow(x, n - 1) * T(2) / d;
      return change / T(2) * T(n) * ipow(T(2) - x, n - 1) * T(2) / d;
    }
    case EasingCurve::elastic: {
      const penner_detail::ElasticSetup<T> e = penner_detail::elastic_setup(direction, time, change, d, params);
      const T gain = e.gain, dgain = e.dgain, amplitude = e.amplitude, period = e.period, x = e.x,
              dx_dtime = e.dx_dtime, s = e.s;
      const T w = T(2) * pi / period;
      const auto wave = [&](T y) { return amplitude * std::pow(T(2), T(10) * y) * std::sin((y * d - s) * w); };
      const auto dwave = [&](T y) {
        const T phase = (y * d - s) * w;
        return amplitude * std::pow(T(2), T(10) * y) * (T(10) * std::log(T(2)) * std::sin(phase) + d * w * std::cos(phase));
      };
      if (direction == EasingDirection::in_out) {
        if (x < T(0)) return T(-0.5) * (dgain * wave(x) + gain * dwave(x)) * dx_dtime;
        // value = 0.5·gain(x)·wave(−x): the blend sees x, the wave −x.
        return T(0.5) * (dgain * wave(-x) - gain * dwave(-x)) * dx_dtime;
      }
      const T dv = dgain * wave(x) + gain * dwave(x);
      return (direction == EasingDirection::in ? -dv : dv) * dx_dtime;
    }
    case EasingCurve::expo:
      if (direction == EasingDirection::in) return penner_detail::expo_in_velocity(time, change, d);
      if (direction == EasingDirection::out) return penner_detail::expo_out_velocity(time, change, d);
      if (time < d * T(0.5)) return penner_detail::expo_in_velocity(time, change * T(0.5), d * T(0.5));
      return penner_detail::expo_out_velocity(time - d * T(0.5), change * T(0.5), d * T(0.5));
    case EasingCurve::sine:
      if (direction == EasingDirection::in) return change * half_pi / d * std::sin(time / d * half_pi);
      if (direction == EasingDirection::out) return change * half_pi / d * std::cos(time / d * half_pi);
      return change / T(2) * pi / d * std::sin(pi * time / d);
  }
  return T(0);
}

/// d²/dtime² of penner_ease(curve, direction, time, begin, change, duration, params): the
/// closed-form second derivative of each formula, branch for branch like penner_ease_velocity
/// (exact inside a branch; at a boundary that of the branch penner_ease takes).  quad … quint,
/// back, sine, expo: derivatives of their polynomials and exponentials; bounce: each arc is a
/// parabola, change·2·7.5625/duration² (sign by direction); circ: ±change·(1 − x²)^(−3/2)/duration²
/// with 1 − x² floored at ε² as for the slope (large, finite where the circle is vertical);
/// elastic: the product rule on gain(x)·wave(x) with the blend's gain piecewise linear (its second
/// derivative 0 away from x = 0) and wave″ = A·2^(10y)·((k² − (dω)²)·sin φ + 2k·dω·cos φ), k = 10 ln 2.
/// duration must be non-zero.
template <Real T>
T penner_ease_acceleration(EasingCurve curve, EasingDirection direction, T time, T change, T duration,
                           const PennerParams<T>& params = {}) noexcept {
  constexpr T half_pi = T(1.57079632679489661923);
  constexpr T pi = T(3.14159265358979323846);
  const T d = duration;
  const T d2 = d * d;
  switch (curve) {
    case EasingCurve::back: {
      T s = params.back;
      if (direction == EasingDirection::in) return change * (T(6) * (s + T(1)) * (time / d) - T(2) * s) / d2;
      if (direction == EasingDirection::out) return change * (T(6) * (s + T(1)) * (time / d - T(1)) + T(2) * s) / d2;
      s *= T(1.525);
      T x = time / (d / T(2));
      if (x < T(1)) return change / T(2) * (T(6) * (s + T(1)) * x - T(2) * s) * T(4) / d2;
      x -= T(2);
      return change / T(2) * (T(6) * (s + T(1)) * x + T(2) * s) * T(4) / d2;
    }
    case EasingCurve::bounce: {
      // bounce_out's arcs: change·(7.5625·(u − a)² + c): second derivative change·2·7.5625/d².
      const T arc = change * T(2) * T(7.5625) / d2;
      if (direction == EasingDirection::in) return -arc;   // change − bounce_out(d − time)
      if (direction == EasingDirection::out) return arc;
      return time < d / T(2) ? -T(2) * arc : T(2) * arc;  // halves at double speed, half the change
    }
    case EasingCurve::circ: {
      const T eps = std::numeric_limits<T>::epsilon();
      // d/dx of x/√(1 − x²) = (1 − x²)^(−3/2), with the slope's floor.
      const auto curvature = [eps](T x) {
        const T q = std::max(T(1) - x * x, eps * eps);
        return T(1) / (q * std::sqrt(q));
      };
      if (direction == EasingDirection::in) return change * curvature(time / d) / d2;
      if (direction == EasingDirection::out) return -change * curvature(time / d - T(1)) / d2;
      T x = time / (d / T(2));
      if (x < T(1)) return change / T(2) * curvature(x) * T(4) / d2;
      x -= T(2);
      return -change / T(2) * curvature(x) * T(4) / d2;
    }
    case EasingCurve::cubic:
    case EasingCurve::quad:
    case EasingCurve::quart:
    case EasingCurve::quint: {
      const int n = curve == EasingCurve::quad ? 2 : curve == EasingCurve::cubic ? 3 : curve == EasingCurve::quart ? 4 : 5;
      const auto ipow = [](T v, int k) { T r = T(1); for (int i = 0; i < k; ++i) r *= v; return r; };
      const T nn = T(n * (n - 1));
      if (direction == EasingDirection::in) return change * nn * ipow(time / d, n - 2) / d2;
      if (direction == EasingDirection::out) return -change * nn * ipow(T(1) - time / d, n - 2) / d2;
      const T x = time / (d / T(2));
      if (x < T(1)) return change / T(2) * nn * ipow(x, n - 2) * T(4) / d2;
      return -change / T(2) * nn * ipow(T(2) - x, n - 2) * T(4) / d2;
    }
    case EasingCurve::elastic: {
      // As penner_ease_velocity, one derivative further.
      const penner_detail::ElasticSetup<T> e = penner_detail::elastic_setup(direction, time, change, d, params);
      const T gain = e.gain, dgain = e.dgain, amplitude = e.amplitude, period = e.period, x = e.x,
              dx_dtime = e.dx_dtime, s = e.s;
      const T w = T(2) * pi / period;
      const T k = T(10) * std::log(T(2));
      const T dw = d * w;
      const auto dwave = [&](T y) {
        const T phase = (y * d - s) * w;
        return amplitude * std::pow(T(2), T(10) * y) * (k * std::sin(phase) + dw * std::cos(phase));
      };
      const auto ddwave = [&](T y) {
        const T phase = (y * d - s) * w;
        return amplitude * std::pow(T(2), T(10) * y) * ((k * k - dw * dw) * std::sin(phase) + T(2) * k * dw * std::cos(phase));
      };
      const T dx2 = dx_dtime * dx_dtime;
      if (direction == EasingDirection::in_out) {
        // x < 0: value = −0.5·gain(x)·wave(x); x ≥ 0: value = 0.5·gain(x)·wave(−x) (+ change).
        if (x < T(0)) return T(-0.5) * (T(2) * dgain * dwave(x) + gain * ddwave(x)) * dx2;
        return T(0.5) * (-T(2) * dgain * dwave(-x) + gain * ddwave(-x)) * dx2;
      }
      const T dv = T(2) * dgain * dwave(x) + gain * ddwave(x);
      return (direction == EasingDirection::in ? -dv : dv) * dx2;
    }
    case EasingCurve::expo: {
      const T k = T(10) * std::log(T(2));
      if (direction == EasingDirection::in) return penner_detail::expo_in_velocity(time, change, d) * k / d;
      if (direction == EasingDirection::out) return -penner_detail::expo_out_velocity(time, change, d) * k / d;
      const T h = d * T(0.5);
      if (time < h) return penner_detail::expo_in_velocity(time, change * T(0.5), h) * k / h;
      return -penner_detail::expo_out_velocity(time - h, change * T(0.5), h) * k / h;
    }
    case EasingCurve::sine:
      if (direction == EasingDirection::in) return change * half_pi * half_pi / d2 * std::cos(time / d * half_pi);
      if (direction == EasingDirection::out) return -change * half_pi * half_pi / d2 * std::sin(time / d * half_pi);
      return change / T(2) * pi * pi / d2 * std::cos(pi * time / d);
  }
  return T(0);
}

/// The normalised easing function e(u) for u in [0, 1]: e(0) = 0, e(1) = 1 (back and elastic
/// overshoot in between).  Equal to penner_ease(curve, direction, u, 0, 1, 1, params); for elastic
/// the period is then in units of the whole segment, so pass e.g. {.amplitude = 1, .period = 0.3}.
template <Real T>
T ease_unit(EasingCurve curve, EasingDirection direction, T u, const PennerParams<T>& params = {}) noexcept {
  return penner_ease(curve, direction, u, T(0), T(1), T(1), params);
}

/// d e/du of ease_unit: penner_ease_velocity(curve, direction, u, 1, 1, params).
template <Real T>
T ease_unit_velocity(EasingCurve curve, EasingDirection direction, T u, const PennerParams<T>& params = {}) noexcept {
  return penner_ease_velocity(curve, direction, u, T(1), T(1), params);
}

}  // namespace inbetween
