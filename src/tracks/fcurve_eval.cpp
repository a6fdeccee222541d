// F-curve evaluation: the Bézier root finder, segment values and extrapolation as Blender 3.4
// evaluates them (in float, in its order of operations), the sequential-playback cursor, and the
// analytic derivative (ours, in double).
#include "inbetween/tracks/fcurve.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "inbetween/math/assert.hpp"

namespace inbetween {

namespace {

using Key = FCurve::Key;

// ------------------------------------------------------------------ evaluation kernels
double cbrt_blender(double v) noexcept {
  if (v == 0.0) return 0.0;
  if (v < 0.0) return -std::exp(std::log(-v) / 3.0);
  return std::exp(std::log(v) / 3.0);
}

// Roots of c0 + c1 u + c2 u² + c3 u³ in the accepted range; returns the first one or nullopt.
std::optional<float> first_cubic_root(double c0, double c1, double c2, double c3) noexcept {
  const float lo = float(-1.0e-10);
  auto ok = [&](double r, float& out) {
    out = float(r);
    return out >= lo && out <= 1.000001f;
  };
  float o = 0;
  if (c3 != 0.0) {
    double a = c2 / c3;
    const double b = c1 / c3;
    const double c = c0 / c3;
    a = a / 3;
    double p = b / 3 - a * a;
    double q = (2 * a * a * a - a * b + c) / 2;
    const double d = q * q + p * p * p;
    if (d > 0.0) {
      const double t = std::sqrt(d);
      if (ok(cbrt_blender(-q + t) + cbrt_blender(-q - t) - a, o)) return o;
      return std::nullopt;
    }
    if (d == 0.0) {
      const double t = cbrt_blender(-q);
      if (ok(2 * t - a, o)) return o;
      if (ok(-t - a, o)) return o;
      return std::nullopt;
    }
    const double phi = std::acos(-q / std::sqrt(-(p * p * p)));
    const double t = std::sqrt(-p);
    p = std::cos(phi / 3);
    q = std::sqrt(3 - 3 * p * p);
    if (ok(2 * t * p - a, o)) return o;
    if (ok(-t * (p + q) - a, o)) return o;
    if (ok(-t * (p - q) - a, o)) return o;
    return std::nullopt;
  }
  const double a = c2, b = c1, c = c0;
  if (a != 0.0) {
    double p = b * b - 4 * a * c;
    if (p > 0) {
      p = std::sqrt(p);
      if (ok((-b - p) / (2 * a), o)) return o;
      if (ok((-b + p) / (2 * a), o)) return o;
      return std::nullopt;
    }
    if (p == 0 && ok(-b / (2 * a), o)) return o;
    return std::nullopt;
  }
  if (b != 0.0) {
    if (ok(-c / b, o)) return o;
    return std::nullopt;
  }
  if (c == 0.0) return 0.0f;
  return std::nullopt;
}

// Handles of a Bézier segment after sample()'s correction of handles longer than the segment.
std::pair<Vec2f, Vec2f> corrected_handles(const Key& ka, const Key& kb) noexcept {
  const Vec2f v1{ka.x, ka.y}, v4{kb.x, kb.y};
  Vec2f v2 = ka.right, v3 = kb.left;
  const Vec2f h1{v1.x - v2.x, v1.y - v2.y};
  const Vec2f h2{v4.x - v3.x, v4.y - v3.y};
  const float len = v4.x - v1.x;
  const float len1 = std::abs(h1.x);
  const float len2 = std::abs(h2.x);
  if (len1 + len2 != 0.0f) {
    if (len1 > len) {
      const float fac = len / len1;
      v2 = Vec2f{v1.x - fac * h1.x, v1.y - fac * h1.y};
    }
    if (len2 > len) {
      const float fac = len / len2;
      v3 = Vec2f{v4.x - fac * h2.x, v4.y - fac * h2.y};
    }
  }
  return {v2, v3};
}

float bezier_segment(const Key& ka, const Key& kb, float t) noexcept {
  const Vec2f v1{ka.x, ka.y}, v4{kb.x, kb.y};
  if (std::abs(v1.y - v4.y) < FLT_EPSILON && std::abs(ka.right.y - kb.left.y) < FLT_EPSILON &&
      std::abs(kb.left.y - v4.y) < FLT_EPSILON) {
    return v1.y;
  }
  // Handles longer than the segment would make time run backwards: shortened along their line.
  const auto [v2, v3] = corrected_handles(ka, kb);
  const double c0 = v1.x - t;
  const double c1 = 3.0f * (v2.x - v1.x);
  const double c2 = 3.0f * (v1.x - 2.0f * v2.x + v3.x);
  const double c3 = v4.x - v1.x + 3.0f * (v2.x - v3.x);
  const std::optional<float> root = first_cubic_root(c0, c1, c2, c3);
  if (!root) return 0.0f;
  const float u = *root;
  const float d0 = v1.y;
  const float d1 = 3.0f * (v2.y - v1.y);
  const float d2 = 3.0f * (v1.y - 2.0f * v2.y + v3.y);
  const float d3 = v4.y - v1.y + 3.0f * (v2.y - v3.y);
  return d0 + u * d1 + u * u * d2 + u * u * u * d3;
}

EasingCurve easing_curve(Interpolation i) noexcept {
  switch (i) {
    case Interpolation::back: return EasingCurve::back;
    case Interpolation::bounce: return EasingCurve::bounce;
    case Interpolation::circ: return EasingCurve::circ;
    case Interpolation::cubic: return EasingCurve::cubic;
    case Interpolation::elastic: return EasingCurve::elastic;
    case Interpolation::expo: return EasingCurve::expo;
    case Interpolation::quad: return EasingCurve::quad;
    case Interpolation::quart: return EasingCurve::quart;
    case Interpolation::quint: return EasingCurve::quint;
    default: return EasingCurve::sine;
  }
}

bool near_frame(float a, float b) noexcept {
  constexpr float threshold = 0.0001f;
  return a > b ? (a - b) <= threshold : (b - a) <= threshold;
}



// dy/dx of the Bézier segment at frame t (in double): x(u) = t is solved on [0, 1] by Newton steps
// kept inside a bisection bracket (x is monotone after the handle correction), then y′(u)/x′(u);
// where x′ vanishes (a zero-length handle at an end) the ratio of second derivatives, the limit.
// The segment's control points (handles corrected) in double and the Bézier parameter u with
// x(u) = t; `flat` when sample() returns the constant value there.
struct BezierAt {
  double x[4], y[4];
  double u = 0;
  bool flat = false;
};

double bezier_d1(const double* p, double u) noexcept {
  const double w = 1 - u;
  return 3 * (w * w * (p[1] - p[0]) + 2 * w * u * (p[2] - p[1]) + u * u * (p[3] - p[2]));
}
double bezier_d2(const double* p, double u) noexcept { return 6 * ((1 - u) * (p[2] - 2 * p[1] + p[0]) + u * (p[3] - 2 * p[2] + p[1])); }

BezierAt solve_bezier(const Key& ka, const Key& kb, double t) noexcept {
  BezierAt b;
  if (std::abs(ka.y - kb.y) < FLT_EPSILON && std::abs(ka.right.y - kb.left.y) < FLT_EPSILON &&
      std::abs(kb.left.y - kb.y) < FLT_EPSILON) {
    b.flat = true;  // sample() returns the constant value here
    return b;
  }
  const auto [v2, v3] = corrected_handles(ka, kb);
  const double xs[4] = {ka.x, v2.x, v3.x, kb.x}, ys[4] = {ka.y, v2.y, v3.y, kb.y};
  std::copy(xs, xs + 4, b.x);
  std::copy(ys, ys + 4, b.y);
  const double* x = b.x;
  const auto bez = [](const double* p, double u) {
    const double w = 1 - u;
    return w * w * w * p[0] + 3 * w * w * u * p[1] + 3 * w * u * u * p[2] + u * u * u * p[3];
  };
  double lo = 0, hi = 1;
  double u = x[3] > x[0] ? std::clamp((t - x[0]) / (x[3] - x[0]), 0.0, 1.0) : 0.0;
  for (int iter = 0; iter < 100; ++iter) {
    const double f = bez(x, u) - t;
    if (f == 0) break;
    if (f < 0) lo = u; else hi = u;
    const double dx = bezier_d1(x, u);
    double next = dx > 0 ? u - f / dx : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == u || hi - lo <= 4 * std::numeric_limits<double>::epsilon()) break;
    u = next;
  }
  b.u = u;
  return b;
}

// |x′(u)| below this fraction of the segment's frame span counts as zero (a zero-length handle at
// an end): the slope is then the limit y″/x″, the second derivative the documented fallback 0.
constexpr double kVerticalX = 1e-9;

double bezier_segment_slope(const Key& ka, const Key& kb, double t) noexcept {
  const BezierAt b = solve_bezier(ka, kb, t);
  if (b.flat) return 0.0;
  const double dx = bezier_d1(b.x, b.u), dy = bezier_d1(b.y, b.u);
  const double scale = std::max(std::abs(b.x[3] - b.x[0]), 1e-30);
  if (std::abs(dx) > kVerticalX * scale) return dy / dx;
  const double ddx = bezier_d2(b.x, b.u), ddy = bezier_d2(b.y, b.u);
  if (std::abs(ddx) > 0) return ddy / ddx;
  return 0.0;
}

// d²y/dx² of the Bézier segment at frame t: with x(u) = t solved as above,
// (y″x′ − y′x″) / x′³ (the derivative of y′/x′ with respect to u, divided by dx/du); 0 where x′
// vanishes (see kVerticalX).
double bezier_segment_second(const Key& ka, const Key& kb, double t) noexcept {
  const BezierAt b = solve_bezier(ka, kb, t);
  if (b.flat) return 0.0;
  const double dx = bezier_d1(b.x, b.u), dy = bezier_d1(b.y, b.u);
  const double scale = std::max(std::abs(b.x[3] - b.x[0]), 1e-30);
  if (!(std::abs(dx) > kVerticalX * scale)) return 0.0;
  const double ddx = bezier_d2(b.x, b.u), ddy = bezier_d2(b.y, b.u);
  return (ddy * dx - dy * ddx) / (dx * dx * dx);
}

// The easing direction of a Penner segment: the key's own, or the curve's automatic one (as
// Blender's BEZT_IPO_EASE_AUTO).
EasingDirection easing_direction(const Key& ka, EasingCurve curve) noexcept {
  switch (ka.easing) {
    case KeyEasing::ease_in: return EasingDirection::in;
    case KeyEasing::ease_out: return EasingDirection::out;
    case KeyEasing::ease_in_out: return EasingDirection::in_out;
    case KeyEasing::automatic: break;
  }
  return automatic_direction(curve);
}

}  // namespace

// ------------------------------------------------------------------ FCurve evaluation
float FCurve::extrapolate(float t, bool before) const noexcept {
  const int n = int(keys_.size());
  const Key& e = before ? keys_.front() : keys_.back();
  if (e.interpolation == Interpolation::constant || extrapolation_ == Extrapolation::constant) return e.y;
  if (e.interpolation == Interpolation::linear) {
    if (n == 1) return e.y;
    const Key& nb = before ? keys_[1] : keys_[n - 2];
    const float dx = e.x - t;
    float fac = nb.x - e.x;
    if (fac == 0.0f) return e.y;
    fac = (nb.y - e.y) / fac;
    return e.y - (fac * dx);
  }
  const Vec2f& h = before ? e.left : e.right;
  const float dx = e.x - t;
  float fac = e.x - h.x;
  if (fac == 0.0f) return e.y;
  fac = (e.y - h.y) / fac;
  return e.y - (fac * dx);
}

float FCurve::interpolate(float t, std::size_t* cursor) const noexcept {
  const int n = int(keys_.size());
  if (cursor != nullptr) {
    // Sequential playback: try the remembered segment and its successor.  The result equals the
    // binary search's whenever t is not within the snap distance of either end of its segment
    // (the search then visits no key that could snap, and ends on the same segment); near a key
    // the full search below decides, exactly as Blender does.
    std::size_t k = std::min(*cursor, std::size_t(n - 2));
    if (!(keys_[k].x <= t && t < keys_[k + 1].x) && k + 2 < std::size_t(n) && keys_[k + 1].x <= t &&
        t < keys_[k + 2].x) {
      ++k;
    }
    if (!(keys_[k].x <= t && t < keys_[k + 1].x)) {
      k = std::size_t(std::upper_bound(keys_.begin(), keys_.end(), t, [](float v, const Key& key) { return v < key.x; }) -
                      keys_.begin());
      k = std::min(k == 0 ? 0 : k - 1, std::size_t(n - 2));
    }
    *cursor = k;
    if (!near_frame(t, keys_[k].x) && !near_frame(t, keys_[k + 1].x)) return segment_value(int(k) + 1, t);
  }
  // Blender's binary search with its 1e-4 "same frame" threshold (a hit returns that key's value).
  int index = 0;
  {
    if (near_frame(t, keys_[0].x)) return keys_[0].y;
    if (t < keys_[0].x) {
      index = 0;
    } else if (near_frame(t, keys_[n - 1].x)) {
      return keys_[n - 1].y;
    } else if (t > keys_[n - 1].x) {
      index = n;
    } else {
      int start = 0, end = n;
      for (int loop = 0; start <= end && loop < 2 * n; ++loop) {
        const int mid = start + (end - start) / 2;
        const float midfra = keys_[mid].x;
        if (near_frame(t, midfra)) return keys_[mid].y;
        if (t > midfra) {
          start = mid + 1;
        } else if (t < midfra) {
          end = mid - 1;
        }
      }
      index = start;
    }
  }
  if (index >= n) index = n - 1;  // unreachable for t inside the keys; keeps the access in range
  return segment_value(index, t);
}

float FCurve::segment_value(int index, float t) const noexcept {
  const Key& kb = keys_[index];
  const Key& ka = index > 0 ? keys_[index - 1] : kb;
  if (std::abs(kb.x - t) < 1.e-8f) return kb.y;
  if (t < ka.x || kb.x < t) return 0.0f;

  const float begin = ka.y;
  const float change = kb.y - ka.y;
  const float duration = kb.x - ka.x;
  const float time = t - ka.x;
  if (ka.interpolation == Interpolation::constant || duration == 0) return ka.y;
  switch (ka.interpolation) {
    case Interpolation::bezier: return bezier_segment(ka, kb, t);
    case Interpolation::linear: return change * time / duration + begin;
    default: {
      const EasingCurve curve = easing_curve(ka.interpolation);
      const EasingDirection dir = easing_direction(ka, curve);
      const PennerParams<float> params{.back = ka.back, .amplitude = ka.amplitude, .period = ka.period};
      return penner_ease(curve, dir, time, begin, change, duration, params);
    }
  }
}

float FCurve::evaluate_keys(float t, std::size_t* cursor) const noexcept {
  if (t <= keys_.front().x) return extrapolate(t, true);
  if (keys_.back().x <= t) return extrapolate(t, false);
  return interpolate(t, cursor);
}

float FCurve::sample(float frame) const noexcept { return evaluate_impl(frame, nullptr); }

float FCurve::sample(float frame, TrackCursor& cursor) const noexcept {
  return evaluate_impl(frame, &cursor.segment);
}

float FCurve::evaluate_impl(float frame, std::size_t* cursor) const noexcept {
  if (keys_.empty()) return 0.0f;
  if (std::isnan(frame)) return keys_.front().y;
  if (!modifiers_.empty() && !simple_cycles_) {
    if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<float>::max(), frame);
    return evaluate_stack(frame, cursor);
  }
  const CycleMap m = map_cycles(frame);
  return evaluate_keys(m.t, cursor) + m.offset;
}

double FCurve::extrapolation_slope(bool before) const noexcept {
  const int n = int(keys_.size());
  const Key& e = before ? keys_.front() : keys_.back();
  if (e.interpolation == Interpolation::constant || extrapolation_ == Extrapolation::constant) return 0.0;
  if (e.interpolation == Interpolation::linear) {
    if (n == 1) return 0.0;
    const Key& nb = before ? keys_[1] : keys_[n - 2];
    const double fac = double(nb.x) - double(e.x);
    if (fac == 0.0) return 0.0;
    return (double(nb.y) - double(e.y)) / fac;
  }
  const Vec2f& h = before ? e.left : e.right;
  const double fac = double(e.x) - double(h.x);
  if (fac == 0.0) return 0.0;
  return (double(e.y) - double(h.y)) / fac;
}

double FCurve::segment_derivative(int index, double t) const noexcept {
  // Segment from key index to key index + 1 (the key on its left decides the interpolation).
  const Key& ka = keys_[index];
  const Key& kb = keys_[index + 1];
  const double duration = double(kb.x) - double(ka.x);
  if (ka.interpolation == Interpolation::constant || duration == 0) return 0.0;
  switch (ka.interpolation) {
    case Interpolation::bezier: return bezier_segment_slope(ka, kb, t);
    case Interpolation::linear: return (double(kb.y) - double(ka.y)) / duration;
    default: {
      const EasingCurve curve = easing_curve(ka.interpolation);
      const EasingDirection dir = easing_direction(ka, curve);
      const PennerParams<double> params{.back = ka.back, .amplitude = ka.amplitude, .period = ka.period};
      return penner_ease_velocity(curve, dir, t - double(ka.x), double(kb.y) - double(ka.y), duration, params);
    }
  }
}

double FCurve::segment_second_derivative(int index, double t) const noexcept {
  const Key& ka = keys_[index];
  const Key& kb = keys_[index + 1];
  const double duration = double(kb.x) - double(ka.x);
  if (ka.interpolation == Interpolation::constant || duration == 0) return 0.0;
  switch (ka.interpolation) {
    case Interpolation::bezier: return bezier_segment_second(ka, kb, t);
    case Interpolation::linear: return 0.0;
    default: {
      const EasingCurve curve = easing_curve(ka.interpolation);
      const EasingDirection dir = easing_direction(ka, curve);
      const PennerParams<double> params{.back = ka.back, .amplitude = ka.amplitude, .period = ka.period};
      return penner_ease_acceleration(curve, dir, t - double(ka.x), double(kb.y) - double(ka.y), duration, params);
    }
  }
}

double FCurve::second_derivative(float frame) const noexcept {
  if (keys_.empty() || std::isnan(frame)) return 0.0;
  if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<float>::max(), frame);
  if (!modifiers_.empty() && !simple_cycles_) {
    // A general stack: the central difference of the (analytic) derivative, documented in fcurve.hpp.
    constexpr float h = 1.0f / 256.0f;
    const float fp = frame + h, fm = frame - h;
    if (!(fp > fm)) return 0.0;
    const double out = (derivative(fp) - derivative(fm)) / (double(fp) - double(fm));
    return std::isfinite(out) ? out : 0.0;
  }
  const CycleMap m = map_cycles(frame);
  const float t = m.t;
  const int n = int(keys_.size());
  // Outside the keys the extrapolation is constant or linear: 0.  A mirrored copy (t = c − frame)
  // keeps the sign of the second derivative: (−1)² = 1.
  if (t < keys_.front().x || t > keys_.back().x || n < 2) return 0.0;
  auto it = std::upper_bound(keys_.begin(), keys_.end(), t, [](float v, const Key& key) { return v < key.x; });
  const int k = std::clamp(int(it - keys_.begin()) - 1, 0, n - 2);
  const double out = segment_second_derivative(k, double(t));
  return std::isfinite(out) ? out : 0.0;
}

double FCurve::derivative(float frame) const noexcept {
  if (keys_.empty() || std::isnan(frame)) return 0.0;
  if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<float>::max(), frame);
  if (!modifiers_.empty() && !simple_cycles_) return stack_derivative(frame);
  const CycleMap m = map_cycles(frame);
  const double out = double(m.sign) * keys_derivative(m.t);
  return std::isfinite(out) ? out : 0.0;
}

double FCurve::keys_derivative(float t) const noexcept {
  const int n = int(keys_.size());
  double slope = 0.0;
  if (t < keys_.front().x) {
    slope = extrapolation_slope(true);
  } else if (t > keys_.back().x) {
    slope = extrapolation_slope(false);
  } else if (n >= 2) {
    // The segment [k, k + 1] holding t; the last key belongs to the last segment.
    auto it = std::upper_bound(keys_.begin(), keys_.end(), t, [](float v, const Key& key) { return v < key.x; });
    int k = int(it - keys_.begin()) - 1;
    k = std::clamp(k, 0, n - 2);
    slope = segment_derivative(k, double(t));
  }
  return std::isfinite(slope) ? slope : 0.0;
}

void FCurve::sample(std::span<const float> frames, std::span<float> out, TrackCursor& cursor) const noexcept {
  INBETWEEN_ASSERT(frames.size() == out.size());
  for (std::size_t i = 0; i < frames.size(); ++i) out[i] = evaluate_impl(frames[i], &cursor.segment);
}

}  // namespace inbetween
