// FCurveClip's fitting: one F-curve cut into degree-9 polynomial pieces that reproduce
// FCurve::sample within the clip's tolerance, Blender's snap bands around keys included
// (fcurve_clip_internal.hpp).
#include "fcurve_clip_internal.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "fcurve_internal.hpp"

namespace inbetween::fcurve_clip_detail {
namespace {

// Blender's snap band at a piece's lo as a frame threshold: the largest float t with
// t − lo ≤ band in float (t − lo is monotone in t, so the band is exactly the frames t ≤ it);
// −∞ for no band (band < 0: no t ≥ lo has t − lo ≤ band).
float band_threshold_lo(float lo, float band) {
  if (band < 0 || !std::isfinite(lo)) return -kInf;
  float t = float(double(lo) + double(band));
  while (t - lo > band) t = std::nextafter(t, -kInf);
  while (std::nextafter(t, kInf) - lo <= band) t = std::nextafter(t, kInf);
  return t;
}
// At hi: the smallest float t with hi − t ≤ band (+∞ for no band).
float band_threshold_hi(float hi, float band) {
  if (band < 0 || !std::isfinite(hi)) return kInf;
  float t = float(double(hi) - double(band));
  while (hi - t > band) t = std::nextafter(t, kInf);
  while (hi - std::nextafter(t, -kInf) <= band) t = std::nextafter(t, -kInf);
  return t;
}

// Pushes a block: lo, hi, origin, inv_length, the band thresholds at lo and hi, c0 … cD.
void push_piece(std::vector<float>& data, float lo, float hi, float origin, float inv_length, float band_lo,
                float band_hi, const std::array<float, D + 1>& c) {
  data.insert(data.end(), {lo, hi, origin, inv_length, band_threshold_lo(lo, band_lo), band_threshold_hi(hi, band_hi)});
  data.insert(data.end(), c.begin(), c.end());
}

// Blender's snap band: near_frame(t, x) ⇔ |t − x| ≤ 1e-4 in float (src/tracks/fcurve_eval.cpp).
bool near_key(float t, float x) { return t > x ? (t - x) <= kBand : (x - t) <= kBand; }

struct Fitter {
  const FCurve& curve;
  float tol_abs, scale;
  std::vector<float>& data;
  float worst = 0;  // relative to scale

  // The degree-D polynomial in u ∈ [−1, 1] over [a, b] through the curve's values at the
  // Chebyshev–Lobatto nodes u = −cos(πk/D) (endpoints included: the keys' values where the piece
  // meets a key), in power form; its worst float error at 96 frames of the piece and at the first
  // and last frames outside the snap bands, evaluated as the runtime does (piece_value).
  // Each node's u is the one the sampler computes for its float frame, (x − origin)·inv_length,
  // so the polynomial interpolates the curve at the parameters the runtime evaluates.
  float fit(float a, float b, float band_lo, float band_hi, std::array<float, 6 + D + 1>& blk) const {
    const double h = double(b) - double(a);
    const float origin = float(0.5 * (double(a) + double(b)));
    const float inv = float(2.0 / h);
    double u[D + 1], y[D + 1];
    bool distinct = true;
    for (std::size_t k = 0; k <= D; ++k) {
      const double node = -std::cos(std::numbers::pi * double(k) / double(D));
      const float x = k == 0 ? a : (k == D ? b : float(0.5 * (double(a) + double(b)) + 0.5 * h * node));
      u[k] = k == 0 ? -1.0 : (k == D ? 1.0 : double((x - origin) * inv));
      y[k] = double(curve.sample(x));
      if (k > 0 && !(u[k] > u[k - 1])) distinct = false;
    }
    double c[D + 1] = {};
    float org = origin, iv = inv;
    std::size_t m = D + 1;  // interpolation points in u[], y[]
    if (!distinct) {
      // A piece a few frame ulps wide: u = (frame − a)/length (0 at its first frame, ul at its
      // last), through those two frames' values and, for a piece with a band, the key's value at
      // u = ∓1, where the band clamps u (the polynomial only matters at these points).
      org = a;
      iv = float(1.0 / h);
      const float last = std::nextafter(b, a);
      const double ul = double((last - a) * iv);
      const double ya = double(curve.sample(a)), yb = double(curve.sample(b));
      m = 0;
      if (band_lo >= 0) u[m] = -1, y[m] = ya, ++m;
      u[m] = 0, y[m] = ya, ++m;
      if (ul > 0 && ul < 1) u[m] = ul, y[m] = double(curve.sample(last)), ++m;
      if (band_hi >= 0) u[m] = 1, y[m] = yb, ++m;
    }
    // Newton divided differences, then the power form in u (Horner on the Newton form).
    double d[D + 1];
    for (std::size_t k = 0; k < m; ++k) d[k] = y[k];
    for (std::size_t j = 1; j < m; ++j)
      for (std::size_t k = m - 1; k >= j; --k) d[k] = (d[k] - d[k - 1]) / (u[k] - u[k - j]);
    c[0] = d[m - 1];
    for (std::size_t k = m - 1; k-- > 0;) {
      // c ← c·(u − u_k) + d_k
      for (std::size_t q = D; q > 0; --q) c[q] = c[q - 1] - u[k] * c[q];
      c[0] = -u[k] * c[0] + d[k];
    }
    blk = {a, b, org, iv, band_threshold_lo(a, band_lo), band_threshold_hi(b, band_hi)};
    for (std::size_t k = 0; k <= D; ++k) blk[6 + k] = float(c[k]);
    float err = 0;
    const auto check = [&](float x) {
      if (x >= a && x < b) err = std::max(err, std::abs(piece_value(blk.data(), x) - curve.sample(x)));
    };
    for (int i = 0; i < 96; ++i) check(float(double(a) + h * (double(i) + 0.5) / 96.0));
    check(a);
    check(std::nextafter(b, a));
    if (band_lo >= 0) check(std::nextafter(float(double(a) + 1e-4), b)), check(float(double(a) + 1e-4));
    if (band_hi >= 0) check(std::nextafter(float(double(b) - 1e-4), a)), check(float(double(b) - 1e-4));
    return err;
  }

  // Pieces for [a, b), halving until each passes or the budget is spent; the bands stay on the
  // outer ends.
  void pieces(float a, float b, float band_lo, float band_hi, int& left) {
    std::array<float, 6 + D + 1> blk{};
    const float err = fit(a, b, band_lo, band_hi, blk);
    const float mid = float(0.5 * (double(a) + double(b)));
    if (err > tol_abs && left > 1 && mid > a && mid < b) {
      --left;
      pieces(a, mid, band_lo, kNoBand, left);
      pieces(mid, b, kNoBand, band_hi, left);
      return;
    }
    worst = std::max(worst, err / scale);
    data.insert(data.end(), blk.begin(), blk.end());
  }

  void constant(float lo, float hi, float y) {
    std::array<float, D + 1> c{};
    c[0] = y;
    push_piece(data, lo, hi, 0, 0, kNoBand, kNoBand, c);
  }
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

}  // namespace

// Appends the pieces of one curve (its keyed range and the two extrapolation lines) to `data`.
void compile_curve(const FCurve& curve, const FCurveClipOptions& options, std::vector<float>& data, float& worst) {
  const auto keys = curve.keys();
  const std::size_t n = keys.size();
  float lo = keys[0].y, hi = keys[0].y, big = std::abs(keys[0].y);
  for (const auto& k : keys) {
    for (const float v : {k.y, k.left.y, k.right.y}) lo = std::min(lo, v), hi = std::max(hi, v), big = std::max(big, std::abs(v));
  }
  float scale = hi - lo;
  scale = std::max(scale, 8.0f * std::numeric_limits<float>::epsilon() * big / options.tolerance);
  if (!(scale > 0)) scale = 1;
  Fitter fitter{curve, options.tolerance * scale, scale, data};
  // Before the first key: the line through it with the extrapolation slope.
  const float x0 = keys[0].x, xn = keys[n - 1].x;
  const float slope_before = extrapolation_slope(curve, true), slope_after = extrapolation_slope(curve, false);
  std::array<float, D + 1> line{};
  line[0] = keys[0].y, line[1] = slope_before;
  push_piece(data, -kInf, x0, x0, 1.0f, kNoBand, kNoBand, line);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const float a = keys[i].x, b = keys[i + 1].x;
    if (keys[i].interpolation == Interpolation::constant) {
      // Key a's value, and key b's within Blender's band before b: y_a + (y_b − y_a)·(u + u²)/2 at
      // u = 0 (inv_length 0), u = +1 in the band at b (a few float ulps from y_b), −1 in a's.
      if (double(b) - double(a) >= 1e-3) {
        const float d = keys[i + 1].y - keys[i].y;
        std::array<float, D + 1> c{};
        c[0] = keys[i].y, c[1] = 0.5f * d, c[2] = 0.5f * d;
        push_piece(data, a, b, 0, 0, kBand, kBand, c);
      } else {
        const float a1 = band_end(a, b), b1 = band_start(b, a1);
        fitter.constant(a, a1, keys[i].y);
        if (a1 < b1) fitter.constant(a1, b1, keys[i].y);
        if (b1 < b) fitter.constant(b1, b, keys[i + 1].y);
      }
      continue;
    }
    // Blender answers the key's own value within 1e-4 frames of a key: on a segment longer than a
    // millisecond-frame the piece's band widths say so (the runtime clamps u to ∓1 there, where the
    // polynomial interpolates the keys); shorter segments get constant band pieces.
    int left = options.max_pieces_per_segment;
    if (double(b) - double(a) >= 1e-3) {
      fitter.pieces(a, b, kBand, kBand, left);
      continue;
    }
    const float a1 = band_end(a, b), b1 = band_start(b, a1);
    if (a1 < b1) {
      fitter.constant(a, a1, keys[i].y);
      fitter.pieces(a1, b1, kNoBand, kNoBand, left);
      fitter.constant(b1, b, keys[i + 1].y);
    } else {
      fitter.pieces(a, b, kNoBand, kNoBand, left);
    }
  }
  line[0] = keys[n - 1].y, line[1] = slope_after;
  push_piece(data, xn, kInf, xn, 1.0f, kNoBand, kNoBand, line);
  worst = std::max(worst, fitter.worst);
}

// A curve whose Cycles modifier changes some frame: ≥ 2 keys (a period) and a side that cycles.
bool cycles_frames(const FCurve& curve) {
  const FCurveCycles* cy = curve.simple_cycles();
  return cy != nullptr && curve.keys().size() >= 2 && (cy->before != CycleMode::none || cy->after != CycleMode::none);
}

}  // namespace inbetween::fcurve_clip_detail
