#pragma once
/// The tracks runtime for Blender F-curves (issue 12): an FCurveClip compiles many built FCurves
/// into pre-solved pieces — every segment of every curve is cut into pieces on which a polynomial
/// of degree 9 in the piece's parameter u = (frame − origin)·2/length ∈ [−1, 1] reproduces
/// FCurve::sample (Blender's root-finding evaluation) to a tolerance checked at build time, so
/// sampling runs no root finder: one polynomial per channel, evaluated native_simd<float>::size()
/// channels at a time from a cache kept in the cursor, with the pieces in a time-sorted stream
/// (the RigClip machinery, rig_clip.hpp).  A piece is 16 floats (lo and hi kept apart from the
/// other 14); the cursor caches the 14 per channel.  Pieces of channels that share their key
/// frames (a rig's joint: its ten curves keyed together) are stored as runs in SIMD-register order:
/// a run that fills a SIMD group is read where it is in the clip (no copy into the cache), a
/// shorter one is copied lane-wise.
///
/// Pieces: Bézier and easing segments are fitted adaptively (the polynomial through the curve's
/// values at the ten Chebyshev–Lobatto nodes u = −cos(πk/9), the keys' values at the ends; checked
/// against FCurve::sample at about 100 frames of the piece, evaluated in float as the sampler does;
/// halved until the check passes); linear segments are the same fit (exact up to rounding).  The
/// smooth Bézier composite y(x(t)) converges fast: the benchmark rig's segments (auto-clamped
/// handles) take one piece each.  Blender's 1e-4-frame snap bands around every key (where it
/// answers the key's value) are not pieces but two band thresholds per piece: within them the runtime
/// sets u to −1 or +1, where the polynomial interpolates the key (segments shorter than 1e-3 frames
/// keep constant band pieces).  Constant segments are one piece (key a's value, key b's in b's
/// band).  Outside the keys a line through the end key with FCurve::derivative's extrapolation
/// slope (Blender snaps only between the keys).
///
/// Cycles modifier (repeat, repeat with offset, mirror, either side, with or without a count): a
/// cycling channel keeps the pieces of its keyed range and extrapolation — nothing is unrolled, so
/// a cycling curve costs no more memory than a plain one and any frame, however far out, is
/// answered — and folds each frame into the keyed range as Blender's fcm_cycles_time does, in
/// float and in its order of operations (the code FCurve::sample runs, fcurve_detail::decide_cycles).
/// The fold is an affine map valid on a window of frames (one cycle copy: local = base ±
/// ((frame − end key) − n·period) + wrap, exact there with n·period stored as two floats, plus the
/// copy's value offset), found at the copy's boundary and kept in the cursor.  Cycling channels
/// with the same end-key frames and Cycles settings form a cycle class (a character's walk cycle:
/// all its curves) with one local frame and one piece stream in local time, consumed as the main
/// stream is; the SIMD loop applies the class's map to each of its channels (identical float
/// operations, so the same local frame) and adds the channel's offset.  Frames where Blender's
/// float arithmetic is irregular (a cycle boundary exactly, a float cycle number that rounds to an
/// integer, 2^23 cycles and beyond) get a one-frame window whose map is decide_cycles' own answer:
/// exact, slower (a scalar fold per sample).  Memory: no copies (the cursor holds 9 floats per
/// channel and 16 per class).  docs/runtime.md has the design and the measured cost.
/// Cycle-aware auto handles (Blender recomputes the end keys' handles as if the curve wrapped) are
/// already in the built FCurve's keys, so the pieces include them.
///
/// sample_fcurve_rig reads 10 curves per joint — location x, y, z, rotation_quaternion w, x, y, z,
/// scale x, y, z, the order of Blender's bone channels — and normalises the quaternion, as Blender
/// does before it builds the bone matrix.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween {

/// Options of build_fcurve_clip.
struct FCurveClipOptions {
  /// Largest |piece − FCurve::sample| accepted at the check frames, relative to the curve's value
  /// scale (the range of its key and handle values, at least 8·ε·max |value|, 1 for a flat curve at 0).
  float tolerance = 1e-5f;
  /// Pieces a single key segment may be cut into before the fit is accepted as it is (the clip's
  /// max_fit_error() then says how far it is).  4096: next to a near-vertical handle of the Blender
  /// reference cases the pieces shrink to a few frame ulps, and 512 left one of them 3e-3 off.
  int max_pieces_per_segment = 4096;
};

/// Agreement of FCurveClip sampling with FCurve::sample at any frame, relative to the curve's value
/// scale, with the default options: 2× the fit tolerance (the fit is checked at about 100 frames
/// per piece; frames between them may exceed the check a little).  Measured 9.9e-6 at most over
/// 9.2 million samples of the 294 Blender-agreement curves, the 32 with a Cycles modifier included
/// (tests/io/fcurve_clip_blender_test.cpp), 7.8e-6 on random curves and 9.4e-6 (beyond one ulp) on random
/// cycling ones (tests/tracks/fcurve_clip_test.cpp).
/// Cycling curves fold the frame exactly as FCurve::sample does, so the same bound holds for the
/// keyed-range value; with repeat_offset both add the copy's offset in float, which can add one
/// float ulp of the result (fcurve_runtime_agrees).
inline constexpr float fcurve_runtime_tolerance = 2e-5f;

/// True when a runtime value agrees with FCurve::sample's `reference` for a curve of value scale
/// `scale`: |value − reference| ≤ fcurve_runtime_tolerance·scale + one float ulp of the reference
/// (the rounding of a repeat_offset copy's offset added in float by both); both infinite and equal
/// (a repeat_offset offset that overflowed float at a far frame) also agrees.
[[nodiscard]] inline bool fcurve_runtime_agrees(float value, float reference, float scale) noexcept {
  if (value == reference) return true;
  const float big = std::max(std::abs(value), std::abs(reference));
  const double ulp = double(std::nextafter(big, std::numeric_limits<float>::infinity())) - double(big);
  return std::abs(double(value) - double(reference)) <= double(fcurve_runtime_tolerance) * double(scale) + ulp;
}

/// The caller-owned state of one playback stream of an FCurveClip (make it with
/// make_fcurve_clip_cursor): the channels' current pieces and their cache.  Was FCurveClip::Context.
struct FCurveClipCursor {
  std::vector<std::uint32_t> segment;  ///< per channel: current piece in the channel
  std::vector<float> cache;            ///< padded channels × FCurveClip::cached_fields, in SIMD-register order
  std::vector<float> values;           ///< per channel (curve c, for a rig too): the last sampled value
  /// Per channel, field-major (fold[k·stride + c]), its cycle class's fold in force: k = 0, 1 the
  /// window [lo, hi] of frames it is valid on, 2 end key, 3 and 4 n·period (cycle number times
  /// period) as a sum of two floats, 5 sign ±1, 6 base, 7 wrap (0 or the period), 8 the channel's
  /// value offset: local = base + sign·(((frame − end) − nd_hi) − nd_lo) + wrap.  Channels
  /// without cycles: the identity on (−∞, +∞).
  std::vector<float> fold;
  /// Per cycle class, 16 floats: its fold (fields 0–7 as in `fold`), 8 the last local frame,
  /// 9 the lo of the next piece of its stream (+∞ past the last).
  std::vector<float> class_fold;
  std::vector<std::size_t> class_next;  ///< per cycle class: first piece of its stream not yet consumed
  std::vector<std::uint8_t> folding;   ///< per SIMD group of channels: 1 if one of them cycles
  /// Per SIMD group of channels: the first stream piece of the run of the clip's main stream the
  /// group's channels read in place (a run that fills the group), or no_run: the group's part of
  /// `cache` holds their pieces.
  std::vector<std::uint32_t> direct;
  /// A `direct` entry for a group read from `cache`.
  static constexpr std::uint32_t no_run = std::numeric_limits<std::uint32_t>::max();
  std::size_t stride = 0;              ///< padded channel count (a multiple of 16)
  std::size_t next = 0;                ///< first stream piece not yet consumed
  float time = -std::numeric_limits<float>::infinity();  ///< last sampled frame (clamped)
};

/// A compiled, immutable set of F-curves (build it with build_fcurve_clip or build_fcurve_rig).
class FCurveClip {
 public:
  /// Number of curves (channels).
  [[nodiscard]] std::size_t channels() const noexcept { return channels_; }
  /// Joints for a clip made by build_fcurve_rig (channels / 10), 0 otherwise.
  [[nodiscard]] std::size_t joints() const noexcept { return joints_; }
  /// Number of pieces over all channels (the clip's size: block floats each).
  [[nodiscard]] std::size_t pieces() const noexcept {
    std::size_t n = data_.owner.size();
    for (const auto& k : classes_) n += k.pieces.owner.size();
    return n;
  }
  /// Number of runs over all pieces: a run is the pieces of channels next to each other in one
  /// SIMD group that start at the same frame (curves keyed together), stored side by side and
  /// handed over at once; pieces() / runs() is the mean run size (1: no curves share keys).
  [[nodiscard]] std::size_t runs() const noexcept {
    std::size_t n = count_runs(data_);
    for (const auto& k : classes_) n += count_runs(k.pieces);
    return n;
  }
  /// Number of channels with a Cycles modifier (folded into their keyed range at sampling).
  [[nodiscard]] std::size_t cycling_channels() const noexcept { return cycling_; }
  /// Number of cycle classes: cycling channels with the same end-key frames and Cycles settings
  /// share one folded local frame and one piece stream.
  [[nodiscard]] std::size_t cycle_classes() const noexcept { return classes_.size(); }
  /// Largest |piece − FCurve::sample| / scale measured at the check frames while building.
  [[nodiscard]] float max_fit_error() const noexcept { return max_fit_error_; }

  /// Degree of a piece's polynomial.
  static constexpr std::size_t degree = 9;
  /// Floats per piece: lo, hi (the frame interval [lo, hi) the piece answers), origin, 2/length
  /// (0 for a constant piece), the snap-band thresholds at lo and hi (Blender's 1e-4-frame bands as
  /// frames: u is −1 for frame ≤ the first, +1 for frame ≥ the second; ∓∞ for no band), then
  /// c0 … c9 of the polynomial in u = (frame − origin)·2/length.
  static constexpr std::size_t block = 6 + degree + 1;
  /// Floats of a piece the cursor's cache holds: the block without lo and hi (the sampling loop
  /// reads only these; the stream and the searches read lo and hi from the clip).
  static constexpr std::size_t cached_fields = block - 2;

  /// Deprecated name of FCurveClipCursor, kept for one release (docs/conventions.md, "Playback state").
  using Context [[deprecated("use FCurveClipCursor")]] = FCurveClipCursor;

 private:
  friend Expected<FCurveClip> build_fcurve_clip(std::span<const FCurve>, FCurveClipOptions);
  friend Expected<FCurveClip> build_fcurve_rig(std::span<const FCurve>, FCurveClipOptions);
  friend FCurveClipCursor make_fcurve_clip_cursor(const FCurveClip&);
  friend void evaluate_channels(const FCurveClip&, float, FCurveClipCursor&) noexcept;
  friend void sample_fcurves(const FCurveClip&, float, FCurveClipCursor&, std::span<float>) noexcept;
  friend void sample_fcurve_rig(const FCurveClip&, float, FCurveClipCursor&, std::span<JointPose<float>>) noexcept;
  friend struct FCurveClipAccess;  // the cycle fold in fcurve_clip.cpp
  FCurveClip() = default;

  // As RigClip's: pieces of every channel in stream order, with lo and hi apart (bounds) and the
  // cached fields in runs: consecutive stream pieces with the same lo whose channels are
  // consecutive within one SIMD group (a joint's curves keyed together) are one run, stored
  // field-major (field k of the run's piece i at data[first·cached_fields + k·size + i]), so
  // handing a run over is a copy of whole lanes — or, for a run that fills a SIMD group, none:
  // the group reads the run where it is (FCurveClipCursor::direct).  A single piece is a run of 1.
  struct Channels {
    std::vector<std::uint32_t> begin, count, where, owner, local;
    std::vector<float> data;    // while compiling: block floats per piece; then cached_fields, in runs
    std::vector<float> bounds;  // per stream piece: lo, hi
    std::vector<std::uint8_t> run, lane;  // per stream piece: its run's size, its index in the run
  };
  static std::size_t count_runs(const Channels& ch) noexcept {
    return std::size_t(std::count(ch.lane.begin(), ch.lane.end(), std::uint8_t(0)));
  }
  Channels data_;  // channels without cycling; a cycling channel has no piece in the stream
  struct CycleClass {  // cycling channels with the same end-key frames and Cycles settings: one local frame
    FCurveCycles cycles;
    float first_x = 0, last_x = 0;
    std::vector<std::uint32_t> members;  // their channels
    std::vector<float> first_y, last_y;  // per member: the end keys' values (repeat_offset's step)
    Channels pieces;  // the members' pieces in local-frame stream order (owner: the channel)
  };
  std::vector<CycleClass> classes_;
  std::vector<std::int32_t> class_of_;     // per channel: its cycle class, −1 for none
  std::vector<std::uint32_t> member_of_;   // per channel: its index in the class's members
  std::size_t cycling_ = 0;
  std::size_t channels_ = 0, joints_ = 0;
  float max_fit_error_ = 0;
};

/// Compiles curves (any number) into a clip; channel c is curves[c].  Curves with a Cycles modifier
/// are folded at sampling (see the file comment).  Error (unsupported): a curve with a modifier
/// stack other than one plain Cycles modifier (FCurve::simple_cycles), which the runtime does not compile.
[[nodiscard]] Expected<FCurveClip> build_fcurve_clip(std::span<const FCurve> curves, FCurveClipOptions options = {});

/// Compiles 10 curves per joint (curves[10·j + k], k: location x y z, rotation_quaternion w x y z,
/// scale x y z) into a rig clip for sample_fcurve_rig.  Errors: a count that is not a multiple of
/// 10 (InvalidArgument).
[[nodiscard]] Expected<FCurveClip> build_fcurve_rig(std::span<const FCurve> curves, FCurveClipOptions options = {});

/// A cursor before the clip's start.
[[nodiscard]] FCurveClipCursor make_fcurve_clip_cursor(const FCurveClip& clip);

/// Deprecated name of make_fcurve_clip_cursor, kept for one release.
[[deprecated("use make_fcurve_clip_cursor")]] [[nodiscard]] inline FCurveClipCursor make_fcurve_context(const FCurveClip& clip) {
  return make_fcurve_clip_cursor(clip);
}

/// Fills out[c] with channel c at `frame` (out.size() == clip.channels()).  Any frame is valid (NaN
/// gives each curve's first key value as FCurve::sample does, ±inf acts as the largest finite float;
/// cycling curves as FCurve::sample cycles them, at any distance from the keys); noexcept, no allocation.
void sample_fcurves(const FCurveClip& clip, float frame, FCurveClipCursor& cursor, std::span<float> out) noexcept;

/// Fills every joint's pose at `frame` (clip from build_fcurve_rig, out.size() == clip.joints()):
/// translation from location, the normalised rotation quaternion (identity when all four curves
/// read 0), scale.  noexcept, no allocation.
void sample_fcurve_rig(const FCurveClip& clip, float frame, FCurveClipCursor& cursor,
                       std::span<JointPose<float>> out) noexcept;

}  // namespace inbetween
