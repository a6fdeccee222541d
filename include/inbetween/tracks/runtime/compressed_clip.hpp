#pragma once
/// A compressed rig clip (issue 24, docs/compression.md): the bytes of an .ibc file, checked once
/// by load_compressed_clip() and then sampled in place.  The clip's frames are cut into pieces
/// (at discontinuities such as a rest pose on frame 0, and at a maximum length); in every piece
/// every joint has three tracks, translation, rotation and scale, each absent (identity),
/// constant, or a uniform cubic B-spline over the piece's frames whose control points are
/// range-reduced and quantised at a per-track bit width in one shared bit stream.  Rotations are stored relative to a per-track reference quaternion r
/// (q = r ⊗ q_rel) as q_rel's x, y, z with w = √(1 − x² − y² − z²) ≥ 0 (or all four components,
/// normalised, when q_rel turns too far for that).  The uniform knots give O(1) random access: a
/// sample reads four control points per track.
///
/// This header holds the format (layout constants, the parsed track table) and the two decoders:
/// decode_frame() in double, the reference that compression's error guarantee is measured on and
/// that the .ibc reader turns into keyed tracks, and sample_compressed(), the runtime's float
/// sampler (no allocation, caller-owned span), which agrees with decode_frame within
/// compressed_sample_tolerance.  The compressor is scene/compress.hpp; the file, io/ibc.hpp.

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween {

/// The .ibc magic, the first four bytes of the file.
inline constexpr std::array<std::uint8_t, 4> ibc_magic = {'I', 'B', 'C', 0x1a};
/// The format version this build writes and reads.
inline constexpr std::uint16_t ibc_version = 1;
/// Bytes of the fixed header.
inline constexpr std::size_t ibc_header_size = 64;
/// Zero bytes after the last control point of the bit stream (one 8-byte load reads any value).
inline constexpr std::size_t ibc_stream_padding = 8;
/// Largest bit width of a quantised value.
inline constexpr unsigned ibc_max_bits = 24;
/// Control points per block.  A track's quantised indices are stored losslessly range-reduced on
/// two levels: a superblock (ibc_superblock_blocks blocks) stores per component the smallest
/// base of its blocks (at the track's `bits`) and the width of the block bases above it (5 bits);
/// a block stores per component its base above the superblock's (at that width) and its offsets'
/// width above the track's width_base (at width_bits bits), then the offsets.
inline constexpr unsigned ibc_block_controls = 12;
/// Blocks per superblock.
inline constexpr unsigned ibc_superblock_blocks = 16;
/// Bits of a superblock's per-component width of block bases (0 … ibc_max_bits).
inline constexpr unsigned ibc_width_bits = 5;

/// What a track stores.
enum class CompressedTrackKind : std::uint8_t {
  absent = 0,    ///< the identity value (translation 0, rotation identity, scale 1); no payload
  constant = 1,  ///< one value (float32), held over the clip
  spline = 2,    ///< a uniform cubic B-spline with quantised control points
};

/// Which of a joint's tracks.
enum class CompressedChannel : std::uint8_t { translation = 0, rotation = 1, scale = 2 };

/// One track as parsed from the file, with the decoding constants precomputed.
struct CompressedTrack {
  CompressedTrackKind kind = CompressedTrackKind::absent;  ///< what it stores
  std::uint8_t components = 3;   ///< spline values per control point: 3, or 4 for a rotation with w stored
  std::uint8_t degree = 3;       ///< 1: linear between control points (h = 1: the samples themselves); 3: cubic B-spline
  std::uint8_t bits = 0;         ///< bits of a block's base index, 0 … ibc_max_bits (indices are < 2^bits)
  std::uint32_t spacing = 1;     ///< frames per knot interval (h ≥ 1)
  std::uint32_t controls = 0;    ///< control points: segments + degree, segments = max(1, ⌈(piece frames − 1)/h⌉)
  std::uint64_t bit_offset = 0;  ///< first bit of the track's first block in the bit stream
  std::uint8_t width_base = 0;   ///< smallest offset width of the track's blocks (≤ bits)
  std::uint8_t width_bits = 0;   ///< bits of a block's width field (≤ 5): width = width_base + field
  std::uint32_t first_index = 0; ///< word of the track's first block in the clip's block index (set on load)
  std::array<float, 4> min{};    ///< spline: per-component lower end of the range; constant: the value (w, x, y, z for a rotation)
  std::array<float, 4> step{};   ///< spline: per-component quantisation step (≥ 0): value = min + step · index
  Quatf reference{};             ///< rotation spline: q = reference ⊗ q_rel; constant rotation: the value normalised (set on load)
};

/// Segments of a spline of `frames` samples at knot spacing `spacing`: max(1, ⌈(frames − 1)/spacing⌉).
[[nodiscard]] constexpr std::uint64_t compressed_segments(std::uint64_t frames, std::uint64_t spacing) noexcept {
  const std::uint64_t s = frames > 1 ? (frames - 1 + spacing - 1) / spacing : 1;
  return s < 1 ? 1 : s;
}

/// The uniform cubic B-spline basis at t ∈ [0, 1]: weights of control points i … i+3 (sum 1, ≥ 0).
template <Real T>
[[gnu::always_inline]] inline std::array<T, 4> bspline_weights(T t) noexcept {
  const T s = T(1) - t, t2 = t * t, t3 = t2 * t;
  return {s * s * s / T(6), (T(3) * t3 - T(6) * t2 + T(4)) / T(6), (T(-3) * t3 + T(3) * t2 + T(3) * t + T(1)) / T(6),
          t3 / T(6)};
}

/// The linear basis at t ∈ [0, 1]: weights of control points i, i+1.
template <Real T>
[[gnu::always_inline]] inline std::array<T, 4> linear_weights(T t) noexcept {
  return {T(1) - t, t, T(0), T(0)};
}

/// Bits of a spline track's superblocks and blocks in the stream, for quantised indices `values`
/// (controls × components, control-major) whose largest is below 2^bits.
[[nodiscard]] std::uint64_t compressed_block_bits(std::span<const std::uint32_t> values, unsigned components, unsigned bits) noexcept;

/// Reconstructs a rotation from a relative rotation's spline components: 3 components → w = √(1 − |v|²)
/// (v scaled to unit length when |v| > 1); 4 → normalised (identity when zero); then reference ⊗ q_rel.
template <Real T>
[[gnu::always_inline]] inline Quat<T> compressed_rotation(const Quat<T>& reference, const T* v, unsigned components) noexcept {
  Quat<T> rel;
  if (components == 3) {
    const T n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (n2 >= T(1)) {
      const T inv = T(1) / std::sqrt(n2);
      rel = Quat<T>::from_wxyz(T(0), v[0] * inv, v[1] * inv, v[2] * inv);
    } else {
      rel = Quat<T>::from_wxyz(std::sqrt(T(1) - n2), v[0], v[1], v[2]);
    }
  } else {
    const T n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
    if (!(n2 > T(0))) return reference;
    const T inv = T(1) / std::sqrt(n2);
    rel = Quat<T>::from_wxyz(v[3] * inv, v[0] * inv, v[1] * inv, v[2] * inv);
  }
  return reference * rel;
}

/// Words of a block's entry in the block index: base index of components 0 … 3 (0 past the
/// track's components), the bit position of the block's first control point, and the components'
/// widths, one per byte (component c at bits 8c).
inline constexpr unsigned ibc_index_words = 6;

/// Largest block index (words) a file of `file_bytes` bytes may refer to: 32 words per byte + 2^20.  A
/// block of zero-width values takes no bits, so the frame count alone does not bound the index;
/// a file whose tracks need more is refused (no compressor output comes near it: a block costs
/// at least its width fields or its values).
[[nodiscard]] constexpr std::uint64_t ibc_max_index_words(std::uint64_t file_bytes) noexcept {
  return 32 * file_bytes + (std::uint64_t(1) << 20);
}

/// A spline track as the runtime sampler reads it (built on load from its CompressedTrack).
struct CompressedSpline {
  double inv_spacing = 1;        ///< 1 / spacing
  std::uint32_t spacing = 1;     ///< frames per knot interval
  std::uint32_t last_segment = 0;  ///< controls − 1 − degree: the last segment
  std::uint32_t first_index = 0;   ///< word of the track's first block in the block index
  std::uint32_t joint = 0;       ///< the joint it drives
  std::uint8_t channel = 0;      ///< CompressedChannel
  std::uint8_t form = 0;         ///< (components − 3) · 2 + (degree == 3): which specialised decoder
  std::array<float, 4> min{};    ///< per-component lower end of the range
  std::array<float, 4> step{};   ///< per-component quantisation step
  Quatf reference{};             ///< rotation: q = reference ⊗ q_rel
};

/// Four rotation spline tracks of a piece side by side, one per lane (built on load): what the
/// sampler's rotation pass needs to finish four rotations at once in the lanes of a vector.
/// Lanes past the piece's rotation splines hold the identity reference and are never stored.
struct CompressedRotationLanes {
  std::array<float, 4> w{1, 1, 1, 1};  ///< per lane: the reference's w
  std::array<float, 4> x{};            ///< per lane: the reference's x
  std::array<float, 4> y{};            ///< per lane: the reference's y
  std::array<float, 4> z{};            ///< per lane: the reference's z
  std::array<std::uint32_t, 4> full{};  ///< per lane: all bits set where the track stores 4 components, else 0
  std::array<std::uint32_t, 4> joint{};  ///< per lane: the joint it drives
};

/// A checked compressed clip: owns the .ibc bytes, the parsed track table and the runtime tables
/// built on load (block index, spline list, rest poses: runtime_bytes()).  Only
/// load_compressed_clip() makes one, so every offset and width in it is in bounds.
class CompressedClip {
 public:
  /// Joints (each with translation, rotation and scale tracks).
  [[nodiscard]] std::size_t joints() const noexcept { return parents_.size(); }
  /// Samples per track (frames of the clip, one per frame).
  [[nodiscard]] std::size_t frames() const noexcept { return frames_; }
  /// Frame of sample 0.
  [[nodiscard]] double first_frame() const noexcept { return first_frame_; }
  /// Frames per second.
  [[nodiscard]] double frame_rate() const noexcept { return frame_rate_; }
  /// Per joint: parent joint or −1 (parents before children).
  [[nodiscard]] std::span<const std::int32_t> parents() const noexcept { return parents_; }
  /// Per joint: name.
  [[nodiscard]] std::span<const std::string> names() const noexcept { return names_; }
  /// First sample of each piece: 0, then strictly increasing, < frames().
  [[nodiscard]] std::span<const std::uint32_t> pieces() const noexcept { return pieces_; }
  /// The piece holding sample `frame_index` (the last piece starting at or before it).
  [[nodiscard]] std::size_t piece_of(std::size_t frame_index) const noexcept {
    std::size_t p = 0;
    while (p + 1 < pieces_.size() && pieces_[p + 1] <= frame_index) ++p;
    return p;
  }
  /// Samples in piece `p`.
  [[nodiscard]] std::size_t piece_frames(std::size_t p) const noexcept {
    return (p + 1 < pieces_.size() ? pieces_[p + 1] : frames_) - pieces_[p];
  }
  /// Track of `joint`'s `channel` in piece `piece`.
  [[nodiscard]] const CompressedTrack& track(std::size_t piece, std::size_t joint, CompressedChannel channel) const noexcept {
    return tracks_[(piece * parents_.size() + joint) * 3 + std::size_t(channel)];
  }
  /// All tracks, piece-major, then joint-major (translation, rotation, scale).
  [[nodiscard]] std::span<const CompressedTrack> tracks() const noexcept { return tracks_; }
  /// The error bound requested at compression (clip units).
  [[nodiscard]] double error_bound() const noexcept { return error_bound_; }
  /// The virtual-vertex error measured at compression (clip units, ≤ error_bound()).
  [[nodiscard]] double measured_error() const noexcept { return measured_error_; }
  /// The shell distance of the error metric (clip units).
  [[nodiscard]] double shell() const noexcept { return shell_; }
  /// The whole file.
  [[nodiscard]] std::span<const std::uint8_t> bytes() const noexcept { return bytes_; }
  /// The bit stream of control points (padded with ibc_stream_padding zero bytes).
  [[nodiscard]] const std::uint8_t* stream() const noexcept { return bytes_.data() + stream_offset_; }
  /// The block index built on load (not in the file): per spline track, in track order from its
  /// first_index, per block ibc_index_words words: the decoded block header (bases, position of
  /// the first control point, widths).
  [[nodiscard]] std::span<const std::uint32_t> block_index() const noexcept { return index_; }
  /// The spline tracks of piece `p` with their runtime constants (built on load): its rotation
  /// splines first (rotation_count(p) of them), then its translation and scale splines, each
  /// group in track order.
  [[nodiscard]] std::span<const CompressedSpline> splines(std::size_t p) const noexcept {
    return std::span<const CompressedSpline>(splines_).subspan(piece_splines_[p], piece_splines_[p + 1] - piece_splines_[p]);
  }
  /// Rotation splines of piece `p`: the first rotation_count(p) entries of splines(p).
  [[nodiscard]] std::size_t rotation_count(std::size_t p) const noexcept { return piece_rotations_[p]; }
  /// Piece `p`'s rotation splines four to an entry, in the order of splines(p) (built on load).
  [[nodiscard]] std::span<const CompressedRotationLanes> rotation_lanes(std::size_t p) const noexcept {
    return std::span<const CompressedRotationLanes>(lanes_).subspan(piece_lanes_[p], piece_lanes_[p + 1] - piece_lanes_[p]);
  }
  /// The pose of piece `p` with every absent and constant track's value (spline tracks: identity),
  /// joints() entries; the sampler copies it before evaluating the splines (built on load).
  [[nodiscard]] std::span<const JointPose<float>> rest_pose(std::size_t p) const noexcept {
    return std::span<const JointPose<float>>(rest_).subspan(p * parents_.size(), parents_.size());
  }
  /// Bytes of the in-memory runtime tables built on load (block index, spline table, rest poses;
  /// not part of the file).
  [[nodiscard]] std::size_t runtime_bytes() const noexcept {
    return index_.size() * sizeof(std::uint32_t) + splines_.size() * sizeof(CompressedSpline) +
           piece_splines_.size() * sizeof(std::uint32_t) + rest_.size() * sizeof(JointPose<float>) +
           lanes_.size() * sizeof(CompressedRotationLanes) + (piece_lanes_.size() + piece_rotations_.size()) * sizeof(std::uint32_t);
  }

 private:
  friend Expected<CompressedClip> load_compressed_clip(std::vector<std::uint8_t> bytes);
  CompressedClip() = default;
  std::vector<std::uint8_t> bytes_;
  std::vector<std::int32_t> parents_;
  std::vector<std::string> names_;
  std::vector<std::uint32_t> pieces_;
  std::vector<CompressedTrack> tracks_;
  std::vector<std::uint32_t> index_;
  std::vector<CompressedSpline> splines_;
  std::vector<std::uint32_t> piece_splines_;
  std::vector<std::uint32_t> piece_rotations_;
  std::vector<CompressedRotationLanes> lanes_;
  std::vector<std::uint32_t> piece_lanes_;
  std::vector<JointPose<float>> rest_;
  std::size_t frames_ = 0, stream_offset_ = 0;
  double first_frame_ = 0, frame_rate_ = 0, error_bound_ = 0, measured_error_ = 0, shell_ = 0;
};

/// Checks and parses .ibc bytes (docs/compression.md, "Format"): magic, version, header size,
/// file size, counts, offsets and sizes in bounds, parents before children, names, track kinds,
/// component counts, bit widths ≤ ibc_max_bits, spacings ≥ 1, control counts matching the frames,
/// control points inside the bit stream, finite floats (ranges ≥ 0, references of unit length
/// within 1e-3, constant rotations non-zero).  Errors: parse, with the place Element{"byte", offset}
/// of the offending field and the field named in the message.
[[nodiscard]] Expected<CompressedClip> load_compressed_clip(std::vector<std::uint8_t> bytes);

/// The quantisation step of component c of a spline track in double (the stored float).
[[nodiscard]] inline double compressed_step(const CompressedTrack& t, unsigned c) noexcept { return double(t.step[c]); }

/// One quantised value of the stream: `bits` bits at bit position `bit` (LSB first).
[[gnu::always_inline]] inline std::uint32_t compressed_value(const std::uint8_t* stream, std::uint64_t bit,
                                                             unsigned bits) noexcept {
  std::uint64_t word;
  __builtin_memcpy(&word, stream + (bit >> 3), 8);
  if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
  return std::uint32_t((word >> (bit & 7)) & ((std::uint64_t(1) << bits) - 1));
}

/// The local pose of every joint at sample `frame_index` (< frames(), asserted), in double: the
/// reference decoder (compression measures its error on this; the .ibc reader keys these values).
/// out.size() == joints() (asserted).  Never allocates.
void decode_frame(const CompressedClip& clip, std::size_t frame_index, std::span<JointPose<double>> out) noexcept;

/// The largest difference between sample_compressed() and decode_frame() at the same frame
/// (translation and scale, relative to the track's largest |value| + 1, and rotation angle, radians):
/// float evaluation of the basis and the range (a few float ulp of each term).
inline constexpr double compressed_sample_tolerance = 1e-5;

/// The runtime sampler: the local pose of every joint at `frame` (a frame number, clamped to the
/// clip's frames; fractional frames evaluate the splines between samples) in float, read in place
/// from the bit stream (four control points per cubic track, two per linear one) with the block
/// headers from the block index built on load (block_index(); docs/compression.md, "The runtime
/// sampler"); the basis weights once per knot spacing, the rotations finished four at a time in
/// vector lanes (rotation_lanes()).  local.size() == joints()
/// (asserted).  Never allocates, noexcept.
void sample_compressed(const CompressedClip& clip, double frame, std::span<JointPose<float>> local) noexcept;

/// The .ibc bytes of a clip: the header fields, the joints, the tracks (kind, widths, ranges; bit
/// offsets are assigned here in track order) and each spline track's quantised control values
/// (controls × components values, control-major).  The compressor's writer; load_compressed_clip()
/// reads it back.
struct CompressedClipParts {
  std::vector<std::int32_t> parents;        ///< per joint
  std::vector<std::string> names;           ///< per joint (≤ 65 535 bytes each)
  std::vector<std::uint32_t> pieces{0};     ///< first sample of each piece (0 first, increasing)
  std::size_t frames = 0;                   ///< samples per track
  double first_frame = 0, frame_rate = 0;   ///< timing
  double error_bound = 0, measured_error = 0, shell = 0;  ///< the metric's figures
  std::vector<CompressedTrack> tracks;      ///< 3 per joint and piece, piece-major then joint-major
  std::vector<std::vector<std::uint32_t>> values;  ///< per track: quantised values (empty unless spline)
};

/// Serialises `parts` (precondition: consistent counts, asserted loosely; load_compressed_clip()
/// is the check).
[[nodiscard]] std::vector<std::uint8_t> write_compressed_clip(const CompressedClipParts& parts);

}  // namespace inbetween
