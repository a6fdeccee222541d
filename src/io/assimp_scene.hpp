#pragma once
// Private to inbetween_io (and its tests): the translation of an already imported aiScene into a
// RawScene, apart from reading the file, so that tests can hand it scenes that no file format
// assimp reads can express (a zero quaternion, a NaN key time).
#include <assimp/scene.h>

#include "inbetween/io/assimp.hpp"

namespace inbetween::detail {

/// The node hierarchy and the selected animation of `scene` as read_assimp_file() translates them
/// (inbetween/io/assimp.hpp); errors carry no file name.
[[nodiscard]] Expected<RawScene> assimp_to_raw_scene(const aiScene& scene, const AssimpReadOptions& options);

}  // namespace inbetween::detail
