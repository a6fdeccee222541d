// DistanceTimeCurve: builders from keys and velocity curves, the backing-up check and the
// Fritsch–Carlson monotone repair.
#include "inbetween/math/format.hpp"
#include "inbetween/timing/distance_time.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>

namespace inbetween {
namespace {


// Checks ≥ 2 keys, finite values and strictly increasing times; `values(i)` lists key i's numbers.
template <class T, class Get>
Expected<void> check_keys(std::size_t n, Get&& get) {
  if (n < 2) return Error{ErrorCode::TooFewPoints, "needs at least 2 keys, got " + std::to_string(n), ""};
  for (std::size_t i = 0; i < n; ++i) {
    const auto [t, a, b] = get(i);
        if (!std::isfinite(t) || !std::isfinite(a) || !std::isfinite(b)) {
      return Error{ErrorCode::NotFinite, "a value is not finite", "", {i}};
    }
    if (i > 0) {
      const T prev = std::get<0>(get(i - 1));
      if (!(prev < t)) {
        return Error{ErrorCode::KeysNotIncreasing, "time " + shortest_text(t) + " is not after " + shortest_text(prev), "", {i}};
      }
    }
  }
  return {};
}

// Cubic Hermite on one interval in τ: end values p0, p1 and end derivatives d0, d1 (per τ).
template <class T>
PowerCubic<T> hermite_cubic(T p0, T p1, T d0, T d1) {
  return {T(2) * (p0 - p1) + d0 + d1, T(3) * (p1 - p0) - T(2) * d0 - d1, d0, p0};
}

// Fritsch–Carlson: limits the key velocities m (in place) so every Hermite interval is monotone;
// requires non-decreasing s.
template <class T>
void fritsch_carlson_limit(const std::vector<T>& t, const std::vector<T>& s, std::vector<T>& m) {
  for (auto& v : m) v = std::max(v, T(0));
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const T delta = (s[i + 1] - s[i]) / (t[i + 1] - t[i]);
    if (!(delta > T(0))) {
      m[i] = T(0);
      m[i + 1] = T(0);
      continue;
    }
    const T alpha = m[i] / delta, beta = m[i + 1] / delta;
    const T r2 = alpha * alpha + beta * beta;
    if (r2 > T(9)) {
      const T tau = T(3) / std::sqrt(r2);
      m[i] = tau * alpha * delta;
      m[i + 1] = tau * beta * delta;
    }
  }
}

}  // namespace

template <Real T>
Expected<DistanceTimeCurve<T>> DistanceTimeCurve<T>::hermite(std::vector<T> t, std::vector<T> s,
                                                             const std::vector<T>& v) {
  DistanceTimeCurve c;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const T h = t[i + 1] - t[i];
    c.seg_.push_back(hermite_cubic(s[i], s[i + 1], v[i] * h, v[i + 1] * h));
  }
  c.t_ = std::move(t);
  c.s_ = std::move(s);
  return c;
}

template <Real T>
Expected<DistanceTimeCurve<T>> DistanceTimeCurve<T>::from_positions(std::span<const TimeDistanceKey<T>> keys,
                                                                    PositionInterpolation how) {
  const auto ok = check_keys<T>(keys.size(), [&](std::size_t i) { return std::tuple{keys[i].t, keys[i].s, T(0)}; });
  if (!ok) return ok.error();
  const std::size_t n = keys.size();
  std::vector<T> t(n), s(n), m(n);
  for (std::size_t i = 0; i < n; ++i) { t[i] = keys[i].t; s[i] = keys[i].s; }
  if (how == PositionInterpolation::linear) {
    DistanceTimeCurve c;
    for (std::size_t i = 0; i + 1 < n; ++i) c.seg_.push_back({T(0), T(0), s[i + 1] - s[i], s[i]});
    c.t_ = std::move(t);
    c.s_ = std::move(s);
    return c;
  }
  auto secant = [&](std::size_t i) { return (s[i + 1] - s[i]) / (t[i + 1] - t[i]); };
  m[0] = secant(0);
  m[n - 1] = secant(n - 2);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (how == PositionInterpolation::catmull_rom) {
      m[i] = (s[i + 1] - s[i - 1]) / (t[i + 1] - t[i - 1]);
    } else {
      // Fritsch–Carlson start: mean of the neighbouring secants, 0 at a local extremum.
      const T d0 = secant(i - 1), d1 = secant(i);
      m[i] = (d0 * d1 > T(0)) ? (d0 + d1) / T(2) : T(0);
    }
  }
  if (how == PositionInterpolation::monotone_cubic) {
    const bool rising = std::is_sorted(s.begin(), s.end());
    if (rising) fritsch_carlson_limit(t, s, m);
  }
  return hermite(std::move(t), std::move(s), m);
}

template <Real T>
Expected<DistanceTimeCurve<T>> DistanceTimeCurve<T>::from_constraints(
    std::span<const TimeDistanceVelocityKey<T>> keys) {
  const auto ok = check_keys<T>(keys.size(), [&](std::size_t i) { return std::tuple{keys[i].t, keys[i].s, keys[i].v}; });
  if (!ok) return ok.error();
  std::vector<T> t, s, v;
  for (const auto& k : keys) { t.push_back(k.t); s.push_back(k.s); v.push_back(k.v); }
  return hermite(std::move(t), std::move(s), v);
}

template <Real T>
Expected<DistanceTimeCurve<T>> DistanceTimeCurve<T>::from_velocity_curve(std::span<const TimeVelocityKey<T>> keys,
                                                                         VelocityFit fit, T total_distance) {
  const auto ok = check_keys<T>(keys.size(), [&](std::size_t i) { return std::tuple{keys[i].t, keys[i].v, T(0)}; });
  if (!ok) return ok.error();
  if (!std::isfinite(total_distance)) return Error{ErrorCode::NotFinite, "total distance is not finite", "", {std::string("total_distance")}};
  const std::size_t n = keys.size();
  const T duration = keys[n - 1].t - keys[0].t;
  T area{};
  for (std::size_t i = 0; i + 1 < n; ++i) area += (keys[i + 1].t - keys[i].t) * (keys[i].v + keys[i + 1].v) / T(2);
  // The distance the straight velocity lines miss; the adjustment contributes exactly this much.
  const T missing = total_distance - area;
  // FixKeysAdjustInterior: interval i gets the bump b_i·6τ(1 − τ) (zero at both keys, area b_i per
  // unit time).  v(τ) = v_i + Δv_i·τ + 6b_iτ(1 − τ) stays between v_i and v_{i+1} (monotone)
  // exactly when |6b_i| ≤ |Δv_i|, so interval i can absorb up to h_i|Δv_i|/6 without leaving its
  // keys' range; an interval between equal speeds can absorb nothing and stays flat.  The missing
  // distance goes first to that room, shared in proportion to it; only what exceeds the whole
  // room (e.g. two keys at rest) is spread evenly over time as the texts do (Eq. 3.20, Fig. 3.19).
  T room{};
  for (std::size_t i = 0; i + 1 < n; ++i) room += (keys[i + 1].t - keys[i].t) * std::fabs(keys[i + 1].v - keys[i].v) / T(6);
  if (!std::isfinite(missing) || !std::isfinite(room)) {
    return Error{ErrorCode::NotFinite,
                 "the distance under the velocity keys overflows (speeds times frame spans beyond the number range)", ""};
  }
  const bool within_room = std::fabs(missing) <= room;
  // Share of each interval's room used (|share| ≤ 1), and the even bump height beyond the room.
  const T share = within_room ? (room > T(0) ? std::clamp(missing / room, T(-1), T(1)) : T(0))
                              : std::copysign(T(1), missing);
  const T even = within_room ? T(0) : (missing - std::copysign(room, missing)) / duration;
  // FloatToKeepAverage: the constant added to every velocity (area c·duration).
  const T c = missing / duration;
  DistanceTimeCurve out;
  T s_acc{};
  for (std::size_t i = 0; i < n; ++i) {
    out.t_.push_back(keys[i].t);
    out.s_.push_back(s_acc);
    if (i + 1 == n) break;
    const T h = keys[i + 1].t - keys[i].t;
    PowerCubic<T> seg;
    if (fit == VelocityFit::float_to_keep_average) {
      const T v0 = keys[i].v + c, v1 = keys[i + 1].v + c;
      seg = {T(0), h * (v1 - v0) / T(2), h * v0, s_acc};  // ∫ linear velocity
    } else {
      const T v0 = keys[i].v, v1 = keys[i + 1].v;
      const T b = share * std::fabs(v1 - v0) / T(6) + even;
      // v(τ) = v0 + (v1 − v0)τ + 6bτ(1 − τ); s = s_i + h∫v dτ.
      seg = {T(-2) * h * b, h * ((v1 - v0) / T(2) + T(3) * b), h * v0, s_acc};
    }
    out.seg_.push_back(seg);
    s_acc = seg.point(T(1));
  }
  out.s_.back() = total_distance;  // exact by construction up to rounding; make the end exact
  return out;
}

template <Real T>
EaseSample<T> DistanceTimeCurve<T>::sample(T t) const noexcept {
  const T lo = t_.front(), hi = t_.back();
  if (!(t > lo)) t = lo;  // NaN → start
  if (t > hi) t = hi;
  std::size_t i = std::size_t(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin());
  i = i == 0 ? 0 : i - 1;
  if (i + 1 >= t_.size()) i = t_.size() - 2;
  const T h = t_[i + 1] - t_[i];
  const T tau = (t - t_[i]) / h;
  const PowerCubic<T>& c = seg_[i];
  if (t == hi) return {s_.back(), c.derivative(T(1), 1) / h, c.derivative(T(1), 2) / (h * h)};
  return {c.point(tau), c.derivative(tau, 1) / h, c.derivative(tau, 2) / (h * h)};
}

template <Real T>
std::optional<BackingUp<T>> DistanceTimeCurve<T>::find_backing_up() const noexcept {
  for (std::size_t i = 0; i < seg_.size(); ++i) {
    const PowerCubic<T>& c = seg_[i];
    const T h = t_[i + 1] - t_[i];
    // Velocity per τ: q(τ) = 3aτ² + 2bτ + c.  Rounding allowance: 16 ulp of its largest term.
    const T A = T(3) * c.a, B = T(2) * c.b, C = c.c;
    const T allowance = T(16) * std::numeric_limits<T>::epsilon() * (std::fabs(A) + std::fabs(B) + std::fabs(C));
    auto q = [&](T x) { return (A * x + B) * x + C; };
    // Split [0, 1] at the roots of q, then look for the first piece where q < 0.
    std::vector<T> cuts{T(0)};
    if (A != T(0)) {
      const T disc = B * B - T(4) * A * C;
      if (disc > T(0)) {
        const T r = std::sqrt(disc);
        const T q1 = -(B + std::copysign(r, B)) / T(2);
        T r1 = q1 / A, r2 = q1 != T(0) ? C / q1 : r1;
        if (r2 < r1) std::swap(r1, r2);
        for (T x : {r1, r2}) if (x > T(0) && x < T(1)) cuts.push_back(x);
      }
    } else if (B != T(0)) {
      const T x = -C / B;
      if (x > T(0) && x < T(1)) cuts.push_back(x);
    }
    cuts.push_back(T(1));
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const T a = cuts[k], b = cuts[k + 1];
      T x_min = a, q_min = q(a);
      if (q(b) < q_min) { x_min = b; q_min = q(b); }
      if (A > T(0)) {
        const T x = -B / (T(2) * A);
        if (x > a && x < b && q(x) < q_min) { x_min = x; q_min = q(x); }
      }
      if (q_min < -allowance && q((a + b) / T(2)) < T(0)) {
        return BackingUp<T>{int(i), t_[i] + a * h, t_[i] + b * h, t_[i] + x_min * h, q_min / h};
      }
    }
  }
  return std::nullopt;
}

template <Real T>
Expected<void> DistanceTimeCurve<T>::check_monotone() const {
  const auto b = find_backing_up();
  if (!b) return {};
  return Error{ErrorCode::NotMonotone,
               "the object backs up from t = " + shortest_text(b->t_begin) + " to t = " + shortest_text(b->t_end) +
                   " (velocity down to " + shortest_text(b->min_velocity) + " at t = " + shortest_text(b->t_min_velocity) + ")",
               "segment " + std::to_string(b->segment)};
}

template <Real T>
Expected<DistanceTimeCurve<T>> DistanceTimeCurve<T>::monotone_repair() const {
  const std::size_t n = t_.size();
  for (std::size_t i = 1; i < n; ++i) {
    if (s_[i] < s_[i - 1]) {
      return Error{ErrorCode::NotMonotone,
                   "distance " + shortest_text(s_[i]) + " at t = " + shortest_text(t_[i]) + " is less than " + shortest_text(s_[i - 1]) +
                       " at the key before: no monotone curve passes through the keys",
                   "", {i}};
    }
  }
  std::vector<T> m(n);
  for (std::size_t i = 0; i < n; ++i) {
    const T right = i + 1 < n ? seg_[i].derivative(T(0), 1) / (t_[i + 1] - t_[i]) : T(0);
    const T left = i > 0 ? seg_[i - 1].derivative(T(1), 1) / (t_[i] - t_[i - 1]) : T(0);
    m[i] = i == 0 ? right : (i + 1 == n ? left : (left + right) / T(2));
  }
  fritsch_carlson_limit(t_, s_, m);
  return hermite(t_, s_, m);
}

template class DistanceTimeCurve<float>;
template class DistanceTimeCurve<double>;

}  // namespace inbetween
