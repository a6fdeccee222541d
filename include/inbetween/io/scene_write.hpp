#pragma once
/// RawScene → scene JSON (docs/scene-format.md, format version 2): the writer that is the inverse
/// of read_scene_json() (io/scene.hpp).  Every member of every RawScene track kind is written —
/// scalar F-curves (handles, handle types, easings and their parameters, extrapolation, auto
/// smoothing, cycles), vector tracks (vec1 … color; tangent kind, explicit tangents, TCB), quaternion
/// tracks and object rotations (interpolation, long_way, glTF tangents, distance factor,
/// time_aware), Euler tracks and objects (constants or keyed channels, parents), and version 2's
/// paths (curve objects, io/curve_file.hpp's writer), path legs (curve name or inline curve, every
/// speed kind with its ease, keys or velocities, orientation with banking and local rotation) and
/// cameras (every COI mode, up, up_path, tilt) — so that
/// read_scene_json(write_scene_json(raw)) == raw member for member, with every double written in
/// its shortest round-trip form (exact).  Members equal to the reader's default are left out.

#include <string>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"

namespace inbetween {

/// Options of write_scene_json().
struct SceneWriteOptions {
  /// Spaces of indentation per level; an array or object whose text fits in 100 characters (a
  /// key, a vector) stays on one line.  Negative: the whole document on one line.
  int indent = 2;
};

/// The scene file text of `scene` (ends with a newline).  Errors: ErrorCode::not_finite when a
/// number is NaN or infinite (JSON cannot hold it), with the structured `location` of the member
/// in the RawScene — which is its JSON pointer in the file ({"tracks", 2, "keys", 3, "value"}).
/// No other check: a RawScene that build_scene() rejects is written as it is.
[[nodiscard]] Expected<std::string> write_scene_json(const RawScene& scene, const SceneWriteOptions& options = {});

}  // namespace inbetween
