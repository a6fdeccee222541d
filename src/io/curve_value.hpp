#pragma once
// Private to src/io: a curve-file object that is already parsed JSON → AnyCurve.  Shared by the
// curve-file reader (parse_curve_json) and the scene reader (inline curves of "paths" and of an
// object's "path").
#include <nlohmann/json.hpp>

#include "inbetween/curves/any_curve.hpp"
#include "inbetween/math/expected.hpp"

namespace inbetween::io_detail {

/// Reads and builds one curve-file object (docs/curve-format.md; "version" optional).  Errors
/// carry a structured `location` relative to `value` ({"points", 3}; empty for the object itself)
/// and an empty `where`.
Expected<AnyCurve> read_curve_value(const nlohmann::json& value);

}  // namespace inbetween::io_detail
