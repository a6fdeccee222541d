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
inline constexpr int scene_format_version_max = 3;

/// Reads scene JSON text into a RawScene.  Errors: ErrorCode::parse at TextLine{L, C} ("line L,
/// column C") for text that is not JSON (also a number beyond double's range, and nesting deeper
/// than 512 levels); otherwise the JSON pointer as location steps (empty for the document root).  `source_path` is the scene file's path: curve files named by
/// "file" members are read relative to its folder (empty or "-", for text from standard input:
/// relative to the current directory).  A curve file that cannot be read is ErrorCode::io at its
/// "file" member, naming the resolved path and the system's reason; an error inside it keeps its
/// own place after the file's name ("/paths/0/file: climb.json:/points/3: …").
[[nodiscard]] Expected<RawScene> read_scene_json(std::string_view json_text, std::string_view source_path = {});

/// read_scene_json() then build_scene(); describe() reads "/tracks/2/keys/3/frame: frame 2.5 is not
/// after …".  An error about the whole document has an empty location; the tool and the Python
/// module print it as "/" (describe_in(e, file, "/")).
/// `source_path` as for read_scene_json().
[[nodiscard]] Expected<Scene> parse_scene(std::string_view json_text, std::string_view source_path = {});

}  // namespace inbetween
