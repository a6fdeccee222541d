#pragma once
/// Ease (distance-time) functions of normalised time t ∈ [0, 1] to normalised distance s ∈ [0, 1]
/// (texts 004 §3.2.2–3.2.3, 000 §2.4): linear, sine (Eq. 3.18), sinusoidal acceleration and
/// deceleration around a constant-speed middle (Eq. 3.19, corrected), the cubic −2t³ + 3t²
/// (Eq. 3.20) and constant acceleration (Eqs. 3.21–3.22, corrected).  Each reports s, the velocity
/// ds/dt and the acceleration d²s/dt² at t.  t is clamped into [0, 1] (NaN counts as 0, as in
/// CubicBezierTiming); the derivatives reported at the ends are the one-sided ones of the function.

#include <cmath>
#include <concepts>
#include <string>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// A distance-time sample: normalised distance and its first two time derivatives.
template <Real T>
struct EaseSample {
  T s{};             ///< distance travelled, normalised (0 at t = 0, 1 at t = 1)
  T velocity{};      ///< ds/dt
  T acceleration{};  ///< d²s/dt²
};

/// Anything that maps time to an EaseSample: the ease functions here, CubicBezierTiming and
/// DistanceTimeCurve.
template <class E, class T>
concept DistanceTimeFunction = Real<T> && requires(const E& e, T t) {
  { e.sample(t) } -> std::same_as<EaseSample<T>>;
};

namespace detail {
/// t clamped into [0, 1], NaN mapped to 0 (so a NaN time gives the start, never NaN).
template <Real T>
constexpr T clamp_unit_time(T t) noexcept {
  return t > T(0) ? (t < T(1) ? t : T(1)) : T(0);
}
}  // namespace detail

/// s = t: constant speed 1.
template <Real T>
struct LinearEase {
  /// s, v = 1, a = 0 at t clamped into [0, 1] (NaN → 0).
  EaseSample<T> sample(T t) const noexcept { return {detail::clamp_unit_time(t), T(1), T(0)}; }
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }
};

/// Eq. 3.18: s = (sin(πt − π/2) + 1)/2 = (1 − cos πt)/2; v = (π/2) sin πt, a = (π²/2) cos πt.
/// ease(0.25) = 0.1465, ease(0.75) = 0.8535 (texts' worked numbers); zero velocity at both ends.
template <Real T>
struct SineEase {
  /// s, v, a at t clamped into [0, 1] (NaN → 0).
  EaseSample<T> sample(T t) const noexcept {
    t = detail::clamp_unit_time(t);
    const T pi = pi_v<T>;
    return {(T(1) - std::cos(pi * t)) / T(2), pi / T(2) * std::sin(pi * t), pi * pi / T(2) * std::cos(pi * t)};
  }
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }
};

/// Eq. 3.20: s = −2t³ + 3t²; v = 6t(1 − t), a = 6 − 12t.  Zero velocity at both ends, no
/// constant-speed middle.
template <Real T>
struct CubicEase {
  /// s, v, a at t clamped into [0, 1] (NaN → 0).
  EaseSample<T> sample(T t) const noexcept {
    t = detail::clamp_unit_time(t);
    return {(T(3) - T(2) * t) * t * t, T(6) * t * (T(1) - t), T(6) - T(12) * t};
  }
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }
};

/// Sinusoidal acceleration on [0, k1], constant speed on [k1, k2], sinusoidal deceleration on
/// [k2, 1] (texts 004 Eq. 3.19 with the corrected normaliser f = 2k1/π + (k2 − k1) + 2(1 − k2)/π,
/// and the final sine piece scaled by (1 − k2)/(π/2), as the code of Figure 3.13 has it).
/// C¹: velocity rises from 0 to 1/f, stays, and falls back to 0.  k1 = 0 or k2 = 1 drop that piece.
template <Real T>
class SineAccelDecelEase {
 public:
  /// Builds the ease; requires 0 ≤ k1 ≤ k2 ≤ 1 (finite).  Error InvalidArgument names k1 or k2.
  static Expected<SineAccelDecelEase> make(T k1, T k2) {
    if (!std::isfinite(k1) || !std::isfinite(k2)) return Error{ErrorCode::not_finite, "k1 and k2 must be finite", {std::string("k1")}};
    if (k1 < T(0) || k1 > T(1)) return Error{ErrorCode::invalid_argument, "k1 = " + shortest_text<double>(double(k1)) + " is outside [0, 1]", {std::string("k1")}};
    if (k2 < k1 || k2 > T(1)) {
      return Error{ErrorCode::invalid_argument,
                   "k2 = " + shortest_text<double>(double(k2)) + " must lie in [k1, 1] with k1 = " + shortest_text<double>(double(k1)), {std::string("k2")}};
    }
    return SineAccelDecelEase(k1, k2);
  }
  /// End of the acceleration phase.
  T k1() const noexcept { return k1_; }
  /// Start of the deceleration phase.
  T k2() const noexcept { return k2_; }
  /// The normaliser f (total distance of the unnormalised curve); the constant speed is 1/f.
  T f() const noexcept { return f_; }

  /// s, v, a at t clamped into [0, 1] (NaN → 0).
  EaseSample<T> sample(T t) const noexcept {
    t = detail::clamp_unit_time(t);
    const T pi = pi_v<T>, two_over_pi = T(2) / pi_v<T>;
    if (t < k1_) {
      const T w = pi / (T(2) * k1_);  // phase rate
      return {k1_ * two_over_pi * (T(1) - std::cos(w * t)) / f_, std::sin(w * t) / f_, w * std::cos(w * t) / f_};
    }
    if (t <= k2_) return {(k1_ * two_over_pi + t - k1_) / f_, T(1) / f_, T(0)};
    const T w = pi / (T(2) * (T(1) - k2_));
    const T x = w * (t - k2_);
    return {(k1_ * two_over_pi + k2_ - k1_ + (T(1) - k2_) * two_over_pi * std::sin(x)) / f_, std::cos(x) / f_,
            -w * std::sin(x) / f_};
  }
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }

 private:
  SineAccelDecelEase(T k1, T k2) : k1_(k1), k2_(k2), f_(T(2) * k1 / pi_v<T> + (k2 - k1) + T(2) * (T(1) - k2) / pi_v<T>) {}
  T k1_{}, k2_{}, f_{1};
};

/// Constant acceleration on [0, t1], constant velocity v0 on [t1, t2], constant deceleration on
/// [t2, 1] (texts 004 "parabolic ease-in/ease-out").  The area under the velocity curve is 1
/// (Eq. 3.21), so v0 = 2/(t2 − t1 + 1) (Eq. 3.22 corrected: the texts print t2 − t2).
/// s is parabolic, linear, parabolic; velocity is a trapezoid; acceleration is v0/t1, 0, −v0/(1 − t2).
template <Real T>
class ConstantAccelerationEase {
 public:
  /// Builds the ease; requires 0 ≤ t1 ≤ t2 ≤ 1 (finite).  t1 = 0 or t2 = 1 drop that phase (the
  /// velocity jumps there).
  static Expected<ConstantAccelerationEase> make(T t1, T t2) {
    if (!std::isfinite(t1) || !std::isfinite(t2)) return Error{ErrorCode::not_finite, "t1 and t2 must be finite", {std::string("t1")}};
    if (t1 < T(0) || t1 > T(1)) return Error{ErrorCode::invalid_argument, "t1 = " + shortest_text<double>(double(t1)) + " is outside [0, 1]", {std::string("t1")}};
    if (t2 < t1 || t2 > T(1)) {
      return Error{ErrorCode::invalid_argument,
                   "t2 = " + shortest_text<double>(double(t2)) + " must lie in [t1, 1] with t1 = " + shortest_text<double>(double(t1)), {std::string("t2")}};
    }
    return ConstantAccelerationEase(t1, t2);
  }
  /// End of the acceleration phase.
  T t1() const noexcept { return t1_; }
  /// Start of the deceleration phase.
  T t2() const noexcept { return t2_; }
  /// The cruising velocity v0 = 2/(t2 − t1 + 1) (Eq. 3.22 corrected).
  T v0() const noexcept { return v0_; }

  /// s, v, a at t clamped into [0, 1] (NaN → 0).
  EaseSample<T> sample(T t) const noexcept {
    t = detail::clamp_unit_time(t);
    if (t < t1_) return {v0_ * t * t / (T(2) * t1_), v0_ * t / t1_, v0_ / t1_};
    const T s1 = v0_ * t1_ / T(2);
    if (t <= t2_) return {s1 + v0_ * (t - t1_), v0_, T(0)};
    const T d = T(1) - t2_, x = t - t2_;
    return {s1 + v0_ * (t2_ - t1_) + v0_ * (x - x * x / (T(2) * d)), v0_ * (T(1) - x / d), -v0_ / d};
  }
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }
  /// The velocity-time curve (Figure 3.17) at t.
  T velocity(T t) const noexcept { return sample(t).velocity; }
  /// The acceleration-time curve (Figure 3.16) at t.
  T acceleration(T t) const noexcept { return sample(t).acceleration; }

 private:
  ConstantAccelerationEase(T t1, T t2) : t1_(t1), t2_(t2), v0_(T(2) / (t2 - t1 + T(1))) {}
  T t1_{}, t2_{}, v0_{1};
};

}  // namespace inbetween
