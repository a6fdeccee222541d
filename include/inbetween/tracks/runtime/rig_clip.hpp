#pragma once
/// The tracks runtime (issue 12, "compile once, sample many channels per call"): a RigClip is an
/// immutable clip compiled from per-joint translation, rotation and scale tracks.  Every channel is
/// cut into segments that tile the whole frame line — a constant segment before the first key, one
/// per key interval, a constant segment after the last key — and each segment is stored as one
/// 16-scalar block (its frame interval, its parameter origin and 1/length, and its coefficients:
/// Vec3 segments in power form in the local parameter u, rotation segments as the two keys with
/// the arc's Ω² and 1/sinc(Ω) precomputed).  A RigClipCursor<T> keeps, per channel, the current
/// segment and a copy of its block in structure-of-arrays order (one array per field over all
/// joints, ozz-animation's "decompressed keys" cache); sample_rig() refreshes only the channels
/// whose segment changed and then evaluates all joints with SIMD: float with
/// std::experimental::native_simd (4 per SSE2 register, 8 with AVX, 16 with AVX-512), double too
/// when the flags give it 4 lanes or more, else (the default SSE2 build) with Highway's run-time
/// dispatch (8 per AVX-512 register, 4 with AVX2); docs/runtime.md, "Which SIMD", has the
/// measurements behind that split.  Rotations are exact slerp
/// weights from an even polynomial: sin(uΩ)/sin(Ω) = u·sinc(uΩ)/sinc(Ω) with sinc's Taylor series
/// in (uΩ)², Ω ≤ π/2 (no trigonometry, no root, no division, no normalisation per sample).
///
/// Supported input (anything else is refused by build_rig_clip with Unsupported and the place):
/// Track<Vec3<T>> of every tangent kind (linear, Hermite, Catmull-Rom, TCB, flat, clamped, plateau,
/// stepped) with TrackExtend::constant at both ends; QuatTrack<T> segments of kind step or slerp
/// whose keys are on the same side of the 4-D sphere (the track's sign continuity guarantees that
/// unless a key asked for the long way).  Outside a channel's keys the end value is held, as the
/// scalar per-track API does for these inputs.  Agreement with the scalar API:
/// rig_runtime_vec_tolerance and rig_runtime_rotation_tolerance (tests/tracks/rig_clip_test.cpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>
#include <experimental/simd>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

/// One joint's sampled local transform.
template <Real T>
struct JointPose {
  Vec3<T> translation{};          ///< translation
  Quat<T> rotation{};             ///< unit quaternion
  Vec3<T> scale{T(1), T(1), T(1)};  ///< per-axis scale
};

/// Agreement of a RigClip's Vec3 channels with Track::sample, relative to the channel's largest
/// |value| + |slope|·(segment length) (power form and Hermite basis round differently: a few ulp
/// of that magnitude; 64·ε leaves room).
template <Real T>
inline constexpr T rig_runtime_vec_tolerance = T(64) * std::numeric_limits<T>::epsilon();

/// Truncation of the runtime's sinc series at Ω = π/2 (its worst case), relative to the slerp
/// weight: the first omitted Taylor term (π/2)^(2n+2)/(2n+3)! divided by sinc(π/2) = 2/π — float
/// keeps terms up to x¹⁰: 5.7e-8; double up to x²⁰: 1.3e-18 (below rounding).
template <Real T>
inline constexpr T rig_slerp_series_error = sizeof(T) == 4 ? T(5.7e-8) : T(1.3e-18);

/// Agreement of a RigClip's rotations with QuatTrack::sample (rotation angle, radians): the series
/// truncation (rig_slerp_series_error, times 2 for the two weights) plus 16·ε of rounding in the
/// weights, the blend and the reference slerp's own few-ulp error.
template <Real T>
inline constexpr T rig_runtime_rotation_tolerance = T(2) * rig_slerp_series_error<T> + T(16) * std::numeric_limits<T>::epsilon();

template <Real T>
class RigClip;
template <Real T>
struct RigClipCursor;

/// Joints per group of a RigClipCursor's cache: one 64-byte line of a field (16 floats, 8 doubles),
/// the widest register (AVX-512) a sampling kernel loads at once, whatever the build's flags.
template <Real T>
inline constexpr std::size_t rig_group = 64 / sizeof(T);

namespace rig_detail {
template <Real T>
T refresh(const RigClip<T>& clip, T frame, RigClipCursor<T>& cursor) noexcept;
}  // namespace rig_detail

/// The caller-owned state of one playback stream of a RigClip (make it with make_rig_clip_cursor;
/// was RigClipCursor): per channel its current
/// segment, and a copy of that segment's block in SIMD-register order (groups of rig_group<T>
/// joints, field by field: ozz-animation's "decompressed keys" cache);
/// per channel kind the position in the clip's time-sorted block stream.  Reusable, copyable;
/// one per character instance that plays the clip.
template <Real T>
struct RigClipCursor {
  std::vector<std::uint32_t> segment;  ///< per channel (T of all joints, then R, then S): segment index in its channel
  std::vector<T> cache;                ///< 3 kinds × padded joints × 16 fields (filled by sample_rig)
  std::size_t stride = 0;              ///< padded joint count (a multiple of 16)
  std::array<std::size_t, 3> next{};   ///< per kind: first stream block not yet consumed (its lo > time)
  T time = -std::numeric_limits<T>::infinity();  ///< frame of the last sample (clamped; −∞ before the first)
};

/// A compiled, immutable T+R+S clip of J joints (build it with build_rig_clip).
template <Real T>
class RigClip {
 public:
  /// Number of joints.
  [[nodiscard]] std::size_t joints() const noexcept { return joints_; }

  /// Scalars per segment block: lo, hi (the frame interval [lo, hi) the segment answers), origin,
  /// 1/length (u = (frame − origin)·inv_length, clamped to [0, 1]; 0 for the constant end
  /// segments) and 12 coefficients: Vec3 c0.xyz, c1.xyz, c2.xyz, c3.xyz of
  /// ((c3·u + c2)·u + c1)·u + c0; rotations q0.xyzw, q1.xyzw, Ω², 1/sinc(Ω), 0, 0.
  static constexpr std::size_t block = 16;

 private:
  template <Real U>
  friend Expected<RigClip<U>> build_rig_clip(std::span<const Track<Vec3<U>>>, std::span<const QuatTrack<U>>,
                                             std::span<const Track<Vec3<U>>>);
  template <Real U>
  friend U rig_detail::refresh(const RigClip<U>&, U, RigClipCursor<U>&) noexcept;
  template <Real U>
  friend RigClipCursor<U> make_rig_clip_cursor(const RigClip<U>&);

  RigClip() = default;

  // One channel kind (0 translations, 1 rotations, 2 scales).  data holds every segment block of
  // every channel of the kind, sorted by lo (then channel): the order forward playback needs
  // them in, so sequential sampling reads data front to back.  Block p belongs to channel
  // owner[p] as its segment local[p]; channel c's segment k is block where[begin[c] + k].
  struct Channels {
    std::vector<std::uint32_t> begin, count;  // per channel
    std::vector<std::uint32_t> where;         // per (channel, segment): block position
    std::vector<std::uint32_t> owner, local;  // per block
    std::vector<T> data;                      // block scalars, blocks in stream order
  };

  std::size_t joints_ = 0;
  std::array<Channels, 3> kind_;
};

/// A cursor before the clip's start (the first sample_rig fills every channel's cache).
template <Real T>
RigClipCursor<T> make_rig_clip_cursor(const RigClip<T>& clip) {
  RigClipCursor<T> ctx;
  ctx.stride = (clip.joints() + 15) / 16 * 16;
  ctx.segment.assign(3 * clip.joints(), 0);
  ctx.cache.assign(3 * RigClip<T>::block * ctx.stride, T(0));
  return ctx;
}

/// Deprecated names of RigClipCursor and make_rig_clip_cursor, kept for one release
/// (docs/conventions.md, "Playback state").
template <Real T>
using RigContext [[deprecated("use RigClipCursor")]] = RigClipCursor<T>;
/// Deprecated name of make_rig_clip_cursor, kept for one release.
template <Real T>
[[deprecated("use make_rig_clip_cursor")]] [[nodiscard]] RigClipCursor<T> make_rig_context(const RigClip<T>& clip) {
  return make_rig_clip_cursor(clip);
}

namespace rig_detail {
namespace stdx = std::experimental;
inline constexpr double inf = std::numeric_limits<double>::infinity();

// sinc(x) = sin(x)/x as a polynomial in x², Taylor coefficients 1/(2k+1)! with alternating signs;
// float keeps 6 terms, double 11 (rig_slerp_series_error).
template <Real T, class V>
inline V sinc_series(V x2) noexcept {
  if constexpr (sizeof(T) == 4) {
    return T(1) + x2 * (T(-1.0 / 6) + x2 * (T(1.0 / 120) + x2 * (T(-1.0 / 5040) + x2 * (T(1.0 / 362880) +
                                                                                          x2 * T(-1.0 / 39916800)))));
  } else {
    V p = V(T(1.0 / 51090942171709440000.0));
    p = T(-1.0 / 121645100408832000.0) + x2 * p;
    p = T(1.0 / 355687428096000.0) + x2 * p;
    p = T(-1.0 / 1307674368000.0) + x2 * p;
    p = T(1.0 / 6227020800.0) + x2 * p;
    p = T(-1.0 / 39916800.0) + x2 * p;
    p = T(1.0 / 362880.0) + x2 * p;
    p = T(-1.0 / 5040.0) + x2 * p;
    p = T(1.0 / 120.0) + x2 * p;
    p = T(-1.0 / 6.0) + x2 * p;
    return T(1) + x2 * p;
  }
}

template <Real T>
void push_block(std::vector<T>& data, T lo, T hi, T origin, T inv_length, std::initializer_list<T> coef) {
  data.push_back(lo);
  data.push_back(hi);
  data.push_back(origin);
  data.push_back(inv_length);
  for (const T c : coef) data.push_back(c);
  for (std::size_t i = 4 + coef.size(); i < RigClip<T>::block; ++i) data.push_back(T(0));
}

template <Real T>
void push_constant_vec(std::vector<T>& data, T lo, T hi, const Vec3<T>& v) {
  push_block<T>(data, lo, hi, T(0), T(0), {v.x, v.y, v.z});
}

template <Real T>
void push_constant_rot(std::vector<T>& data, T lo, T hi, const Quat<T>& q) {
  // q0 = q1 = q, Ω = 0: the weights (1 − u) and u blend q with itself.
  push_block<T>(data, lo, hi, T(0), T(0), {q.x, q.y, q.z, q.w, q.x, q.y, q.z, q.w, T(0), T(1)});
}

// Compiles one Vec3 track into the channel's blocks; Unsupported for extend modes other than constant.
template <Real T, class Channels>
Expected<bool> add_vec(Channels& ch, const Track<Vec3<T>>& tr, std::size_t joint, const char* kind) {
  if (tr.extend_before() != TrackExtend::constant || tr.extend_after() != TrackExtend::constant) {
    return Error{ErrorCode::Unsupported,
                 std::string("the runtime holds the end values outside the keys; this ") + kind +
                     " track extends otherwise (use TrackExtend::constant)",
                 "", {std::string(kind), joint}};
  }
  const auto f = tr.frames();
  const auto v = tr.values();
  const auto in = tr.in_tangents();
  const auto out = tr.out_tangents();
  const std::size_t n = f.size();
  const T inf_t = std::numeric_limits<T>::infinity();
  ch.begin.push_back(std::uint32_t(ch.data.size() / RigClip<T>::block));
  ch.count.push_back(std::uint32_t(n + 1));
  push_constant_vec<T>(ch.data, -inf_t, f[0], v[0]);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const T h = f[i + 1] - f[i];
    if (tr.stepped(i)) {
      push_constant_vec<T>(ch.data, f[i], f[i + 1], v[i]);
      continue;
    }
    // Hermite p0, p1, m0 = out_i·h, m1 = in_{i+1}·h to power form.
    const Vec3<T> p0 = v[i], p1 = v[i + 1], m0 = out[i] * h, m1 = in[i + 1] * h;
    const Vec3<T> c2 = (p1 - p0) * T(3) - m0 * T(2) - m1, c3 = (p0 - p1) * T(2) + m0 + m1;
    push_block<T>(ch.data, f[i], f[i + 1], f[i], T(1) / h,
                  {p0.x, p0.y, p0.z, m0.x, m0.y, m0.z, c2.x, c2.y, c2.z, c3.x, c3.y, c3.z});
  }
  push_constant_vec<T>(ch.data, f[n - 1], inf_t, v[n - 1]);
  return true;
}

// Sorts a kind's blocks (pushed channel by channel, channel c's at begin[c] …) into stream order.
template <Real T, std::size_t B, class Channels>
void finish_stream(Channels& ch) {
  const std::size_t n = ch.data.size() / B;
  std::vector<std::uint32_t> owner(n), local(n), order(n);
  for (std::size_t c = 0; c < ch.begin.size(); ++c)
    for (std::uint32_t k = 0; k < ch.count[c]; ++k) owner[ch.begin[c] + k] = std::uint32_t(c), local[ch.begin[c] + k] = k;
  for (std::size_t i = 0; i < n; ++i) order[i] = std::uint32_t(i);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const T la = ch.data[a * B], lb = ch.data[b * B];
    return la < lb || (la == lb && owner[a] < owner[b]);
  });
  std::vector<T> data(n * B);
  ch.where.assign(n, 0);
  ch.owner.resize(n);
  ch.local.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::copy_n(ch.data.begin() + std::ptrdiff_t(order[p] * B), B, data.begin() + std::ptrdiff_t(p * B));
    ch.owner[p] = owner[order[p]];
    ch.local[p] = local[order[p]];
    ch.where[order[p]] = std::uint32_t(p);  // channel c's segment k was pushed at begin[c] + k
  }
  ch.data = std::move(data);
}

// Segment of a channel (its k-th block at data[where[b + k]·B]) whose [lo, hi) holds `frame`,
// starting from the cursor: a short walk when playback moves a segment or two, a binary search
// otherwise.  The segments tile (−∞, +∞), so one always answers.
template <Real T, std::size_t B>
std::uint32_t find_segment(const T* data, const std::uint32_t* where, std::uint32_t count, T frame,
                           std::uint32_t cursor) noexcept {
  const auto lo_of = [&](std::uint32_t k) { return data[std::size_t(where[k]) * B]; };
  const auto hi_of = [&](std::uint32_t k) { return data[std::size_t(where[k]) * B + 1]; };
  std::uint32_t k = std::min(cursor, count - 1);
  for (int step = 0; step < 2; ++step) {
    if (frame >= hi_of(k) && k + 1 < count) ++k;
    else if (frame < lo_of(k) && k > 0) --k;
  }
  if (frame >= lo_of(k) && frame < hi_of(k)) return k;
  std::uint32_t lo = 0, hi = count - 1;  // last segment with lo ≤ frame
  while (lo < hi) {
    const std::uint32_t mid = (lo + hi + 1) / 2;
    if (lo_of(mid) <= frame) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

// Copies block src into joint j's column of a kind's cache (groups of G joints, field-major).
template <Real T, std::size_t G, std::size_t B>
inline void put_block(const T* src, T* cache, std::size_t j) noexcept {
  T* dst = cache + (j / G) * B * G + j % G;
  for (std::size_t f = 0; f < B; ++f) dst[f * G] = src[f];
}

// Brings one kind's cache to `frame`.  Forward playback consumes the stream's next blocks (those
// whose lo ≤ frame, in time order: each replaces its channel's cached segment, the last one wins);
// backward playback, or a forward jump past more blocks than 16 per channel, finds each
// stale channel's segment from its cursor and repositions the stream.
template <Real T, std::size_t G, std::size_t B, class Channels>
inline void advance(const Channels& ch, std::size_t joints, T frame, T previous, std::size_t& next,
                    std::uint32_t* segment, T* cache) noexcept {
  const T* data = ch.data.data();
  const std::size_t n = ch.owner.size();
  if (frame >= previous) {
    const std::size_t limit = std::min(n, next + 16 * joints);
    std::size_t p = next;
    for (; p < limit && data[p * B] <= frame; ++p) {
      const std::uint32_t c = ch.owner[p];
      segment[c] = ch.local[p];
      put_block<T, G, B>(data + p * B, cache, c);
    }
    if (p == n || data[p * B] > frame) {
      next = p;
      return;
    }
  }
  for (std::size_t j = 0; j < joints; ++j) {
    if (ch.count[j] == 0) continue;  // a channel kept out of the stream (FCurveClip's cycling ones)
    const T* col = cache + (j / G) * B * G + j % G;
    if (frame >= col[0] && frame < col[G]) continue;  // cached [lo, hi) still holds frame
    const std::uint32_t k = find_segment<T, B>(data, ch.where.data() + ch.begin[j], ch.count[j], frame, segment[j]);
    segment[j] = k;
    put_block<T, G, B>(data + std::size_t(ch.where[ch.begin[j] + k]) * B, cache, j);
  }
  // First block whose lo > frame.
  std::size_t lo = 0, hi = n;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (data[mid * B] <= frame) lo = mid + 1;
    else hi = mid;
  }
  next = lo;
}
// SIMD helpers over V::size() joints' cached fields (field f at c + f·G, G joints per group).
template <class V>
[[gnu::always_inline]] inline V load(const typename V::value_type* p) noexcept {
  return V(p, stdx::element_aligned);
}
// u = clamp((frame − origin)·inv_length, 0, 1); finite because sample_rig keeps frame finite.
template <class V, std::size_t G>
[[gnu::always_inline]] inline V param(const typename V::value_type* c, V frame) noexcept {
  using T = typename V::value_type;
  return stdx::max(V(T(0)), stdx::min((frame - load<V>(c + 2 * G)) * load<V>(c + 3 * G), V(T(1))));
}
// ((c3·u + c2)·u + c1)·u + c0 for one axis.
template <class V, std::size_t G>
[[gnu::always_inline]] inline V cubic(const typename V::value_type* c, std::size_t axis, V u) noexcept {
  return ((load<V>(c + (13 + axis) * G) * u + load<V>(c + (10 + axis) * G)) * u + load<V>(c + (7 + axis) * G)) * u +
         load<V>(c + (4 + axis) * G);
}

// The lane arithmetic of sample_rig, std::experimental::native_simd<T>: for one cache group (the
// translation, rotation and scale fields of G = rig_group<T> joints, field f at t/r/s + f·G) and
// its first n ≤ G joints, writes res[0..2] translation xyz, res[3..6] rotation xyzw, res[7..9]
// scale xyz.  The benchmarks' xsimd and Highway kernels (bench/rig_lanes.hpp) implement the same
// call with the same operations in the same order, and evaluate() runs any of them.
template <Real T>
struct StdSimdLanes {
  [[gnu::always_inline]] inline void operator()(const T* tc, const T* rc, const T* sc, T frame, std::size_t n,
                                                T (*res)[rig_group<T>]) const noexcept {
    using V = stdx::native_simd<T>;
    constexpr std::size_t W = V::size(), G = rig_group<T>;
    static_assert(G % W == 0, "a cache group holds whole registers");
    const V f(frame), one(T(1));
    for (std::size_t s = 0; s < n; s += W) {
      {
        const V u = param<V, G>(tc + s, f);
        for (std::size_t axis = 0; axis < 3; ++axis) cubic<V, G>(tc + s, axis, u).copy_to(res[axis] + s, stdx::vector_aligned);
      }
      {
        const V u = param<V, G>(sc + s, f);
        for (std::size_t axis = 0; axis < 3; ++axis)
          cubic<V, G>(sc + s, axis, u).copy_to(res[7 + axis] + s, stdx::vector_aligned);
      }
      {
        const V u = param<V, G>(rc + s, f);
        const V v = one - u;
        const V omega2 = load<V>(rc + s + 12 * G), k = load<V>(rc + s + 13 * G);
        // slerp weights sin(vΩ)/sin Ω and sin(uΩ)/sin Ω = v·sinc(vΩ)/sinc Ω, u·sinc(uΩ)/sinc Ω.
        const V w0 = v * sinc_series<T>(v * v * omega2) * k;
        const V w1 = u * sinc_series<T>(u * u * omega2) * k;
        for (std::size_t c = 0; c < 4; ++c)
          (w0 * load<V>(rc + s + (4 + c) * G) + w1 * load<V>(rc + s + (8 + c) * G))
              .copy_to(res[3 + c] + s, stdx::vector_aligned);
      }
    }
  }
};

// The same lane arithmetic in Highway (src/tracks/rig_lanes_hwy.cpp; res is res[0] of a [10][G]
// array).  dynamic: HWY_DYNAMIC_DISPATCH over every x86 target compiled in (SSSE3 … AVX-512),
// chosen at run time — sample_rig<double> uses it when the flags give double 2 lanes; static: the build's baseline target (SCALAR,
// one lane, under the default SSE2 flags: Highway 1.0.3 has no SSE2 target), for the benchmarks.
void hwy_lanes_dynamic(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res) noexcept;
void hwy_lanes_dynamic(const double* tc, const double* rc, const double* sc, double frame, std::size_t n,
                       double* res) noexcept;
void hwy_lanes_static(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res) noexcept;
void hwy_lanes_static(const double* tc, const double* rc, const double* sc, double frame, std::size_t n,
                      double* res) noexcept;
// Highway's name of the static target and of the one dynamic dispatch picks ("AVX3", "SCALAR", …).
const char* hwy_static_target();
const char* hwy_dynamic_target();
// Tests and benchmarks: limit dynamic dispatch to AVX2 and below (a machine without AVX-512) when
// true, every target the CPU supports when false (Highway's SetSupportedTargetsForTest; global).
void hwy_limit_to_avx2(bool limit);

// hwy_lanes_dynamic / hwy_lanes_static as lanes for evaluate().
template <Real T>
struct HwyDynamicLanes {
  void operator()(const T* tc, const T* rc, const T* sc, T frame, std::size_t n, T (*res)[rig_group<T>]) const noexcept {
    hwy_lanes_dynamic(tc, rc, sc, frame, n, res[0]);
  }
};
template <Real T>
struct HwyStaticLanes {
  void operator()(const T* tc, const T* rc, const T* sc, T frame, std::size_t n, T (*res)[rig_group<T>]) const noexcept {
    hwy_lanes_static(tc, rc, sc, frame, n, res[0]);
  }
};

// sample_rig's first half: clamps frame to a finite value (NaN → −max; returned) and brings every
// channel's cached segment to it.
template <Real T>
T refresh(const RigClip<T>& clip, T frame, RigClipCursor<T>& cursor) noexcept {
  constexpr std::size_t B = RigClip<T>::block, G = rig_group<T>;
  const std::size_t J = clip.joints_;
  const std::size_t S = cursor.stride;
  static_assert(16 % G == 0, "the padded joint count is a multiple of 16");
  INBETWEEN_ASSERT(cursor.segment.size() == 3 * J && cursor.cache.size() == 3 * B * S);
  // A finite frame keeps u = (frame − origin)·0 finite on the constant end segments.
  const T big = std::numeric_limits<T>::max();
  frame = frame > -big ? (frame < big ? frame : big) : -big;  // NaN → −big
  for (std::size_t kind = 0; kind < 3; ++kind) {
    advance<T, G, B>(clip.kind_[kind], J, frame, cursor.time, cursor.next[kind], cursor.segment.data() + kind * J,
                     cursor.cache.data() + kind * B * S);
  }
  cursor.time = frame;
  return frame;
}

// sample_rig's second half: evaluates the refreshed cache at the (finite) frame group by group
// with `lanes` (StdSimdLanes or a benchmark's kernel) and writes the AoS poses.
template <Real T, class Lanes>
void evaluate(const RigClipCursor<T>& cursor, T frame, std::span<JointPose<T>> out, const Lanes& lanes) noexcept {
  constexpr std::size_t B = RigClip<T>::block, G = rig_group<T>;
  const std::size_t J = out.size();
  const std::size_t S = cursor.stride;
  INBETWEEN_ASSERT(J <= S && cursor.cache.size() == 3 * B * S);
  const T* tc = cursor.cache.data();
  const T* rc = tc + B * S;
  const T* sc = rc + B * S;
  for (std::size_t j0 = 0; j0 < J; j0 += G) {
    alignas(64) T res[10][G];
    const std::size_t g = j0 * B;  // this group's fields start at cache + (j0 / G)·B·G
    const std::size_t n = std::min(G, J - j0);
    lanes(tc + g, rc + g, sc + g, frame, n, res);
    for (std::size_t i = 0; i < n; ++i) {
      JointPose<T>& p = out[j0 + i];
      p.translation = Vec3<T>{res[0][i], res[1][i], res[2][i]};
      p.rotation = Quat<T>::from_xyzw(res[3][i], res[4][i], res[5][i], res[6][i]);
      p.scale = Vec3<T>{res[7][i], res[8][i], res[9][i]};
    }
  }
}
}  // namespace rig_detail

/// Compiles J joints' tracks (three spans of equal size J) into a RigClip.  Errors (Unsupported,
/// with the place {"translations"|"scales"|"rotations", joint[, "keys", i]}): spans of different
/// sizes (InvalidArgument), a Vec3 track whose extend mode is not constant, a rotation segment
/// other than step or slerp, or a slerp segment between keys on opposite sides of the 4-D sphere
/// (a long-way segment).
template <Real T>
Expected<RigClip<T>> build_rig_clip(std::span<const Track<Vec3<T>>> translations,
                                    std::span<const QuatTrack<T>> rotations,
                                    std::span<const Track<Vec3<T>>> scales) {
  if (translations.size() != rotations.size() || scales.size() != rotations.size()) {
    return Error{ErrorCode::InvalidArgument, "translations, rotations and scales need one track per joint each", ""};
  }
  RigClip<T> clip;
  clip.joints_ = rotations.size();
  const T inf_t = std::numeric_limits<T>::infinity();
  for (std::size_t j = 0; j < clip.joints_; ++j) {
    if (auto r = rig_detail::add_vec<T>(clip.kind_[0], translations[j], j, "translations"); !r) return r.error();
    if (auto r = rig_detail::add_vec<T>(clip.kind_[2], scales[j], j, "scales"); !r) return r.error();
    const QuatTrack<T>& q = rotations[j];
    auto& ch = clip.kind_[1];
    const auto f = q.frames();
    const auto k = q.keys();
    const std::size_t n = f.size();
    ch.begin.push_back(std::uint32_t(ch.data.size() / RigClip<T>::block));
    ch.count.push_back(std::uint32_t(n + 1));
    rig_detail::push_constant_rot<T>(ch.data, -inf_t, f[0], k[0]);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const QuatInterpolation mode = q.interpolation(i);
      if (mode != QuatInterpolation::step && mode != QuatInterpolation::slerp) {
        return Error{ErrorCode::Unsupported, "the runtime samples step and slerp rotation segments only", "",
                     {"rotations", j, "keys", i}};
      }
      if (mode == QuatInterpolation::slerp && dot(k[i], k[i + 1]) < T(0)) {
        return Error{ErrorCode::Unsupported, "a long-way slerp segment (keys on opposite sides) is not supported",
                     "", {"rotations", j, "keys", i + 1}};
      }
      if (mode == QuatInterpolation::step) {
        rig_detail::push_constant_rot<T>(ch.data, f[i], f[i + 1], k[i]);
        continue;
      }
      // Ω, the 4-D angle between the keys, in double from the stored keys: 2·atan2(|a − b|, |a + b|)
      // (accurate at every angle), in [0, π/2] because dot ≥ 0.
      const Quat<T>& a = k[i];
      const Quat<T>& b = k[i + 1];
      const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z, dw = double(a.w) - b.w;
      const double sx = double(a.x) + b.x, sy = double(a.y) + b.y, sz = double(a.z) + b.z, sw = double(a.w) + b.w;
      const double omega = 2 * std::atan2(std::sqrt(dx * dx + dy * dy + dz * dz + dw * dw),
                                          std::sqrt(sx * sx + sy * sy + sz * sz + sw * sw));
      const double inv_sinc = omega < 1e-8 ? 1.0 : omega / std::sin(omega);
      rig_detail::push_block<T>(ch.data, f[i], f[i + 1], f[i], T(1) / (f[i + 1] - f[i]),
                                {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w, T(omega * omega), T(inv_sinc)});
    }
    rig_detail::push_constant_rot<T>(ch.data, f[n - 1], inf_t, k[n - 1]);
  }
  for (auto& ch : clip.kind_) rig_detail::finish_stream<T, RigClip<T>::block>(ch);
  return clip;
}

/// Convenience overload for vectors.
template <Real T>
Expected<RigClip<T>> build_rig_clip(const std::vector<Track<Vec3<T>>>& translations,
                                    const std::vector<QuatTrack<T>>& rotations,
                                    const std::vector<Track<Vec3<T>>>& scales) {
  return build_rig_clip<T>(std::span<const Track<Vec3<T>>>(translations), std::span<const QuatTrack<T>>(rotations),
                           std::span<const Track<Vec3<T>>>(scales));
}

/// Samples every joint at `frame` into out (out.size() must equal clip.joints(), cursor made for
/// this clip by make_rig_clip_cursor), advancing the cursor.  Outside a channel's keys its end value
/// is held; NaN reads as −∞ (the first value), ±∞ as the end values.  noexcept, no allocation.
template <Real T>
void sample_rig(const RigClip<T>& clip, T frame, RigClipCursor<T>& cursor, std::span<JointPose<T>> out) noexcept {
  INBETWEEN_ASSERT(out.size() == clip.joints());
  frame = rig_detail::refresh(clip, frame, cursor);
  // Which SIMD (docs/runtime.md, measured per character): when the build's flags give double only
  // 2 lanes (SSE2, the default), Highway's dynamic dispatch to AVX-512/AVX2 at run time (1.3–1.9×
  // std::experimental::simd there); with AVX or wider flags std::experimental::simd, inlined (the
  // out-of-line Highway call per group then lost up to 20 %).  Float stays std::experimental::simd
  // (Highway gained 1.1–1.3× in the default build: the float kernel is bound by its stores).
  if constexpr (std::is_same_v<T, double> && rig_detail::stdx::native_simd<double>::size() < 4)
    rig_detail::evaluate(cursor, frame, out, rig_detail::HwyDynamicLanes<T>{});
  else
    rig_detail::evaluate(cursor, frame, out, rig_detail::StdSimdLanes<T>{});
}

}  // namespace inbetween
