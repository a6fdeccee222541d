#pragma once
/// The inbetween scene file (docs/scene-format.md, docs/scene.schema.json): a versioned JSON
/// document with named animation tracks and objects, read into built, ready-to-evaluate tracks.
/// Every error names its place with a JSON pointer ("/tracks/2/keys/3/frame").

#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/tracks/fcurve.hpp"

namespace inbetween {

/// A named scalar track with Blender F-curve semantics.
struct SceneScalarTrack {
  std::string name;  ///< column name in baked output, e.g. "cube.location.x"
  FCurve curve;      ///< the built curve
};

/// A parsed scene.
struct Scene {
  int version = 1;                        ///< the "inbetween" format version
  double fps = 24;                        ///< frames per second (> 0)
  double range_start = 1, range_end = 1;  ///< default frame range for baking (start ≤ end)
  std::vector<SceneScalarTrack> scalar_tracks;  ///< "tracks" with kind "scalar" (the default)
};

/// Parses scene JSON text.  Errors carry ErrorCode::Parse for malformed JSON (where = "line L,
/// column C") and otherwise the code of the failed check with `where` = the JSON pointer.
[[nodiscard]] Expected<Scene> parse_scene(std::string_view json_text);

}  // namespace inbetween
