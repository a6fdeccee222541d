#pragma once
/// The tracks runtime (issue 12, "compile once, sample many channels per call"): a RigClip is an
/// immutable clip compiled from per-joint translation, rotation and scale tracks, with every key
/// laid out for the sampler — structure of arrays per channel kind, Vec3 segments pre-converted
/// from Hermite to power form in the segment's local parameter, rotation segments kept as key
/// pairs with their slerp arc precomputed (fast_slerp_on_arc: no dot, root or division per
/// sample) — and a RigContext that carries every channel's cursor.  One call,
/// sample_rig(), fills a caller-owned span with every joint's pose and never allocates.
///
/// Supported input (anything else is refused by build_rig_clip with Unsupported and the place):
/// Track<Vec3<T>> of every tangent kind (linear, Hermite, Catmull-Rom, TCB, flat, clamped, plateau,
/// stepped) with TrackExtend::constant at both ends; QuatTrack<T> segments of kind step or slerp
/// whose keys are on the same side of the 4-D sphere (the track's sign continuity guarantees that
/// unless a key asked for the long way).  Outside a channel's keys the end value is held, as the
/// scalar per-track API does for these inputs.  Agreement with the scalar API:
/// rig_runtime_vec_tolerance and rig_runtime_rotation_tolerance (tests/tracks/rig_clip_test.cpp).

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/orientation_interp.hpp"
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
/// Agreement of a RigClip's rotations with QuatTrack::sample (rotation angle, radians):
/// fast_slerp's bound plus slerp's own few-ulp error.
template <Real T>
inline constexpr T rig_runtime_rotation_tolerance = fast_slerp_max_error_rad<T> + T(16) * std::numeric_limits<T>::epsilon();

/// Every channel's cursor for one playback stream of a RigClip (make it with make_rig_context).
struct RigContext {
  std::vector<std::uint32_t> segment;  ///< per channel (3 per joint: T, R, S): last segment used
};

/// A compiled, immutable T+R+S clip of J joints.
template <Real T>
class RigClip {
 public:
  /// Number of joints.
  [[nodiscard]] std::size_t joints() const noexcept { return joints_; }

 private:
  template <Real U>
  friend Expected<RigClip<U>> build_rig_clip(std::span<const Track<Vec3<U>>>, std::span<const QuatTrack<U>>,
                                             std::span<const Track<Vec3<U>>>);
  template <Real U>
  friend void sample_rig(const RigClip<U>&, U, RigContext&, std::span<JointPose<U>>) noexcept;

  RigClip() = default;

  // A Vec3 channel kind (translations or scales), structure of arrays over all joints' segments:
  // segment k of channel c is begin[c] + k; start frame, 1/length and the power-form coefficients
  // value(u) = ((c3·u + c2)·u + c1)·u + c0, u = (frame − start)·inv_length in [0, 1].
  struct VecChannels {
    std::vector<std::uint32_t> begin, count;  // per channel: first segment and number of segments
    std::vector<T> start, inv_length;
    std::vector<Vec3<T>> c0, c1, c2, c3;
    std::vector<T> first, last;               // per channel: first and last key frame
    std::vector<Vec3<T>> first_value, last_value;
  };
  // Rotation channels: per segment the two keys and whether it is a step.
  struct RotChannels {
    std::vector<std::uint32_t> begin, count;
    std::vector<T> start, inv_length;
    std::vector<Quat<T>> q0, q1;
    std::vector<FastSlerpArc<T>> arc;  // per segment: the slerp arc, precomputed
    std::vector<std::uint8_t> step;
    std::vector<T> first, last;
    std::vector<Quat<T>> first_value, last_value;
  };

  std::size_t joints_ = 0;
  VecChannels translation_, scale_;
  RotChannels rotation_;
};

/// A context with every channel's cursor at the clip's start.
template <Real T>
RigContext make_rig_context(const RigClip<T>& clip) {
  return RigContext{std::vector<std::uint32_t>(3 * clip.joints(), 0)};
}

namespace rig_detail {
template <Real T>
std::string vec_name(bool translation) {
  return translation ? "translations" : "scales";
}

// Compiles one Vec3 track into the channel arrays; Unsupported for extend modes other than constant.
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
  ch.begin.push_back(std::uint32_t(ch.start.size()));
  ch.count.push_back(std::uint32_t(n > 1 ? n - 1 : 1));
  ch.first.push_back(f[0]);
  ch.last.push_back(f[n - 1]);
  ch.first_value.push_back(v[0]);
  ch.last_value.push_back(v[n - 1]);
  if (n == 1) {  // one key: a constant segment
    ch.start.push_back(f[0]);
    ch.inv_length.push_back(T(0));
    ch.c0.push_back(v[0]);
    ch.c1.push_back({});
    ch.c2.push_back({});
    ch.c3.push_back({});
    return true;
  }
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const T h = f[i + 1] - f[i];
    ch.start.push_back(f[i]);
    ch.inv_length.push_back(T(1) / h);
    if (tr.stepped(i)) {
      ch.c0.push_back(v[i]);
      ch.c1.push_back({});
      ch.c2.push_back({});
      ch.c3.push_back({});
      continue;
    }
    // Hermite p0, p1, m0 = out_i·h, m1 = in_{i+1}·h to power form.
    const Vec3<T> p0 = v[i], p1 = v[i + 1], m0 = out[i] * h, m1 = in[i + 1] * h;
    ch.c0.push_back(p0);
    ch.c1.push_back(m0);
    ch.c2.push_back((p1 - p0) * T(3) - m0 * T(2) - m1);
    ch.c3.push_back((p0 - p1) * T(2) + m0 + m1);
  }
  return true;
}

// Segment of channel c holding `frame` (first ≤ frame < last), from the cursor; O(1) when playback
// moves less than a segment per call.
template <Real T>
std::uint32_t find_segment(std::span<const T> start, std::uint32_t begin, std::uint32_t count, T frame,
                           std::uint32_t cursor) noexcept {
  std::uint32_t k = std::min(cursor, count - 1);
  while (k + 1 < count && start[begin + k + 1] <= frame) ++k;
  while (k > 0 && start[begin + k] > frame) --k;
  return k;
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
  for (std::size_t j = 0; j < clip.joints_; ++j) {
    if (auto r = rig_detail::add_vec<T>(clip.translation_, translations[j], j, "translations"); !r) return r.error();
    if (auto r = rig_detail::add_vec<T>(clip.scale_, scales[j], j, "scales"); !r) return r.error();
    const QuatTrack<T>& q = rotations[j];
    auto& ch = clip.rotation_;
    const auto f = q.frames();
    const auto k = q.keys();
    const std::size_t n = f.size();
    ch.begin.push_back(std::uint32_t(ch.start.size()));
    ch.count.push_back(std::uint32_t(n > 1 ? n - 1 : 1));
    ch.first.push_back(f[0]);
    ch.last.push_back(f[n - 1]);
    ch.first_value.push_back(k[0]);
    ch.last_value.push_back(k[n - 1]);
    if (n == 1) {
      ch.start.push_back(f[0]);
      ch.inv_length.push_back(T(0));
      ch.q0.push_back(k[0]);
      ch.q1.push_back(k[0]);
      ch.arc.push_back({});
      ch.step.push_back(1);
      continue;
    }
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
      ch.start.push_back(f[i]);
      ch.inv_length.push_back(T(1) / (f[i + 1] - f[i]));
      ch.q0.push_back(k[i]);
      ch.q1.push_back(k[i + 1]);
      ch.arc.push_back(fast_slerp_arc(k[i], k[i + 1]));
      ch.step.push_back(mode == QuatInterpolation::step ? 1 : 0);
    }
  }
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

/// Samples every joint at `frame` into out (out.size() must equal clip.joints(), context made for
/// this clip), advancing the context's cursors.  Outside a channel's keys its end value is held;
/// NaN reads as the first frame.  noexcept, no allocation.
template <Real T>
void sample_rig(const RigClip<T>& clip, T frame, RigContext& context, std::span<JointPose<T>> out) noexcept {
  INBETWEEN_ASSERT(out.size() == clip.joints_ && context.segment.size() == 3 * clip.joints_);
  if (std::isnan(frame)) frame = -std::numeric_limits<T>::infinity();
  const auto vec_at = [frame](const typename RigClip<T>::VecChannels& ch, std::size_t c,
                              std::uint32_t& cursor) noexcept -> Vec3<T> {
    if (!(frame > ch.first[c])) return ch.first_value[c];
    if (!(frame < ch.last[c])) return ch.last_value[c];
    const std::uint32_t b = ch.begin[c];
    const std::uint32_t k = rig_detail::find_segment<T>(ch.start, b, ch.count[c], frame, cursor);
    cursor = k;
    const std::size_t s = b + k;
    const T u = (frame - ch.start[s]) * ch.inv_length[s];
    return ((ch.c3[s] * u + ch.c2[s]) * u + ch.c1[s]) * u + ch.c0[s];
  };
  const auto& rc = clip.rotation_;
  for (std::size_t j = 0; j < clip.joints_; ++j) {
    out[j].translation = vec_at(clip.translation_, j, context.segment[3 * j]);
    out[j].scale = vec_at(clip.scale_, j, context.segment[3 * j + 2]);
    if (!(frame > rc.first[j])) {
      out[j].rotation = rc.first_value[j];
    } else if (!(frame < rc.last[j])) {
      out[j].rotation = rc.last_value[j];
    } else {
      const std::uint32_t b = rc.begin[j];
      const std::uint32_t k = rig_detail::find_segment<T>(rc.start, b, rc.count[j], frame, context.segment[3 * j + 1]);
      context.segment[3 * j + 1] = k;
      const std::size_t s = b + k;
      const T u = std::clamp((frame - rc.start[s]) * rc.inv_length[s], T(0), T(1));
      out[j].rotation = rc.step[s] ? rc.q0[s] : fast_slerp_on_arc(rc.q0[s], rc.q1[s], rc.arc[s], u);
    }
  }
}

}  // namespace inbetween
