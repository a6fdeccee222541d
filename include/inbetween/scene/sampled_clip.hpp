#pragma once
/// A rig clip sampled at its own frames, and the error between two of them (issue 24).  The
/// reference of compression: compress_clip() (scene/compressed_clip.hpp) reads a SampledClip and
/// guarantees clip_error(reference, decompressed, shell).max ≤ the requested error.
///
/// The metric is ACL 2.1's virtual-vertex error (acl/compression/transform_error_metrics.h,
/// qvvf_transform_error_metric): for every frame and joint, points rigidly attached to the joint
/// are carried by the raw and by the lossy object-space (world) transform, and the error is the
/// largest distance between the two images.  ACL uses the three points at `shell` along the local
/// x, y, z axes (two, x and y, when the clip has no scale); we add the joint's origin, so our
/// error is never below ACL's on the same transforms.  Scale is applied as ACL does (qvv: point
/// scaled, rotated, translated); world transforms are composed with compose() (ACL's qvv_mul: the
/// same TRS product, exact unless a parent with non-uniform scale has a rotated child).  We compute
/// in double, ACL in float.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/scene/scene.hpp"
#include "inbetween/tracks/runtime/rig_clip.hpp"

namespace inbetween {

/// A rig clip sampled at its own frames: local poses of every joint (an object of the scene), frame-major.
struct SampledClip {
  std::vector<std::int32_t> parents;    ///< per joint: parent joint or -1; parents before children
  std::vector<std::string> names;       ///< per joint
  double first_frame = 0;               ///< frame of sample 0
  double frame_rate = 0;                ///< frames per second of the scene
  std::size_t frames = 0;               ///< samples per joint (one per frame, first..last key)
  std::vector<JointPose<double>> poses; ///< frames × joints, frame-major
  /// Joint count.
  std::size_t joints() const noexcept { return parents.size(); }
  /// The local poses of frame `f` (f < frames, asserted).
  std::span<const JointPose<double>> frame(std::size_t f) const noexcept;
};

/// Samples every object of `scene` at the whole frames of its range (range_start() … range_end(),
/// one sample per frame: frames = ⌊end − start⌋ + 1), as local transforms (Scene::sample with
/// Space::local).  Joints are the scene's objects reordered so that parents come before children
/// (the scene's evaluation order); names keep the objects' names.  Errors: Unsupported when the
/// scene has no objects, or when frames × joints exceeds 2³² samples.
Expected<SampledClip> sample_clip(const Scene& scene);

/// World (object-space) transforms of frame `f` of `clip`: out[j] = out[parent] ∘ local[j]
/// (out.size() == clip.joints(), asserted).
void world_poses(const SampledClip& clip, std::size_t f, std::span<Transform<double>> out) noexcept;

/// The largest virtual-vertex error over a clip, and where it is.
struct ClipError {
  double max = 0;                     ///< largest distance (clip units)
  std::size_t frame = 0, joint = 0;   ///< sample index and joint where it is reached
};

/// ACL's virtual-vertex error: world (object-space) transforms of both clips applied to the joint's origin and the points at distance `shell` along its local x, y, z; the largest distance over frames, joints, points.
/// The clips must have the same joints and frames (asserted).  A NaN distance counts as +∞.
ClipError clip_error(const SampledClip& reference, const SampledClip& candidate, double shell);

/// The four virtual vertices of one joint's world transform: origin and the points at `shell`
/// along the local x, y, z axes (the metric's points, shared with the compressor).
void virtual_vertices(const Transform<double>& world, double shell, std::span<Vec3d, 4> out) noexcept;

}  // namespace inbetween
