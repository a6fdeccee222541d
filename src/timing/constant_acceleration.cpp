// Constant-acceleration ease from any sufficient parameters: closed forms (docs/timing.md).
#include "inbetween/timing/constant_acceleration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "inbetween/math/format.hpp"

namespace inbetween {
namespace {

std::string num(double v) { return shortest_text<double>(v); }

template <Real T>
Error bad(ErrorCode code, const char* member, std::string message) {
  return Error{code, std::move(message), {std::string(member)}};
}

// Relative slack for a value at the edge of its admissible range: the closed forms round by a few
// ulps (e.g. a = 2/t1 gives v0 = 2 and t2 = t1 + 2/2 − 1 one ulp from t1); 16 ulps of the type.
template <Real T>
constexpr T kEdgeSlack = T(16) * std::numeric_limits<T>::epsilon();

// v inside [lo, hi] up to kEdgeSlack relative (hi may be +∞).
template <Real T>
bool within(T v, T lo, T hi) {
  const T s = kEdgeSlack<T>;
  return v >= lo - s * std::abs(lo) && v <= hi + s * std::abs(hi);
}

std::string range_text(double lo, double hi) {
  if (std::isinf(lo)) return "finite, and no finite value works";
  return std::isinf(hi) ? "≥ " + num(lo) : "in [" + num(lo) + ", " + num(hi) + "]";
}

// "acceleration = 3 with t1 = 0.2 has no profile: acceleration must be in [..]".
template <Real T>
Error no_profile(const char* member, T value, const char* other, T other_value, T lo, T hi) {
  return bad<T>(ErrorCode::invalid_argument, member,
                std::string(member) + " = " + num(double(value)) + " with " + other + " = " + num(double(other_value)) +
                    " has no constant-acceleration profile over distance 1 and time 1: " + member + " must be " +
                    range_text(double(lo), double(hi)));
}

// t1 ≤ t2 in [0, 1] after rounding: values within kEdgeSlack of an edge are put on it.
template <Real T>
void snap(T& t1, T& t2) {
  t1 = std::clamp(t1, T(0), T(1));
  t2 = std::clamp(t2, t1, T(1));
}

}  // namespace

template <Real T>
Expected<ConstantAccelerationEase<T>> solve_constant_acceleration(const ConstantAccelerationParams<T>& p) {
  const std::array<std::pair<const char*, const std::optional<T>*>, 5> members{
      {{"t1", &p.t1}, {"t2", &p.t2}, {"v0", &p.v0}, {"acceleration", &p.acceleration}, {"deceleration", &p.deceleration}}};
  int given = 0;
  const char* names[2] = {nullptr, nullptr};
  for (const auto& [name, value] : members) {
    if (!value->has_value()) continue;
    if (given == 2)
      return bad<T>(ErrorCode::invalid_argument, name,
                    std::string("over-determined: ") + names[0] + " and " + names[1] +
                        " already fix the profile (distance 1 over time 1); leave " + name + " out");
    if (!std::isfinite(**value)) return bad<T>(ErrorCode::not_finite, name, std::string(name) + " is not finite");
    names[given++] = name;
  }
  if (given < 2)
    return Error{ErrorCode::invalid_argument,
                 std::string("under-determined: constant acceleration needs two of t1, t2, v0, acceleration, deceleration; got ") +
                     (given == 0 ? "none" : std::string("only ") + names[0])};
  // Ranges of the single values.
  if (p.t1 && !(*p.t1 >= T(0) && *p.t1 <= T(1)))
    return bad<T>(ErrorCode::invalid_argument, "t1", "t1 = " + num(double(*p.t1)) + " is outside [0, 1]");
  if (p.t2 && !(*p.t2 >= T(0) && *p.t2 <= T(1)))
    return bad<T>(ErrorCode::invalid_argument, "t2", "t2 = " + num(double(*p.t2)) + " is outside [0, 1]");
  if (p.v0 && !(*p.v0 >= T(1) && *p.v0 <= T(2)))
    return bad<T>(ErrorCode::invalid_argument, "v0",
                  "v0 = " + num(double(*p.v0)) + " must lie in [1, 2] (the cruise covers 2/v0 − 1 of the time)");
  if (p.acceleration && !(*p.acceleration > T(0)))
    return bad<T>(ErrorCode::invalid_argument, "acceleration", "acceleration = " + num(double(*p.acceleration)) + " must be > 0");
  if (p.deceleration && !(*p.deceleration > T(0)))
    return bad<T>(ErrorCode::invalid_argument, "deceleration", "deceleration = " + num(double(*p.deceleration)) + " must be > 0");

  const T inf = std::numeric_limits<T>::infinity();
  T t1{}, t2{};
  if (p.t1 && p.t2) {
    t1 = *p.t1, t2 = *p.t2;
    if (t2 < t1) return bad<T>(ErrorCode::invalid_argument, "t2", "t2 = " + num(double(t2)) + " must lie in [t1, 1] with t1 = " + num(double(t1)));
  } else if (p.t1 && p.v0) {
    // Eq. 3.21: t2 − t1 = 2/v0 − 1 ≤ 1 − t1.
    const T lo = T(2) / (T(2) - *p.t1);
    if (!within(*p.v0, lo, T(2))) return no_profile<T>("v0", *p.v0, "t1", *p.t1, lo, T(2));
    t1 = *p.t1, t2 = *p.t1 + T(2) / *p.v0 - T(1);
  } else if (p.t2 && p.v0) {
    const T lo = T(2) / (T(1) + *p.t2);
    if (!within(*p.v0, lo, T(2))) return no_profile<T>("v0", *p.v0, "t2", *p.t2, lo, T(2));
    t2 = *p.t2, t1 = *p.t2 - T(2) / *p.v0 + T(1);
  } else if (p.t1 && p.acceleration) {
    // v0 = a·t1 ∈ [2/(2 − t1), 2].
    const T a = *p.acceleration, lo = T(2) / (*p.t1 * (T(2) - *p.t1)), hi = T(2) / *p.t1;
    if (!(*p.t1 > T(0)) || !within(a, lo, hi)) return no_profile<T>("acceleration", a, "t1", *p.t1, lo, hi);
    const T v0 = std::clamp(a * *p.t1, T(1), T(2));
    t1 = *p.t1, t2 = *p.t1 + T(2) / v0 - T(1);
  } else if (p.t2 && p.deceleration) {
    const T d = *p.deceleration, e = T(1) - *p.t2, lo = T(2) / (e * (T(2) - e)), hi = T(2) / e;
    if (!(e > T(0)) || !within(d, lo, hi)) return no_profile<T>("deceleration", d, "t2", *p.t2, lo, hi);
    const T v0 = std::clamp(d * e, T(1), T(2));
    t2 = *p.t2, t1 = *p.t2 - T(2) / v0 + T(1);
  } else if (p.v0 && (p.acceleration || p.deceleration)) {
    // t1 + (1 − t2) = v0/a + v0/d = 2 − 2/v0 (Eq. 3.21): the one given rate must leave room.
    const T v0 = *p.v0;
    const T lo = v0 > T(1) ? v0 * v0 / (T(2) * (v0 - T(1))) : inf;
    const char* name = p.acceleration ? "acceleration" : "deceleration";
    const T rate = p.acceleration ? *p.acceleration : *p.deceleration;
    if (!(v0 > T(1)) || !within(rate, lo, inf)) return no_profile<T>(name, rate, "v0", v0, lo, inf);
    if (p.acceleration) t1 = v0 / rate, t2 = t1 + T(2) / v0 - T(1);
    else t2 = T(1) - v0 / rate, t1 = t2 - T(2) / v0 + T(1);
  } else if (p.t2 && p.acceleration) {
    // a·t1·(1 + t2 − t1) = 2: t1 is the root below t2 of a·t1² − a(1 + t2)·t1 + 2, which exists iff
    // a·t2 ≥ 2 (the quadratic is ≤ 0 at t2); the form 4/(a(b + √disc)) avoids cancellation.
    const T a = *p.acceleration, b = T(1) + *p.t2;
    if (!(*p.t2 > T(0)) || !within(a, T(2) / *p.t2, inf)) return no_profile<T>("acceleration", a, "t2", *p.t2, T(2) / *p.t2, inf);
    const T disc = std::max(T(0), b * b - T(8) / a);
    t2 = *p.t2, t1 = T(4) / (a * (b + std::sqrt(disc)));
  } else if (p.t1 && p.deceleration) {
    const T d = *p.deceleration, e1 = T(1) - *p.t1, b = T(1) + e1;
    if (!(e1 > T(0)) || !within(d, T(2) / e1, inf)) return no_profile<T>("deceleration", d, "t1", *p.t1, T(2) / e1, inf);
    const T disc = std::max(T(0), b * b - T(8) / d);
    t1 = *p.t1, t2 = T(1) - T(4) / (d * (b + std::sqrt(disc)));
  } else {  // acceleration and deceleration
    // (1/a + 1/d)·v0² − 2·v0 + 2 = 0; the smaller root (the larger one puts t1 after t2).
    const T a = *p.acceleration, d = *p.deceleration, k = T(1) / a + T(1) / d;
    if (!within(k, T(0), T(0.5))) {
      const T lo = a > T(2) ? T(2) * a / (a - T(2)) : inf;
      return bad<T>(ErrorCode::invalid_argument, "deceleration",
                    "deceleration = " + num(double(d)) + " with acceleration = " + num(double(a)) +
                        " has no constant-acceleration profile over distance 1 and time 1: 1/acceleration + 1/deceleration = " +
                        num(double(k)) + " must be ≤ 1/2" + (std::isinf(lo) ? std::string(" (acceleration must exceed 2)") : ", so deceleration ≥ " + num(double(lo))));
    }
    const T v0 = T(2) / (T(1) + std::sqrt(std::max(T(0), T(1) - T(2) * k)));
    t1 = v0 / a, t2 = T(1) - v0 / d;
  }
  snap(t1, t2);
  return ConstantAccelerationEase<T>::make(t1, t2);
}

template <Real T>
Expected<ConstantAccelerationGraph<T>> solve_equal_areas(const EqualAreasParams<T>& p) {
  const std::array<std::pair<const char*, const std::optional<T>*>, 4> members{
      {{"acceleration", &p.acceleration}, {"deceleration", &p.deceleration}, {"t1", &p.t1}, {"t2", &p.t2}}};
  int given = 0;
  const char* missing = nullptr;
  for (const auto& [name, value] : members) {
    if (!value->has_value()) {
      if (!missing) missing = name;
      continue;
    }
    if (!std::isfinite(**value)) return bad<T>(ErrorCode::not_finite, name, std::string(name) + " is not finite");
    ++given;
  }
  if (given == 4)
    return bad<T>(ErrorCode::invalid_argument, "t2",
                  "over-determined: acceleration, deceleration and t1 already fix t2 (a·t1 = d·(1 − t2)); leave one out");
  if (given < 3)
    return Error{ErrorCode::invalid_argument,
                 "under-determined: the acceleration graph needs three of acceleration, deceleration, t1, t2; got " + std::to_string(given)};
  if (p.acceleration && !(*p.acceleration > T(0)))
    return bad<T>(ErrorCode::invalid_argument, "acceleration", "acceleration = " + num(double(*p.acceleration)) + " must be > 0");
  if (p.deceleration && !(*p.deceleration > T(0)))
    return bad<T>(ErrorCode::invalid_argument, "deceleration", "deceleration = " + num(double(*p.deceleration)) + " must be > 0");
  if (p.t1 && !(*p.t1 > T(0) && *p.t1 < T(1)))
    return bad<T>(ErrorCode::invalid_argument, "t1", "t1 = " + num(double(*p.t1)) + " must lie in (0, 1) (a finite acceleration needs time)");
  if (p.t2 && !(*p.t2 > T(0) && *p.t2 < T(1)))
    return bad<T>(ErrorCode::invalid_argument, "t2", "t2 = " + num(double(*p.t2)) + " must lie in (0, 1) (a finite deceleration needs time)");

  ConstantAccelerationGraph<T> g;
  const std::string m = missing;
  if (m == "t2") {
    g.acceleration = *p.acceleration, g.deceleration = *p.deceleration, g.t1 = *p.t1;
    g.t2 = T(1) - g.acceleration * g.t1 / g.deceleration;
  } else if (m == "t1") {
    g.acceleration = *p.acceleration, g.deceleration = *p.deceleration, g.t2 = *p.t2;
    g.t1 = g.deceleration * (T(1) - g.t2) / g.acceleration;
  } else if (m == "acceleration") {
    g.deceleration = *p.deceleration, g.t1 = *p.t1, g.t2 = *p.t2;
    g.acceleration = g.deceleration * (T(1) - g.t2) / g.t1;
  } else {
    g.acceleration = *p.acceleration, g.t1 = *p.t1, g.t2 = *p.t2;
    g.deceleration = g.acceleration * g.t1 / (T(1) - g.t2);
  }
  if (!(g.t1 <= g.t2)) {
    const bool solved_time = m == "t1" || m == "t2";
    if (solved_time && std::abs(g.t1 - g.t2) <= kEdgeSlack<T> * g.t2) {
      (m == "t1" ? g.t1 : g.t2) = (m == "t1" ? g.t2 : g.t1);  // one rounding apart: a triangle
    } else {
      const char* name = solved_time ? missing : "t2";
      return bad<T>(ErrorCode::invalid_argument, name,
                    "t1 = " + num(double(g.t1)) + " comes after t2 = " + num(double(g.t2)) +
                        ": the accelerating and decelerating phases overlap (a·t1 = d·(1 − t2) needs a·t1/d ≤ 1 − t1)");
    }
  }
  if (!(g.t1 > T(0)) || !(g.t2 < T(1)) || !std::isfinite(g.acceleration) || !std::isfinite(g.deceleration))
    return bad<T>(ErrorCode::invalid_argument, missing, std::string("the solved ") + missing + " is out of range");
  g.v0 = g.acceleration * g.t1;
  g.distance = g.v0 * (T(1) + g.t2 - g.t1) / T(2);
  return g;
}

template <Real T>
ConstantAccelerationGraph<T> graph_of(const ConstantAccelerationEase<T>& ease) noexcept {
  const T inf = std::numeric_limits<T>::infinity();
  const T v0 = ease.v0();
  return {ease.t1() > T(0) ? v0 / ease.t1() : inf,
          ease.t2() < T(1) ? v0 / (T(1) - ease.t2()) : inf,
          ease.t1(),
          ease.t2(),
          v0,
          T(1)};
}

template Expected<ConstantAccelerationEase<float>> solve_constant_acceleration(const ConstantAccelerationParams<float>&);
template Expected<ConstantAccelerationEase<double>> solve_constant_acceleration(const ConstantAccelerationParams<double>&);
template Expected<ConstantAccelerationGraph<float>> solve_equal_areas(const EqualAreasParams<float>&);
template Expected<ConstantAccelerationGraph<double>> solve_equal_areas(const EqualAreasParams<double>&);
template ConstantAccelerationGraph<float> graph_of(const ConstantAccelerationEase<float>&) noexcept;
template ConstantAccelerationGraph<double> graph_of(const ConstantAccelerationEase<double>&) noexcept;

}  // namespace inbetween
