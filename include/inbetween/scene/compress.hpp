#pragma once
/// Error-bounded clip compression (issue 24, docs/compression.md): a SampledClip becomes a
/// CompressedClip (tracks/runtime/compressed_clip.hpp) whose virtual-vertex error (clip_error,
/// scene/sampled_clip.hpp) is at most the requested error — a guarantee, checked on the decoded
/// bytes before they are returned.
///
/// Method: every track (a joint's translation, rotation or scale) is absent, constant, or a
/// uniform cubic B-spline fitted by least squares at a per-track knot spacing, its control points
/// range-reduced and quantised at a per-track bit width (rounded jointly: round_controls_jointly).  Each track gets a share of the error
/// budget weighted by its lever (a rotation error moves every descendant's virtual vertices in
/// proportion to their distance), the cheapest (spacing, bits) meeting its share is chosen, one
/// global factor on the shares is bisected against the exact metric, and a greedy pass then
/// relaxes tracks one by one while the exact metric stays within the bound.

#include <cstddef>
#include <cstdint>
#include <span>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/sampled_clip.hpp"
#include "inbetween/tracks/runtime/compressed_clip.hpp"

namespace inbetween {

/// Options of compress_clip().
struct CompressOptions {
  double error = 0.01;  ///< the largest virtual-vertex error allowed (clip units, finite, > 0)
  double shell = 3;     ///< distance of the virtual vertices from each joint (clip units, finite, ≥ 0)
  int piece_frames = 0;   ///< largest piece (samples), 0 for no limit: pieces cut only at jumps
  int refine_passes = 3;  ///< greedy relaxation passes after the bisection (0: none; more: smaller, slower)
};

/// Compresses `clip` (docs/compression.md).  The result's measured_error() is the larger
/// clip_error of decompress(result) and of sample_float(result) against `clip`, and is ≤ options.error.  Errors: invalid_argument naming
/// the option (error not finite or ≤ 0, shell not finite or < 0); not_finite for a non-finite
/// pose ({"frames", f, "joints", j}); unsupported for more than 65 535 frames per knot interval
/// never arises (spacings are small) — and for a clip whose bytes would exceed 4 GiB.
[[nodiscard]] Expected<CompressedClip> compress_clip(const SampledClip& clip, const CompressOptions& options = {});

/// Rounds the control points of one component of a uniform spline (degree 1 or 3, knot spacing
/// h ≥ 1, over `frames` samples; t.size() == compressed_segments(frames, h) + degree, asserted),
/// given in quantisation steps above the range's minimum (t ≥ 0), each to its floor or its ceiling
/// so that the largest error of the spline at the samples, |Σ w·(out − t)|, is the smallest such a
/// choice can give (then the smallest sum of errors): a trellis over the last `degree` choices.
/// Rounding each to nearest lets neighbouring errors add up at a sample; the compressor's
/// quantiser uses this (docs/compression.md, "Method").  out.size() == t.size().
void round_controls_jointly(std::span<const double> t, std::size_t frames, std::uint32_t h, unsigned degree,
                            std::span<std::uint32_t> out);

/// Every sample of a compressed clip, decoded in double (decode_frame), as a SampledClip.
[[nodiscard]] SampledClip decompress(const CompressedClip& clip);

/// Every sample of a compressed clip through the runtime's float sampler (sample_compressed at
/// first_frame() + f), widened to double.  compress_clip() bounds the error of this too.
[[nodiscard]] SampledClip sample_float(const CompressedClip& clip);

}  // namespace inbetween
