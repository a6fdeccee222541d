// FCurveClip: Blender F-curves pre-solved into degree-9 polynomial pieces (include/inbetween/tracks/runtime/fcurve_clip.hpp):
// building a clip, making a cursor and sampling.  The fitting is in fcurve_clip_fit.cpp, the
// cycle fold in fcurve_clip_cycles.cpp, what they share in fcurve_clip_internal.hpp.
#include "fcurve_clip_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "fcurve_internal.hpp"

namespace inbetween {

using namespace fcurve_clip_detail;

namespace {
// The runtime compiles keys and one plain Cycles modifier; any other modifier stack is refused.
std::optional<Error> unsupported_modifiers(std::span<const FCurve> curves) {
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (!curves[c].modifiers().empty() && curves[c].simple_cycles() == nullptr) {
      return Error{ErrorCode::unsupported,
                   "curve " + std::to_string(c) +
                       ": the F-curve runtime compiles keys and a lone Cycles modifier only, not this modifier stack "
                       "(sample it with FCurve::sample)"};
    }
  }
  return std::nullopt;
}
}  // namespace

Expected<FCurveClip> build_fcurve_clip(std::span<const FCurve> curves, FCurveClipOptions options) {
  if (auto e = unsupported_modifiers(curves)) return std::move(*e);
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
  if (auto e = unsupported_modifiers(curves)) return std::move(*e);
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

FCurveClipCursor make_fcurve_clip_cursor(const FCurveClip& clip) {
  FCurveClipCursor ctx;
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
// stream's next runs (a run that fills a SIMD group is read in place, FCurveClipCursor::direct; others
// are copied into the cache); a seek back, or a forward jump past more than 16 pieces per channel,
// finds each stale channel's piece from its cursor (the current piece's [lo, hi) read from
// `bounds` through the cursor), copies it into the cache, and repositions the stream.
template <class Channels>
void advance_main(const Channels& ch, std::size_t C, float frame, FCurveClipCursor& context) noexcept {
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
// `data`: the main stream's runs (a group whose FCurveClipCursor::direct names one reads it in place).
template <bool Folding>
void evaluate_groups(FCurveClipCursor& context, const float* data, std::size_t C, float frame) noexcept {
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

void evaluate_channels(const FCurveClip& clip, float frame, FCurveClipCursor& context) noexcept {
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

void sample_fcurves(const FCurveClip& clip, float frame, FCurveClipCursor& context, std::span<float> out) noexcept {
  INBETWEEN_ASSERT(out.size() == clip.channels_);
  evaluate_channels(clip, frame, context);
  std::copy_n(context.values.begin(), clip.channels_, out.begin());
}

void sample_fcurve_rig(const FCurveClip& clip, float frame, FCurveClipCursor& context,
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

