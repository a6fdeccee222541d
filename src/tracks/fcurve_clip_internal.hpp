#pragma once
// Internals shared by the FCurveClip sources (not installed): the piece layout's constants, the
// runs of a stream and their hand-over to a cursor, the fitting of one curve into pieces
// (fcurve_clip_fit.cpp), and FCurveClipAccess, the cycle fold (fcurve_clip_cycles.cpp).
// fcurve_clip.cpp builds clips and samples them.
#include "inbetween/tracks/runtime/fcurve_clip.hpp"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

namespace inbetween {
namespace fcurve_clip_detail {

constexpr std::size_t B = FCurveClip::block;
constexpr float kInf = std::numeric_limits<float>::infinity();

constexpr std::size_t D = FCurveClip::degree;
constexpr float kBand = 0.0001f;  // Blender's snap band around a key, in frames
constexpr float kNoBand = -1.0f;  // a band width no |frame − key| ≤ it

// Fields of a piece the cache holds (the SIMD loop's): origin, inv_length, the two band
// thresholds, c0 … cD — the block without lo and hi, which only the stream and the searches read.
constexpr std::size_t CB = FCurveClip::cached_fields;
constexpr std::size_t kCachedFrom = B - CB;  // first cached field of a block

// The runtime's evaluation of a block at `frame`, in float, in the operations evaluate_channels
// does: u = (frame − origin)·inv_length, u = +1 inside the band at hi (frame ≥ its threshold),
// −1 inside the band at lo (frame ≤ its threshold; that one wins), then Horner.
inline float piece_value(const float* blk, float frame) {
  float u = (frame - blk[2]) * blk[3];
  if (frame >= blk[5]) u = 1.0f;
  if (frame <= blk[4]) u = -1.0f;
  float v = blk[6 + D];
  for (std::size_t k = D; k-- > 0;) v = v * u + blk[6 + k];
  return v;
}

// Appends the pieces of one curve (its keyed range and the two extrapolation lines) to `data`;
// `worst` grows to the largest relative fit error met (fcurve_clip_fit.cpp).
void compile_curve(const FCurve& curve, const FCurveClipOptions& options, std::vector<float>& data, float& worst);

// A curve whose Cycles modifier changes some frame: ≥ 2 keys (a period) and a side that cycles.
bool cycles_frames(const FCurve& curve);

// ---- Runs (fcurve_clip.hpp, FCurveClip::Channels) -----------------------------------------------

constexpr std::size_t W = rig_detail::stdx::native_simd<float>::size();  // channels per SIMD group
static_assert(W <= 255, "a run's size and lane are bytes");
constexpr std::uint32_t kNoRun = FCurveClipCursor::no_run;

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
inline void unshare(FCurveClipCursor& ctx, const float* data, std::size_t g) noexcept {
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
std::size_t take_run(const Channels& ch, std::size_t p, FCurveClipCursor& ctx) noexcept {
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

}  // namespace fcurve_clip_detail

// The cycle fold (see fcurve_clip.hpp): private parts of FCurveClip and its FCurveClipCursor.
struct FCurveClipAccess {
  // Fold fields: lo, hi (the window), end, n·period as hi + lo floats, sign, base, wrap, offset.
  static constexpr std::size_t kFold = 9;
  // A class's state: its fold (fields 0–7 as the channels'), 8 its last local frame, 9 the lo of
  // its next stream piece (+∞ past the last): a class whose local frame moves on within
  // [last, next lo) has nothing to do.  16 floats: one cache line.
  static constexpr std::size_t kClass = 16;
  using CycleClass = FCurveClip::CycleClass;

  static void compile(std::span<const FCurve> curves, const FCurveClipOptions& options, FCurveClip& clip);

  // The discrete decisions of Blender's fold at a frame, computed cheaply (no fmod): two frames
  // with equal signatures in one window get their local frame from the same affine map.
  struct Signature {
    int side = 0;
    bool cycled = false, regular = false, mirrored = false, wrap = false;
    float m = 0;  // trunc(cycle number)
    bool operator==(const Signature&) const = default;
  };

  static Signature signature(const CycleClass& cy, float g) noexcept;

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
  static float edge(const CycleClass& cy, const Signature& s0, float f, double guess, int dir) noexcept;

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
  static FoldKind set_fold(const CycleClass& cy, float f, float* S) noexcept;

  // Brings cycle class q to frame f: its fold (and its members' SIMD fold fields and value offsets
  // when the fold changes), its local frame, and its members' cached pieces, consumed from the
  // class's stream in local-frame order as the main stream is (rig_detail::advance).
  static void advance_class(const FCurveClip& clip, FCurveClipCursor& ctx, std::size_t q, float f) noexcept;

  // Channel c's second piece (the one starting at its first key) as a block.
  static void nan_block(const FCurveClip& clip, std::size_t c, float* blk) noexcept;
};

}  // namespace inbetween
