#pragma once
// Private to src/io: JSON text → nlohmann::json with bounded nesting and every failure turned into
// a position and a short description (no exception escapes, no unbounded input in a message).
#include <nlohmann/json.hpp>

#include "inbetween/math/expected.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace inbetween::io_detail {

/// Deepest nesting of arrays and objects accepted (issue 9: 100 000 levels crashed a dump()).
inline constexpr std::size_t kMaxJsonDepth = 512;
/// Longest piece of the input quoted in a message.
inline constexpr std::size_t kMaxQuoted = 40;

/// What went wrong while reading JSON text.
enum class JsonFailure { none, syntax, number_out_of_range, too_deep };

/// The outcome of parse_json_text().
struct JsonText {
  nlohmann::json value;             ///< the document (when failure == none)
  JsonFailure failure = JsonFailure::none;
  std::size_t line = 1, column = 1;  ///< where reading stopped (1-based)
  std::string detail;               ///< nlohmann's description (syntax) or the number (out of range), truncated
};

/// `text` cut to kMaxQuoted characters with "..." when longer.
std::string truncated(std::string_view text);

/// Reads `text` as one JSON document; never throws.
JsonText parse_json_text(std::string_view text);

/// The error of a text that is not a JSON document, `where` = `source` ("invalid JSON at line L,
/// column C: …", the number beyond double's range, or the nesting limit); nothing when it parsed.
/// The environment and surface readers' message.
std::optional<Error> json_text_error(const JsonText& parsed, const std::string& source);

/// A short rendering of a value for a message: numbers, booleans, null and short strings as JSON,
/// others by their type name ("array"), cut to kMaxQuoted characters.
std::string short_dump(const nlohmann::json& value);

}  // namespace inbetween::io_detail
