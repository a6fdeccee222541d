// FCurveClip: Blender F-curves pre-solved into degree-9 polynomial pieces (include/inbetween/tracks/runtime/fcurve_clip.hpp).
#include "inbetween/tracks/runtime/fcurve_clip.hpp"

#include "fcurve_internal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace inbetween {
namespace {

constexpr std::size_t B = FCurveClip::block;
constexpr float kInf = std::numeric_limits<float>::infinity();

constexpr std::size_t D = FCurveClip::degree;
constexpr float kBand = 0.0001f;  // Blender's snap band around a key, in frames
constexpr float kNoBand = -1.0f;  // a band width no |frame − key| ≤ it

// Fields of a piece the cache holds (the SIMD loop's): origin, inv_length, the two band
// thresholds, c0 … cD — the block without lo and hi, which only the stream and the searches read.
constexpr std::size_t CB = FCurveClip::cached_fields;
constexpr std::size_t kCachedFrom = B - CB;  // first cached field of a block

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

// The runtime's evaluation of a block at `frame`, in float, in the operations evaluate_channels
// does: u = (frame − origin)·inv_length, u = +1 inside the band at hi (frame ≥ its threshold),
// −1 inside the band at lo (frame ≤ its threshold; that one wins), then Horner.
float piece_value(const float* blk, float frame) {
  float u = (frame - blk[2]) * blk[3];
  if (frame >= blk[5]) u = 1.0f;
  if (frame <= blk[4]) u = -1.0f;
  float v = blk[6 + D];
  for (std::size_t k = D; k-- > 0;) v = v * u + blk[6 + k];
  return v;
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
  const auto& cy = curve.cycles();
  return cy && curve.keys().size() >= 2 && (cy->before != CycleMode::none || cy->after != CycleMode::none);
}

// ---- Runs (fcurve_clip.hpp, FCurveClip::Channels) -----------------------------------------------

constexpr std::size_t W = rig_detail::stdx::native_simd<float>::size();  // channels per SIMD group
static_assert(W <= 255, "a run's size and lane are bytes");
constexpr std::uint32_t kNoRun = FCurveClip::Context::no_run;

// Turns a stream sorted by rig_detail::finish_stream (B floats per piece, owners final) into
// bounds and runs: the pieces from p on with p's lo whose owners are p's owner + 1, + 2, … within
// its SIMD group form one run, its cached fields field-major (those of the run's piece i, field k,
// at data[p·CB + k·size + i]: for a run that fills a group, the cache's own group layout).
template <class Channels>
void finish_runs(Channels& ch) {
  const std::size_t n = ch.owner.size();
  ch.bounds.resize(2 * n);
  ch.run.assign(n, 1);
  ch.lane.assign(n, 0);
  std::vector<float> out(n * CB);
  for (std::size_t p = 0; p < n;) {
    const float lo = ch.data[p * B];
    const std::size_t c = ch.owner[p];
    std::size_t b = 1;
    while (p + b < n && (c + b) % W != 0 && ch.owner[p + b] == c + b && ch.data[(p + b) * B] == lo) ++b;
    for (std::size_t i = 0; i < b; ++i) {
      const float* blk = ch.data.data() + (p + i) * B;
      ch.bounds[2 * (p + i)] = blk[0];
      ch.bounds[2 * (p + i) + 1] = blk[1];
      ch.run[p + i] = std::uint8_t(b);
      ch.lane[p + i] = std::uint8_t(i);
      for (std::size_t k = 0; k < CB; ++k) out[p * CB + k * b + i] = blk[kCachedFrom + k];
    }
    p += b;
  }
  ch.data = std::move(out);
}

// Stream piece p as a block of B floats (lo, hi, then the cached fields), for piece_value.
template <class Channels>
void block_of(const Channels& ch, std::size_t p, float* blk) noexcept {
  const std::size_t i = ch.lane[p], b = ch.run[p];
  const float* src = ch.data.data() + (p - i) * CB + i;
  blk[0] = ch.bounds[2 * p];
  blk[1] = ch.bounds[2 * p + 1];
  for (std::size_t k = 0; k < CB; ++k) blk[kCachedFrom + k] = src[k * b];
}

// Copies stream piece p's cached fields into channel c's lane of the cache.
template <class Channels>
void put_piece(const Channels& ch, std::size_t p, float* cache, std::size_t c) noexcept {
  const std::size_t i = ch.lane[p], b = ch.run[p];
  const float* src = ch.data.data() + (p - i) * CB + i;
  float* dst = cache + (c / W) * CB * W + c % W;
  for (std::size_t k = 0; k < CB; ++k) dst[k * W] = src[k * b];
}

// Fetches the run whose first piece is stream piece d (its CB·W cached floats) ahead of its use.
inline void prefetch_run(const float* data, std::uint32_t d) noexcept {
  const char* run = reinterpret_cast<const char*>(data + std::size_t(d) * CB);
  for (std::size_t off = 0; off < CB * W * sizeof(float); off += 64) __builtin_prefetch(run + off);
  __builtin_prefetch(run + CB * W * sizeof(float) - 1);
}

// The first of the n stream pieces whose lo (bounds[2p]) is after t: where the stream resumes.
inline std::size_t first_piece_after(const float* bounds, std::size_t n, float t) noexcept {
  std::size_t lo = 0, hi = n;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (bounds[2 * mid] <= t) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// Whether a seek back to t is served by replaying the stream of n pieces over `channels` channels
// from its start: t lies before the piece a replay of at most 4 pieces per channel would stop at
// (every channel's first piece begins at −∞, so the replay leaves each channel's cached piece as
// the one holding t): a sequential read, where the per-channel search makes a few dependent reads
// each, scattered over the whole clip.  Same pieces and cursors either way.
inline bool replays_from_start(const float* bounds, std::size_t n, std::size_t channels, float t) noexcept {
  const std::size_t replay = std::min(n, 4 * channels);  // pieces a replay may consume
  return replay == n || bounds[2 * replay] > t;
}

// Group g reads the cache from now on: a run it read in place (main stream data) is copied there
// first (the same layout: one contiguous copy), so that a lane can be replaced.
inline void unshare(FCurveClip::Context& ctx, const float* data, std::size_t g) noexcept {
  std::uint32_t& d = ctx.direct[g];
  if (d == kNoRun) return;
  std::memcpy(ctx.cache.data() + g * CB * W, data + std::size_t(d) * CB, CB * W * sizeof(float));
  d = kNoRun;
}

// Copies the Nb lanes of a run's fields (field k at src + k·Nb) to dst + k·W.
template <std::size_t Nb>
inline void copy_lanes(const float* src, float* dst) noexcept {
  for (std::size_t k = 0; k < CB; ++k) std::memcpy(dst + k * W, src + k * Nb, Nb * sizeof(float));
}

// Hands the run starting at stream piece p over to its channels (their cursors and cache lanes;
// Main: the clip's main stream, where a run that fills its group is read in place instead);
// returns its size.
template <bool Main, class Channels>
std::size_t take_run(const Channels& ch, std::size_t p, FCurveClip::Context& ctx) noexcept {
  const std::size_t b = ch.run[p];
  const std::size_t c = ch.owner[p];
  for (std::size_t i = 0; i < b; ++i) ctx.segment[c + i] = ch.local[p + i];
  const std::size_t g = c / W;
  if constexpr (Main) {
    if (b == W) {
      ctx.direct[g] = std::uint32_t(p);
      // The evaluation reads the run in group order, not stream order: fetch it now, while the
      // stream is read front to back (without this the reads wait on memory one group at a time).
      prefetch_run(ch.data.data(), std::uint32_t(p));
      return b;
    }
    unshare(ctx, ch.data.data(), g);
  }
  const float* src = ch.data.data() + p * CB;
  float* dst = ctx.cache.data() + g * CB * W + c % W;
  switch (b) {
    case 1: copy_lanes<1>(src, dst); break;
    case 2: copy_lanes<2>(src, dst); break;
    case 3: copy_lanes<3>(src, dst); break;
    case 4: copy_lanes<4>(src, dst); break;
    default:
      for (std::size_t k = 0; k < CB; ++k)
        for (std::size_t i = 0; i < b; ++i) dst[k * W + i] = src[k * b + i];
  }
  return b;
}

}  // namespace

// The cycle fold (see fcurve_clip.hpp): private parts of FCurveClip and its Context.
struct FCurveClipAccess {
  // Fold fields: lo, hi (the window), end, n·period as hi + lo floats, sign, base, wrap, offset.
  static constexpr std::size_t kFold = 9;
  // A class's state: its fold (fields 0–7 as the channels'), 8 its last local frame, 9 the lo of
  // its next stream piece (+∞ past the last): a class whose local frame moves on within
  // [last, next lo) has nothing to do.  16 floats: one cache line.
  static constexpr std::size_t kClass = 16;
  using CycleClass = FCurveClip::CycleClass;

  static void compile(std::span<const FCurve> curves, const FCurveClipOptions& options, FCurveClip& clip) {
    auto& ch = clip.data_;
    clip.class_of_.assign(curves.size(), -1);
    clip.member_of_.assign(curves.size(), 0);
    for (std::size_t c = 0; c < curves.size(); ++c) {
      ch.begin.push_back(std::uint32_t(ch.data.size() / B));
      if (cycles_frames(curves[c])) {
        const auto keys = curves[c].keys();
        const FCurveCycles& m = *curves[c].cycles();
        const float x0 = keys.front().x, x1 = keys.back().x;
        std::size_t q = 0;
        for (; q < clip.classes_.size(); ++q) {
          const CycleClass& k = clip.classes_[q];
          if (k.first_x == x0 && k.last_x == x1 && k.cycles.before == m.before && k.cycles.after == m.after &&
              k.cycles.count_before == m.count_before && k.cycles.count_after == m.count_after)
            break;
        }
        if (q == clip.classes_.size()) {
          CycleClass k;
          k.cycles = m, k.first_x = x0, k.last_x = x1;
          clip.classes_.push_back(std::move(k));
        }
        CycleClass& k = clip.classes_[q];
        clip.class_of_[c] = std::int32_t(q);
        clip.member_of_[c] = std::uint32_t(k.members.size());
        k.members.push_back(std::uint32_t(c));
        k.first_y.push_back(keys.front().y);
        k.last_y.push_back(keys.back().y);
        k.pieces.begin.push_back(std::uint32_t(k.pieces.data.size() / B));
        compile_curve(curves[c], options, k.pieces.data, clip.max_fit_error_);
        k.pieces.count.push_back(std::uint32_t(k.pieces.data.size() / B - k.pieces.begin.back()));
        ++clip.cycling_;
      } else {
        compile_curve(curves[c], options, ch.data, clip.max_fit_error_);
      }
      ch.count.push_back(std::uint32_t(ch.data.size() / B - ch.begin.back()));
    }
    rig_detail::finish_stream<float, B>(ch);
    finish_runs(ch);
    for (CycleClass& k : clip.classes_) {
      rig_detail::finish_stream<float, B>(k.pieces);
      for (auto& o : k.pieces.owner) o = k.members[o];  // member index → channel (the cache column)
      finish_runs(k.pieces);
    }
  }

  // The discrete decisions of Blender's fold at a frame, computed cheaply (no fmod): two frames
  // with equal signatures in one window get their local frame from the same affine map.
  struct Signature {
    int side = 0;
    bool cycled = false, regular = false, mirrored = false, wrap = false;
    float m = 0;  // trunc(cycle number)
    bool operator==(const Signature&) const = default;
  };

  static Signature signature(const CycleClass& cy, float g) noexcept {
    Signature s;
    const FCurveCycles& m = cy.cycles;
    if (g < cy.first_x && m.before != CycleMode::none) s.side = -1;
    else if (g > cy.last_x && m.after != CycleMode::none) s.side = 1;
    if (s.side == 0) return s;
    const float period = cy.last_x - cy.first_x;
    const float ofs = s.side > 0 ? cy.last_x : cy.first_x;
    const int count = s.side > 0 ? m.count_after : m.count_before;
    const CycleMode mode = s.side > 0 ? m.after : m.before;
    const float rel = g - ofs;
    const float cycle = float(s.side) * rel / period;
    s.cycled = count == 0 || !(cycle > float(count));
    if (!s.cycled) return s;
    s.m = std::trunc(cycle);
    s.regular = cycle != s.m;  // a cycle number strictly between integers (2^23 and beyond: never)
    if (!s.regular) {
      s.m = cycle;
      return s;
    }
    s.mirrored = mode == CycleMode::mirror && (static_cast<long long>(std::min(cycle, 2.0e9f) + 1) % 2) != 0;
    // fmod(rel, period) = rel − side·m·period exactly: the difference fits a float (|r| < period,
    // on rel's and period's grid) and double holds side·m·period (m < 2^23) and the difference exactly.
    const float r = float(double(rel) - double(float(s.side) * s.m) * double(period));
    const float base = s.mirrored ? (s.side < 0 ? cy.first_x : cy.last_x) : cy.first_x;
    const float local = base + (s.mirrored ? -r : r);
    s.wrap = local < cy.first_x;
    return s;
  }

  // Float order as unsigned integers (for bisection over the floats between two frames).
  static std::uint32_t key(float x) noexcept {
    std::uint32_t b;
    std::memcpy(&b, &x, 4);
    return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
  }
  static float unkey(std::uint32_t k) noexcept {
    const std::uint32_t b = (k & 0x80000000u) ? (k & 0x7fffffffu) : ~k;
    float x;
    std::memcpy(&x, &b, 4);
    return x;
  }

  // The farthest frame from f in direction dir (±1) up to which the signature stays s0 (the frames
  // of one signature form an interval: each decision is monotone in the frame within one cycle).
  // Starts at `guess` (the cycle boundary in double): a few float steps usually settle it,
  // otherwise bisection.  Never past a frame whose signature differs, so the window is exact or short.
  static float edge(const CycleClass& cy, const Signature& s0, float f, double guess, int dir) noexcept {
    const float big = std::numeric_limits<float>::max();
    const float outward = dir > 0 ? kInf : -kInf;
    float g = float(std::clamp(guess, -double(big), double(big)));
    if (!(dir > 0 ? g > f : g < f)) g = f;
    if (signature(cy, g) == s0) {
      for (int i = 0; i < 4 && std::abs(g) < big; ++i) {
        const float h = std::nextafter(g, outward);
        if (!(signature(cy, h) == s0)) return g;
        g = h;
      }
      return g;  // short of the edge: a shorter window, still exact
    }
    float in = f, out = g;
    for (int i = 0; i < 3; ++i) {
      const float h = std::nextafter(out, -outward);
      if (h == in) return in;
      if (signature(cy, h) == s0) return h;
      out = h;
    }
    std::uint32_t ki = key(in), ko = key(out);
    while (ki + 1 != ko && ko + 1 != ki) {
      const std::uint32_t km = ki < ko ? ki + (ko - ki) / 2 : ko + (ki - ko) / 2;
      if (signature(cy, unkey(km)) == s0) ki = km;
      else ko = km;
    }
    return unkey(ki);
  }

  // The local frame from fold fields at frame f (field k at F[k·s]; the operations the SIMD loop
  // does): r = ((f − end) − nd_hi) − nd_lo, exact in the window (f − end − n·period fits a float
  // there, the first difference is exact by Sterbenz's lemma — (f − end)/(n·period) ∈ [1/2, 2] for
  // n ≠ 0 — and nd_hi + nd_lo = n·period exactly, Dekker's two-product split); then base ± r and the wrap.
  static float local(const float* F, std::size_t s, float f) noexcept {
    const float rel = f - F[2 * s];
    const float r = (rel - F[3 * s]) - F[4 * s];
    const float t = F[6 * s] + F[5 * s] * r;
    return t + F[7 * s];
  }

  enum class FoldKind { identity, copy, one_frame };

  // Sets a class's fold S[0 … 7] for frame f: the decisions Blender takes at f (decide_cycles) and
  // the window of frames around f on which the same affine map gives its local frames.
  static FoldKind set_fold(const CycleClass& cy, float f, float* S) noexcept {
    const float period = cy.last_x - cy.first_x;
    const auto d = fcurve_detail::decide_cycles(cy.cycles, cy.first_x, 0.0f, cy.last_x, 0.0f, f);
    const auto put = [&](float lo, float hi, float ofs, float n, float per, float sign, float base, float wrap) {
      const double nd = double(n) * double(per);  // exact: |n| < 2^23, 24-bit period
      const float nd_hi = float(nd), nd_lo = float(nd - double(nd_hi));  // nd_lo exact (two-product)
      const float v[8] = {lo, hi, ofs, nd_hi, nd_lo, sign, base, wrap};
      std::copy_n(v, 8, S);
    };
    const FCurveCycles& m = cy.cycles;
    if (!d.cycled) {
      // The keys' own pieces at f (inside, on a side without cycling, or past its count).
      if (d.side == 0) {
        // Side 0 holds from the first key (or −∞ when nothing cycles before it) to the last (or +∞).
        put(m.before != CycleMode::none ? cy.first_x : -kInf, m.after != CycleMode::none ? cy.last_x : kInf, 0, 0, 0,
            1, 0, 0);
        return FoldKind::identity;
      }
      const Signature s0 = signature(cy, f);
      if (d.side > 0) {
        put(edge(cy, s0, f, double(cy.last_x) + double(m.count_after) * double(period), -1), kInf, 0, 0, 0, 1, 0, 0);
      } else {
        put(-kInf, edge(cy, s0, f, double(cy.first_x) - double(m.count_before) * double(period), 1), 0, 0, 0, 1, 0, 0);
      }
      return FoldKind::identity;
    }
    const Signature s0 = signature(cy, f);
    if (s0.regular) {
      const float ofs = d.side > 0 ? cy.last_x : cy.first_x;
      const float n = float(d.side) * s0.m;
      const float sign = s0.mirrored ? -1.0f : 1.0f;
      const float base = s0.mirrored ? (d.side < 0 ? cy.first_x : cy.last_x) : cy.first_x;
      const float wrap = s0.wrap ? period : 0.0f;
      put(f, f, ofs, n, period, sign, base, wrap);
      if (local(S, 1, f) == d.t) {  // as proven above; checked, else the one-frame fold below
        // The copy: cycle numbers in (m, m + 1), frames ofs + side·(m … m + 1)·period.
        const double a = double(ofs) + double(n) * double(period), b = double(ofs) + (double(n) + d.side) * double(period);
        S[0] = edge(cy, s0, f, std::min(a, b), -1);
        S[1] = edge(cy, s0, f, std::max(a, b), 1);
        return FoldKind::copy;
      }
    }
    // One frame: local = base = Blender's own answer.
    put(f, f, f, 0, 0, 1, d.t, 0);
    return FoldKind::one_frame;
  }

  // Brings cycle class q to frame f: its fold (and its members' SIMD fold fields and value offsets
  // when the fold changes), its local frame, and its members' cached pieces, consumed from the
  // class's stream in local-frame order as the main stream is (rig_detail::advance).
  static void advance_class(const FCurveClip& clip, FCurveClip::Context& ctx, std::size_t q, float f) noexcept {
    const CycleClass& cy = clip.classes_[q];
    float* S = ctx.class_fold.data() + q * kClass;
    const std::size_t s = ctx.stride;
    if (!(f >= S[0] && f <= S[1])) {
      const FoldKind kind = set_fold(cy, f, S);
      float* F = ctx.fold.data();
      for (std::size_t i = 0; i < cy.members.size(); ++i) {
        const std::size_t c = cy.members[i];
        for (std::size_t k = 0; k < 8; ++k) F[k * s + c] = S[k];
        // The value offset: Blender's own (the same on the whole copy: k = side·(m + 1) there).
        F[8 * s + c] = kind == FoldKind::identity ? 0.0f
                                                  : fcurve_detail::decide_cycles(cy.cycles, cy.first_x, cy.first_y[i],
                                                                                 cy.last_x, cy.last_y[i], f).offset;
      }
    }
    const float t = local(S, 1, f);
    const auto& ch = cy.pieces;
    const float* bounds = ch.bounds.data();
    const std::size_t n = ch.owner.size();
    float* cache = ctx.cache.data();
    std::size_t& next = ctx.class_next[q];
    const float previous = S[8];
    S[8] = t;
    bool forward = t >= previous;
    if (!forward) {
      // A local frame back near the stream's start (the wrap to the next copy of a repeat):
      // replay the stream from its start, as evaluate_channels does for the main stream.
      if (replays_from_start(bounds, n, cy.members.size(), t)) next = 0, forward = true;
    }
    if (forward) {
      // A class's channels are never in a group read in place (a main-stream run fills its group).
      const std::size_t limit = std::min(n, next + 16 * cy.members.size());
      std::size_t p = next;
      while (p < limit && bounds[2 * p] <= t) p += take_run<false>(ch, p, ctx);
      if (p == n || bounds[2 * p] > t) {
        next = p;
        S[9] = p < n ? bounds[2 * p] : kInf;
        return;
      }
    }
    for (std::size_t i = 0; i < cy.members.size(); ++i) {
      const std::size_t c = cy.members[i];
      const float* cur = bounds + 2 * std::size_t(ch.where[ch.begin[i] + ctx.segment[c]]);  // the cached piece
      if (t >= cur[0] && t < cur[1]) continue;  // its [lo, hi) still holds t
      const std::uint32_t k = rig_detail::find_segment<float, 2>(bounds, ch.where.data() + ch.begin[i], ch.count[i], t,
                                                                 ctx.segment[c]);
      ctx.segment[c] = k;
      put_piece(ch, ch.where[ch.begin[i] + k], cache, c);
    }
    next = first_piece_after(bounds, n, t);
    S[9] = next < n ? bounds[2 * next] : kInf;
  }

  // Channel c's second piece (the one starting at its first key) as a block.
  static void nan_block(const FCurveClip& clip, std::size_t c, float* blk) noexcept {
    const std::int32_t q = clip.class_of_[c];
    if (q >= 0) {
      const auto& ch = clip.classes_[std::size_t(q)].pieces;
      block_of(ch, ch.where[ch.begin[clip.member_of_[c]] + 1], blk);
      return;
    }
    block_of(clip.data_, clip.data_.where[clip.data_.begin[c] + 1], blk);
  }
};

Expected<FCurveClip> build_fcurve_clip(std::span<const FCurve> curves, FCurveClipOptions options) {
  FCurveClip clip;
  clip.channels_ = curves.size();
  FCurveClipAccess::compile(curves, options, clip);
  return clip;
}

Expected<FCurveClip> build_fcurve_rig(std::span<const FCurve> curves, FCurveClipOptions options) {
  if (curves.size() % 10 != 0) {
    return Error{ErrorCode::invalid_argument,
                 "a rig needs 10 F-curves per joint (location xyz, rotation_quaternion wxyz, scale xyz); got " +
                     std::to_string(curves.size())};
  }
  FCurveClip clip;
  clip.channels_ = curves.size();
  clip.joints_ = curves.size() / 10;
  // Internal channel c is curve c (joint-major, 10·j + k): a joint's curves usually share their
  // key frames (Blender keys a bone's channels together), so the stream hands over a joint's ten
  // pieces one after another and they land in three neighbouring groups of the context's cache
  // (component-major, k·J + j, put them in ten groups far apart: 3× the cache lines written).
  FCurveClipAccess::compile(curves, options, clip);
  return clip;
}

FCurveClip::Context make_fcurve_context(const FCurveClip& clip) {
  FCurveClip::Context ctx;
  ctx.stride = (clip.channels() + 15) / 16 * 16;
  ctx.segment.assign(clip.channels(), 0);
  ctx.cache.assign(CB * ctx.stride, 0.0f);
  ctx.values.assign(ctx.stride, 0.0f);
  // The identity fold on (−∞, +∞) for every channel; a cycling channel's fields are its class's,
  // written when the class's fold is first set (the first sample).
  const std::size_t s = ctx.stride;
  ctx.fold.assign(FCurveClipAccess::kFold * s, 0.0f);
  ctx.folding.assign(s / W, 0);
  ctx.direct.assign(s / W, kNoRun);
  for (std::size_t c = 0; c < s; ++c) {
    ctx.fold[0 * s + c] = -kInf, ctx.fold[1 * s + c] = kInf, ctx.fold[5 * s + c] = 1.0f;
    if (c < clip.channels() && clip.class_of_[c] >= 0) ctx.folding[c / W] = 1;
  }
  // Each class's fold starts empty (set at the first sample) and its local frame before any.
  ctx.class_fold.assign(FCurveClipAccess::kClass * clip.classes_.size(), 0.0f);
  for (std::size_t q = 0; q < clip.classes_.size(); ++q) {
    float* S = ctx.class_fold.data() + q * FCurveClipAccess::kClass;
    S[0] = kInf, S[1] = -kInf, S[8] = -kInf, S[9] = -kInf;
  }
  ctx.class_next.assign(clip.classes_.size(), 0);
  return ctx;
}

namespace {

// Brings the cache of the channels in the main stream to `frame`: rig_detail::advance, with the
// stream's lo and hi in `bounds` and its cached fields in runs: forward playback consumes the
// stream's next runs (a run that fills a SIMD group is read in place, Context::direct; others
// are copied into the cache); a seek back, or a forward jump past more than 16 pieces per channel,
// finds each stale channel's piece from its cursor (the current piece's [lo, hi) read from
// `bounds` through the cursor), copies it into the cache, and repositions the stream.
template <class Channels>
void advance_main(const Channels& ch, std::size_t C, float frame, FCurveClip::Context& context) noexcept {
  const float* bounds = ch.bounds.data();
  const std::size_t n = ch.owner.size();
  std::uint32_t* segment = context.segment.data();
  if (frame >= context.time) {
    const std::size_t limit = std::min(n, context.next + 16 * C);
    std::size_t p = context.next;
    while (p < limit && bounds[2 * p] <= frame) p += take_run<true>(ch, p, context);
    if (p == n || bounds[2 * p] > frame) {
      context.next = p;
      return;
    }
  }
  for (std::size_t c = 0; c < C; ++c) {
    if (ch.count[c] == 0) continue;  // a cycling channel (not in the main stream)
    const std::uint32_t* where = ch.where.data() + ch.begin[c];
    const float* cur = bounds + 2 * std::size_t(where[segment[c]]);
    if (frame >= cur[0] && frame < cur[1]) continue;  // the current piece's [lo, hi) still holds frame
    const std::uint32_t k = rig_detail::find_segment<float, 2>(bounds, where, ch.count[c], frame, segment[c]);
    segment[c] = k;
    unshare(context, ch.data.data(), c / W);
    put_piece(ch, where[k], context.cache.data(), c);
  }
  context.next = first_piece_after(bounds, n, frame);
}

// evaluate_channels' SIMD loop over groups of native_simd<float>::size() channels from the cache;
// Folding: some channel cycles (apply each group's cycle fold where one of its channels does).
constexpr std::size_t kPrefetchGroups = 8;
// `data`: the main stream's runs (a group whose Context::direct names one reads it in place).
template <bool Folding>
void evaluate_groups(FCurveClip::Context& context, const float* data, std::size_t C, float frame) noexcept {
  namespace stdx = rig_detail::stdx;
  using V = stdx::native_simd<float>;
  static_assert(V::size() == W);
  const V f(frame);
  const float* cache = context.cache.data();
  const std::uint32_t* direct = context.direct.data();
  float* values = context.values.data();
  for (std::size_t c0 = 0; c0 < C; c0 += W) {
    // This group's cached fields, field k at g + k·W: its part of the cache or a run in the clip.
    const std::uint32_t d = direct[c0 / W];
    const float* g = d == kNoRun ? cache + c0 * CB : data + std::size_t(d) * CB;
    if (c0 + kPrefetchGroups * W < C) {
      const std::uint32_t e = direct[c0 / W + kPrefetchGroups];
      if (e != kNoRun) prefetch_run(data, e);
    }
    const auto ld = [g](std::size_t k) noexcept { return rig_detail::load<V>(g + k * W); };
    V t = f;  // the frame each channel's piece is evaluated at
    V offset = V(0.0f);
    if constexpr (Folding) {
      if (context.folding[c0 / W]) {
        const float* fold = context.fold.data();
        const std::size_t s = context.stride;
        // The cycle fold: local = base + sign·((frame − end) − n·period) + wrap, the class's local
        // frame bit for bit (the same float operations; the identity for channels that do not
        // cycle), and the channel's value offset.
        const auto fl = [fold, s, c0](std::size_t k) noexcept { return rig_detail::load<V>(fold + k * s + c0); };
        const V r = ((f - fl(2)) - fl(3)) - fl(4);
        t = (fl(6) + fl(5) * r) + fl(7);
        offset = fl(8);
      }
    }
    V u = (t - ld(0)) * ld(1);
    // Blender's snap bands: u = +1 from the threshold at hi on, −1 up to the one at lo (that one wins).
    stdx::where(t >= ld(3), u) = V(1.0f);
    stdx::where(t <= ld(2), u) = V(-1.0f);
    V v = ld(4 + D);
    for (std::size_t k = D; k-- > 0;) v = v * u + ld(4 + k);
    if constexpr (Folding) v += offset;
    v.copy_to(values + c0, stdx::element_aligned);
  }
}

}  // namespace

void evaluate_channels(const FCurveClip& clip, float frame, FCurveClip::Context& context) noexcept {
  const std::size_t C = clip.channels_;
  INBETWEEN_ASSERT(context.segment.size() == C && context.cache.size() == CB * context.stride &&
                   context.fold.size() == FCurveClipAccess::kFold * context.stride &&
                   context.direct.size() == context.stride / W);
  if (std::isnan(frame)) {
    // As FCurve::sample: the first key's value, each channel's second piece at its start (it
    // starts at the first key: a fitted piece whose band there clamps u to −1, where it
    // interpolates the key, a constant piece, or, for one key, the held end).  Cache, folds and
    // stream are untouched.
    for (std::size_t i = 0; i < C; ++i) {
      float blk[B];
      FCurveClipAccess::nan_block(clip, i, blk);
      context.values[i] = piece_value(blk, blk[0]);
    }
    return;
  }
  const float big = std::numeric_limits<float>::max();
  frame = frame > -big ? (frame < big ? frame : big) : -big;
  if (frame < context.time) {
    // A seek back to a frame near the stream's start (a looping playback's wrap to its first
    // frame): replay the stream from its start (see replays_from_start).
    const auto& ch = clip.data_;
    if (replays_from_start(ch.bounds.data(), ch.owner.size(), C, frame)) {
      context.next = 0;
      context.time = -kInf;
    }
  }
  advance_main(clip.data_, C, frame, context);
  context.time = frame;
  for (std::size_t q = 0; q < clip.classes_.size(); ++q) {
    // The common case inline: the class's fold still holds and its local frame moved on within
    // [last local frame, its next piece's lo) — nothing to consume, no cached piece to change.
    float* S = context.class_fold.data() + q * FCurveClipAccess::kClass;
    if (frame >= S[0] && frame <= S[1]) {
      const float t = FCurveClipAccess::local(S, 1, frame);
      if (t >= S[8] && t < S[9]) {
        S[8] = t;
        continue;
      }
    }
    FCurveClipAccess::advance_class(clip, context, q, frame);
  }
  // The SIMD loop, without the cycle fold when no channel cycles (chosen once per call: a
  // non-cycling clip pays neither the per-group branch nor the offset add).
  if (clip.classes_.empty()) {
    evaluate_groups<false>(context, clip.data_.data.data(), C, frame);
  } else {
    evaluate_groups<true>(context, clip.data_.data.data(), C, frame);
  }
}

void sample_fcurves(const FCurveClip& clip, float frame, FCurveClip::Context& context, std::span<float> out) noexcept {
  INBETWEEN_ASSERT(out.size() == clip.channels_);
  evaluate_channels(clip, frame, context);
  std::copy_n(context.values.begin(), clip.channels_, out.begin());
}

void sample_fcurve_rig(const FCurveClip& clip, float frame, FCurveClip::Context& context,
                       std::span<JointPose<float>> out) noexcept {
  const std::size_t J = clip.joints_;
  INBETWEEN_ASSERT(out.size() == J);
  evaluate_channels(clip, frame, context);
  // The quaternion's 1/|q| for a block of joints at a time, W lanes at once (std::sqrt and the
  // division are correctly rounded in both, so the same bits as the scalar 1/sqrt per joint),
  // then the AoS write.
  namespace stdx = rig_detail::stdx;
  using V = stdx::native_simd<float>;
  constexpr std::size_t kBlock = 64;  // joints per block (a multiple of W)
  static_assert(kBlock % W == 0);
  const float* v = context.values.data();
  alignas(64) float n2[kBlock], inv[kBlock];
  for (std::size_t j0 = 0; j0 < J; j0 += kBlock) {
    const std::size_t n = std::min(kBlock, J - j0);
    for (std::size_t i = 0; i < n; ++i) {
      const float* q = v + 10 * (j0 + i);
      n2[i] = q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6];
    }
    for (std::size_t i = n; i < (n + W - 1) / W * W; ++i) n2[i] = 1.0f;  // lanes past the last joint
    for (std::size_t i = 0; i < n; i += W) {
      const V m(n2 + i, stdx::vector_aligned);
      const V r = V(1.0f) / stdx::sqrt(m);  // used where n2 > 0 only
      r.copy_to(inv + i, stdx::vector_aligned);
    }
    for (std::size_t i = 0; i < n; ++i) {
      JointPose<float>& p = out[j0 + i];
      const float* q = v + 10 * (j0 + i);
      p.translation = Vec3f{q[0], q[1], q[2]};
      const float s = inv[i];
      p.rotation = n2[i] > 0 ? Quatf::from_wxyz(q[3] * s, q[4] * s, q[5] * s, q[6] * s) : Quatf{};
      p.scale = Vec3f{q[7], q[8], q[9]};
    }
  }
}

}  // namespace inbetween
