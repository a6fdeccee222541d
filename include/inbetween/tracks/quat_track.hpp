#pragma once
/// Orientation tracks: unit-quaternion keys interpolated per segment by step, slerp, the Bézier
/// quaternion spline of the texts (004 §3.3.1: automatic control points by "double" and
/// "bisect", distance factor k of Eq. 3.30, de Casteljau with slerp), Shoemake's squad, or the
/// glTF cubic form (4-D Hermite, then normalised).  docs/orientation.md derives each one.
///
/// Keys are normalised and their signs made continuous when the track is built (each key on the
/// same side of the 4-D sphere as its predecessor, so every segment takes the short way), unless
/// a key asks for the long way.  Exception: glTF cubic segments interpolate the keys and tangents
/// with the signs they were authored with, as the glTF specification and every glTF viewer do (a
/// flipped key would no longer match its tangents).  Sampling is noexcept and returns a unit
/// quaternion.

#include <array>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "inbetween/math/format.hpp"
#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/enum_names.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

/// Interpolation of the segment that starts at a quaternion key.
enum class QuatInterpolation : std::uint8_t {
  step,        ///< hold the key's orientation
  slerp,       ///< constant-speed great arc (Eq. 3.29)
  bezier,      ///< the Bézier quaternion spline with automatic control points (§3.3.1)
  squad,       ///< Shoemake's spherical quadrangle interpolation
  gltf_cubic,  ///< glTF CUBICSPLINE: 4-D Hermite with the keys' tangents, then normalised
};

/// File and command-line names of the QuatInterpolation enumerators, in declaration order.
inline constexpr std::array<std::string_view, 5> quat_interpolation_names = {"step", "slerp", "bezier", "squad", "gltf_cubic"};
/// The name table of QuatInterpolation (math/enum_names.hpp).
template <>
constexpr std::span<const std::string_view> enum_names<QuatInterpolation>() noexcept {
  return quat_interpolation_names;
}

/// One authored orientation key (48 bytes in double: a motion-capture clip has one per frame and
/// joint, so the glTF tangents that only gltf_cubic keys read live beside the keys, in
/// QuatKeyTangents).
template <Real T>
struct QuatKey {
  T frame{};                                                ///< time in frames
  Quat<T> value{};                                          ///< orientation (normalised when built)
  QuatInterpolation interpolation = QuatInterpolation::slerp;  ///< of the segment to the right
  bool long_way = false;  ///< the segment arriving at this key takes the long way round
};

/// The glTF CUBICSPLINE tangents of one key, per frame (read by gltf_cubic segments only): a
/// track's tangents are either none (all zero) or one per key, in the keys' order.
template <Real T>
struct QuatKeyTangents {
  Quat<T> in = Quat<T>::from_wxyz(0, 0, 0, 0);   ///< in-tangent, arriving at the key
  Quat<T> out = Quat<T>::from_wxyz(0, 0, 0, 0);  ///< out-tangent, leaving the key
  friend bool operator==(const QuatKeyTangents&, const QuatKeyTangents&) = default;
};

/// Options of the Bézier quaternion spline.
template <Real T>
struct QuatSplineOptions {
  /// k of Eq. 3.30: control points at fraction k of the constructed ones (1/3 makes the spline
  /// Catmull-Rom on the angle for keys about one axis).
  T distance_factor = T(1) / T(3);
  /// Scale each side's control point by its segment's share of the two neighbouring intervals, so
  /// the angular velocity is continuous in time with unevenly spaced keys (no effect when even).
  bool time_aware = true;
};

namespace quat_track_detail {

/// slerp of unit quaternions a → b along the arc exactly as given (the track chose the signs),
/// by the math module's slerp (constant speed, accurate for tiny angles, never NaN).
template <Real T>
Quat<T> slerp_unit(const Quat<T>& a, const Quat<T>& b, T u) noexcept {
  return slerp(a, b, u, SlerpOptions{.path = RotationPath::as_given});
}

/// (a + b)/|a + b|: slerp at ½ without trigonometry (the text's bisect); a or b if they cancel.
template <Real T>
Quat<T> bisect(const Quat<T>& a, const Quat<T>& b) noexcept {
  const Quat<T> s = a + b;
  const T n = norm(s);
  if (!(n > T(1e-12))) return slerp_unit(a, b, T(0.5));
  return s / n;
}

/// Eq. 3.31: r = 2(p·q)q − p, the reflection of p through q ("p to q, continued by as much").
template <Real T>
Quat<T> double_through(const Quat<T>& p, const Quat<T>& q) noexcept {
  return normalized(q * (T(2) * dot(p, q)) - p);
}

/// slerp(a, b, j/2^m) by m bisections (the text's fast evaluation at dyadic parameters).
template <Real T>
Quat<T> slerp_dyadic(Quat<T> a, Quat<T> b, std::uint64_t j, int m) noexcept {
  if (j == 0) return a;
  if (j >= (std::uint64_t(1) << m)) return b;
  for (int bit = m - 1; bit >= 0; --bit) {
    const Quat<T> mid = bisect(a, b);
    if ((j >> bit) & 1U) a = mid;
    else b = mid;
  }
  return a;  // after m halvings [a, b] spans [j/2^m, (j+1)/2^m]
}

}  // namespace quat_track_detail

/// A built orientation track.
template <Real T>
class QuatTrack {
 public:
  /// Number of keys (≥ 1).
  [[nodiscard]] std::size_t size() const noexcept { return frames_.size(); }
  /// Key frames (strictly increasing).
  [[nodiscard]] std::span<const T> frames() const noexcept { return frames_; }
  /// Keys after normalisation and sign continuity.
  [[nodiscard]] std::span<const Quat<T>> keys() const noexcept { return keys_; }
  /// Interpolation of the segment that starts at key i (i < size()).
  [[nodiscard]] QuatInterpolation interpolation(std::size_t i) const noexcept { return mode_[i]; }
  /// Bézier control point after key i (a'_i of §3.3.1, scaled by the distance factor); computed
  /// only for keys at a Bézier or squad segment, elsewhere the key itself.
  [[nodiscard]] const Quat<T>& control_after(std::size_t i) const noexcept { return after_.empty() ? keys_[i] : after_[i]; }
  /// Bézier control point before key i (b'_i); as control_after(), the key where not computed.
  [[nodiscard]] const Quat<T>& control_before(std::size_t i) const noexcept { return before_.empty() ? keys_[i] : before_[i]; }

  /// Orientation at `frame` (clamped to the keyed range); a unit quaternion.
  [[nodiscard]] Quat<T> sample(T frame) const noexcept {
    TrackCursor c;
    return sample(frame, c, false);
  }
  /// Orientation at `frame`, using and updating `cursor` (O(1) for sequential playback).
  [[nodiscard]] Quat<T> sample(T frame, TrackCursor& cursor) const noexcept { return sample(frame, cursor, true); }
  /// out[i] = sample(frames[i], cursor); equal sizes; no allocation.
  void sample(std::span<const T> frames, std::span<Quat<T>> out, TrackCursor& cursor) const noexcept {
    INBETWEEN_ASSERT(frames.size() == out.size());
    for (std::size_t i = 0; i < frames.size(); ++i) out[i] = sample(frames[i], cursor, true);
  }

  /// The point of segment i at u = j/2^m of the Bézier spline, computed by bisections only
  /// (the text's fast evaluation); i < size() − 1, 0 ≤ j ≤ 2^m, m ≤ 30.  The spline's control
  /// points exist at Bézier and squad segments only (control_after()).
  [[nodiscard]] Quat<T> bezier_dyadic(std::size_t i, std::uint64_t j, int m) const noexcept {
    INBETWEEN_ASSERT(i + 1 < keys_.size() && m >= 0 && m <= 30);
    using quat_track_detail::slerp_dyadic;
    const Quat<T>&a = control_after(i), &b = control_before(i + 1);
    const Quat<T> p1 = slerp_dyadic(keys_[i], a, j, m);
    const Quat<T> p2 = slerp_dyadic(a, b, j, m);
    const Quat<T> p3 = slerp_dyadic(b, keys_[i + 1], j, m);
    const Quat<T> p12 = slerp_dyadic(p1, p2, j, m);
    const Quat<T> p23 = slerp_dyadic(p2, p3, j, m);
    return slerp_dyadic(p12, p23, j, m);
  }

  /// The Bézier spline of segment i at parameter u in [0, 1] by de Casteljau with slerp.
  [[nodiscard]] Quat<T> bezier(std::size_t i, T u) const noexcept {
    using quat_track_detail::slerp_unit;
    const Quat<T>&a = control_after(i), &b = control_before(i + 1);
    const Quat<T> p1 = slerp_unit(keys_[i], a, u);
    const Quat<T> p2 = slerp_unit(a, b, u);
    const Quat<T> p3 = slerp_unit(b, keys_[i + 1], u);
    return slerp_unit(slerp_unit(p1, p2, u), slerp_unit(p2, p3, u), u);
  }

 private:
  template <Real U>
  friend Expected<QuatTrack<U>> build_quat_track(std::span<const QuatKey<U>> keys, std::span<const QuatKeyTangents<U>> tangents,
                                                 const QuatSplineOptions<U>& options);

  QuatTrack() = default;  // only build_quat_track() makes tracks: ≥ 1 key
  Quat<T> sample(T frame, TrackCursor& cursor, bool use_cursor) const noexcept;

  std::vector<T> frames_;
  std::vector<Quat<T>> keys_;
  std::vector<Quat<T>> after_, before_, squad_;  // empty when no key is Bézier or squad
  std::vector<Quat<T>> tin_, tout_;              // empty when no key is glTF cubic
  std::vector<T> sign_;  // ±1 applied to each authored key (and its tangents) for continuity
  std::vector<T> length_;  // |authored key|: glTF cubic segments use the key as authored, not normalised
  std::vector<QuatInterpolation> mode_;
};

/// Validates (≥ 1 key; finite frames strictly increasing; finite, non-zero quaternions; finite
/// tangents, none or one per key; distance factor in (0, 1]) and builds a quaternion track.
/// `tangents` empty means every key's are zero.  Error locations: {"keys", i, member} ("frame",
/// "value", "in_tangent", "out_tangent": the scene file keeps the tangents in the key), {"keys"}
/// when there is no key, {"tangents"} when their count is neither 0 nor the keys', and
/// {"distance_factor"} for the option.
template <Real T>
[[nodiscard]] Expected<QuatTrack<T>> build_quat_track(std::span<const QuatKey<T>> keys,
                                                      std::span<const QuatKeyTangents<T>> tangents,
                                                      const QuatSplineOptions<T>& options = {});

/// Keys without tangents (none is gltf_cubic, or its tangents are zero).
template <Real T>
[[nodiscard]] Expected<QuatTrack<T>> build_quat_track(std::span<const QuatKey<T>> keys,
                                                      const QuatSplineOptions<T>& options = {}) {
  return build_quat_track(keys, std::span<const QuatKeyTangents<T>>(), options);
}

/// Convenience overload for a vector of keys (and, optionally, their tangents).
template <Real T>
[[nodiscard]] Expected<QuatTrack<T>> build_quat_track(const std::vector<QuatKey<T>>& keys,
                                                      const QuatSplineOptions<T>& options = {}) {
  return build_quat_track(std::span<const QuatKey<T>>(keys), std::span<const QuatKeyTangents<T>>(), options);
}

/// Convenience overload for vectors of keys and their tangents.
template <Real T>
[[nodiscard]] Expected<QuatTrack<T>> build_quat_track(const std::vector<QuatKey<T>>& keys,
                                                      const std::vector<QuatKeyTangents<T>>& tangents,
                                                      const QuatSplineOptions<T>& options = {}) {
  return build_quat_track(std::span<const QuatKey<T>>(keys), std::span<const QuatKeyTangents<T>>(tangents), options);
}

// ============================================================================ implementation
template <Real T>
Expected<QuatTrack<T>> build_quat_track(std::span<const QuatKey<T>> keys, std::span<const QuatKeyTangents<T>> tangents,
                                        const QuatSplineOptions<T>& options) {
  using namespace quat_track_detail;
  if (keys.empty()) return Error{ErrorCode::too_few_points, "a track needs at least one key", {"keys"}};
  if (!tangents.empty() && tangents.size() != keys.size()) {
    return Error{ErrorCode::wrong_arity,
                 std::to_string(tangents.size()) + " tangent pairs for " + std::to_string(keys.size()) +
                     " keys (none, or one per key)", {"tangents"}};
  }
  if (!(options.distance_factor > T(0) && options.distance_factor <= T(1))) {
    return Error{ErrorCode::invalid_argument, "must be in (0, 1]", {"distance_factor"}};
  }
  const std::size_t n = keys.size();
  auto fail = [](ErrorCode code, std::string message, std::initializer_list<LocationStep> steps) {
    Error e{code, std::move(message)};
    e.prepend(steps);
    return e;
  };
  // Only the arrays some key's interpolation reads are made (a motion-capture clip's slerp keys
  // need neither control points nor tangents).
  bool any_controls = false, any_cubic = false;
  for (const auto& k : keys) {
    any_controls |= k.interpolation == QuatInterpolation::bezier || k.interpolation == QuatInterpolation::squad;
    any_cubic |= k.interpolation == QuatInterpolation::gltf_cubic;
  }
  QuatTrack<T> tr;
  tr.frames_.resize(n);
  tr.keys_.resize(n);
  tr.mode_.resize(n);
  if (any_cubic) {
    tr.tin_.resize(n);
    tr.tout_.resize(n);
  }
  tr.sign_.resize(n);
  tr.length_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& k = keys[i];
    if (!std::isfinite(k.frame)) return fail(ErrorCode::not_finite, "frame is not finite", {"keys", i, "frame"});
    if (!is_finite(k.value)) return fail(ErrorCode::not_finite, "quaternion or tangent is not finite", {"keys", i, "value"});
    if (!tangents.empty()) {  // none: all zero (a motion-capture clip's keys are checked without them)
      if (!is_finite(tangents[i].in)) {
        return fail(ErrorCode::not_finite, "quaternion or tangent is not finite", {"keys", i, "in_tangent"});
      }
      if (!is_finite(tangents[i].out)) {
        return fail(ErrorCode::not_finite, "quaternion or tangent is not finite", {"keys", i, "out_tangent"});
      }
    }
    const T len = norm(k.value);
    if (!(len > T(0))) return fail(ErrorCode::invalid_argument, "zero quaternion is not a rotation", {"keys", i, "value"});
    if (i > 0 && !(k.frame > keys[i - 1].frame)) {
      return fail(ErrorCode::keys_not_increasing,
                  "frame " + shortest_text(double(k.frame)) + " is not after the previous key's frame " +
                      shortest_text(double(keys[i - 1].frame)) + " (keys must be sorted by strictly increasing frame)",
                  {"keys", i, "frame"});
    }
    tr.frames_[i] = k.frame;
    Quat<T> q = k.value / len;
    T sign = T(1);
    if (i > 0) {
      const bool negative = dot(tr.keys_[i - 1], q) < T(0);
      if (negative != k.long_way) sign = T(-1);
    }
    tr.keys_[i] = q * sign;
    if (any_cubic) {
      const QuatKeyTangents<T> t = tangents.empty() ? QuatKeyTangents<T>{} : tangents[i];
      tr.tin_[i] = t.in * sign;
      tr.tout_[i] = t.out * sign;
    }
    tr.sign_[i] = sign;
    tr.length_[i] = len;
    tr.mode_[i] = k.interpolation;
  }
  // Bézier control points (§3.3.1): a_i = bisect(double(q_{i−1}, q_i), q_{i+1}), b_i = double(a_i, q_i);
  // at the ends the missing neighbour is the reflection of the other one through the end key.
  // Only keys at a Bézier or squad segment (the one starting at key i or the one ending there) get
  // them: each key's points depend on its neighbouring keys only, so they are the same as if every
  // key had them.  Elsewhere they are the key itself (step, slerp and glTF cubic never read them);
  // a track without Bézier and squad keys stores none (control_after() gives the key).
  if (!any_controls) return tr;
  tr.after_.assign(tr.keys_.begin(), tr.keys_.end());
  tr.before_.assign(tr.keys_.begin(), tr.keys_.end());
  tr.squad_.assign(tr.keys_.begin(), tr.keys_.end());
  const auto uses_controls = [&](std::size_t s) {
    return tr.mode_[s] == QuatInterpolation::bezier || tr.mode_[s] == QuatInterpolation::squad;
  };
  const T k = options.distance_factor;
  for (std::size_t i = 0; n > 1 && i < n; ++i) {
    // Segment i starts at key i; segment i − 1 ends there (the last key starts none).
    if (!((i + 1 < n && uses_controls(i)) || (i > 0 && uses_controls(i - 1)))) continue;
    const Quat<T>& q = tr.keys_[i];
    const Quat<T> prev = i > 0 ? tr.keys_[i - 1] : double_through(tr.keys_[i + 1], q);
    const Quat<T> next = i + 1 < n ? tr.keys_[i + 1] : double_through(tr.keys_[i - 1], q);
    const Quat<T> a = bisect(double_through(prev, q), next);
    const Quat<T> b = double_through(a, q);
    T ka = k, kb = k;
    if (options.time_aware && i > 0 && i + 1 < n) {
      const T hl = tr.frames_[i] - tr.frames_[i - 1], hr = tr.frames_[i + 1] - tr.frames_[i];
      ka = k * T(2) * hr / (hl + hr);
      kb = k * T(2) * hl / (hl + hr);
    }
    tr.after_[i] = slerp_unit(q, a, ka);
    tr.before_[i] = slerp_unit(q, b, kb);
    // Squad's inner quadrangle point s_i = q_i exp(−(log(q_i⁻¹ q_{i+1}) + log(q_i⁻¹ q_{i−1}))/4);
    // the end keys use s = q.
    if (i == 0 || i + 1 == n) {
      tr.squad_[i] = q;
    } else {
      const Quat<T> inv = conjugate(q);
      const Quat<T> l = log(inv * tr.keys_[i + 1]) + log(inv * tr.keys_[i - 1]);
      tr.squad_[i] = normalized(q * exp(l * T(-0.25)));
    }
  }
  return tr;
}

template <Real T>
Quat<T> QuatTrack<T>::sample(T frame, TrackCursor& cursor, bool use_cursor) const noexcept {
  using namespace quat_track_detail;
  const std::size_t n = frames_.size();
  if (n == 1 || std::isnan(frame) || frame <= frames_[0]) return keys_[0];
  if (frame >= frames_[n - 1]) return keys_[n - 1];
  std::size_t i = use_cursor ? std::min(cursor.segment, n - 2) : 0;
  if (use_cursor && frame >= frames_[i] && frame <= frames_[i + 1]) {
  } else if (use_cursor && i + 2 < n && frame >= frames_[i + 1] && frame <= frames_[i + 2]) {
    ++i;
  } else {
    // The segment upper_bound finds (frames_[i] ≤ frame < frames_[i + 1]); first tried at the
    // frame's proportion of the keyed range and its neighbour on the frame's side (rounding), which
    // is it for evenly spaced keys (motion capture).
    const T guess = (frame - frames_[0]) / (frames_[n - 1] - frames_[0]) * T(n - 1);
    std::size_t g = guess > T(0) && guess < T(n - 1) ? std::min(std::size_t(guess), n - 2) : 0;
    if (frame < frames_[g]) {
      if (g > 0) --g;
    } else if (frame >= frames_[g + 1] && g + 2 < n) {
      ++g;
    }
    if (frames_[g] <= frame && frame < frames_[g + 1]) {
      i = g;
    } else {
      const auto it = std::upper_bound(frames_.begin(), frames_.end(), frame);
      i = std::min(std::size_t(it - frames_.begin()) - 1, n - 2);
    }
  }
  cursor.segment = i;
#if defined(__GNUC__)
  // Playback walks the keys in order, one track after another: with dozens of tracks (a skeleton)
  // the hardware's stream prefetchers lose track and each key was a cache miss.  Ask for the key a
  // few segments ahead (a hint only: no effect on the result).
  __builtin_prefetch(keys_.data() + std::min(i + 8, n - 1));
#endif
  const T h = frames_[i + 1] - frames_[i];
  const T u = std::clamp((frame - frames_[i]) / h, T(0), T(1));
  switch (mode_[i]) {
    case QuatInterpolation::step:
      return keys_[i];
    case QuatInterpolation::slerp:
      return slerp_unit(keys_[i], keys_[i + 1], u);
    case QuatInterpolation::bezier:
      return bezier(i, u);
    case QuatInterpolation::squad:
      return slerp_unit(slerp_unit(keys_[i], keys_[i + 1], u), slerp_unit(squad_[i], squad_[i + 1], u),
                        T(2) * u * (T(1) - u));
    case QuatInterpolation::gltf_cubic: {
      // The keys as authored (undo the continuity flip of each end together with its tangent, and
      // the normalisation: the glTF specification normalises only the result).
      const T u2 = u * u, u3 = u2 * u;
      const Quat<T> start =
          (keys_[i] * ((T(2) * u3 - T(3) * u2 + T(1)) * length_[i]) + tout_[i] * ((u3 - T(2) * u2 + u) * h)) * sign_[i];
      const Quat<T> end = (keys_[i + 1] * ((T(-2) * u3 + T(3) * u2) * length_[i + 1]) + tin_[i + 1] * ((u3 - u2) * h)) * sign_[i + 1];
      return normalized(start + end);
    }
  }
  return keys_[i];
}

}  // namespace inbetween
