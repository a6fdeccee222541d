#pragma once
/// The `--axes` option of the readers of files in their own axes (BVH, assimp): one vocabulary,
/// one parser, so that `--axes z-up` means the same for every format (docs/conventions.md).

#include <array>
#include <string_view>

#include "inbetween/math/expected.hpp"

namespace inbetween {

/// A change of axes as a signed permutation: row r has ±1 in the column of the file's axis that
/// new axis r comes from (positions map as p' = M p, rotations as R' = M R Mᵀ).
using AxesMatrix = std::array<std::array<int, 3>, 3>;

/// Parses an axes name: "" keeps the file's axes (the identity); "z-up" turns a Y-up file into
/// Z-up, (x, y, z) → (x, −z, y), what Blender's importers do by default; "y-up" turns a Z-up file
/// into Y-up, (x, y, z) → (x, z, −y); otherwise three signed axis letters separated by commas
/// naming where each new axis comes from, e.g. "x,-z,y" (= "z-up") or "-x,y,-z" (a half turn about
/// y).  A mirror (determinant −1) is allowed.  Error: ErrorCode::parse at Parameter{"--axes"}.
[[nodiscard]] Expected<AxesMatrix> parse_axes(std::string_view name);

}  // namespace inbetween
