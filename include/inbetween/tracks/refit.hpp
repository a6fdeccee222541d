#pragma once
/// Keyframe reduction: given a channel sampled densely (every frame and a few frames in between,
/// the caller's grid), choose as few keys as the tolerance allows, with the interpolations glTF
/// plays — STEP (hold), LINEAR (lerp, slerp for rotations) or CUBICSPLINE (Hermite keys with
/// separate in and out slopes; for rotations a 4-D Hermite then normalised) — keeping cubic keys
/// rather than resampling.  Keys sit on grid points; each segment is grown greedily (doubling,
/// then bisection) to the farthest grid point whose fit keeps the error at every grid point in
/// between within the tolerance.  A cubic segment's two slopes are the least-squares fit to the
/// grid points inside it (the end values are the samples themselves).  The sampler kind with the
/// fewest keys wins (ties: step, then linear, then cubic), except that a STEP fit with keys on three
/// consecutive grid points is not taken when another kind is allowed: it follows a continuously
/// moving value, which it would hold between grid points.  docs/gltf.md has the figures.
///
/// Errors are measured on the grid only: a jump between two grid points is invisible to it (the
/// caller's grid decides what "checked densely" means).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/quat.hpp"

namespace inbetween {

/// The interpolation of a refitted channel (glTF's sampler kinds).
enum class RefitInterpolation : std::uint8_t {
  step,    ///< hold the key's value until the next key (glTF STEP)
  linear,  ///< straight line; slerp (shortest path) for rotations (glTF LINEAR)
  cubic,   ///< Hermite with per-key in and out slopes (glTF CUBICSPLINE)
};

/// Options of refit_vector() and refit_rotation().
struct RefitOptions {
  double tolerance = 1e-5;    ///< largest error allowed: value units (∞-norm), radians for rotations (> 0)
  bool allow_step = true;     ///< consider STEP
  bool allow_linear = true;   ///< consider LINEAR
  bool allow_cubic = true;    ///< consider CUBICSPLINE
  /// Rotations: LINEAR segments must also stay within the tolerance when played component-wise
  /// (normalised lerp), as Blender's glTF importer plays them; the keys then serve both players.
  bool linear_rotation_also_nlerp = false;
  /// Still stretches the caller left out of its grid: each j (strictly increasing, below the last
  /// sample) says that the channel holds the value of sample j, equal to sample j + 1, at every
  /// frame between them.  Keys are then placed on both and the segment between them holds the
  /// value (zero slopes), whatever the kind, so that a long idle part of a range costs two grid
  /// points instead of a grid point per step.  Unequal samples at a hold are InvalidArgument
  /// ({"holds", i}).
  std::span<const std::size_t> holds{};
};

/// Keys of a refitted channel of `dim` components.  Slopes are per frame (glTF tangent = slope ×
/// fps, tangent_convert.hpp); for rotations the components are w, x, y, z.
struct RefitKeys {
  RefitInterpolation interpolation = RefitInterpolation::linear;  ///< the chosen sampler kind
  std::size_t dim = 1;              ///< components per key
  std::vector<double> frames;       ///< key frames (a subset of the grid), strictly increasing
  std::vector<double> values;       ///< dim values per key
  std::vector<double> in_slopes;    ///< dim slopes per key arriving (cubic only; else empty)
  std::vector<double> out_slopes;   ///< dim slopes per key leaving (cubic only; else empty)
  double max_error = 0;             ///< largest error over the grid (∞-norm, or rotation angle in radians)

  /// Number of keys.
  [[nodiscard]] std::size_t size() const noexcept { return frames.size(); }
};

/// Refits a vector channel: `values` holds dim components for each of the `frames` (strictly
/// increasing, finite, ≥ 1).  Errors (InvalidArgument / NotFinite / KeysNotIncreasing) name the
/// offending sample ({"samples", j}) or option ({"tolerance"}, {"dim"}).
[[nodiscard]] Expected<RefitKeys> refit_vector(std::span<const double> frames, std::span<const double> values,
                                               std::size_t dim, const RefitOptions& options = {});

/// Refits a rotation channel on the sphere: samples are made sign-continuous first; the error is
/// the rotation angle between the played and the sampled orientation.  Non-zero quaternions only.
[[nodiscard]] Expected<RefitKeys> refit_rotation(std::span<const double> frames, std::span<const Quatd> values,
                                                 const RefitOptions& options = {});

/// The refitted vector channel's value at `frame` as glTF plays it (held before the first and
/// after the last key), into out (size dim).
void evaluate_refit(const RefitKeys& keys, double frame, std::span<double> out) noexcept;

/// The refitted rotation channel's orientation at `frame` as glTF plays it (slerp shortest path
/// for linear; normalised 4-D Hermite for cubic).
[[nodiscard]] Quatd evaluate_refit_rotation(const RefitKeys& keys, double frame) noexcept;

/// Rotation angle (radians, in [0, π]) between two unit quaternions, accurate for tiny angles:
/// 4·atan2(|a − b|, |a + b|) after putting b on a's side.
[[nodiscard]] double rotation_angle_between(const Quatd& a, const Quatd& b) noexcept;

}  // namespace inbetween
