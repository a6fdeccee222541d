#pragma once
/// The inbetween scene file (docs/scene-format.md, docs/scene.schema.json), format versions 1 and
/// 2: JSON text → RawScene (read_scene_json), and read + build in one call (parse_scene).  The
/// reader checks only what the format says about shape (JSON syntax, member types, unknown members,
/// names of enumerations, the version); every other check is build_scene()'s (scene/scene.hpp).

#include <string_view>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/raw_scene.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween {

/// Scene format versions this reader accepts (1 and 2 read the same members today).
inline constexpr int scene_format_version_min = 1;
/// The newest scene format version this reader accepts.
inline constexpr int scene_format_version_max = 2;

/// Reads scene JSON text into a RawScene.  Errors: ErrorCode::Parse with `where` = "line L, column
/// C" for text that is not JSON (also a number beyond double's range, and nesting deeper than
/// 512 levels); otherwise a structured `location` (the JSON pointer as steps, empty for the
/// document root) with `where` empty.
[[nodiscard]] Expected<RawScene> read_scene_json(std::string_view json_text);

/// read_scene_json() then build_scene().  A structured location is rendered once, into `where`,
/// as a JSON pointer ("/tracks/2/keys/3/frame"; "/" for the document root), so describe() reads
/// "/tracks/2/keys/3/frame: frame 2.5 is not after …".
[[nodiscard]] Expected<Scene> parse_scene(std::string_view json_text);

}  // namespace inbetween
