#pragma once
/// CSS-style cubic-bezier(x1, y1, x2, y2) timing functions: the 2-D Bézier from (0, 0) through
/// control points (x1, y1), (x2, y2) to (1, 1), read as s = y where x = t.  x1 and x2 must lie in
/// [0, 1] (as CSS requires, so x is monotone and each t has one s); y1 and y2 may be anything, so
/// the motion may overshoot or back up (anticipation).  s(t) is found by solving x(p) = t for the
/// Bézier parameter p with safeguarded Newton iteration, to |x(p) − t| ≤ 1e-7 at the very least
/// (in practice to a few ulp).

#include <cmath>
#include <limits>
#include <string>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/timing/ease.hpp"

namespace inbetween {

/// A cubic-bezier timing function with normalised time and distance.
template <Real T>
class CubicBezierTiming {
 public:
  /// Builds the function; x1, x2 ∈ [0, 1] and all four finite, else an Error naming the argument.
  static Expected<CubicBezierTiming> make(T x1, T y1, T x2, T y2) {
    const T v[4] = {x1, y1, x2, y2};
    const char* names[4] = {"x1", "y1", "x2", "y2"};
    for (int i = 0; i < 4; ++i) {
      if (!std::isfinite(v[i])) return Error{ErrorCode::not_finite, std::string(names[i]) + " is not finite", {std::string(names[i])}};
    }
    if (x1 < T(0) || x1 > T(1)) {
      return Error{ErrorCode::invalid_argument, "x1 = " + shortest_text<double>(double(x1)) + " is outside [0, 1]", {std::string("x1")}};
    }
    if (x2 < T(0) || x2 > T(1)) {
      return Error{ErrorCode::invalid_argument, "x2 = " + shortest_text<double>(double(x2)) + " is outside [0, 1]", {std::string("x2")}};
    }
    return CubicBezierTiming(x1, y1, x2, y2);
  }
  /// CSS `ease` = cubic-bezier(0.25, 0.1, 0.25, 1).
  static CubicBezierTiming css_ease() noexcept { return {T(0.25), T(0.1), T(0.25), T(1)}; }
  /// CSS `ease-in` = cubic-bezier(0.42, 0, 1, 1).
  static CubicBezierTiming css_ease_in() noexcept { return {T(0.42), T(0), T(1), T(1)}; }
  /// CSS `ease-out` = cubic-bezier(0, 0, 0.58, 1).
  static CubicBezierTiming css_ease_out() noexcept { return {T(0), T(0), T(0.58), T(1)}; }
  /// CSS `ease-in-out` = cubic-bezier(0.42, 0, 0.58, 1).
  static CubicBezierTiming css_ease_in_out() noexcept { return {T(0.42), T(0), T(0.58), T(1)}; }

  /// The Bézier parameter p ∈ [0, 1] with x(p) = t (t clamped into [0, 1]).
  T solve_parameter(T t) const noexcept {
    t = clamp(t, T(0), T(1));
    if (!(t > T(0))) return T(0);
    if (!(t < T(1))) return T(1);
    // x is non-decreasing on [0, 1]: keep a bracket and take Newton steps only inside it.
    T lo = 0, hi = 1, p = t;
    const T tol = T(2) * std::numeric_limits<T>::epsilon();
    for (int iter = 0; iter < 100; ++iter) {
      const T f = x_of(p) - t;
      if (std::fabs(f) <= tol) return p;
      if (f < T(0)) lo = p; else hi = p;
      const T d = dx_of(p);
      T next = d > T(0) ? p - f / d : lo + (hi - lo) / T(2);
      if (!(lo < next && next < hi)) next = lo + (hi - lo) / T(2);
      if (next == p) return p;
      p = next;
    }
    return p;
  }

  /// s = y(p) where x(p) = t, with velocity ds/dt = y'/x' and acceleration
  /// d²s/dt² = (y''x' − y'x'')/x'³.  Where x'(p) = 0 (x1 = 0 at t = 0, x2 = 1 at t = 1, or an
  /// interior inflection with x1 = x2) the limits are taken by l'Hôpital (y''/x''); a vertical
  /// tangent (x' = 0, y' ≠ 0) reports velocity ±infinity and acceleration 0, never NaN.
  EaseSample<T> sample(T t) const noexcept {
    const T p = solve_parameter(t);
    const T dx = dx_of(p), dy = dy_of(p), ddx = ddx_of(p), ddy = ddy_of(p);
    const T small = T(64) * std::numeric_limits<T>::epsilon();
    EaseSample<T> out{p == T(1) ? T(1) : y_of(p), T(0), T(0)};  // exact at the end
    if (std::fabs(dx) > small) {
      out.velocity = dy / dx;
      out.acceleration = (ddy * dx - dy * ddx) / (dx * dx * dx);
    } else if (std::fabs(dy) > small) {
      out.velocity = std::copysign(std::numeric_limits<T>::infinity(), dy);  // x' → 0⁺ (x is monotone)
    } else if (std::fabs(ddx) > small) {
      out.velocity = ddy / ddx;  // both first derivatives vanish: ratio of second derivatives
    }
    return out;
  }
  /// s only.
  T operator()(T t) const noexcept { return sample(t).s; }

  T x1() const noexcept { return x1_; }  ///< first control point, x
  T y1() const noexcept { return y1_; }  ///< first control point, y
  T x2() const noexcept { return x2_; }  ///< second control point, x
  T y2() const noexcept { return y2_; }  ///< second control point, y

 private:
  CubicBezierTiming(T x1, T y1, T x2, T y2) noexcept : x1_(x1), y1_(y1), x2_(x2), y2_(y2) {}
  // B(p) = 3(1−p)²p c1 + 3(1−p)p² c2 + p³, in power form: ((a p + b) p + c) p with
  // c = 3c1, b = 3(c2 − 2c1), a = 1 − 3c2 + 3c1.
  static T val(T c1, T c2, T p) noexcept {
    const T c = T(3) * c1, b = T(3) * (c2 - T(2) * c1), a = T(1) - T(3) * c2 + T(3) * c1;
    return ((a * p + b) * p + c) * p;
  }
  static T d1(T c1, T c2, T p) noexcept {
    const T c = T(3) * c1, b = T(3) * (c2 - T(2) * c1), a = T(1) - T(3) * c2 + T(3) * c1;
    return (T(3) * a * p + T(2) * b) * p + c;
  }
  static T d2(T c1, T c2, T p) noexcept {
    const T b = T(3) * (c2 - T(2) * c1), a = T(1) - T(3) * c2 + T(3) * c1;
    return T(6) * a * p + T(2) * b;
  }
  T x_of(T p) const noexcept { return val(x1_, x2_, p); }
  T y_of(T p) const noexcept { return val(y1_, y2_, p); }
  T dx_of(T p) const noexcept { return d1(x1_, x2_, p); }
  T dy_of(T p) const noexcept { return d1(y1_, y2_, p); }
  T ddx_of(T p) const noexcept { return d2(x1_, x2_, p); }
  T ddy_of(T p) const noexcept { return d2(y1_, y2_, p); }

  T x1_, y1_, x2_, y2_;
};

}  // namespace inbetween
