#pragma once
/// Surface files: the versioned JSON form of the named surfaces of paths/surface_shapes.hpp
/// (docs/paths.md, "Paths on named surfaces"), read by `inbetween path surface`.  One kind member
/// beside the version:
///
///   {"inbetween_surface": 1, "sphere": {"center": [0, 0, 0], "radius": 2}}
///   "plane":        {"origin": [x, y, z], "u_axis": [x, y, z], "v_axis": [x, y, z]} (defaults: 0, +x, +z)
///   "torus":        {"center": [x, y, z], "major_radius": R, "minor_radius": r} (center default 0)
///   "height_field": {"origin": [x0, z0], "spacing": [dx, dz], "heights": [[row z0: h at x0, x0 + dx, …], …]}
///                   (origin default [0, 0], spacing default [1, 1])
///   "bezier_patch": {"points": [[P00, P10, P20, P30], [P01, …], …]} (4 rows of 4 points [x, y, z])
///
/// The reader checks the JSON shape (types, arities, unknown fields); the values are checked by
/// SurfaceShape::build, whose errors carry locations of this shape.

#include <string_view>

#include "inbetween/math/expected.hpp"
#include "inbetween/paths/surface_shapes.hpp"

namespace inbetween {

/// The surface format version this library reads ("inbetween_surface": 1).
inline constexpr int surface_format_version = 1;

/// Parses and builds a surface file.  The JSON is read with bounded nesting; a syntax error names
/// its line and column.  Every error is located {Source{source_name}, members…}:
/// "<source_name>:<JSON pointer>" ("terrain.json:/height_field/heights/2/5") or just the source name for the whole text.
Expected<SurfaceShape> parse_surface_json(std::string_view text, std::string_view source_name);

}  // namespace inbetween
