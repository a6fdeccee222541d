#include "inbetween/tracks/tangent_convert.hpp"

#include <algorithm>
#include <cmath>

namespace inbetween {

BezierSegment corrected(const BezierSegment& seg) noexcept {
  BezierSegment s = seg;
  s.h0.x = std::max(s.h0.x, s.p0.x);
  s.h1.x = std::min(s.h1.x, s.p1.x);
  // Blender 3.4's BKE_fcurve_correct_bezpart: each handle longer than the interval is scaled
  // back to the interval's length (fcurve.cpp reproduces the same).
  const double len = s.p1.x - s.p0.x;
  const double len0 = s.h0.x - s.p0.x, len1 = s.p1.x - s.h1.x;
  if (len0 > len) s.h0 = s.p0 + (s.h0 - s.p0) * (len / len0);
  if (len1 > len) s.h1 = s.p1 - (s.p1 - s.h1) * (len / len1);
  return s;
}

HermiteSegment bezier_to_hermite(const BezierSegment& seg) noexcept {
  const BezierSegment s = corrected(seg);
  HermiteSegment out{s.p0.x, s.p1.x, s.p0.y, s.p1.y, 0, 0};
  const double chord = (s.p1.y - s.p0.y) / (s.p1.x - s.p0.x);
  const double dx0 = s.h0.x - s.p0.x, dx1 = s.p1.x - s.h1.x;
  out.out_slope = dx0 > 0 ? (s.h0.y - s.p0.y) / dx0 : chord;
  out.in_slope = dx1 > 0 ? (s.p1.y - s.h1.y) / dx1 : chord;
  if (!std::isfinite(out.out_slope)) out.out_slope = chord;
  if (!std::isfinite(out.in_slope)) out.in_slope = chord;
  return out;
}

BezierSegment hermite_to_bezier(const HermiteSegment& seg) noexcept {
  const double third = (seg.frame1 - seg.frame0) / 3.0;
  BezierSegment s;
  s.p0 = Vec2d{seg.frame0, seg.value0};
  s.p1 = Vec2d{seg.frame1, seg.value1};
  s.h0 = Vec2d{seg.frame0 + third, seg.value0 + seg.out_slope * third};
  s.h1 = Vec2d{seg.frame1 - third, seg.value1 - seg.in_slope * third};
  return s;
}

bool handles_at_thirds(const BezierSegment& seg, double relative_tolerance) noexcept {
  const BezierSegment s = corrected(seg);
  const double h = s.p1.x - s.p0.x;
  return std::abs(s.h0.x - s.p0.x - h / 3) <= relative_tolerance * h &&
         std::abs(s.p1.x - s.h1.x - h / 3) <= relative_tolerance * h;
}

double hermite_value(const HermiteSegment& seg, double frame) noexcept {
  const double h = seg.frame1 - seg.frame0;
  const double u = std::clamp((frame - seg.frame0) / h, 0.0, 1.0);
  const double u2 = u * u, u3 = u2 * u;
  return seg.value0 * (2 * u3 - 3 * u2 + 1) + seg.out_slope * h * (u3 - 2 * u2 + u) +
         seg.value1 * (-2 * u3 + 3 * u2) + seg.in_slope * h * (u3 - u2);
}

namespace {
double bernstein(double a, double b, double c, double d, double u) noexcept {
  const double v = 1 - u;
  return a * v * v * v + 3 * b * u * v * v + 3 * c * u * u * v + d * u * u * u;
}
}  // namespace

double bezier_value(const BezierSegment& seg, double frame) noexcept {
  const BezierSegment s = corrected(seg);
  if (!(frame > s.p0.x)) return s.p0.y;
  if (!(frame < s.p1.x)) return s.p1.y;
  // x(u) − frame is negative at u = 0 and positive at u = 1; when the handles together are longer
  // than the interval x(u) may turn back, and the first root is taken: scan 64 steps for the
  // first sign change, then bisect to double precision.
  auto fx = [&](double u) { return bernstein(s.p0.x, s.h0.x, s.h1.x, s.p1.x, u) - frame; };
  double lo = 0, hi = 1;
  for (int i = 1; i <= 64; ++i) {
    const double u = double(i) / 64;
    if (fx(u) >= 0) {
      lo = double(i - 1) / 64;
      hi = u;
      break;
    }
  }
  for (int it = 0; it < 80 && hi - lo > 1e-17; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (fx(mid) < 0) lo = mid;
    else hi = mid;
  }
  const double u = 0.5 * (lo + hi);
  return bernstein(s.p0.y, s.h0.y, s.h1.y, s.p1.y, u);
}

ConversionLoss bezier_hermite_loss(const BezierSegment& seg, int samples) noexcept {
  samples = std::max(samples, 2);
  const HermiteSegment h = bezier_to_hermite(seg);
  ConversionLoss loss;
  for (int i = 0; i <= samples; ++i) {
    const double f = seg.p0.x + (seg.p1.x - seg.p0.x) * double(i) / double(samples);
    const double e = std::abs(bezier_value(seg, f) - hermite_value(h, f));
    if (e > loss.max_error) loss = {e, f};
  }
  return loss;
}

}  // namespace inbetween
