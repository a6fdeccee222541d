#pragma once
/// Curve files: the versioned JSON form of every curve family (docs/curve-format.md), read into a
/// type-erased AnyCurve over Vec3d and written back.  1-D and 2-D points are padded with zeros; the
/// file's dimension is remembered for output.  JSON handling stays in the .cpp (no nlohmann here).

#include <string>
#include <string_view>

#include "inbetween/curves/any_curve.hpp"
#include "inbetween/math/expected.hpp"

namespace inbetween {

/// The curve format version this library reads and writes.
inline constexpr int curve_format_version = 1;

/// Parses and builds a curve file.  Errors are located {Source{source_name}, members…}, rendered
/// "<source_name>:<JSON pointer>" (for example "path.json:/points/3"), and a message such as "expected 3 numbers".
Expected<AnyCurve> parse_curve_json(std::string_view text, std::string_view source_name);

/// Writes a curve as a version-1 curve file (pretty-printed JSON ending in a newline) with
/// `dimension` components per point.  Every kind round-trips through parse_curve_json; a periodic
/// B-spline is written with its wrapped control points and explicit knots.
std::string write_curve_json(const AnyCurve& curve);

}  // namespace inbetween
