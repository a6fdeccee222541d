// FCurveClip: Blender F-curves pre-solved into cubic pieces (include/inbetween/tracks/runtime/fcurve_clip.hpp).
#include "inbetween/tracks/runtime/fcurve_clip.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <cstdio>
#include <cstdlib>

namespace inbetween {
namespace {

constexpr std::size_t B = FCurveClip::block;
constexpr float kInf = std::numeric_limits<float>::infinity();

void push_piece(std::vector<float>& data, float lo, float hi, float origin, float inv_length,
                const std::array<float, 4>& c) {
  data.insert(data.end(), {lo, hi, origin, inv_length, c[0], c[1], c[2], c[3]});
}

// The runtime's evaluation of a piece at `frame`, in float, as sample_fcurves does it.
float piece_value(float frame, float origin, float inv_length, const std::array<float, 4>& c) {
  const float u = (frame - origin) * inv_length;
  return ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
}

// Blender's snap band: near_frame(t, x) ⇔ |t − x| ≤ 1e-4 in float (src/tracks/fcurve_eval.cpp).
bool near_key(float t, float x) { return t > x ? (t - x) <= 0.0001f : (x - t) <= 0.0001f; }

struct Fitter {
  const FCurve& curve;
  float tol_abs, scale;
  int budget;
  std::vector<float>& data;
  float worst = 0;  // relative to scale

  // The cubic through the curve's values at u = 0, ¼, ¾, 1 of [a, b] (Chebyshev–Lobatto nodes of
  // degree 3), in power form; its worst float error at 28 frames of the piece.
  float fit(float a, float b, std::array<float, 4>& c, float& inv_length) const {
    const double h = double(b) - double(a);
    inv_length = float(1.0 / h);
    // Nodes at u ≈ 0, ¼, ¾, 1 rounded to float frames; each node's u is the one the sampler will
    // compute for that frame, (x − a)·inv_length in float, so the cubic interpolates the curve at
    // the parameters the runtime evaluates (a node's frame rounding would otherwise cost up to half
    // a frame ulp times the slope).  The last node is the last float frame before b.
    const double un[4] = {0, 0.25, 0.75, 1};
    double u[4], y[4];
    for (int i = 0; i < 4; ++i) {
      const float x = i == 0 ? a : (i == 3 ? std::nextafter(b, a) : float(double(a) + un[i] * h));
      u[i] = double((x - a) * inv_length);
      y[i] = double(curve.sample(x));
    }
    if (!(u[0] < u[1] && u[1] < u[2] && u[2] < u[3])) {
      // A piece a few frame ulps wide: the line through its end values (constant if one frame).
      const double slope = u[3] > u[0] ? (y[3] - y[0]) / (u[3] - u[0]) : 0.0;
      c = {float(y[0]), float(slope), 0.0f, 0.0f};
    } else {
    // Newton divided differences, then the power form in u.
    const double d1 = (y[1] - y[0]) / (u[1] - u[0]), d1b = (y[2] - y[1]) / (u[2] - u[1]),
                 d1c = (y[3] - y[2]) / (u[3] - u[2]);
    const double d2 = (d1b - d1) / (u[2] - u[0]), d2b = (d1c - d1b) / (u[3] - u[1]);
    const double d3 = (d2b - d2) / (u[3] - u[0]);
    // p(u) = y0 + d1·(u − u0) + d2·(u − u0)(u − u1) + d3·(u − u0)(u − u1)(u − u2), u0 = 0.
    const double s1 = u[1] + u[2], p1 = u[1] * u[2];
    const double c0 = y[0] - d1 * u[0];
    const double c1 = d1 - d2 * u[1] + d3 * p1;
    const double c2 = d2 - d3 * s1;
    const double c3 = d3;
    c = {float(c0), float(c1), float(c2), float(c3)};
    }
    float err = 0;
    for (int i = 0; i < 28; ++i) {
      const float x = float(double(a) + h * (double(i) + 0.5) / 28.0);
      if (!(x >= a && x < b)) continue;
      err = std::max(err, std::abs(piece_value(x, a, inv_length, c) - curve.sample(x)));
    }
    err = std::max(err, std::abs(piece_value(a, a, inv_length, c) - curve.sample(a)));
    return err;
  }

  // Pieces for [a, b), halving until each passes or the budget is spent.
  void pieces(float a, float b, int& left) {
    std::array<float, 4> c{};
    float inv = 0;
    const float err = fit(a, b, c, inv);
    const float mid = float(0.5 * (double(a) + double(b)));
    if (err > tol_abs && left > 1 && mid > a && mid < b) {
      --left;
      pieces(a, mid, left);
      pieces(mid, b, left);
      return;
    }
    worst = std::max(worst, err / scale);
    push_piece(data, a, b, a, inv, c);
  }

  void constant(float lo, float hi, float y) { push_piece(data, lo, hi, 0, 0, {y, 0, 0, 0}); }
};

// First float t > x (t ≤ limit) that is outside key x's snap band.
float band_end(float x, float limit) {
  float t = std::min(float(double(x) + 1e-4), limit);
  while (t > x && !near_key(t, x)) t = std::nextafter(t, x);  // step back into the band
  while (t < limit && near_key(t, x)) t = std::nextafter(t, limit);
  return t;
}
// First float t ≥ x − 1e-4 (t > limit) inside key x's snap band.
float band_start(float x, float limit) {
  float t = std::max(float(double(x) - 1e-4), limit);
  while (t < x && near_key(t, x)) t = std::nextafter(t, limit);
  while (t < x && !near_key(t, x)) t = std::nextafter(t, x);
  return t;
}

// FCurve::extrapolate's slope in its float operations (src/tracks/fcurve_eval.cpp), so that the
// end piece c0 + c1·(t − x) gives its bits: e.y − fac·(x − t).
float extrapolation_slope(const FCurve& curve, bool before) {
  const auto keys = curve.keys();
  const std::size_t n = keys.size();
  const auto& e = before ? keys.front() : keys.back();
  if (e.interpolation == Interpolation::constant || curve.extrapolation() == Extrapolation::constant) return 0.0f;
  if (e.interpolation == Interpolation::linear) {
    if (n == 1) return 0.0f;
    const auto& nb = before ? keys[1] : keys[n - 2];
    const float fac = nb.x - e.x;
    return fac == 0.0f ? 0.0f : (nb.y - e.y) / fac;
  }
  const Vec2f& h = before ? e.left : e.right;
  const float fac = e.x - h.x;
  return fac == 0.0f ? 0.0f : (e.y - h.y) / fac;
}

Expected<bool> compile_curve(const FCurve& curve, std::size_t index, const FCurveClipOptions& options,
                             std::vector<float>& data, float& worst) {
  if (curve.cycles()) {
    return Error{ErrorCode::Unsupported,
                 "the runtime does not cycle F-curves (a Cycles modifier): sample this curve with FCurve::sample",
                 "", {"curves", index}};
  }
  const auto keys = curve.keys();
  const std::size_t n = keys.size();
  float lo = keys[0].y, hi = keys[0].y, big = std::abs(keys[0].y);
  for (const auto& k : keys) {
    for (const float v : {k.y, k.left.y, k.right.y}) lo = std::min(lo, v), hi = std::max(hi, v), big = std::max(big, std::abs(v));
  }
  float scale = hi - lo;
  scale = std::max(scale, 8.0f * std::numeric_limits<float>::epsilon() * big / options.tolerance);
  if (!(scale > 0)) scale = 1;
  Fitter fitter{curve, options.tolerance * scale, scale, options.max_pieces_per_segment, data};
  // Before the first key: the line through it with the extrapolation slope.
  const float x0 = keys[0].x, xn = keys[n - 1].x;
  const float slope_before = extrapolation_slope(curve, true), slope_after = extrapolation_slope(curve, false);
  push_piece(data, -kInf, x0, x0, 1.0f, {keys[0].y, slope_before, 0, 0});
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const float a = keys[i].x, b = keys[i + 1].x;
    if (keys[i].interpolation == Interpolation::constant) {
      fitter.constant(a, b, keys[i].y);
      continue;
    }
    // Blender answers the key's own value within 1e-4 frames of a key: constant pieces there.
    const float a1 = band_end(a, b), b1 = band_start(b, a1);
    int left = options.max_pieces_per_segment;
    if (a1 < b1) {
      fitter.constant(a, a1, keys[i].y);
      fitter.pieces(a1, b1, left);
      fitter.constant(b1, b, keys[i + 1].y);
    } else {
      fitter.pieces(a, b, left);
    }
  }
  push_piece(data, xn, kInf, xn, 1.0f, {keys[n - 1].y, slope_after, 0, 0});
  worst = std::max(worst, fitter.worst);
  return true;
}

}  // namespace

Expected<FCurveClip> build_fcurve_clip(std::span<const FCurve> curves, FCurveClipOptions options) {
  FCurveClip clip;
  clip.channels_ = curves.size();
  auto& ch = clip.data_;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    ch.begin.push_back(std::uint32_t(ch.data.size() / B));
    if (auto r = compile_curve(curves[c], c, options, ch.data, clip.max_fit_error_); !r) return r.error();
    ch.count.push_back(std::uint32_t(ch.data.size() / B - ch.begin.back()));
  }
  rig_detail::finish_stream<float, B>(ch);
  return clip;
}

Expected<FCurveClip> build_fcurve_rig(std::span<const FCurve> curves, FCurveClipOptions options) {
  if (curves.size() % 10 != 0) {
    return Error{ErrorCode::InvalidArgument,
                 "a rig needs 10 F-curves per joint (location xyz, rotation_quaternion wxyz, scale xyz); got " +
                     std::to_string(curves.size()),
                 ""};
  }
  const std::size_t J = curves.size() / 10;
  FCurveClip clip;
  clip.channels_ = curves.size();
  clip.joints_ = J;
  auto& ch = clip.data_;
  // Internal channel k·J + j is curve 10·j + k: one component of every joint side by side.
  for (std::size_t k = 0; k < 10; ++k) {
    for (std::size_t j = 0; j < J; ++j) {
      const std::size_t c = 10 * j + k;
      ch.begin.push_back(std::uint32_t(ch.data.size() / B));
      if (auto r = compile_curve(curves[c], c, options, ch.data, clip.max_fit_error_); !r) return r.error();
      ch.count.push_back(std::uint32_t(ch.data.size() / B - ch.begin.back()));
    }
  }
  rig_detail::finish_stream<float, B>(ch);
  return clip;
}

FCurveClip::Context make_fcurve_context(const FCurveClip& clip) {
  FCurveClip::Context ctx;
  ctx.stride = (clip.channels() + 15) / 16 * 16;
  ctx.segment.assign(clip.channels(), 0);
  ctx.cache.assign(B * ctx.stride, 0.0f);
  ctx.values.assign(ctx.stride, 0.0f);
  return ctx;
}

void evaluate_channels(const FCurveClip& clip, float frame, FCurveClip::Context& context) noexcept {
  namespace stdx = rig_detail::stdx;
  using V = stdx::native_simd<float>;
  constexpr std::size_t W = V::size();
  const std::size_t C = clip.channels_;
  INBETWEEN_ASSERT(context.segment.size() == C && context.cache.size() == B * context.stride);
  if (std::isnan(frame)) {
    // As FCurve::sample: the first key's value, c0 of each channel's second piece (it starts at
    // the first key: its snap band, a constant segment, a fitted piece whose first node is the
    // key — Blender snaps there — or, for one key, the held end).  Cache and stream are untouched.
    for (std::size_t i = 0; i < C; ++i)
      context.values[i] = clip.data_.data[std::size_t(clip.data_.where[clip.data_.begin[i] + 1]) * B + 4];
    return;
  }
  const float big = std::numeric_limits<float>::max();
  frame = frame > -big ? (frame < big ? frame : big) : -big;
  rig_detail::advance<float, W, B>(clip.data_, C, frame, context.time, context.next, context.segment.data(),
                                   context.cache.data());
  context.time = frame;
  const V f(frame);
  const float* cache = context.cache.data();
  float* values = context.values.data();
  for (std::size_t c0 = 0; c0 < C; c0 += W) {
    const float* g = cache + c0 * B;  // this group's fields: field k at g + k·W
    const auto ld = [g](std::size_t k) noexcept { return rig_detail::load<V>(g + k * W); };
    const V u = (f - ld(2)) * ld(3);
    const V v = ((ld(7) * u + ld(6)) * u + ld(5)) * u + ld(4);
    v.copy_to(values + c0, stdx::element_aligned);
  }
}

void sample_fcurves(const FCurveClip& clip, float frame, FCurveClip::Context& context, std::span<float> out) noexcept {
  INBETWEEN_ASSERT(out.size() == clip.channels_);
  evaluate_channels(clip, frame, context);
  const std::size_t J = clip.joints_;
  if (J == 0) {
    std::copy_n(context.values.begin(), clip.channels_, out.begin());
    return;
  }
  for (std::size_t j = 0; j < J; ++j)
    for (std::size_t k = 0; k < 10; ++k) out[10 * j + k] = context.values[k * J + j];
}

void sample_fcurve_rig(const FCurveClip& clip, float frame, FCurveClip::Context& context,
                       std::span<JointPose<float>> out) noexcept {
  const std::size_t J = clip.joints_;
  INBETWEEN_ASSERT(out.size() == J);
  evaluate_channels(clip, frame, context);
  const float* v = context.values.data();
  for (std::size_t j = 0; j < J; ++j) {
    JointPose<float>& p = out[j];
    p.translation = Vec3f{v[j], v[J + j], v[2 * J + j]};
    const float w = v[3 * J + j], x = v[4 * J + j], y = v[5 * J + j], z = v[6 * J + j];
    const float n2 = w * w + x * x + y * y + z * z;
    if (n2 > 0) {
      const float inv = 1.0f / std::sqrt(n2);
      p.rotation = Quatf::from_wxyz(w * inv, x * inv, y * inv, z * inv);
    } else {
      p.rotation = Quatf{};
    }
    p.scale = Vec3f{v[7 * J + j], v[8 * J + j], v[9 * J + j]};
  }
}

}  // namespace inbetween
