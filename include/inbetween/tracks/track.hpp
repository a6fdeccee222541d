#pragma once
/// A keyframed track for any vector-like value (a scalar, Vec2/3/4, or a colour held as Vec4
/// r, g, b, a): cubic Hermite segments whose tangents come from each key's tangent kind
/// (explicit Hermite, Catmull-Rom, Kochanek–Bartels, Maya's flat / linear / clamped / plateau /
/// stepped), and Maya-style behaviour before and after the keys (constant, linear, repeat,
/// repeat with offset, mirror; Maya's cycle, cycle with offset, oscillate).  docs/tracks.md gives each definition with its formula.
///
/// Sampling is noexcept and total.  A TrackCursor remembers the last segment, so sequential
/// playback costs O(1) per sample whatever the number of keys; without a cursor a sample is a
/// binary search.

#include <array>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <utility>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "inbetween/math/format.hpp"
#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/math/enum_names.hpp"

namespace inbetween {

/// How a key's tangents are obtained (slopes in value units per frame).
enum class TangentKind : std::uint8_t {
  explicit_hermite,  ///< in_tangent / out_tangent given by the key
  catmull_rom,       ///< (p[i+1] − p[i−1]) / (t[i+1] − t[i−1]); one-sided chord at the ends
  kochanek_bartels,  ///< TCB: tension, continuity, bias (see TrackKey)
  flat,              ///< zero slope on both sides
  linear,            ///< each side's slope is its own segment's chord slope
  clamped,           ///< Catmull-Rom, but flat when the key equals a neighbour (per component)
  plateau,           ///< Catmull-Rom limited so no segment overshoots its keys; flat at extremes and ends
  stepped,           ///< the segment after this key holds the key's value (in tangent: chord)
};

/// File and command-line names of the TangentKind enumerators, in declaration order.
inline constexpr std::array<std::string_view, 8> tangent_kind_names = {
    "hermite", "catmull_rom", "kochanek_bartels", "flat", "linear", "clamped", "plateau", "stepped"};
/// The name table of TangentKind (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<TangentKind>() noexcept {
  return tangent_kind_names;
}

/// Behaviour before the first or after the last key (Maya's pre/post infinity).
enum class TrackExtend : std::uint8_t {
  constant,      ///< the end key's value
  linear,        ///< continue along the end key's outer tangent
  repeat,         ///< repeat the keyed range (file name "cycle")
  repeat_offset,  ///< repeat, shifted by (last − first value) per cycle (file name "cycle_offset")
  mirror,         ///< repeat alternately forwards and backwards (file name "oscillate")
  /// Deprecated spellings, kept for one release (docs/conventions.md: one spelling per behaviour,
  /// shared with CycleMode).
  cycle [[deprecated("use TrackExtend::repeat")]] = repeat,
  cycle_offset [[deprecated("use TrackExtend::repeat_offset")]] = repeat_offset,  ///< deprecated
  oscillate [[deprecated("use TrackExtend::mirror")]] = mirror,                   ///< deprecated
};

/// File and command-line names of the TrackExtend enumerators, in declaration order.
inline constexpr std::array<std::string_view, 5> track_extend_names = {"constant", "linear", "cycle", "cycle_offset", "oscillate"};
/// The name table of TrackExtend (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<TrackExtend>() noexcept {
  return track_extend_names;
}

/// One authored key of a Track<V>.
template <class V>
struct TrackKey {
  using T = scalar_of<V>;  ///< scalar type of V (float or double)
  T frame{};                                     ///< time in frames (any real number)
  V value{};                                     ///< value at the key
  TangentKind tangent = TangentKind::catmull_rom;  ///< how this key's tangents are made
  V in_tangent{};                                ///< slope arriving (explicit_hermite only)
  V out_tangent{};                               ///< slope leaving (explicit_hermite only)
  T tension{};      ///< TCB tension in [−1, 1]: 1 → zero tangent, −1 → doubled (kochanek_bartels only)
  T continuity{};   ///< TCB continuity in [−1, 1]: ≠ 0 makes in and out tangents differ
  T bias{};         ///< TCB bias in [−1, 1]: > 0 weights the incoming chord, < 0 the outgoing
};

/// A remembered segment index that makes sequential sampling O(1); one per playback stream.
struct TrackCursor {
  std::size_t segment = 0;  ///< index of the key that starts the last segment used
};

/// A built track: keys with strictly increasing frames and resolved tangents.
template <class V>
class Track {
 public:
  using T = scalar_of<V>;  ///< scalar type of V (float or double)

  /// Number of keys (≥ 1).
  [[nodiscard]] std::size_t size() const noexcept { return frames_.size(); }
  /// Key frames, strictly increasing.
  [[nodiscard]] std::span<const T> frames() const noexcept { return frames_; }
  /// Key values.
  [[nodiscard]] std::span<const V> values() const noexcept { return values_; }
  /// Resolved incoming slope of each key (value per frame).
  [[nodiscard]] std::span<const V> in_tangents() const noexcept { return in_; }
  /// Resolved outgoing slope of each key (value per frame).
  [[nodiscard]] std::span<const V> out_tangents() const noexcept { return out_; }
  /// True when the segment after key i holds key i's value (TangentKind::stepped); i < size().
  [[nodiscard]] bool stepped(std::size_t i) const noexcept { return stepped_[i] != 0; }
  /// Behaviour before the first key.
  [[nodiscard]] TrackExtend extend_before() const noexcept { return before_; }
  /// Behaviour after the last key.
  [[nodiscard]] TrackExtend extend_after() const noexcept { return after_; }

  /// Value at `frame`; outside the keys the extend modes apply.  NaN gives the first value; ±inf
  /// acts as the largest finite frame of that sign.
  [[nodiscard]] V sample(T frame) const noexcept {
    TrackCursor cursor;
    return sample(frame, cursor, false);
  }
  /// Value at `frame`, starting the segment search from `cursor` and updating it: O(1) when
  /// frames advance (or go back) by less than a segment per call.
  [[nodiscard]] V sample(T frame, TrackCursor& cursor) const noexcept {
    // Fast path of sequential playback, inline at the call site: the frame is strictly inside
    // the cursor's segment (NaN fails both comparisons), so no extend mode, search or end-key case
    // applies.  The same power form as the full path below: identical values.
    const std::size_t i = cursor.segment;
    if (i + 1 < frames_.size() && frame > frames_[i] && frame < frames_[i + 1]) [[likely]]
      return segments_[i].value(frame - frames_[i]);
    return sample(frame, cursor, true);
  }
  /// out[i] = sample(frames[i], cursor); spans of equal size; no allocation.  Frames that fall in
  /// the same segment one after another are evaluated in a run (the segment's power form kept in
  /// registers, no per-frame search or extend checks); the values equal the single form's bit for
  /// bit, because both evaluate the same power form.
  void sample(std::span<const T> frames, std::span<V> out, TrackCursor& cursor) const noexcept {
    INBETWEEN_ASSERT(frames.size() == out.size());
    const std::size_t count = frames.size(), n = frames_.size();
    std::size_t k = 0;
    while (k < count) {
      out[k] = sample(frames[k], cursor, true);
      ++k;
      const std::size_t i = cursor.segment;
      if (i + 1 >= n) continue;
      const T t0 = frames_[i], t1 = frames_[i + 1];
      const Segment g = segments_[i];
      // Find the run first, then evaluate it in a counted loop the compiler can vectorise.
      std::size_t end = k;
      while (end < count && frames[end] > t0 && frames[end] < t1) ++end;
      for (; k < end; ++k) out[k] = g.value(frames[k] - t0);
    }
  }

 private:
  template <class W>
  friend Expected<Track<W>> build_track(std::span<const TrackKey<W>> keys, TrackExtend before, TrackExtend after);

  /// Segment i's Hermite cubic pre-converted to power form in v = (frame − t_i)/h (built once):
  /// ((a·v + b)·v + c)·v + d with a = 2(p₀ − p₁) + m₀ + m₁, b = 3(p₁ − p₀) − 2m₀ − m₁, c = m₀,
  /// d = p₀, m₀ = out_i·h, m₁ = in_{i+1}·h; a stepped segment is the constant p₀ (a = b = c = 0).
  struct Segment {
    V a{}, b{}, c{}, d{};  ///< power-form coefficients
    T inv_span{};          ///< 1/h (+inf when h is subnormal: v is then clamped to 1)
    /// The value at `offset` = frame − t_i in (0, h).
    [[gnu::always_inline]] V value(T offset) const noexcept {
      const T v = std::min(offset * inv_span, T(1));
      return ((a * v + b) * v + c) * v + d;
    }
  };

  Track() = default;  // only build_track() makes tracks: a Track always has ≥ 1 key
  V sample(T frame, TrackCursor& cursor, bool use_cursor) const noexcept;
  V evaluate_inside(T frame, TrackCursor& cursor, bool use_cursor) const noexcept;

  std::vector<T> frames_;
  std::vector<V> values_, in_, out_;
  std::vector<std::uint8_t> stepped_;
  std::vector<Segment> segments_;  // n − 1 power-form segments (sampling's working form)
  TrackExtend before_ = TrackExtend::constant, after_ = TrackExtend::constant;
};

/// Validates and builds a track: ≥ 1 key, finite frames strictly increasing, finite values,
/// tangents and TCB parameters, TCB parameters in [−1, 1], and finite resolved tangents (values
/// near the type's maximum a frame apart overflow the slope).  Error locations are structured:
/// {"keys", i, member} for a key's member ("frame", "value", "tension", …), {"keys", i} for the
/// key as a whole, {"keys"} when there is none.
template <class V>
[[nodiscard]] Expected<Track<V>> build_track(std::span<const TrackKey<V>> keys,
                                             TrackExtend before = TrackExtend::constant,
                                             TrackExtend after = TrackExtend::constant);

/// Convenience overload for a vector of keys.
template <class V>
[[nodiscard]] Expected<Track<V>> build_track(const std::vector<TrackKey<V>>& keys,
                                             TrackExtend before = TrackExtend::constant,
                                             TrackExtend after = TrackExtend::constant) {
  return build_track(std::span<const TrackKey<V>>(keys), before, after);
}

// ============================================================================ implementation
namespace track_detail {

template <class V>
V component_map(const V& a, auto&& f) {
  V r = a;
  for (int i = 0; i < PointTraits<V>::dim; ++i) PointTraits<V>::set(r, i, f(i));
  return r;
}


template <class V>
bool finite(const V& v) noexcept {
  for (int i = 0; i < PointTraits<V>::dim; ++i)
    if (!std::isfinite(PointTraits<V>::get(v, i))) return false;
  return true;
}

}  // namespace track_detail

template <class V>
Expected<Track<V>> build_track(std::span<const TrackKey<V>> keys, TrackExtend before, TrackExtend after) {
  using T = scalar_of<V>;
  using PT = PointTraits<V>;
  if (keys.empty()) return Error{ErrorCode::TooFewPoints, "a track needs at least one key", "", {"keys"}};
  const std::size_t n = keys.size();
  auto fail = [](ErrorCode code, std::string message, std::initializer_list<LocationStep> steps) {
    Error e{code, std::move(message), ""};
    e.prepend(steps);
    return e;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const auto& k = keys[i];
    if (!std::isfinite(k.frame)) return fail(ErrorCode::NotFinite, "frame is not finite", {"keys", i, "frame"});
    if (!track_detail::finite(k.value)) return fail(ErrorCode::NotFinite, "value is not finite", {"keys", i, "value"});
    if (!track_detail::finite(k.in_tangent)) return fail(ErrorCode::NotFinite, "a tangent is not finite", {"keys", i, "in_tangent"});
    if (!track_detail::finite(k.out_tangent)) return fail(ErrorCode::NotFinite, "a tangent is not finite", {"keys", i, "out_tangent"});
    for (auto [member, p] : {std::pair<const char*, T>{"tension", k.tension}, {"continuity", k.continuity}, {"bias", k.bias}}) {
      if (!(p >= T(-1) && p <= T(1))) return fail(ErrorCode::InvalidArgument, "must be in [-1, 1]", {"keys", i, std::string(member)});
    }
    if (i > 0 && !(k.frame > keys[i - 1].frame)) {
      return fail(ErrorCode::KeysNotIncreasing,
                  "frame " + shortest_text(double(k.frame)) + " is not after the previous key's frame " +
                      shortest_text(double(keys[i - 1].frame)) + " (keys must be sorted by strictly increasing frame)",
                  {"keys", i, "frame"});
    }
  }
  Track<V> tr;
  tr.before_ = before;
  tr.after_ = after;
  tr.frames_.resize(n);
  tr.values_.resize(n);
  tr.in_.assign(n, V{});
  tr.out_.assign(n, V{});
  tr.stepped_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    tr.frames_[i] = keys[i].frame;
    tr.values_[i] = keys[i].value;
  }
  // Chord slopes of the segments on each side (one-sided at the ends).
  auto chord = [&](std::size_t a, std::size_t b) -> V {
    return (tr.values_[b] - tr.values_[a]) / (tr.frames_[b] - tr.frames_[a]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const auto& k = keys[i];
    const bool has_prev = i > 0, has_next = i + 1 < n;
    if (n == 1) break;  // a single key: zero tangents
    const V left = has_prev ? chord(i - 1, i) : chord(i, i + 1);
    const V right = has_next ? chord(i, i + 1) : chord(i - 1, i);
    // Non-uniform Catmull-Rom: the chord over both neighbours; one-sided chord at the ends.
    const V cr = (has_prev && has_next) ? (tr.values_[i + 1] - tr.values_[i - 1]) / (tr.frames_[i + 1] - tr.frames_[i - 1])
                                        : (has_prev ? left : right);
    V in{}, out{};
    switch (k.tangent) {
      case TangentKind::explicit_hermite:
        in = k.in_tangent;
        out = k.out_tangent;
        break;
      case TangentKind::catmull_rom:
        in = out = cr;
        break;
      case TangentKind::kochanek_bartels: {
        // Kochanek & Bartels (1984) on chord slopes, which makes them valid for uneven key spacing:
        // out = ((1−t)(1+c)(1+b)/2)·left + ((1−t)(1−c)(1−b)/2)·right, in with c → −c.
        const T t = k.tension, c = k.continuity, b = k.bias;
        out = left * ((1 - t) * (1 + c) * (1 + b) / 2) + right * ((1 - t) * (1 - c) * (1 - b) / 2);
        in = left * ((1 - t) * (1 - c) * (1 + b) / 2) + right * ((1 - t) * (1 + c) * (1 - b) / 2);
        break;
      }
      case TangentKind::flat:
        break;
      case TangentKind::linear:
        in = left;
        out = right;
        break;
      case TangentKind::stepped:
        in = left;
        tr.stepped_[i] = 1;
        break;
      case TangentKind::clamped:
        in = out = track_detail::component_map(cr, [&](int d) {
          const T v = PT::get(tr.values_[i], d);
          const bool eq_prev = has_prev && PT::get(tr.values_[i - 1], d) == v;
          const bool eq_next = has_next && PT::get(tr.values_[i + 1], d) == v;
          return (eq_prev || eq_next) ? T(0) : PT::get(cr, d);
        });
        break;
      case TangentKind::plateau:
        in = out = track_detail::component_map(cr, [&](int d) {
          if (!has_prev || !has_next) return T(0);
          const T sl = PT::get(left, d), sr = PT::get(right, d);
          if (sl * sr <= T(0)) return T(0);  // extreme or flat neighbour
          // Fritsch–Carlson: |m| ≤ 3·min(|left|, |right|) keeps both Hermite segments monotone.
          const T m = PT::get(cr, d);
          const T lim = T(3) * std::min(std::abs(sl), std::abs(sr));
          return std::clamp(m, -lim, lim);
        });
        break;
    }
    // Finite keys can still give an infinite slope (values near the type's maximum a frame apart).
    if (!track_detail::finite(in) || !track_detail::finite(out)) {
      return fail(ErrorCode::NotFinite, "the tangent overflows (values too far apart for the key spacing)", {"keys", i});
    }
    tr.in_[i] = in;
    tr.out_[i] = out;
  }
  tr.segments_.resize(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    typename Track<V>::Segment& g = tr.segments_[i];
    const T h = tr.frames_[i + 1] - tr.frames_[i];
    g.inv_span = T(1) / h;
    g.d = tr.values_[i];
    if (tr.stepped_[i]) continue;  // the constant p₀
    const V p0 = tr.values_[i], p1 = tr.values_[i + 1];
    const V m0 = tr.out_[i] * h, m1 = tr.in_[i + 1] * h;
    g.a = (p0 - p1) * T(2) + m0 + m1;
    g.b = (p1 - p0) * T(3) - m0 * T(2) - m1;
    g.c = m0;
    // Finite keys and slopes can still overflow here (values near the type's maximum, or a slope
    // times a huge key spacing): reject, so that no built track evaluates to inf or NaN.
    if (!track_detail::finite(g.a) || !track_detail::finite(g.b) || !track_detail::finite(g.c))
      return fail(ErrorCode::NotFinite,
                  "the segment after this key overflows (values or tangents times the key spacing too large for the "
                  "scalar type)",
                  {"keys", i});
  }
  return tr;
}

template <class V>
V Track<V>::evaluate_inside(T frame, TrackCursor& cursor, bool use_cursor) const noexcept {
  const std::size_t n = frames_.size();
  // Segment i covers [frames_[i], frames_[i+1]); the last key's frame belongs to segment n − 2.
  std::size_t i = use_cursor ? std::min(cursor.segment, n - 2) : 0;
  if (use_cursor && frame >= frames_[i] && frame <= frames_[i + 1]) {
    // cursor hit
  } else if (use_cursor && i + 2 < n && frame >= frames_[i + 1] && frame <= frames_[i + 2]) {
    ++i;
  } else if (use_cursor && i > 0 && frame >= frames_[i - 1] && frame <= frames_[i]) {
    --i;
  } else {
    const auto it = std::upper_bound(frames_.begin(), frames_.end(), frame);
    i = std::size_t(it - frames_.begin());
    i = i == 0 ? 0 : std::min(i - 1, n - 2);
  }
  cursor.segment = i;
  const T t0 = frames_[i], t1 = frames_[i + 1];
  if (frame <= t0) return values_[i];
  if (frame >= t1) return values_[i + 1];
  return segments_[i].value(frame - t0);
}

template <class V>
V Track<V>::sample(T frame, TrackCursor& cursor, bool use_cursor) const noexcept {
  const std::size_t n = frames_.size();
  // Fast path of sequential playback: the frame is strictly inside the cursor's segment (NaN
  // fails both comparisons), so no extend mode, search or end-key case applies.
  if (use_cursor) {
    const std::size_t i = cursor.segment;
    if (i + 1 < n && frame > frames_[i] && frame < frames_[i + 1]) [[likely]]
      return segments_[i].value(frame - frames_[i]);
  }
  if (std::isnan(frame) || n == 1) return values_[0];
  // ±inf acts as the largest finite frame: linear extension would give 0·inf and the cycle modes
  // inf − inf, both NaN.
  if (std::isinf(frame)) frame = std::copysign(std::numeric_limits<T>::max(), frame);
  const T first = frames_[0], last = frames_[n - 1];
  const T span = last - first;
  if (frame < first || frame > last) {
    const bool is_before = frame < first;
    const TrackExtend mode = is_before ? before_ : after_;
    switch (mode) {
      case TrackExtend::constant:
        return is_before ? values_[0] : values_[n - 1];
      case TrackExtend::linear:
        // A stepped end key holds its value (a branch, not a factor 0: 0·inf is NaN far out).
        if (is_before) return stepped_[0] ? values_[0] : values_[0] + in_[0] * (frame - first);
        return stepped_[n - 1] ? values_[n - 1] : values_[n - 1] + out_[n - 1] * (frame - last);
      case TrackExtend::repeat:
      case TrackExtend::repeat_offset:
      case TrackExtend::mirror: {
        const T rel = frame - first;
        // Cycle number (…, −1 before, 1, 2 … after).  Keys very close together and a far frame
        // overflow it (1e9 / 1e-300): it then acts as ±max, so a zero per-cycle offset stays 0
        // (not 0·inf = NaN) and a non-zero one saturates to ±inf.
        T k = std::floor(rel / span);
        if (std::isinf(k)) k = std::copysign(std::numeric_limits<T>::max(), k);
        T local = rel - k * span;            // in [0, span] up to rounding
        local = std::clamp(local, T(0), span);
        if (mode == TrackExtend::mirror && std::fmod(std::abs(k), T(2)) == T(1)) local = span - local;
        const V v = evaluate_inside(first + local, cursor, use_cursor);
        if (mode == TrackExtend::repeat_offset) return v + (values_[n - 1] - values_[0]) * k;
        return v;
      }
    }
  }
  return evaluate_inside(frame, cursor, use_cursor);
}

}  // namespace inbetween
