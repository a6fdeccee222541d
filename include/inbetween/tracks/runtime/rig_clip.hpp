#pragma once
/// The tracks runtime (issue 12, "compile once, sample many channels per call"; compact layout,
/// issue 24): a RigClip is an immutable clip compiled from per-joint translation, rotation and
/// scale tracks.  Every channel is cut into segments that tile the whole frame line — a constant
/// segment before the first key, one per key interval, a constant segment after the last key —
/// and the segments of all channels are one time-sorted stream per kind (ozz-animation's key
/// stream), each in the smallest exact form: a key record (a line or slerp that starts at the
/// channel's previous end key stores only its end key, 1/length and, rotations, Ω² and 1/sinc Ω),
/// a hold (a constant segment; a constant channel is one hold for the whole clip), a full block
/// (cubic segments: power form), and dense groups (a frame where every channel of the kind starts
/// a key record of one length: the end keys field by field, 12 bytes per float Vec3 channel, 24
/// per rotation).  A RigClipCursor<T> keeps, per channel, the current segment's fields in
/// structure-of-arrays order (ozz-animation's "decompressed keys" cache); sample_rig() applies the
/// records and groups the frame reached and then evaluates all joints with SIMD: Highway's
/// run-time dispatch in the default SSE2 build (16 floats / 8 doubles per AVX-512 register, 8 / 4
/// with AVX2), std::experimental::native_simd, inlined, when the flags give a wider register;
/// docs/runtime.md ("RigClip", "Which SIMD", "The long clip against ozz-animation") has the layout
/// and the measurements.  Rotations
/// are exact slerp weights from an even polynomial: sin(uΩ)/sin(Ω) = u·sinc(uΩ)/sinc(Ω) with sinc's
/// Taylor series in (uΩ)², Ω ≤ π/2 (no trigonometry, no root, no division, no normalisation per
/// sample).
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
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>
#include <experimental/simd>
#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

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

// Cache fields per channel (field f of joint j at its kind's cache + (j / G)·fields·G + f·G + j % G):
// Vec3 lo (the u origin), 1/length, c0.xyz, c1.xyz and, when the clip has cubic segments
// (vec_fields_cubic), c2.xyz, c3.xyz of ((c3·u + c2)·u + c1)·u + c0, then the segment's end key
// p1.xyz (where a following key record starts; the lanes do not read it); rotations lo, 1/length,
// q0.xyzw, q1.xyzw, Ω², 1/sinc(Ω).  A full record's block holds the same fields.
inline constexpr std::size_t vec_fields_line = 11;
inline constexpr std::size_t vec_fields_cubic = 17;
inline constexpr std::size_t rot_fields = 12;

// Form of a stream record (the top two bits of Record::owner; the low 30 bits are the channel).
inline constexpr std::uint32_t rec_key = 0;           // from the channel's previous end key to v
inline constexpr std::uint32_t rec_hold = 1u << 30;   // the constant v
inline constexpr std::uint32_t rec_full = 2u << 30;   // a block of Stream::full
inline constexpr std::uint32_t rec_channel = (1u << 30) - 1;
// Stream::where of a segment in a dense group: this bit and the group's index.
inline constexpr std::uint32_t in_dense = 1u << 31;

// One segment of one channel in a kind's time-sorted stream: its start lo (its end is the start of
// the channel's next segment), for key records 1/length, its channel and form, and N scalars.
// Vec3 (N = 3): key — the end key's value (the segment is the line from the channel's previous end
// key p0: its power form c0 = p0, c1 = p1 − p0); hold — the value.  Rotation (N = 6): key — the
// end key xyzw, Ω² and 1/sinc(Ω) of the slerp from the previous end key; hold — the key xyzw.
// full: v[0]'s first 4 bytes are the block's index in Stream::full.  float: 24 bytes (Vec3), 36
// (rotation), against the 64 of a segment block before issue 24.
template <Real T, std::size_t N>
struct Record {
  T lo, inv_length;
  std::uint32_t owner;
  T v[N];
};

// One channel kind of a RigClip.  Segments that start on a frame where every channel of the kind
// starts a key record of the same length (a sampled clip: BVH, baked glTF) form a dense group:
// lo, 1/length and the N scalars of every channel, field by field (N·J scalars: 12 bytes per
// float Vec3 channel, 24 per rotation; no channel, no form).  Every other segment is a record of
// the general stream.  Both are sorted by lo, the order forward playback needs them in; channel c's
// segment k is where[begin[c] + k]: a position in records, or in_dense | its dense group.
template <Real T, std::size_t N>
struct Stream {
  std::vector<std::uint32_t> begin, count;  // per channel
  std::vector<std::uint32_t> where;         // per (channel, segment)
  std::vector<Record<T, N>> records;        // general stream order
  std::vector<T> dense_lo, dense_inv;       // per dense group
  std::vector<T> dense_v;                   // per dense group N·J scalars: v[a] of channel c at a·J + c
  std::vector<T> full;                      // the full records' blocks (rig_detail::apply)
  bool cubic = false;                       // Vec3: some segment is not a line (its blocks keep c2, c3)
  [[nodiscard]] std::size_t bytes() const noexcept {
    return (begin.size() + count.size() + where.size()) * sizeof(std::uint32_t) + records.size() * sizeof(Record<T, N>) +
           (dense_lo.size() + dense_inv.size() + dense_v.size() + full.size()) * sizeof(T);
  }
};
}  // namespace rig_detail

/// The caller-owned state of one playback stream of a RigClip (make it with make_rig_clip_cursor):
/// per channel its current segment and that segment's fields in SIMD-register order (groups of
/// rig_group<T> joints, field by field: ozz-animation's "decompressed keys" cache), per channel
/// kind the position in the clip's time-sorted record stream and dense groups.  Reusable,
/// copyable; one per character instance that plays the clip.
template <Real T>
struct RigClipCursor {
  std::vector<std::uint32_t> segment;  ///< per channel (T of all joints, then R, then S): segment index in its channel
  std::vector<T> cache;                ///< T, R, S fields × padded joints (filled by sample_rig; rig_detail::apply)
  std::size_t stride = 0;              ///< padded joint count (a multiple of 16)
  std::size_t vec_fields = 11;         ///< cache fields per Vec3 channel: 11 (lines only), 17 (cubic segments too)
  std::array<std::size_t, 3> next{};   ///< per kind: first general record not yet consumed (its lo > time)
  std::array<std::size_t, 3> next_dense{};  ///< per kind: first dense group not yet consumed
  T time = -std::numeric_limits<T>::infinity();  ///< frame of the last sample (clamped; −∞ before the first)
};

/// A compiled, immutable T+R+S clip of J joints (build it with build_rig_clip).
template <Real T>
class RigClip {
 public:
  /// Number of joints.
  [[nodiscard]] std::size_t joints() const noexcept { return joints_; }

  /// Bytes the clip holds (its arrays' elements; the object itself and allocator slack excluded).
  [[nodiscard]] std::size_t bytes() const noexcept {
    return translations_.bytes() + rotations_.bytes() + scales_.bytes();
  }

  /// Scalars per segment block of the layout before issue 24 (one 16-scalar block per segment), kept
  /// for source compatibility: the clip now holds compact records (rig_detail::Record, dense
  /// groups) and a cursor caches rig_detail::vec_fields_line / vec_fields_cubic fields per Vec3
  /// channel and rig_detail::rot_fields per rotation.
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

  std::size_t joints_ = 0;
  bool cubic_ = false;  // some Vec3 segment is not a line: the cursors' cache keeps c2 and c3
  rig_detail::Stream<T, 3> translations_, scales_;
  rig_detail::Stream<T, 6> rotations_;
};

/// A cursor before the clip's start (the first sample_rig fills every channel's cache).
template <Real T>
RigClipCursor<T> make_rig_clip_cursor(const RigClip<T>& clip) {
  RigClipCursor<T> ctx;
  ctx.stride = (clip.joints() + 15) / 16 * 16;
  ctx.segment.assign(3 * clip.joints(), ~std::uint32_t(0));  // none yet: the first record consumed is 0
  ctx.vec_fields = clip.cubic_ ? rig_detail::vec_fields_cubic : rig_detail::vec_fields_line;
  ctx.cache.assign((2 * ctx.vec_fields + rig_detail::rot_fields) * ctx.stride, T(0));
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

// Appends a record to a kind's stream (channel by channel while building; finish_records sorts).
template <Real T, std::size_t N>
void push_record(Stream<T, N>& ch, T lo, T hi, std::uint32_t form, std::uint32_t channel, std::initializer_list<T> v) {
  Record<T, N> r{lo, form == rec_key ? T(1) / (hi - lo) : T(0), form | channel, {}};
  std::copy(v.begin(), v.end(), r.v);
  ch.records.push_back(r);
}

// Appends a full record and its block: lo, 1/length, then the coefficients (rig_detail::apply's
// fields) and, Vec3, the end key.
template <Real T, std::size_t N>
void push_full(Stream<T, N>& ch, std::uint32_t channel, T lo, T inv_length, std::initializer_list<T> coef) {
  Record<T, N> r{lo, T(0), rec_full | channel, {}};
  const auto index = std::uint32_t(ch.full.size() / (2 + coef.size()));
  std::memcpy(r.v, &index, sizeof index);
  ch.records.push_back(r);
  ch.full.push_back(lo);
  ch.full.push_back(inv_length);
  for (const T c : coef) ch.full.push_back(c);
}

// Compiles one Vec3 track into the kind's records; Unsupported for extend modes other than constant.
// A constant channel (one key, or equal values and zero tangents) is one hold over (lowest, +∞); a
// stepped segment a hold; a line (its power form's c2 and c3 are rounding residue: |c2| + |c3| ≤
// 8ε·(|p0| + |p1| + |m0| + |m1|) per axis, so the line stays within a few ulp of the cubic) a key
// record when it starts where the previous record ended, else (after a step) a full block
// c0 = p0, c1 = p1 − p0, c2 = c3 = 0; any other segment a full block of its power form.  Full
// blocks end with the end key p1 (a following key record starts there).
template <Real T>
Expected<bool> add_vec(Stream<T, 3>& ch, const Track<Vec3<T>>& tr, std::size_t joint, const char* kind) {
  if (tr.extend_before() != TrackExtend::constant || tr.extend_after() != TrackExtend::constant) {
    return Error{ErrorCode::unsupported,
                 std::string("the runtime holds the end values outside the keys; this ") + kind +
                     " track extends otherwise (use TrackExtend::constant)", {std::string(kind), joint}};
  }
  const auto f = tr.frames();
  const auto v = tr.values();
  const auto in = tr.in_tangents();
  const auto out = tr.out_tangents();
  const std::size_t n = f.size();
  const T inf_t = std::numeric_limits<T>::infinity(), lowest = std::numeric_limits<T>::lowest();
  const auto c = std::uint32_t(ch.begin.size());
  const std::size_t first = ch.records.size();
  ch.begin.push_back(std::uint32_t(first));
  const auto hold = [&](T lo, T hi, const Vec3<T>& x) { push_record<T, 3>(ch, lo, hi, rec_hold, c, {x.x, x.y, x.z}); };
  const Vec3<T> zero{};
  bool constant = true;
  for (std::size_t i = 0; i < n && constant; ++i) constant = v[i] == v[0] && in[i] == zero && out[i] == zero;
  if (constant) {
    hold(lowest, inf_t, v[0]);
    ch.count.push_back(1);
    return true;
  }
  hold(lowest, f[0], v[0]);
  Vec3<T> last = v[0];
  const T eps8 = T(8) * std::numeric_limits<T>::epsilon();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const T h = f[i + 1] - f[i];
    if (tr.stepped(i)) {
      hold(f[i], f[i + 1], v[i]);
      last = v[i];
      continue;
    }
    // Hermite p0, p1, m0 = out_i·h, m1 = in_{i+1}·h to power form.
    const Vec3<T> p0 = v[i], p1 = v[i + 1], m0 = out[i] * h, m1 = in[i + 1] * h;
    const Vec3<T> c2 = (p1 - p0) * T(3) - m0 * T(2) - m1, c3 = (p0 - p1) * T(2) + m0 + m1;
    bool line = true;
    for (int a = 0; a < 3 && line; ++a)
      line = std::abs(c2[a]) + std::abs(c3[a]) <= eps8 * (std::abs(p0[a]) + std::abs(p1[a]) + std::abs(m0[a]) + std::abs(m1[a]));
    if (line && last == p0) {
      push_record<T, 3>(ch, f[i], f[i + 1], rec_key, c, {p1.x, p1.y, p1.z});
    } else if (line) {
      const Vec3<T> d = p1 - p0;
      push_full<T, 3>(ch, c, f[i], T(1) / h,
                      {p0.x, p0.y, p0.z, d.x, d.y, d.z, T(0), T(0), T(0), T(0), T(0), T(0), p1.x, p1.y, p1.z});
    } else {
      push_full<T, 3>(ch, c, f[i], T(1) / h,
                      {p0.x, p0.y, p0.z, m0.x, m0.y, m0.z, c2.x, c2.y, c2.z, c3.x, c3.y, c3.z, p1.x, p1.y, p1.z});
      ch.cubic = true;
    }
    last = p1;
  }
  hold(f[n - 1], inf_t, v[n - 1]);
  ch.count.push_back(std::uint32_t(ch.records.size() - first));
  return true;
}

// Sorts a kind's records (pushed channel by channel) into stream order, moves the frames where
// every channel starts a key record of one length into dense groups, and fills where.
template <Real T, std::size_t N>
void finish_records(Stream<T, N>& ch) {
  const std::size_t n = ch.records.size(), J = ch.begin.size();
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = std::uint32_t(i);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Record<T, N>&ra = ch.records[a], &rb = ch.records[b];
    return ra.lo < rb.lo || (ra.lo == rb.lo && (ra.owner & rec_channel) < (rb.owner & rec_channel));
  });
  std::vector<Record<T, N>> records;
  ch.where.assign(n, 0);
  for (std::size_t p = 0; p < n;) {
    std::size_t e = p + 1;
    while (e < n && ch.records[order[e]].lo == ch.records[order[p]].lo) ++e;
    bool dense = e - p == J;  // sorted by channel: channels 0 … J − 1 in order
    for (std::size_t q = p; q < e && dense; ++q) {
      const Record<T, N>& r = ch.records[order[q]];
      dense = (r.owner & ~rec_channel) == rec_key && r.inv_length == ch.records[order[p]].inv_length;
    }
    if (dense) {
      const auto d = std::uint32_t(ch.dense_lo.size());
      ch.dense_lo.push_back(ch.records[order[p]].lo);
      ch.dense_inv.push_back(ch.records[order[p]].inv_length);
      ch.dense_v.resize(ch.dense_v.size() + N * J);
      T* v = ch.dense_v.data() + std::size_t(d) * N * J;
      for (std::size_t c = 0; c < J; ++c) {
        for (std::size_t a = 0; a < N; ++a) v[a * J + c] = ch.records[order[p + c]].v[a];
        ch.where[order[p + c]] = in_dense | d;  // channel c's segment k was pushed at begin[c] + k
      }
    } else {
      for (std::size_t q = p; q < e; ++q) {
        ch.where[order[q]] = std::uint32_t(records.size());
        records.push_back(ch.records[order[q]]);
      }
    }
    p = e;
  }
  ch.records = std::move(records);
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

// One segment as the refresh reads it: start, 1/length, form, its N scalars (v[a·stride]).
template <Real T>
struct SegmentView {
  T lo, inv_length;
  std::uint32_t form;
  const T* v;
  std::size_t stride;
};

// Channel c's segment k.
template <Real T, std::size_t N>
SegmentView<T> segment_view(const Stream<T, N>& ch, std::size_t c, std::uint32_t k) noexcept {
  const std::uint32_t w = ch.where[ch.begin[c] + k];
  if (w & in_dense) {
    const std::size_t d = w & ~in_dense, J = ch.begin.size();
    return {ch.dense_lo[d], ch.dense_inv[d], rec_key, ch.dense_v.data() + d * N * J + c, J};
  }
  const Record<T, N>& r = ch.records[w];
  return {r.lo, r.inv_length, r.owner & ~rec_channel, r.v, 1};
}

// Start of channel c's segment k, +∞ past its last.
template <Real T, std::size_t N>
T segment_lo(const Stream<T, N>& ch, std::size_t c, std::uint32_t k) noexcept {
  if (k >= ch.count[c]) return std::numeric_limits<T>::infinity();
  const std::uint32_t w = ch.where[ch.begin[c] + k];
  return (w & in_dense) ? ch.dense_lo[w & ~in_dense] : ch.records[w].lo;
}

// Segment of channel c whose [lo, hi) holds `frame`, starting from the cursor: a short walk when
// playback moves a segment or two, a binary search otherwise.  The segments tile (lowest, +∞),
// and frame is finite, so one always answers.
template <Real T, std::size_t N>
std::uint32_t find_record(const Stream<T, N>& ch, std::size_t c, T frame, std::uint32_t cursor) noexcept {
  const std::uint32_t count = ch.count[c];
  std::uint32_t k = std::min(cursor, count - 1);
  for (int step = 0; step < 2; ++step) {
    if (frame >= segment_lo(ch, c, k + 1) && k + 1 < count) ++k;
    else if (frame < segment_lo(ch, c, k) && k > 0) --k;
  }
  if (frame >= segment_lo(ch, c, k) && frame < segment_lo(ch, c, k + 1)) return k;
  std::uint32_t lo = 0, hi = count - 1;  // last segment with lo ≤ frame
  while (lo < hi) {
    const std::uint32_t mid = (lo + hi + 1) / 2;
    if (segment_lo(ch, c, mid) <= frame) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

// Writes segment s into its channel's cache column col (field f at col[f·G]); F fields per channel.
// key: lo, 1/length and, Vec3, from the cached end key p1: c0 = p1, c1 = v − p1 (c2 = c3 = 0 in the
// cubic layout), p1 = v; rotation: q0 = the cached q1 (the previous segment's end key), q1 = v, Ω²,
// 1/sinc Ω.  hold: 1/length 0 (u = 0): Vec3 c0 = p1 = v (the other coefficients are multiplied by
// u = 0); rotation q0 = q1 = v, Ω² = 0, 1/sinc = 1 (weights 1 and 0).  full: the block's F fields.
template <Real T, std::size_t G, std::size_t N, std::size_t F>
[[gnu::always_inline]] inline void apply(const SegmentView<T>& s, const T* full, T* col) noexcept {
  const T* v = s.v;
  const std::size_t st = s.stride;
  if (s.form == rec_key) {
    col[0] = s.lo;
    col[G] = s.inv_length;
    if constexpr (N == 3) {
      for (std::size_t a = 0; a < 3; ++a) {
        const T p = col[(F - 3 + a) * G];
        col[(2 + a) * G] = p;
        col[(5 + a) * G] = v[a * st] - p;
        if constexpr (F == vec_fields_cubic) col[(8 + a) * G] = col[(11 + a) * G] = T(0);
        col[(F - 3 + a) * G] = v[a * st];
      }
    } else {
      for (std::size_t a = 0; a < 4; ++a) {
        col[(2 + a) * G] = col[(6 + a) * G];
        col[(6 + a) * G] = v[a * st];
      }
      col[10 * G] = v[4 * st];
      col[11 * G] = v[5 * st];
    }
  } else if (s.form == rec_hold) {
    col[0] = s.lo;
    col[G] = T(0);
    if constexpr (N == 3) {
      for (std::size_t a = 0; a < 3; ++a) col[(2 + a) * G] = col[(F - 3 + a) * G] = v[a];
    } else {
      for (std::size_t a = 0; a < 4; ++a) col[(2 + a) * G] = col[(6 + a) * G] = v[a];
      col[10 * G] = T(0);
      col[11 * G] = T(1);
    }
  } else {
    std::uint32_t index;
    std::memcpy(&index, v, sizeof index);
    const T* src = full + std::size_t(index) * F;
    for (std::size_t f = 0; f < F; ++f) col[f * G] = src[f];
  }
}

// A dense group d: every channel's key record at once, field by field over cache groups of G
// joints (contiguous in the cache and in dense_v: loops the compiler vectorises).
template <Real T, std::size_t G, std::size_t N, std::size_t F>
inline void apply_dense(const Stream<T, N>& ch, std::size_t d, T* cache) noexcept {
  const std::size_t J = ch.begin.size();
  const T lo = ch.dense_lo[d], inv = ch.dense_inv[d];
  const T* v = ch.dense_v.data() + d * N * J;
  for (std::size_t j0 = 0; j0 < J; j0 += G) {
    T* g = cache + j0 * F;  // group j0 / G
    const T* gv = v + j0;
    const std::size_t n = std::min(G, J - j0);
    for (std::size_t i = 0; i < n; ++i) g[i] = lo;
    for (std::size_t i = 0; i < n; ++i) g[G + i] = inv;
    if constexpr (N == 3) {
      for (std::size_t a = 0; a < 3; ++a) {
        T* c0 = g + (2 + a) * G;
        T* c1 = g + (5 + a) * G;
        T* p1 = g + (F - 3 + a) * G;
        const T* va = gv + a * J;
        for (std::size_t i = 0; i < n; ++i) {
          const T p = p1[i];
          c0[i] = p;
          c1[i] = va[i] - p;
          p1[i] = va[i];
        }
        if constexpr (F == vec_fields_cubic) {
          for (std::size_t i = 0; i < n; ++i) g[(8 + a) * G + i] = T(0);
          for (std::size_t i = 0; i < n; ++i) g[(11 + a) * G + i] = T(0);
        }
      }
    } else {
      for (std::size_t a = 0; a < 4; ++a) {
        T* q0 = g + (2 + a) * G;
        T* q1 = g + (6 + a) * G;
        const T* va = gv + a * J;
        for (std::size_t i = 0; i < n; ++i) q0[i] = q1[i];
        for (std::size_t i = 0; i < n; ++i) q1[i] = va[i];
      }
      for (std::size_t i = 0; i < n; ++i) g[10 * G + i] = gv[4 * J + i];
      for (std::size_t i = 0; i < n; ++i) g[11 * G + i] = gv[5 * J + i];
    }
  }
}

// Brings one kind's cache (F fields per channel) to `frame`.  Forward playback consumes the next
// dense groups and general records whose lo ≤ frame, in time order (each is its channel's next
// segment); backward playback, or a forward jump past more than 16 segments per channel, finds
// each stale channel's segment from its cursor (a key record's start by applying the channel's
// previous segment first) and repositions both streams.
template <Real T, std::size_t G, std::size_t N, std::size_t F>
inline void advance(const Stream<T, N>& ch, std::size_t joints, T frame, T previous, std::size_t& next,
                    std::size_t& next_dense, std::uint32_t* segment, T* cache) noexcept {
  const Record<T, N>* records = ch.records.data();
  const T* full = ch.full.data();
  const std::size_t n = ch.records.size(), nd = ch.dense_lo.size();
  const T past = std::numeric_limits<T>::infinity();
  if (frame >= previous) {
    std::size_t budget = 16 * joints;
    std::size_t p = next, d = next_dense;
    for (;;) {
      const T lg = p < n ? records[p].lo : past, ld = d < nd ? ch.dense_lo[d] : past;
      if (std::min(lg, ld) > frame || budget < joints) break;
      if (ld <= lg) {
        apply_dense<T, G, N, F>(ch, d, cache);
        for (std::size_t c = 0; c < joints; ++c) ++segment[c];
        ++d;
        budget -= joints;
      } else {
        const std::uint32_t c = records[p].owner & rec_channel;
        ++segment[c];
        apply<T, G, N, F>({records[p].lo, records[p].inv_length, records[p].owner & ~rec_channel, records[p].v, 1}, full,
                          cache + (c / G) * F * G + c % G);
        ++p;
        --budget;
      }
    }
    next = p;
    next_dense = d;
    if (std::min(p < n ? records[p].lo : past, d < nd ? ch.dense_lo[d] : past) > frame) return;
  }
  for (std::size_t j = 0; j < joints; ++j) {
    const std::uint32_t s = segment[j];
    if (s < ch.count[j] && frame >= segment_lo(ch, j, s) && frame < segment_lo(ch, j, s + 1)) continue;  // still holds
    T* col = cache + (j / G) * F * G + j % G;
    const std::uint32_t k = find_record(ch, j, frame, s);
    segment[j] = k;
    const SegmentView<T> view = segment_view(ch, j, k);
    if (view.form == rec_key) apply<T, G, N, F>(segment_view(ch, j, k - 1), full, col);
    apply<T, G, N, F>(view, full, col);
  }
  // First general record and first dense group whose lo > frame.
  next = std::size_t(std::upper_bound(records, records + n, frame, [](T f, const Record<T, N>& r) { return f < r.lo; }) - records);
  next_dense = std::size_t(std::upper_bound(ch.dense_lo.begin(), ch.dense_lo.end(), frame) - ch.dense_lo.begin());
}
// SIMD helpers over V::size() joints' cached fields (field f at c + f·G, G joints per group).
template <class V>
[[gnu::always_inline]] inline V load(const typename V::value_type* p) noexcept {
  return V(p, stdx::element_aligned);
}
// u = clamp((frame − lo)·inv_length, 0, 1); finite because sample_rig keeps frame finite and
// every cached lo is finite (the first segment starts at the lowest finite value, not −∞).
template <class V, std::size_t G>
[[gnu::always_inline]] inline V param(const typename V::value_type* c, V frame) noexcept {
  using T = typename V::value_type;
  return stdx::max(V(T(0)), stdx::min((frame - load<V>(c)) * load<V>(c + G), V(T(1))));
}
// One axis of a Vec3 channel: c1·u + c0 (Cubic false: the clip's Vec3 segments are all lines),
// ((c3·u + c2)·u + c1)·u + c0 (Cubic).
template <class V, std::size_t G, bool Cubic>
[[gnu::always_inline]] inline V vec_axis(const typename V::value_type* c, std::size_t axis, V u) noexcept {
  if constexpr (Cubic)
    return ((load<V>(c + (11 + axis) * G) * u + load<V>(c + (8 + axis) * G)) * u + load<V>(c + (5 + axis) * G)) * u +
           load<V>(c + (2 + axis) * G);
  else
    return load<V>(c + (5 + axis) * G) * u + load<V>(c + (2 + axis) * G);
}

// The lane arithmetic of sample_rig, std::experimental::native_simd<T>: for one cache group (the
// translation, rotation and scale fields of G = rig_group<T> joints, field f at t/r/s + f·G, the
// layout of apply()) and its first n ≤ G joints, writes res[0..2] translation xyz, res[3..6]
// rotation xyzw, res[7..9] scale xyz; Cubic: the Vec3 channels have c2 and c3.  The benchmarks'
// xsimd and Highway kernels (bench/rig_lanes.hpp) implement the same call with the same
// operations in the same order, and evaluate() runs any of them.
template <Real T>
struct StdSimdLanes {
  template <bool Cubic>
  [[gnu::always_inline]] inline void operator()(const T* tc, const T* rc, const T* sc, T frame, std::size_t n,
                                                T (*res)[rig_group<T>], std::bool_constant<Cubic>) const noexcept {
    using V = stdx::native_simd<T>;
    constexpr std::size_t W = V::size(), G = rig_group<T>;
    static_assert(G % W == 0, "a cache group holds whole registers");
    const V f(frame), one(T(1));
    for (std::size_t s = 0; s < n; s += W) {
      {
        const V u = param<V, G>(tc + s, f);
        for (std::size_t axis = 0; axis < 3; ++axis)
          vec_axis<V, G, Cubic>(tc + s, axis, u).copy_to(res[axis] + s, stdx::vector_aligned);
      }
      {
        const V u = param<V, G>(sc + s, f);
        for (std::size_t axis = 0; axis < 3; ++axis)
          vec_axis<V, G, Cubic>(sc + s, axis, u).copy_to(res[7 + axis] + s, stdx::vector_aligned);
      }
      {
        const V u = param<V, G>(rc + s, f);
        const V v = one - u;
        const V omega2 = load<V>(rc + s + 10 * G), k = load<V>(rc + s + 11 * G);
        // slerp weights sin(vΩ)/sin Ω and sin(uΩ)/sin Ω = v·sinc(vΩ)/sinc Ω, u·sinc(uΩ)/sinc Ω.
        const V w0 = v * sinc_series<T>(v * v * omega2) * k;
        const V w1 = u * sinc_series<T>(u * u * omega2) * k;
        for (std::size_t c = 0; c < 4; ++c)
          (w0 * load<V>(rc + s + (2 + c) * G) + w1 * load<V>(rc + s + (6 + c) * G))
              .copy_to(res[3 + c] + s, stdx::vector_aligned);
      }
    }
  }
};

// The same lane arithmetic in Highway (src/tracks/rig_lanes_hwy.cpp; res is res[0] of a [10][G]
// array).  dynamic: HWY_DYNAMIC_DISPATCH over every x86 target compiled in (SSSE3 … AVX-512),
// chosen at run time — sample_rig uses it when the flags give T fewer than 4 (double) or 8 (float)
// lanes; static: the build's baseline target (SCALAR, one lane, under the default SSE2 flags:
// Highway 1.0.3 has no SSE2 target), for the benchmarks.  cubic: as StdSimdLanes' Cubic.
void hwy_lanes_dynamic(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res,
                       bool cubic) noexcept;
void hwy_lanes_dynamic(const double* tc, const double* rc, const double* sc, double frame, std::size_t n,
                       double* res, bool cubic) noexcept;
void hwy_lanes_static(const float* tc, const float* rc, const float* sc, float frame, std::size_t n, float* res,
                      bool cubic) noexcept;
void hwy_lanes_static(const double* tc, const double* rc, const double* sc, double frame, std::size_t n,
                      double* res, bool cubic) noexcept;
// Highway's name of the static target and of the one dynamic dispatch picks ("AVX3", "SCALAR", …).
const char* hwy_static_target();
const char* hwy_dynamic_target();
// Tests and benchmarks: limit dynamic dispatch to AVX2 and below (a machine without AVX-512) when
// true, every target the CPU supports when false (Highway's SetSupportedTargetsForTest; global).
void hwy_limit_to_avx2(bool limit);

// hwy_lanes_dynamic / hwy_lanes_static as lanes for evaluate().
template <Real T>
struct HwyDynamicLanes {
  template <bool Cubic>
  void operator()(const T* tc, const T* rc, const T* sc, T frame, std::size_t n, T (*res)[rig_group<T>],
                  std::bool_constant<Cubic>) const noexcept {
    hwy_lanes_dynamic(tc, rc, sc, frame, n, res[0], Cubic);
  }
};
template <Real T>
struct HwyStaticLanes {
  template <bool Cubic>
  void operator()(const T* tc, const T* rc, const T* sc, T frame, std::size_t n, T (*res)[rig_group<T>],
                  std::bool_constant<Cubic>) const noexcept {
    hwy_lanes_static(tc, rc, sc, frame, n, res[0], Cubic);
  }
};

// sample_rig's first half: clamps frame to a finite value (NaN → −max; returned) and brings every
// channel's cached segment to it.
template <Real T>
T refresh(const RigClip<T>& clip, T frame, RigClipCursor<T>& cursor) noexcept {
  constexpr std::size_t G = rig_group<T>;
  const std::size_t J = clip.joints_;
  const std::size_t S = cursor.stride;
  const std::size_t Fv = cursor.vec_fields;
  static_assert(16 % G == 0, "the padded joint count is a multiple of 16");
  INBETWEEN_ASSERT(cursor.segment.size() == 3 * J && cursor.cache.size() == (2 * Fv + rot_fields) * S &&
                   Fv == (clip.cubic_ ? vec_fields_cubic : vec_fields_line));
  // A finite frame keeps u = (frame − lo)·0 finite on the constant end segments.
  const T big = std::numeric_limits<T>::max();
  frame = frame > -big ? (frame < big ? frame : big) : -big;  // NaN → −big
  T* tc = cursor.cache.data();
  T* rc = tc + Fv * S;
  T* sc = rc + rot_fields * S;
  std::uint32_t* segment = cursor.segment.data();
  const T prev = cursor.time;
  auto& next = cursor.next;
  auto& dense = cursor.next_dense;
  if (clip.cubic_) {
    advance<T, G, 3, vec_fields_cubic>(clip.translations_, J, frame, prev, next[0], dense[0], segment, tc);
    advance<T, G, 3, vec_fields_cubic>(clip.scales_, J, frame, prev, next[2], dense[2], segment + 2 * J, sc);
  } else {
    advance<T, G, 3, vec_fields_line>(clip.translations_, J, frame, prev, next[0], dense[0], segment, tc);
    advance<T, G, 3, vec_fields_line>(clip.scales_, J, frame, prev, next[2], dense[2], segment + 2 * J, sc);
  }
  advance<T, G, 6, rot_fields>(clip.rotations_, J, frame, prev, next[1], dense[1], segment + J, rc);
  cursor.time = frame;
  return frame;
}

// Writes n joints' results (res[0..2] translation xyz, res[3..6] rotation xyzw, res[7..9] scale xyz,
// rig_group<T> joints per row) as JointPose structs: with SSE, 4×4 (float) or 2×2 (double)
// transposes and whole-register stores (the 10 scalars of a pose are translation xyz, rotation
// wxyz, scale xyz in memory), joint by joint otherwise and for a tail.
template <Real T>
[[gnu::always_inline]] inline void write_poses(const T (*res)[rig_group<T>], std::size_t n, JointPose<T>* out) noexcept {
  std::size_t i = 0;
#if defined(__SSE2__)
  static_assert(std::is_standard_layout_v<JointPose<T>> && sizeof(JointPose<T>) == 10 * sizeof(T) &&
                    offsetof(JointPose<T>, rotation) == 3 * sizeof(T) && offsetof(JointPose<T>, scale) == 7 * sizeof(T),
                "JointPose is 10 packed scalars: translation, rotation (w first), scale");
  if constexpr (std::is_same_v<T, float>) {
    for (; i + 4 <= n; i += 4) {
      float* o = &out[i].translation.x;
      __m128 a = _mm_load_ps(res[0] + i), b = _mm_load_ps(res[1] + i), c = _mm_load_ps(res[2] + i), d = _mm_load_ps(res[6] + i);
      _MM_TRANSPOSE4_PS(a, b, c, d);  // joint k: t.x t.y t.z r.w
      __m128 e = _mm_load_ps(res[3] + i), f = _mm_load_ps(res[4] + i), g = _mm_load_ps(res[5] + i), h = _mm_load_ps(res[7] + i);
      _MM_TRANSPOSE4_PS(e, f, g, h);  // joint k: r.x r.y r.z s.x
      const __m128 sy = _mm_load_ps(res[8] + i), sz = _mm_load_ps(res[9] + i);
      const __m128 lo = _mm_unpacklo_ps(sy, sz), hi = _mm_unpackhi_ps(sy, sz);  // s.y s.z of joints 0, 1 | 2, 3
      _mm_storeu_ps(o, a);
      _mm_storeu_ps(o + 4, e);
      _mm_storel_pi(reinterpret_cast<__m64*>(o + 8), lo);
      _mm_storeu_ps(o + 10, b);
      _mm_storeu_ps(o + 14, f);
      _mm_storeh_pi(reinterpret_cast<__m64*>(o + 18), lo);
      _mm_storeu_ps(o + 20, c);
      _mm_storeu_ps(o + 24, g);
      _mm_storel_pi(reinterpret_cast<__m64*>(o + 28), hi);
      _mm_storeu_ps(o + 30, d);
      _mm_storeu_ps(o + 34, h);
      _mm_storeh_pi(reinterpret_cast<__m64*>(o + 38), hi);
    }
  } else {
    constexpr int rows[10] = {0, 1, 2, 6, 3, 4, 5, 7, 8, 9};  // memory order of a pose's scalars
    for (; i + 2 <= n; i += 2) {
      double* o = &out[i].translation.x;
      for (int k = 0; k < 10; k += 2) {
        const __m128d x = _mm_load_pd(res[rows[k]] + i), y = _mm_load_pd(res[rows[k + 1]] + i);
        _mm_storeu_pd(o + k, _mm_unpacklo_pd(x, y));
        _mm_storeu_pd(o + 10 + k, _mm_unpackhi_pd(x, y));
      }
    }
  }
#endif
  for (; i < n; ++i) {
    JointPose<T>& p = out[i];
    p.translation = Vec3<T>{res[0][i], res[1][i], res[2][i]};
    p.rotation = Quat<T>::from_xyzw(res[3][i], res[4][i], res[5][i], res[6][i]);
    p.scale = Vec3<T>{res[7][i], res[8][i], res[9][i]};
  }
}

// sample_rig's second half: evaluates the refreshed cache at the (finite) frame group by group
// with `lanes` (StdSimdLanes or a benchmark's kernel) and writes the AoS poses.  A kernel that
// takes no layout argument (a benchmark's that reads nothing) is called without it.
template <Real T, bool Cubic, class Lanes>
void evaluate_layout(const RigClipCursor<T>& cursor, T frame, std::span<JointPose<T>> out, const Lanes& lanes) noexcept {
  constexpr std::size_t G = rig_group<T>, Fv = Cubic ? vec_fields_cubic : vec_fields_line;
  const std::size_t J = out.size();
  const std::size_t S = cursor.stride;
  INBETWEEN_ASSERT(J <= S && cursor.cache.size() == (2 * Fv + rot_fields) * S);
  const T* tc = cursor.cache.data();
  const T* rc = tc + Fv * S;
  const T* sc = rc + rot_fields * S;
  for (std::size_t j0 = 0; j0 < J; j0 += G) {
    alignas(64) T res[10][G];
    const std::size_t n = std::min(G, J - j0);
    // This group's fields start at cache + (j0 / G)·F·G = cache + j0·F.
    if constexpr (std::is_invocable_v<const Lanes&, const T*, const T*, const T*, T, std::size_t, T (*)[G],
                                      std::bool_constant<Cubic>>)
      lanes(tc + j0 * Fv, rc + j0 * rot_fields, sc + j0 * Fv, frame, n, res, std::bool_constant<Cubic>{});
    else
      lanes(tc + j0 * Fv, rc + j0 * rot_fields, sc + j0 * Fv, frame, n, res);
    write_poses<T>(res, n, out.data() + j0);
  }
}
template <Real T, class Lanes>
void evaluate(const RigClipCursor<T>& cursor, T frame, std::span<JointPose<T>> out, const Lanes& lanes) noexcept {
  if (cursor.vec_fields == vec_fields_cubic) evaluate_layout<T, true>(cursor, frame, out, lanes);
  else evaluate_layout<T, false>(cursor, frame, out, lanes);
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
    return Error{ErrorCode::invalid_argument, "translations, rotations and scales need one track per joint each"};
  }
  RigClip<T> clip;
  clip.joints_ = rotations.size();
  const T inf_t = std::numeric_limits<T>::infinity(), lowest = std::numeric_limits<T>::lowest();
  using rig_detail::rec_full;
  using rig_detail::rec_hold;
  using rig_detail::rec_key;
  for (std::size_t j = 0; j < clip.joints_; ++j) {
    if (auto r = rig_detail::add_vec<T>(clip.translations_, translations[j], j, "translations"); !r) return r.error();
    if (auto r = rig_detail::add_vec<T>(clip.scales_, scales[j], j, "scales"); !r) return r.error();
    const QuatTrack<T>& q = rotations[j];
    auto& ch = clip.rotations_;
    const auto f = q.frames();
    const auto k = q.keys();
    const std::size_t n = f.size();
    const auto c = std::uint32_t(j);
    const std::size_t first = ch.records.size();
    ch.begin.push_back(std::uint32_t(first));
    const auto hold = [&](T lo, T hi, const Quat<T>& x) {
      rig_detail::push_record<T, 6>(ch, lo, hi, rec_hold, c, {x.x, x.y, x.z, x.w});
    };
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const QuatInterpolation mode = q.interpolation(i);
      if (mode != QuatInterpolation::step && mode != QuatInterpolation::slerp) {
        return Error{ErrorCode::unsupported, "the runtime samples step and slerp rotation segments only",
                     {"rotations", j, "keys", i}};
      }
      if (mode == QuatInterpolation::slerp && dot(k[i], k[i + 1]) < T(0)) {
        return Error{ErrorCode::unsupported, "a long-way slerp segment (keys on opposite sides) is not supported", {"rotations", j, "keys", i + 1}};
      }
    }
    // A constant channel (every key the same) is one hold over (−∞, +∞).
    const auto same = [](const Quat<T>& a, const Quat<T>& b) { return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z; };
    bool constant = true;
    for (std::size_t i = 1; i < n && constant; ++i) constant = same(k[i], k[0]);
    if (constant) {
      hold(lowest, inf_t, k[0]);
      ch.count.push_back(1);
      continue;
    }
    hold(lowest, f[0], k[0]);
    Quat<T> last = k[0];
    for (std::size_t i = 0; i + 1 < n; ++i) {
      if (q.interpolation(i) == QuatInterpolation::step) {
        hold(f[i], f[i + 1], k[i]);
        last = k[i];
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
      if (same(last, a)) {
        rig_detail::push_record<T, 6>(ch, f[i], f[i + 1], rec_key, c, {b.x, b.y, b.z, b.w, T(omega * omega), T(inv_sinc)});
      } else {  // after a step segment: the slerp starts at a key the previous record does not end on
        rig_detail::push_full<T, 6>(ch, c, f[i], T(1) / (f[i + 1] - f[i]),
                                    {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w, T(omega * omega), T(inv_sinc)});
      }
      last = b;
    }
    hold(f[n - 1], inf_t, k[n - 1]);
    ch.count.push_back(std::uint32_t(ch.records.size() - first));
  }
  clip.cubic_ = clip.translations_.cubic || clip.scales_.cubic;
  if (!clip.cubic_) {  // lines only: drop every Vec3 block's c2 and c3 (rig_detail::vec_fields_line)
    for (auto* ch : {&clip.translations_, &clip.scales_}) {
      constexpr std::size_t from = rig_detail::vec_fields_cubic;  // lo, 1/length, c0, c1, [c2, c3,] p1
      std::vector<T> full;
      for (std::size_t b = 0; b < ch->full.size(); b += from) {
        full.insert(full.end(), ch->full.begin() + std::ptrdiff_t(b), ch->full.begin() + std::ptrdiff_t(b + 8));
        full.insert(full.end(), ch->full.begin() + std::ptrdiff_t(b + 14), ch->full.begin() + std::ptrdiff_t(b + 17));
      }
      ch->full = std::move(full);
    }
  }
  rig_detail::finish_records(clip.translations_);
  rig_detail::finish_records(clip.rotations_);
  rig_detail::finish_records(clip.scales_);
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
  // Which SIMD (docs/runtime.md, measured per character): when the build's flags give only one
  // SSE register's lanes (SSE2, the default: 4 floats, 2 doubles), Highway's dynamic dispatch to
  // AVX-512/AVX2 at run time; with AVX or wider flags std::experimental::simd, inlined (the
  // out-of-line Highway call per group then lost up to 20 %).
  if constexpr (rig_detail::stdx::native_simd<T>::size() * sizeof(T) < 32)
    rig_detail::evaluate(cursor, frame, out, rig_detail::HwyDynamicLanes<T>{});
  else
    rig_detail::evaluate(cursor, frame, out, rig_detail::StdSimdLanes<T>{});
}

}  // namespace inbetween
