// The .ibc format (docs/compression.md, "Format"): writer, checked reader, and the two decoders.
#include "inbetween/tracks/runtime/compressed_clip.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string_view>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "inbetween/math/assert.hpp"

namespace inbetween {
namespace {

// ---- little-endian byte writing
void put_u8(std::vector<std::uint8_t>& out, std::uint8_t v) { out.push_back(v); }
void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  for (int i = 0; i < 2; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}
void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}
void put_f32(std::vector<std::uint8_t>& out, float v) { put_u32(out, std::bit_cast<std::uint32_t>(v)); }
void put_f64(std::vector<std::uint8_t>& out, double v) { put_u64(out, std::bit_cast<std::uint64_t>(v)); }
void set_u32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}
// A float not below v (the stored measured error must not understate it).
float float_up(double v) {
  float f = float(v);
  if (double(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// ---- checked little-endian reading: every read names its field and byte offset on failure
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::size_t at = 0;
  Error fail(std::size_t offset, const std::string& what) const {
    return Error{ErrorCode::parse, what, {Element{"byte", offset}}};
  }
  bool has(std::size_t n) const { return at <= bytes_.size() && bytes_.size() - at >= n; }
  Expected<std::uint64_t> uint(std::size_t n, const char* field) {
    if (!has(n)) return fail(at, std::string(field) + ": the file ends (truncated)");
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t(bytes_[at + i]) << (8 * i);
    at += n;
    return v;
  }
  Expected<float> f32(const char* field) {
    const std::size_t start = at;
    auto u = uint(4, field);
    if (!u) return u.error();
    const float f = std::bit_cast<float>(std::uint32_t(*u));
    if (!std::isfinite(f)) return fail(start, std::string(field) + ": not finite");
    return f;
  }
  Expected<double> f64(const char* field) {
    const std::size_t start = at;
    auto u = uint(8, field);
    if (!u) return u.error();
    const double f = std::bit_cast<double>(*u);
    if (!std::isfinite(f)) return fail(start, std::string(field) + ": not finite");
    return f;
  }

 private:
  std::span<const std::uint8_t> bytes_;
};

#define IBC_TRY(var, expr)          \
  auto var##_r = (expr);            \
  if (!var##_r) return var##_r.error(); \
  auto var = *var##_r

// Per block and component: the smallest index and the width of the offsets from it.
struct BlockComponent {
  std::uint32_t base = 0;
  unsigned width = 0;
};
BlockComponent block_component(std::span<const std::uint32_t> values, unsigned comps, std::size_t first, std::size_t count,
                               unsigned c) {
  std::uint32_t lo = std::numeric_limits<std::uint32_t>::max(), hi = 0;
  for (std::size_t i = first; i < first + count; ++i) lo = std::min(lo, values[i * comps + c]), hi = std::max(hi, values[i * comps + c]);
  return {lo, unsigned(std::bit_width(hi - lo))};
}

// Sets `bits` bits of v at bit position `bit` of `out` (zeroed bytes); a null `out` only counts.
void put_bits(std::uint8_t* out, std::uint64_t bit, std::uint32_t v, unsigned bits) {
  if (out == nullptr) return;
  for (unsigned b = 0; b < bits; ++b, ++bit)
    if ((v >> b) & 1u) out[bit >> 3] |= std::uint8_t(1u << (bit & 7));
}

// The track's width_base and width_bits.
std::pair<unsigned, unsigned> track_widths(std::span<const std::uint32_t> values, unsigned comps) {
  const std::size_t n = values.size() / comps;
  unsigned lo = 32, hi = 0;
  for (std::size_t first = 0; first < n; first += ibc_block_controls) {
    const std::size_t count = std::min<std::size_t>(ibc_block_controls, n - first);
    for (unsigned c = 0; c < comps; ++c) {
      const unsigned w = block_component(values, comps, first, count, c).width;
      lo = std::min(lo, w), hi = std::max(hi, w);
    }
  }
  if (lo > hi) lo = hi = 0;
  return {lo, unsigned(std::bit_width(hi - lo))};
}

// Writes (or with a null `out`, counts) a spline track's superblocks and blocks from bit `bit`;
// returns the bit after them.
std::uint64_t encode_track(std::span<const std::uint32_t> values, unsigned comps, unsigned bits, std::uint8_t* out,
                           std::uint64_t bit) {
  const std::size_t n = values.size() / comps;
  const auto [width_base, width_bits] = track_widths(values, comps);
  const std::size_t super_controls = std::size_t(ibc_block_controls) * ibc_superblock_blocks;
  for (std::size_t sfirst = 0; sfirst < n; sfirst += super_controls) {
    const std::size_t scount = std::min(super_controls, n - sfirst);
    std::uint32_t sbase[4], swidth[4];
    for (unsigned c = 0; c < comps; ++c) {
      std::uint32_t lo = std::numeric_limits<std::uint32_t>::max(), hi = 0;
      for (std::size_t first = sfirst; first < sfirst + scount; first += ibc_block_controls) {
        const std::uint32_t b = block_component(values, comps, first, std::min<std::size_t>(ibc_block_controls, n - first), c).base;
        lo = std::min(lo, b), hi = std::max(hi, b);
      }
      sbase[c] = lo, swidth[c] = unsigned(std::bit_width(hi - lo));
    }
    // Fixed offsets (no field's place depends on another's value): the widths, then the bases.
    for (unsigned c = 0; c < comps; ++c) put_bits(out, bit + c * ibc_width_bits, swidth[c], ibc_width_bits);
    bit += comps * ibc_width_bits;
    for (unsigned c = 0; c < comps; ++c) put_bits(out, bit + c * bits, sbase[c], bits);
    bit += comps * bits;
    for (std::size_t first = sfirst; first < sfirst + scount; first += ibc_block_controls) {
      const std::size_t count = std::min<std::size_t>(ibc_block_controls, n - first);
      BlockComponent bc[4];
      for (unsigned c = 0; c < comps; ++c) {  // the width fields at fixed offsets, then the bases
        bc[c] = block_component(values, comps, first, count, c);
        put_bits(out, bit, bc[c].width - width_base, width_bits);
        bit += width_bits;
      }
      for (unsigned c = 0; c < comps; ++c) {
        put_bits(out, bit, bc[c].base - sbase[c], swidth[c]);
        bit += swidth[c];
      }
      for (std::size_t i = first; i < first + count; ++i)
        for (unsigned c = 0; c < comps; ++c) {
          put_bits(out, bit, values[i * comps + c] - bc[c].base, bc[c].width);
          bit += bc[c].width;
        }
    }
  }
  return bit;
}

}  // namespace

std::uint64_t compressed_block_bits(std::span<const std::uint32_t> values, unsigned components, unsigned bits) noexcept {
  return encode_track(values, components, bits, nullptr, 0);
}

std::vector<std::uint8_t> write_compressed_clip(const CompressedClipParts& parts) {
  const std::size_t joints = parts.parents.size();
  INBETWEEN_ASSERT(parts.names.size() == joints && parts.tracks.size() == 3 * joints * parts.pieces.size() &&
                   parts.values.size() == parts.tracks.size());
  std::vector<std::uint8_t> out;
  out.insert(out.end(), ibc_magic.begin(), ibc_magic.end());
  put_u16(out, ibc_version);
  put_u16(out, std::uint16_t(ibc_header_size));
  put_u32(out, 0);  // file size, set below
  put_u32(out, std::uint32_t(joints));
  put_u32(out, std::uint32_t(parts.frames));
  put_u32(out, 0);  // names offset
  put_u32(out, 0);  // tracks offset
  put_u32(out, 0);  // stream offset
  put_u32(out, 0);  // stream size
  put_f64(out, parts.first_frame);
  put_f64(out, parts.frame_rate);
  put_f32(out, float(parts.error_bound));
  put_f32(out, float_up(parts.measured_error));
  put_f32(out, float(parts.shell));
  INBETWEEN_ASSERT(out.size() == ibc_header_size);
  for (std::int32_t p : parts.parents) put_u32(out, std::uint32_t(p));
  put_u32(out, std::uint32_t(parts.pieces.size()));
  for (std::uint32_t start : parts.pieces) put_u32(out, start);
  set_u32(out, 20, std::uint32_t(out.size()));
  for (const std::string& name : parts.names) {
    const std::size_t n = std::min<std::size_t>(name.size(), 65535);
    put_u16(out, std::uint16_t(n));
    out.insert(out.end(), name.begin(), name.begin() + std::ptrdiff_t(n));
  }
  set_u32(out, 24, std::uint32_t(out.size()));
  std::uint64_t bit = 0;
  for (std::size_t k = 0; k < parts.tracks.size(); ++k) {
    const CompressedTrack& t = parts.tracks[k];
    const bool rotation = k % 3 == 1;
    put_u8(out, std::uint8_t(t.kind));
    if (t.kind == CompressedTrackKind::constant) {
      for (unsigned c = 0; c < (rotation ? 4u : 3u); ++c) put_f32(out, t.min[c]);
    } else if (t.kind == CompressedTrackKind::spline) {
      const auto [width_base, width_bits] = track_widths(parts.values[k], t.components);
      put_u8(out, t.components);
      put_u8(out, t.degree);
      put_u8(out, t.bits);
      put_u8(out, std::uint8_t(width_base));
      put_u8(out, std::uint8_t(width_bits));
      put_u16(out, std::uint16_t(t.spacing));
      put_u32(out, std::uint32_t(bit));
      for (unsigned c = 0; c < t.components; ++c) put_f32(out, t.min[c]);
      for (unsigned c = 0; c < t.components; ++c) put_f32(out, t.step[c]);
      if (rotation) {
        put_f32(out, t.reference.w), put_f32(out, t.reference.x), put_f32(out, t.reference.y), put_f32(out, t.reference.z);
      }
      bit += compressed_block_bits(parts.values[k], t.components, t.bits);
    }
  }
  set_u32(out, 28, std::uint32_t(out.size()));
  const std::size_t stream_start = out.size();
  const std::size_t stream_size = std::size_t((bit + 7) / 8) + ibc_stream_padding;
  out.resize(stream_start + stream_size, 0);
  bit = 0;
  std::uint8_t* stream = out.data() + stream_start;
  for (std::size_t k = 0; k < parts.tracks.size(); ++k) {
    const CompressedTrack& t = parts.tracks[k];
    if (t.kind == CompressedTrackKind::spline) bit = encode_track(parts.values[k], t.components, t.bits, stream, bit);
  }
  set_u32(out, 32, std::uint32_t(stream_size));
  set_u32(out, 8, std::uint32_t(out.size()));
  return out;
}

Expected<CompressedClip> load_compressed_clip(std::vector<std::uint8_t> bytes) {
  CompressedClip clip;
  Reader r(bytes);
  if (bytes.size() < ibc_header_size)
    return r.fail(bytes.size(), "header: the file ends after " + std::to_string(bytes.size()) + " bytes, a header has " +
                                    std::to_string(ibc_header_size) + " (truncated)");
  if (!std::equal(ibc_magic.begin(), ibc_magic.end(), bytes.begin())) return r.fail(0, "magic: not an .ibc file");
  r.at = 4;
  IBC_TRY(version, r.uint(2, "version"));
  if (version != ibc_version)
    return r.fail(4, "version: " + std::to_string(version) + ", this build reads version " + std::to_string(ibc_version));
  IBC_TRY(header_size, r.uint(2, "header size"));
  if (header_size != ibc_header_size) return r.fail(6, "header size: " + std::to_string(header_size) + ", expected 64");
  IBC_TRY(file_size, r.uint(4, "file size"));
  if (file_size != bytes.size())
    return r.fail(8, "file size: the header says " + std::to_string(file_size) + " bytes, the file has " +
                         std::to_string(bytes.size()) + (file_size > bytes.size() ? " (truncated)" : ""));
  IBC_TRY(joints, r.uint(4, "joint count"));
  IBC_TRY(frames, r.uint(4, "frame count"));
  if (joints == 0) return r.fail(12, "joint count: 0");
  if (frames == 0) return r.fail(16, "frame count: 0");
  IBC_TRY(names_offset, r.uint(4, "names offset"));
  IBC_TRY(tracks_offset, r.uint(4, "tracks offset"));
  IBC_TRY(stream_offset, r.uint(4, "stream offset"));
  IBC_TRY(stream_size, r.uint(4, "stream size"));
  IBC_TRY(first_frame, r.f64("first frame"));
  if (std::abs(first_frame) + double(frames) >= 9007199254740992.0)
    return r.fail(36, "first frame: |first| + frames reaches 2^53, where whole frames are no longer distinct");
  IBC_TRY(frame_rate, r.f64("frame rate"));
  if (!(frame_rate > 0)) return r.fail(44, "frame rate: not > 0");
  IBC_TRY(error_bound, r.f32("error bound"));
  IBC_TRY(measured_error, r.f32("measured error"));
  IBC_TRY(shell, r.f32("shell"));
  if (error_bound < 0 || measured_error < 0 || shell < 0) return r.fail(52, "error bound, measured error, shell: negative");
  if (joints > (bytes.size() - ibc_header_size) / 4)
    return r.fail(12, "joint count: " + std::to_string(joints) + " joints do not fit in the file");
  clip.parents_.resize(joints);
  for (std::size_t j = 0; j < joints; ++j) {
    const std::size_t at = r.at;
    IBC_TRY(p, r.uint(4, "parent"));
    const auto parent = std::int32_t(std::uint32_t(p));
    if (parent < -1 || parent >= std::int32_t(j))
      return r.fail(at, "parent of joint " + std::to_string(j) + ": " + std::to_string(parent) + " is not -1 or an earlier joint");
    clip.parents_[j] = parent;
  }
  const std::size_t pieces_at = r.at;
  IBC_TRY(pieces, r.uint(4, "piece count"));
  if (pieces == 0 || pieces > frames) return r.fail(pieces_at, "piece count: " + std::to_string(pieces) + " is not in 1 … frames");
  if (!r.has(4 * pieces)) return r.fail(r.at, "piece starts: the file ends (truncated)");
  clip.pieces_.resize(pieces);
  for (std::size_t p = 0; p < pieces; ++p) {
    const std::size_t at = r.at;
    IBC_TRY(start, r.uint(4, "piece start"));
    if (p == 0 ? start != 0 : (start <= clip.pieces_[p - 1] || start >= frames))
      return r.fail(at, "piece start " + std::to_string(p) + ": " + std::to_string(start) +
                            (p == 0 ? " is not 0" : " does not increase or is past the last frame"));
    clip.pieces_[p] = std::uint32_t(start);
  }
  if (names_offset != r.at)
    return r.fail(20, "names offset: " + std::to_string(names_offset) + ", expected " + std::to_string(r.at));
  clip.names_.resize(joints);
  std::set<std::string_view> seen;
  for (std::size_t j = 0; j < joints; ++j) {
    const std::size_t at = r.at;
    IBC_TRY(n, r.uint(2, "name length"));
    if (n == 0) return r.fail(at, "name of joint " + std::to_string(j) + ": empty");
    if (!r.has(n)) return r.fail(r.at, "name of joint " + std::to_string(j) + ": the file ends (truncated)");
    clip.names_[j].assign(reinterpret_cast<const char*>(bytes.data() + r.at), n);
    if (!seen.insert(std::string_view(reinterpret_cast<const char*>(bytes.data() + r.at), n)).second)
      return r.fail(at, "name of joint " + std::to_string(j) + ": '" + clip.names_[j] + "' names an earlier joint too");
    r.at += n;
  }
  if (tracks_offset != r.at)
    return r.fail(24, "tracks offset: " + std::to_string(tracks_offset) + ", the names end at " + std::to_string(r.at));
  if (stream_offset > bytes.size() || stream_size != bytes.size() - stream_offset || stream_size < ibc_stream_padding)
    return r.fail(28, "stream offset and size: " + std::to_string(stream_offset) + " + " + std::to_string(stream_size) +
                          " do not end the " + std::to_string(bytes.size()) + "-byte file with at least " +
                          std::to_string(ibc_stream_padding) + " bytes");
  const std::uint64_t stream_bits = std::uint64_t(stream_size - ibc_stream_padding) * 8;
  if (stream_bits >= (std::uint64_t(1) << 32)) return r.fail(32, "stream size: more than 2^32 bits");
  if (3 * joints * pieces > stream_offset) return r.fail(12, "joint and piece counts: more tracks than the track table holds");
  clip.tracks_.resize(3 * joints * pieces);
  clip.frames_ = frames;
  for (std::size_t k = 0; k < clip.tracks_.size(); ++k) {
    const std::size_t piece_frames = clip.piece_frames(k / (3 * joints));
    CompressedTrack& t = clip.tracks_[k];
    const bool rotation = k % 3 == 1;
    const std::size_t track_at = r.at;
    if (r.at >= stream_offset) return r.fail(r.at, "track " + std::to_string(k) + ": the track table runs into the stream");
    IBC_TRY(kind, r.uint(1, "track kind"));
    if (kind > 2) return r.fail(track_at, "track kind: " + std::to_string(kind) + " is not 0, 1 or 2");
    t.kind = CompressedTrackKind(kind);
    if (t.kind == CompressedTrackKind::constant) {
      for (unsigned c = 0; c < (rotation ? 4u : 3u); ++c) {
        IBC_TRY(v, r.f32("constant value"));
        t.min[c] = v;
      }
      if (rotation && t.min[0] == 0 && t.min[1] == 0 && t.min[2] == 0 && t.min[3] == 0)
        return r.fail(track_at + 1, "constant rotation: zero quaternion");
      if (rotation) t.reference = normalized(Quatd::from_wxyz(t.min[0], t.min[1], t.min[2], t.min[3])).cast<float>();
    } else if (t.kind == CompressedTrackKind::spline) {
      IBC_TRY(components, r.uint(1, "components"));
      if (components != 3 && !(rotation && components == 4))
        return r.fail(track_at + 1, "components: " + std::to_string(components) + (rotation ? " is not 3 or 4" : " is not 3"));
      t.components = std::uint8_t(components);
      IBC_TRY(degree, r.uint(1, "degree"));
      if (degree != 1 && degree != 3) return r.fail(track_at + 2, "degree: " + std::to_string(degree) + " is not 1 or 3");
      t.degree = std::uint8_t(degree);
      IBC_TRY(bits, r.uint(1, "bits"));
      if (bits > ibc_max_bits) return r.fail(track_at + 3, "bits: " + std::to_string(bits) + " > " + std::to_string(ibc_max_bits));
      t.bits = std::uint8_t(bits);
      IBC_TRY(width_base, r.uint(1, "width base"));
      if (width_base > bits) return r.fail(track_at + 4, "width base: " + std::to_string(width_base) + " > bits " + std::to_string(bits));
      t.width_base = std::uint8_t(width_base);
      IBC_TRY(width_bits, r.uint(1, "width bits"));
      if (width_bits > ibc_width_bits) return r.fail(track_at + 5, "width bits: " + std::to_string(width_bits) + " > 5");
      t.width_bits = std::uint8_t(width_bits);
      IBC_TRY(spacing, r.uint(2, "spacing"));
      if (spacing == 0) return r.fail(track_at + 6, "spacing: 0");
      t.spacing = std::uint32_t(spacing);
      IBC_TRY(bit_offset, r.uint(4, "bit offset"));
      t.bit_offset = bit_offset;
      const std::uint64_t controls = compressed_segments(piece_frames, spacing) + degree;
      if (controls >= (std::uint64_t(1) << 31)) return r.fail(track_at + 6, "spacing: 2^31 control points or more");
      t.controls = std::uint32_t(controls);
      // Walk the superblocks and blocks: headers and offsets inside the stream, widths ≤ bits.
      // Walk the superblocks and blocks: headers and offsets inside the stream, widths ≤ bits; the
      // decoded headers go to the block index.
      // Blocks of zero-width values take no bits: bound the index by the file (ibc_max_index_words).
      if (clip.index_.size() + std::uint64_t(t.controls / ibc_block_controls + 1) * ibc_index_words >
          ibc_max_index_words(bytes.size()))
        return r.fail(track_at + 6, "spacing: the block index would pass " + std::to_string(ibc_max_index_words(bytes.size())) +
                                        " words (32 per byte of the file, + 2^20): too many empty blocks");
      t.first_index = std::uint32_t(clip.index_.size());
      const std::uint8_t* stream = bytes.data() + stream_offset;
      std::uint64_t pos = bit_offset;
      const auto past = [&](std::uint64_t need) { return pos > stream_bits || need > stream_bits - pos; };
      const auto overrun = [&](std::uint32_t block) {
        return r.fail(track_at + 8, "bit offset: block " + std::to_string(block) + " of track " + std::to_string(k) +
                                        " runs past the " + std::to_string(stream_bits) + "-bit stream");
      };
      unsigned swidth[4] = {0, 0, 0, 0};
      std::uint32_t sbase[4] = {0, 0, 0, 0};
      for (std::uint32_t first = 0, block = 0; first < t.controls; first += ibc_block_controls, ++block) {
        if (block % ibc_superblock_blocks == 0) {
          if (past(std::uint64_t(t.components) * (t.bits + ibc_width_bits))) return overrun(block);
          for (unsigned c = 0; c < t.components; ++c) {
            swidth[c] = compressed_value(stream, pos + c * ibc_width_bits, ibc_width_bits);
            if (swidth[c] > t.bits)
              return r.fail(std::size_t(stream_offset + (pos >> 3)), "superblock width: " + std::to_string(swidth[c]) +
                                                                       " > the track's " + std::to_string(bits) + " bits (track " + std::to_string(k) + ")");
            sbase[c] = compressed_value(stream, pos + t.components * ibc_width_bits + c * t.bits, t.bits);
          }
          pos += std::uint64_t(t.components) * (t.bits + ibc_width_bits);
        }
        const std::uint32_t count = std::min<std::uint32_t>(ibc_block_controls, t.controls - first);
        std::uint64_t header = 0;
        for (unsigned c = 0; c < t.components; ++c) header += swidth[c] + t.width_bits;
        if (past(header)) return overrun(block);
        std::uint64_t row = 0;
        std::uint32_t entry[ibc_index_words] = {0, 0, 0, 0, 0, 0};
        std::uint64_t base_at = pos + std::uint64_t(t.components) * t.width_bits;
        for (unsigned c = 0; c < t.components; ++c) {
          const unsigned width = t.width_base + compressed_value(stream, pos + c * t.width_bits, t.width_bits);
          if (width > t.bits)
            return r.fail(std::size_t(stream_offset + (pos >> 3)), "block width: " + std::to_string(width) + " > the track's " +
                                                                     std::to_string(bits) + " bits (track " + std::to_string(k) + ")");
          row += width;
          entry[c] = sbase[c] + compressed_value(stream, base_at, swidth[c]);  // < 2^bits + 2^swidth ≤ 2^25
          entry[5] |= std::uint32_t(width) << (8 * c);
          base_at += swidth[c];
        }
        pos += header;
        if (past(row * count)) return overrun(block);
        entry[4] = std::uint32_t(pos);
        clip.index_.insert(clip.index_.end(), entry, entry + ibc_index_words);
        pos += row * count;
      }
      for (unsigned c = 0; c < t.components; ++c) {
        IBC_TRY(v, r.f32("range minimum"));
        t.min[c] = v;
      }
      for (unsigned c = 0; c < t.components; ++c) {
        const std::size_t at = r.at;
        IBC_TRY(v, r.f32("step"));
        if (v < 0) return r.fail(at, "step: negative");
        t.step[c] = v;
        // Indices are below 2^(bits + 1) (a base below 2^bits plus an offset below 2^bits).
        if (!std::isfinite(t.min[c] + t.step[c] * 33554432.0f)) return r.fail(at, "step: min + step · 2^25 overflows float");
      }
      if (rotation) {
        const std::size_t at = r.at;
        std::array<float, 4> q{};
        for (float& v : q) {
          IBC_TRY(x, r.f32("reference rotation"));
          v = x;
        }
        const double n = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]);
        if (std::abs(n - 1) > 1e-3) return r.fail(at, "reference rotation: not of unit length");
        t.reference = Quatf::from_wxyz(q[0], q[1], q[2], q[3]);
      }
    }
  }
  if (r.at != stream_offset)
    return r.fail(28, "stream offset: " + std::to_string(stream_offset) + ", the track table ends at " + std::to_string(r.at));
  // The runtime tables: per piece the rest pose (absent and constant values), the spline list
  // (rotations first, then translations and scales) and the rotations' lanes.
  clip.rest_.assign(pieces * joints, JointPose<float>{});
  clip.piece_splines_.assign(1, 0);
  clip.piece_lanes_.assign(1, 0);
  std::vector<CompressedSpline> vectors;
  for (std::size_t k = 0; k < clip.tracks_.size(); ++k) {
    const CompressedTrack& t = clip.tracks_[k];
    const std::size_t piece = k / (3 * joints), joint = (k / 3) % joints;
    const unsigned channel = unsigned(k % 3);
    JointPose<float>& rest = clip.rest_[piece * joints + joint];
    if (t.kind == CompressedTrackKind::constant) {
      if (channel == 1) rest.rotation = t.reference;
      else (channel == 0 ? rest.translation : rest.scale) = Vec3f{t.min[0], t.min[1], t.min[2]};
    } else if (t.kind == CompressedTrackKind::spline) {
      CompressedSpline s;
      s.inv_spacing = 1.0 / double(t.spacing);
      s.spacing = t.spacing;
      s.last_segment = t.controls - 1 - t.degree;
      s.first_index = t.first_index;
      s.joint = std::uint32_t(joint);
      s.channel = std::uint8_t(channel);
      s.form = std::uint8_t((t.components - 3) * 2 + (t.degree == 3 ? 1 : 0));
      s.min = t.min;
      s.step = t.step;
      s.reference = t.reference;
      if (channel != 1) {
        vectors.push_back(s);
      } else {
        const std::size_t lane = clip.splines_.size() - clip.piece_splines_.back();
        if (lane % 4 == 0) clip.lanes_.emplace_back();
        CompressedRotationLanes& l = clip.lanes_.back();
        l.w[lane % 4] = t.reference.w, l.x[lane % 4] = t.reference.x, l.y[lane % 4] = t.reference.y, l.z[lane % 4] = t.reference.z;
        l.full[lane % 4] = t.components == 4 ? ~std::uint32_t(0) : 0;
        l.joint[lane % 4] = std::uint32_t(joint);
        clip.splines_.push_back(s);
      }
    }
    if (k % (3 * joints) == 3 * joints - 1) {
      clip.piece_rotations_.push_back(std::uint32_t(clip.splines_.size() - clip.piece_splines_.back()));
      clip.splines_.insert(clip.splines_.end(), vectors.begin(), vectors.end());
      vectors.clear();
      clip.piece_splines_.push_back(std::uint32_t(clip.splines_.size()));
      clip.piece_lanes_.push_back(std::uint32_t(clip.lanes_.size()));
    }
  }
  clip.stream_offset_ = stream_offset;
  clip.first_frame_ = first_frame;
  clip.frame_rate_ = frame_rate;
  clip.error_bound_ = error_bound;
  clip.measured_error_ = measured_error;
  clip.shell_ = shell;
  clip.bytes_ = std::move(bytes);
  return clip;
}

namespace {

// Block index entry of control point `control` of a track whose block index starts at `first`.
[[gnu::always_inline]] inline const std::uint32_t* index_entry(const std::uint32_t* index, std::uint32_t first,
                                                               std::uint32_t control) noexcept {
  return index + first + (control / ibc_block_controls) * ibc_index_words;
}

// The quantised indices of control point `control` of a track (any block): its block's decoded
// header from the index, then the offsets at their widths.
template <unsigned Comps>
[[gnu::always_inline]] inline void control_indices(const std::uint32_t* index, std::uint32_t first, const std::uint8_t* stream,
                                                   std::uint32_t control, std::uint32_t* idx) noexcept {
  const std::uint32_t* e = index_entry(index, first, control);
  const std::uint32_t widths = e[5];
  const unsigned row = (widths * 0x01010101u) >> 24;  // the widths' sum (each ≤ 24: no carry)
  std::uint64_t pos = e[4] + std::uint64_t(control % ibc_block_controls) * row;
  for (unsigned c = 0; c < Comps; ++c) {
    const unsigned width = (widths >> (8 * c)) & 0xff;
    idx[c] = e[c] + compressed_value(stream, pos, width);
    pos += width;
  }
}

// Spline values of one track at segment `seg`, local parameter u, in the reference arithmetic
// (T = double: decode_frame, which compression's guarantee is measured on).
template <unsigned Degree, unsigned Comps, Real T>
void spline_values_reference(const CompressedTrack& t, const CompressedClip& clip, std::uint32_t seg, T u, T* out) noexcept {
  std::array<T, 4> w;
  if constexpr (Degree == 3) w = bspline_weights(u);
  else w = linear_weights(u);
  T acc[Comps] = {};
  std::uint32_t idx[Comps];
  for (unsigned k = 0; k <= Degree; ++k) {
    control_indices<Comps>(clip.block_index().data(), t.first_index, clip.stream(), seg + k, idx);
    for (unsigned c = 0; c < Comps; ++c) acc[c] += w[k] * T(idx[c]);
  }
  for (unsigned c = 0; c < Comps; ++c) out[c] = T(t.min[c]) + T(compressed_step(t, c)) * acc[c];
}

template <Real T>
void spline_values(const CompressedTrack& t, const CompressedClip& clip, std::uint32_t seg, T u, T* out) noexcept {
  if (t.components == 3) {
    if (t.degree == 3) spline_values_reference<3, 3>(t, clip, seg, u, out);
    else spline_values_reference<1, 3>(t, clip, seg, u, out);
  } else {
    if (t.degree == 3) spline_values_reference<3, 4>(t, clip, seg, u, out);
    else spline_values_reference<1, 4>(t, clip, seg, u, out);
  }
}

using F32x4 = float __attribute__((vector_size(16)));
using I32x4 = std::int32_t __attribute__((vector_size(16)));
using U64x4 = std::uint64_t __attribute__((vector_size(32)));
using U8x4 = std::uint8_t __attribute__((vector_size(4)));

// Segment, parameter and basis weights of the splines of one knot spacing at piece sample x (≥ 0).
// Every spline of a piece with the same spacing has the same segments (the piece's frames), so
// the sampler computes these once per spacing, not per track.
struct SegmentWeights {
  std::uint32_t spacing = 0;  // 0: not computed yet
  std::uint32_t seg = 0;
  std::array<float, 4> cubic{}, linear{};
};
[[gnu::always_inline]] inline void segment_weights(const CompressedSpline& s, double x, SegmentWeights& out) noexcept {
  const double ux = x * s.inv_spacing;
  auto seg = std::uint32_t(ux);
  if (double(seg + 1) * double(s.spacing) <= x) ++seg;  // x / spacing exactly at a knot
  if (seg > s.last_segment) seg = s.last_segment;
  const auto u = float((x - double(seg) * double(s.spacing)) * s.inv_spacing);
  // bspline_weights with products by 1/6 (no division in the hot path)
  constexpr float sixth = 1.0f / 6.0f;
  const float t = u, r = 1.0f - t, t2 = t * t, t3 = t2 * t;
  out.cubic = {r * r * r * sixth, (0.5f * t3 - t2) + 4.0f * sixth, (-0.5f * t3 + 0.5f * t2) + (0.5f * t + sixth), t3 * sixth};
  out.linear = linear_weights(u);
  out.spacing = s.spacing;
  out.seg = seg;
}

// The runtime's values of one spline track at segment `seg` with basis weights `w`: the block's
// decoded header from the index (no stream header read), the Degree + 1 control points — one
// 8-byte load each when a row fits — weighted in float: min + step · Σ w·index per component, in
// the lanes of a vector (lanes past the components are 0).
template <unsigned Degree, unsigned Comps>
[[gnu::always_inline]] inline F32x4 sample_spline(const CompressedSpline& s, const std::uint32_t* index, const std::uint8_t* stream,
                                                  std::uint32_t seg, const std::array<float, 4>& w) noexcept {
  F32x4 accv{};
  const std::uint32_t i0 = seg % ibc_block_controls;
  if (i0 + Degree < ibc_block_controls) {  // all control points in one block (the common case)
    // The block's header in lane form: bases loaded as a vector, widths and their prefix sums
    // (one multiplication each: bytes ≤ 24 never carry) widened from bytes.
    const std::uint32_t* e = index_entry(index, s.first_index, seg);
    const std::uint32_t widths = e[5], befores = widths * 0x01010100u;
    const unsigned row = (widths * 0x01010101u) >> 24;
    I32x4 basev;
    __builtin_memcpy(&basev, e, sizeof basev);
    U8x4 wb, bb;
    __builtin_memcpy(&wb, &widths, 4);
    __builtin_memcpy(&bb, &befores, 4);
    const U64x4 mask = (U64x4{1, 1, 1, 1} << __builtin_convertvector(wb, U64x4)) - 1;
    const U64x4 before = __builtin_convertvector(bb, U64x4);
    std::uint64_t pos = e[4] + std::uint64_t(i0) * row;
    if (row <= 56) {
      // The components in the lanes of a vector (GCC vector extensions: AVX2's variable shifts in
      // the x86-64-v3 clone, SSE2 emulation in the baseline): per control point one 8-byte load,
      // each lane shifted to its component, masked, its base added, converted, weighted.
      for (unsigned k = 0; k <= Degree; ++k, pos += row) {
        std::uint64_t word;
        __builtin_memcpy(&word, stream + (pos >> 3), 8);
        if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
        const U64x4 offsets = (U64x4{} + word) >> (before + (pos & 7)) & mask;
        accv += w[k] * __builtin_convertvector(__builtin_convertvector(offsets, I32x4) + basev, F32x4);
      }
    } else {
      for (unsigned k = 0; k <= Degree; ++k, pos += row) {
        for (unsigned c = 0; c < Comps; ++c)
          accv[c] += w[k] * float(std::uint32_t(basev[c]) + compressed_value(stream, pos + before[c], (widths >> (8 * c)) & 0xff));
      }
    }
  } else {  // the control points straddle two blocks: each read with its own block's lanes
    const std::uint32_t* e0 = index_entry(index, s.first_index, seg);
    bool scalar = false;
    for (unsigned k = 0; k <= Degree; ++k) {
      const std::uint32_t i = i0 + k;
      const std::uint32_t* e = i < ibc_block_controls ? e0 : e0 + ibc_index_words;
      const std::uint32_t at = i < ibc_block_controls ? i : i - ibc_block_controls;
      const std::uint32_t widths = e[5], befores = widths * 0x01010100u;
      const unsigned row = (widths * 0x01010101u) >> 24;
      scalar |= row > 56;
      I32x4 basev;
      __builtin_memcpy(&basev, e, sizeof basev);
      U8x4 wb, bb;
      __builtin_memcpy(&wb, &widths, 4);
      __builtin_memcpy(&bb, &befores, 4);
      const std::uint64_t pos = e[4] + std::uint64_t(at) * row;
      std::uint64_t word;
      __builtin_memcpy(&word, stream + (pos >> 3), 8);
      if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
      const U64x4 offsets = (U64x4{} + word) >> (__builtin_convertvector(bb, U64x4) + (pos & 7)) &
                            ((U64x4{1, 1, 1, 1} << __builtin_convertvector(wb, U64x4)) - 1);
      accv += w[k] * __builtin_convertvector(__builtin_convertvector(offsets, I32x4) + basev, F32x4);
    }
    if (scalar) [[unlikely]] {  // a row past 56 bits: one load per component
      accv = F32x4{};
      std::uint32_t idx[Comps];
      for (unsigned k = 0; k <= Degree; ++k) {
        control_indices<Comps>(index, s.first_index, stream, seg + k, idx);
        for (unsigned c = 0; c < Comps; ++c) accv[c] += w[k] * float(idx[c]);
      }
    }
  }
  F32x4 minv, stepv;  // lanes past the components: 0 (a CompressedTrack's min and step start zeroed)
  __builtin_memcpy(&minv, s.min.data(), sizeof minv);
  __builtin_memcpy(&stepv, s.step.data(), sizeof stepv);
  return minv + stepv * accv;
}

// One spline's values at piece sample x, the weights of its spacing cached in `sw`.
[[gnu::always_inline]] inline F32x4 spline_at(const CompressedSpline& s, const std::uint32_t* index, const std::uint8_t* stream,
                                              double x, SegmentWeights& sw) noexcept {
  if (s.spacing != sw.spacing) [[unlikely]] segment_weights(s, x, sw);
  switch (s.form) {
    case 1: return sample_spline<3, 3>(s, index, stream, sw.seg, sw.cubic);
    case 0: return sample_spline<1, 3>(s, index, stream, sw.seg, sw.linear);
    case 3: return sample_spline<3, 4>(s, index, stream, sw.seg, sw.cubic);
    default: return sample_spline<1, 4>(s, index, stream, sw.seg, sw.linear);
  }
}

// Four rotations at once, one per lane: the relative rotations' spline values `rel` (x, y, z and,
// for a 4-component track, w, per row) finished as compressed_rotation() does — w = √(1 − |v|²)
// or normalised — and multiplied by their references, then stored to their joints (`count` ≤ 4
// lanes in use).
[[gnu::always_inline]] inline void finish_rotations(const CompressedRotationLanes& l, const F32x4* rel, unsigned count,
                                                    JointPose<float>* out) noexcept {
#if defined(__SSE2__)
  __m128 x = rel[0], y = rel[1], z = rel[2], w4 = rel[3];
  _MM_TRANSPOSE4_PS(x, y, z, w4);
  const __m128 full = _mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(l.full.data())));
  const __m128 one = _mm_set1_ps(1.0f), zero = _mm_setzero_ps();
  const __m128 n3 = x * x + y * y + z * z;
  const __m128 n2 = _mm_or_ps(_mm_and_ps(full, n3 + w4 * w4), _mm_andnot_ps(full, n3));
  // 3 components: |v| < 1 → w = √(1 − |v|²), no normalisation; |v| ≥ 1 → w = 0, v / |v|.
  // 4 components: |q| > 0 → q / |q|; q = 0 → the identity.
  const __m128 w3 = _mm_sqrt_ps(_mm_max_ps(one - n3, zero));
  const __m128 norm = _mm_or_ps(_mm_and_ps(full, _mm_cmpgt_ps(n2, zero)), _mm_andnot_ps(full, _mm_cmpge_ps(n2, one)));
  const __m128 inv = _mm_or_ps(_mm_and_ps(norm, one / _mm_sqrt_ps(n2)), _mm_andnot_ps(norm, one));
  const __m128 w = _mm_or_ps(_mm_and_ps(full, _mm_or_ps(_mm_and_ps(norm, w4), _mm_andnot_ps(norm, one))), _mm_andnot_ps(full, w3));
  const __m128 bw = w * inv, bx = x * inv, by = y * inv, bz = z * inv;
  const __m128 aw = _mm_loadu_ps(l.w.data()), ax = _mm_loadu_ps(l.x.data()), ay = _mm_loadu_ps(l.y.data()),
               az = _mm_loadu_ps(l.z.data());
  __m128 qw = aw * bw - ax * bx - ay * by - az * bz;  // reference ⊗ q_rel (Quat's operator*)
  __m128 qx = aw * bx + ax * bw + ay * bz - az * by;
  __m128 qy = aw * by - ax * bz + ay * bw + az * bx;
  __m128 qz = aw * bz + ax * by - ay * bx + az * bw;
  _MM_TRANSPOSE4_PS(qw, qx, qy, qz);
  const __m128 q[4] = {qw, qx, qy, qz};
  for (unsigned k = 0; k < count; ++k) _mm_storeu_ps(&out[l.joint[k]].rotation.w, q[k]);
#else
  for (unsigned k = 0; k < count; ++k) {
    const float v[4] = {rel[k][0], rel[k][1], rel[k][2], rel[k][3]};
    out[l.joint[k]].rotation = compressed_rotation(Quatf::from_wxyz(l.w[k], l.x[k], l.y[k], l.z[k]), v, l.full[k] ? 4u : 3u);
  }
#endif
}
}  // namespace

void decode_frame(const CompressedClip& clip, std::size_t frame_index, std::span<JointPose<double>> out) noexcept {
  INBETWEEN_ASSERT(frame_index < clip.frames() && out.size() == clip.joints());
  const std::size_t piece = clip.piece_of(frame_index);
  frame_index -= clip.pieces()[piece];
  for (std::size_t j = 0; j < clip.joints(); ++j) {
    JointPose<double>& pose = out[j];
    for (unsigned ch = 0; ch < 3; ++ch) {
      const CompressedTrack& t = clip.track(piece, j, CompressedChannel(ch));
      if (t.kind == CompressedTrackKind::absent) {
        if (ch == 0) pose.translation = {};
        if (ch == 1) pose.rotation = {};
        if (ch == 2) pose.scale = {1, 1, 1};
        continue;
      }
      if (t.kind == CompressedTrackKind::constant) {
        if (ch == 1) {
          pose.rotation = normalized(Quatd::from_wxyz(t.min[0], t.min[1], t.min[2], t.min[3]));
        } else {
          (ch == 0 ? pose.translation : pose.scale) = Vec3d{t.min[0], t.min[1], t.min[2]};
        }
        continue;
      }
      const std::uint64_t seg = std::min<std::uint64_t>(frame_index / t.spacing, t.controls - 1 - t.degree);
      const double u = double(frame_index - seg * t.spacing) / double(t.spacing);
      double v[4];
      spline_values(t, clip, std::uint32_t(seg), u, v);
      if (ch == 1) {
        pose.rotation = compressed_rotation(t.reference.cast<double>(), v, t.components);
      } else {
        (ch == 0 ? pose.translation : pose.scale) = Vec3d{v[0], v[1], v[2]};
      }
    }
  }
}

// Clones for x86-64-v3 (AVX2, FMA, BMI2: Haswell, Zen and later; resolved once at load) and the
// baseline.  clang and other targets: the baseline only.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target_clones("arch=x86-64-v3", "default")]]
#endif
void sample_compressed(const CompressedClip& clip, double frame, std::span<JointPose<float>> local) noexcept {
  INBETWEEN_ASSERT(local.size() == clip.joints());
  double x = frame - clip.first_frame();
  const double last = double(clip.frames() - 1);
  if (!(x > 0)) x = 0;  // NaN too
  if (x > last) x = last;
  const std::size_t piece = clip.piece_of(std::size_t(x));
  x -= double(clip.pieces()[piece]);
  const auto rest = clip.rest_pose(piece);
  std::memcpy(static_cast<void*>(local.data()), rest.data(), rest.size_bytes());
  const std::uint32_t* index = clip.block_index().data();
  const std::uint8_t* stream = clip.stream();
  JointPose<float>* out = local.data();
  const std::span<const CompressedSpline> splines = clip.splines(piece);
  const std::size_t rotations = clip.rotation_count(piece);
  const CompressedRotationLanes* lanes = clip.rotation_lanes(piece).data();
  SegmentWeights sw;
  // The pose's absent and constant values are copied above.  Rotations, a chunk at a time: each
  // spline's values into `rel`, then four rotations at once in the lanes of a vector
  // (finish_rotations).  Then each translation and scale spline's values, written once.
  constexpr std::size_t chunk = 64;
  F32x4 rel[chunk];
  for (std::size_t first = 0; first < rotations; first += chunk) {
    const std::size_t n = std::min(chunk, rotations - first);
    for (std::size_t i = 0; i < n; ++i) rel[i] = spline_at(splines[first + i], index, stream, x, sw);
    for (std::size_t i = n; i % 4 != 0; ++i) rel[i] = F32x4{};
    for (std::size_t i = 0; i < n; i += 4)
      finish_rotations(lanes[(first + i) / 4], rel + i, unsigned(std::min<std::size_t>(4, n - i)), out);
  }
  for (std::size_t i = rotations; i < splines.size(); ++i) {
    const CompressedSpline& s = splines[i];
    const F32x4 v = spline_at(s, index, stream, x, sw);
    (s.channel == std::uint8_t(CompressedChannel::translation) ? out[s.joint].translation : out[s.joint].scale) =
        Vec3f{v[0], v[1], v[2]};
  }
}

}  // namespace inbetween
