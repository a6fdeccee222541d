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

/// Scene format versions this reader accepts (2 adds "paths" and objects' "path" and "camera";
/// a version-1 file that uses them is an error saying it needs version 2).
inline constexpr int scene_format_version_min = 1;
/// The newest scene format version this reader accepts.
inline constexpr int scene_format_version_max = 2;

/// Reads scene JSON text into a RawScene.  Errors: ErrorCode::parse with `where` = "line L, column
/// C" for text that is not JSON (also a number beyond double's range, and nesting deeper than
/// 512 levels); otherwise a structured `location` (the JSON pointer as steps, empty for the
/// document root) with `where` empty.  `source_path` is the scene file's path: curve files named by
/// "file" members are read relative to its folder (empty or "-", for text from standard input:
/// relative to the current directory).  A curve file that cannot be read is ErrorCode::io at its
/// "file" member, naming the resolved path and the system's reason; an error inside it keeps its
/// own place after the file's name ("/paths/0/file: climb.json:/points/3: …").
[[nodiscard]] Expected<RawScene> read_scene_json(std::string_view json_text, std::string_view source_path = {});

/// read_scene_json() then build_scene().  A structured location is rendered once, into `where`,
/// as a JSON pointer ("/tracks/2/keys/3/frame"; "/" for the document root), so describe() reads
/// "/tracks/2/keys/3/frame: frame 2.5 is not after …".
/// `source_path` as for read_scene_json().
[[nodiscard]] Expected<Scene> parse_scene(std::string_view json_text, std::string_view source_path = {});

}  // namespace inbetween
