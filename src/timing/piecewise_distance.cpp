// PiecewiseDistanceCurve: Hermite polynomials through ⟨t, s, v, a⟩ tuples, closed-form integration
// of acceleration–time curves, and the exact backing-up test by Bernstein subdivision.
#include "inbetween/timing/piecewise_distance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "inbetween/math/format.hpp"

namespace inbetween {
namespace {

template <class T>
std::string num(T v) {
  return shortest_text<double>(double(v));
}

template <class T>
using Coeffs = typename PiecewiseDistanceCurve<T>::Coefficients;

// The Hermite polynomial in τ ∈ [0, 1] with s(0) = p0, s'(0) = d0, s(1) = p1, s'(1) = d1 and,
// when given, s''(0) = a0 and s''(1) = a1 (d and a already per τ: d = v·h, a = acc·h²).
// Degree 3, 4 or 5 with the number of given accelerations.
template <class T>
Coeffs<T> hermite(T p0, T d0, std::optional<T> a0, T p1, T d1, std::optional<T> a1) {
  Coeffs<T> c{};
  const T dp = p1 - p0;
  c[0] = p0;
  c[1] = d0;
  if (a0 && a1) {
    // Quintic Hermite basis (e.g. Farin, Curves and Surfaces for CAGD, §7.4).
    c[2] = *a0 / T(2);
    c[3] = T(10) * dp - T(6) * d0 - T(4) * d1 - (T(3) * *a0 - *a1) / T(2);
    c[4] = T(-15) * dp + T(8) * d0 + T(7) * d1 + (T(3) * *a0 - T(2) * *a1) / T(2);
    c[5] = T(6) * dp - T(3) * d0 - T(3) * d1 - (*a0 - *a1) / T(2);
  } else if (a0) {
    // c3 + c4 = A, 3c3 + 4c4 = B.
    c[2] = *a0 / T(2);
    const T A = dp - d0 - c[2], B = d1 - d0 - *a0;
    c[4] = B - T(3) * A;
    c[3] = T(4) * A - B;
  } else if (a1) {
    // c2 + c3 + c4 = A, 2c2 + 3c3 + 4c4 = B, 2c2 + 6c3 + 12c4 = C.
    const T A = dp - d0, B = d1 - d0, C = *a1;
    c[4] = (C - T(4) * B + T(6) * A) / T(2);
    c[3] = T(5) * B - T(8) * A - C;
    c[2] = A - c[3] - c[4];
  } else {
    c[2] = T(3) * dp - T(2) * d0 - d1;
    c[3] = T(-2) * dp + d0 + d1;
  }
  return c;
}

// s, ds/dτ, d²s/dτ² of one interval.
template <class T>
std::array<T, 3> eval(const Coeffs<T>& c, T x) noexcept {
  T s = c[5], d = T(5) * c[5], a = T(20) * c[5];
  for (int k = 4; k >= 0; --k) s = s * x + c[k];
  for (int k = 4; k >= 1; --k) d = d * x + T(k) * c[k];
  for (int k = 4; k >= 2; --k) a = a * x + T(k * (k - 1)) * c[k];
  return {s, d, a};
}

// The minimum of the speed polynomial (degree ≤ 4, in τ) on [lo, hi] ⊂ [0, 1], when it is below
// −tol: Bernstein coefficients of the piece are an upper and lower hull of it (convex hull
// property); subdivide until all are ≥ −tol (no dip) or an end value, a real speed, is < −tol.
template <class T>
bool dips(std::array<T, 5> b, T tol, T lo, T hi, int depth, T& where) noexcept {
  if (*std::min_element(b.begin(), b.end()) >= -tol) return false;
  if (b[0] < -tol) { where = lo; return true; }
  if (b[4] < -tol) { where = hi; return true; }
  if (depth == 0) return false;  // a dip narrower than 2^-depth and shallower than the hull's slack
  // de Casteljau at ½.
  std::array<T, 5> left{}, right{};
  std::array<T, 5> w = b;
  for (int r = 0; r < 5; ++r) {
    left[r] = w[0];
    right[4 - r] = w[4 - r];
    for (int i = 0; i + 1 < 5 - r; ++i) w[i] = (w[i] + w[i + 1]) / T(2);
  }
  const T mid = (lo + hi) / T(2);
  return dips(left, tol, lo, mid, depth - 1, where) || dips(right, tol, mid, hi, depth - 1, where);
}

// The speed ds/dτ = Σ k c_k τ^{k−1} as degree-4 Bernstein coefficients:
// b_i = Σ_{j ≤ i} C(i, j)/C(4, j) p_j for power coefficients p_j.
template <class T>
std::array<T, 5> speed_bernstein(const Coeffs<T>& c) noexcept {
  const std::array<T, 5> p{c[1], T(2) * c[2], T(3) * c[3], T(4) * c[4], T(5) * c[5]};
  constexpr double binom[5][5] = {{1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
  std::array<T, 5> b{};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j <= i; ++j) b[i] += T(binom[i][j] / binom[4][j]) * p[j];
  return b;
}

constexpr int kSubdivisionDepth = 40;  // 2^-40 of an interval: far below any frame resolution
constexpr int kBackingUpSamples = 256;  // resolution of the reported span of negative speed

// Every interval's polynomial and its speed hull finite.  Finite tuples can still overflow them (a
// speed of 1e308 times an interval of 10 frames); find_backing_up() on an infinite or NaN hull
// would subdivide to its full depth everywhere (2^40 pieces: a hang), so such curves are refused.
template <class T>
Expected<void> check_finite_segments(const std::vector<Coeffs<T>>& seg, const char* what) {
  for (std::size_t i = 0; i < seg.size(); ++i) {
    const auto b = speed_bernstein<T>(seg[i]);
    const bool finite = std::all_of(seg[i].begin(), seg[i].end(), [](T v) { return std::isfinite(v); }) &&
                        std::all_of(b.begin(), b.end(), [](T v) { return std::isfinite(v); });
    if (!finite) {
      return Error{ErrorCode::NotFinite,
                   std::string(what) + " " + std::to_string(i) + " → " + std::to_string(i + 1) +
                       ": the distance curve between them overflows (speeds or accelerations too large for the interval)",
                   "", {i}};
    }
  }
  return {};
}

template <class T>
Expected<void> check_times(std::size_t n, auto&& time_of) {
  for (std::size_t i = 0; i < n; ++i) {
    const T t = time_of(i);
    if (i > 0 && !(time_of(i - 1) < t)) {
      return Error{ErrorCode::KeysNotIncreasing,
                   "time " + num(t) + " of tuple " + std::to_string(i) + " is not after time " + num(time_of(i - 1)) +
                       (time_of(i - 1) == t ? " (two tuples at the same time)" : ""),
                   "", {i}};
    }
  }
  return {};
}

}  // namespace

template <Real T>
Expected<PiecewiseDistanceCurve<T>> PiecewiseDistanceCurve<T>::from_constraints(
    std::span<const MotionConstraint<T>> k) {
  const std::size_t n = k.size();
  if (n == 0) return Error{ErrorCode::TooFewPoints, "needs at least 1 constraint tuple, got none", ""};
  for (std::size_t i = 0; i < n; ++i) {
    const bool finite = std::isfinite(k[i].t) && std::isfinite(k[i].s) && (!k[i].v || std::isfinite(*k[i].v)) &&
                        (!k[i].a || std::isfinite(*k[i].a));
    if (!finite) return Error{ErrorCode::NotFinite, "tuple " + std::to_string(i) + " has a value that is not finite", "", {i}};
    if (k[i].v && *k[i].v < T(0))
      return Error{ErrorCode::InvalidArgument,
                   "tuple " + std::to_string(i) + ": speed " + num(*k[i].v) + " is negative (the object would move backwards)",
                   "", {i}};
    if (i > 0 && k[i].s < k[i - 1].s)
      return Error{ErrorCode::NotMonotone,
                   "tuple " + std::to_string(i) + ": distance " + num(k[i].s) + " is below the previous tuple's " +
                       num(k[i - 1].s) + " (the object would move backwards)",
                   "", {i}};
  }
  if (auto ok = check_times<T>(n, [&](std::size_t i) { return k[i].t; }); !ok) return ok.error();

  PiecewiseDistanceCurve c;
  for (const auto& tuple : k) c.t_.push_back(tuple.t);
  if (n == 1) {
    if ((k[0].v && *k[0].v != T(0)) || (k[0].a && *k[0].a != T(0)))
      return Error{ErrorCode::InvalidArgument,
                   "a single constraint tuple describes an object at rest: its speed and acceleration must be 0", "", {std::size_t{0}}};
    c.t_.push_back(k[0].t);
    c.v_ = {T(0), T(0)};
    c.seg_.push_back(Coefficients{k[0].s, 0, 0, 0, 0, 0});  // a zero-length interval, never divided by
    return c;
  }

  // Speeds: given, or estimated (Fritsch–Butland inside; the end cubic with zero end acceleration).
  auto h = [&](std::size_t i) { return k[i + 1].t - k[i].t; };
  auto slope = [&](std::size_t i) { return (k[i + 1].s - k[i].s) / h(i); };
  c.v_.assign(n, T(0));
  for (std::size_t i = 0; i < n; ++i) {
    if (k[i].v) { c.v_[i] = *k[i].v; continue; }
    if (i == 0 || i + 1 == n) continue;
    const T d0 = slope(i - 1), d1 = slope(i);
    if (d0 > T(0) && d1 > T(0)) {
      const T w0 = T(2) * h(i) + h(i - 1), w1 = h(i) + T(2) * h(i - 1);
      c.v_[i] = (w0 + w1) / (w0 / d0 + w1 / d1);
    }
  }
  // The end speed of the cubic with zero acceleration at the end: v_end = (3d − v_other)/2, kept in
  // [0, 3d] (Fritsch–Carlson's box, so the end interval alone cannot back up).
  auto end_speed = [&](std::size_t other, std::size_t interval) {
    const T d = slope(interval);
    if (!k[other].v && n == 2) return d;  // both ends free: the straight line
    return std::clamp((T(3) * d - c.v_[other]) / T(2), T(0), T(3) * d);
  };
  if (!k[0].v) c.v_[0] = end_speed(1, 0);
  if (!k[n - 1].v) c.v_[n - 1] = end_speed(n - 2, n - 2);

  for (std::size_t i = 0; i + 1 < n; ++i) {
    const T hi = h(i);
    auto acc = [&](std::size_t j) { return k[j].a ? std::optional<T>(*k[j].a * hi * hi) : std::nullopt; };
    c.seg_.push_back(hermite<T>(k[i].s, c.v_[i] * hi, acc(i), k[i + 1].s, c.v_[i + 1] * hi, acc(i + 1)));
  }
  if (auto ok = check_finite_segments<T>(c.seg_, "tuples"); !ok) return ok.error();
  if (const auto back = c.find_backing_up()) {
    const std::size_t i = std::size_t(back->segment);
    return Error{ErrorCode::NotMonotone,
                 "tuples " + std::to_string(i) + " → " + std::to_string(i + 1) + ": the object would move backwards between t = " +
                     num(back->t_begin) + " and " + num(back->t_end) + " (speed down to " + num(back->min_velocity) +
                     " at t = " + num(back->t_min_velocity) + "); give smaller accelerations or speeds there",
                 "", {i}};
  }
  return c;
}

template <Real T>
Expected<PiecewiseDistanceCurve<T>> PiecewiseDistanceCurve<T>::from_acceleration_curve(
    std::span<const TimeAccelerationKey<T>> keys, const AccelerationIntegration<T>& opt) {
  const std::size_t n = keys.size();
  if (n < 2) return Error{ErrorCode::TooFewPoints, "needs at least 2 acceleration keys, got " + std::to_string(n), ""};
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(keys[i].t) || !std::isfinite(keys[i].a))
      return Error{ErrorCode::NotFinite, "key " + std::to_string(i) + " has a value that is not finite", "", {i}};
  if (auto ok = check_times<T>(n, [&](std::size_t i) { return keys[i].t; }); !ok) return ok.error();
  if (!std::isfinite(opt.start_speed) || opt.start_speed < T(0))
    return Error{ErrorCode::InvalidArgument, "start speed " + num(opt.start_speed) + " must be finite and ≥ 0", "",
                 {std::string("start_speed")}};
  if (!std::isfinite(opt.start_distance))
    return Error{ErrorCode::NotFinite, "start distance is not finite", "", {std::string("start_distance")}};
  if (opt.end_distance && !std::isfinite(*opt.end_distance))
    return Error{ErrorCode::NotFinite, "end distance is not finite", "", {std::string("end_distance")}};

  const bool linear = opt.shape == AccelerationShape::linear;
  // Integrates with accelerations scaled by `scale`; returns the curve (no monotone check).
  auto integrate = [&](T scale) {
    PiecewiseDistanceCurve c;
    T v = opt.start_speed, s = opt.start_distance;
    for (std::size_t i = 0; i < n; ++i) {
      c.t_.push_back(keys[i].t);
      c.v_.push_back(v);
      if (i + 1 == n) break;
      const T h = keys[i + 1].t - keys[i].t;
      const T a0 = scale * keys[i].a;
      const T da = linear ? scale * keys[i + 1].a - a0 : T(0);
      // a(τ) = a0 + da·τ; v = v_i + h(a0 τ + da τ²/2); s = s_i + h v_i τ + h²(a0 τ²/2 + da τ³/6).
      c.seg_.push_back(Coefficients{s, h * v, h * h * a0 / T(2), h * h * da / T(6), T(0), T(0)});
      s += h * v + h * h * (a0 / T(2) + da / T(6));
      v += h * (a0 + da / T(2));
    }
    return c;
  };
  T scale = T(1);
  if (opt.end_distance) {
    const PiecewiseDistanceCurve coast = integrate(T(0));  // s(t_n) = s_0 + v_0·(t_n − t_0)
    const PiecewiseDistanceCurve unit = integrate(T(1));
    const T s_coast = coast.sample(keys[n - 1].t).s;
    const T from_acc = unit.sample(keys[n - 1].t).s - s_coast;
    const T need = *opt.end_distance - s_coast;
    const T scale_ref = std::max({std::abs(need), std::abs(from_acc), std::abs(*opt.end_distance), T(1)});
    if (std::abs(from_acc) <= backwards_tolerance<T>() * scale_ref) {
      if (std::abs(need) > backwards_tolerance<T>() * scale_ref)
        return Error{ErrorCode::InvalidArgument,
                     "the accelerations add no distance, so the end distance " + num(*opt.end_distance) +
                         " cannot be reached (coasting gives " + num(s_coast) + ")",
                     "", {std::string("end_distance")}};
    } else {
      scale = need / from_acc;
    }
  }
  PiecewiseDistanceCurve c = integrate(scale);
  if (auto ok = check_finite_segments<T>(c.seg_, "keys"); !ok) return ok.error();
  if (const auto back = c.find_backing_up()) {
    const std::size_t i = std::size_t(back->segment);
    return Error{ErrorCode::NotMonotone,
                 "keys " + std::to_string(i) + " → " + std::to_string(i + 1) + ": the speed turns negative between t = " +
                     num(back->t_begin) + " and " + num(back->t_end) + " (down to " + num(back->min_velocity) + " at t = " +
                     num(back->t_min_velocity) + "): the object would move backwards",
                 "", {i}};
  }
  return c;
}

template <Real T>
EaseSample<T> PiecewiseDistanceCurve<T>::sample(T t) const noexcept {
  const T lo = t_.front(), hi = t_.back();
  if (!(t >= lo)) t = lo;  // also NaN
  if (t > hi) t = hi;
  if (!(hi > lo)) return {seg_.front()[0], T(0), T(0)};
  std::size_t i = std::size_t(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin());
  i = std::clamp<std::size_t>(i, 1, seg_.size()) - 1;
  const T h = t_[i + 1] - t_[i];
  const T x = std::clamp((t - t_[i]) / h, T(0), T(1));
  const auto [s, d, a] = eval<T>(seg_[i], x);
  return {s, d / h, a / (h * h)};
}

template <Real T>
std::optional<BackingUp<T>> PiecewiseDistanceCurve<T>::find_backing_up() const noexcept {
  if (!(t_.back() > t_.front())) return std::nullopt;
  for (std::size_t i = 0; i < seg_.size(); ++i) {
    const Coefficients& c = seg_[i];
    // Speed scale per τ: the larger of the end speeds and the mean speed over the interval.
    const auto e0 = eval<T>(c, T(0)), e1 = eval<T>(c, T(1));
    const T scale = std::max({std::abs(e0[1]), std::abs(e1[1]), std::abs(e1[0] - e0[0]),
                              std::numeric_limits<T>::min()});
    const T tol = backwards_tolerance<T>() * scale;
    T where{};
    if (!dips(speed_bernstein<T>(c), tol, T(0), T(1), kSubdivisionDepth, where)) continue;
    const T h = t_[i + 1] - t_[i];
    BackingUp<T> out;
    out.segment = int(i);
    bool seen = false;
    T min_d = eval<T>(c, where)[1], min_x = where;
    for (int j = 0; j <= kBackingUpSamples; ++j) {
      const T x = T(j) / T(kBackingUpSamples);
      const T d = eval<T>(c, x)[1];
      if (d < min_d) { min_d = d; min_x = x; }
      if (d < -tol) {
        if (!seen) out.t_begin = t_[i] + h * x;
        out.t_end = t_[i] + h * x;
        seen = true;
      }
    }
    if (!seen) out.t_begin = out.t_end = t_[i] + h * where;
    out.t_min_velocity = t_[i] + h * min_x;
    out.min_velocity = min_d / h;
    return out;
  }
  return std::nullopt;
}

template class PiecewiseDistanceCurve<float>;
template class PiecewiseDistanceCurve<double>;

}  // namespace inbetween
