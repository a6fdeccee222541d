#pragma once
// Private helpers of the io readers (curve files, environment files): errors located by
// "<source>:<JSON pointer>" and numbers read with their pointer.  Not installed.
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <string_view>

#include "inbetween/math/expected.hpp"

namespace inbetween::io_detail {

using json = nlohmann::json;

// "file:/points/3", or just "file" for the document root (whose JSON pointer is empty).
inline std::string located(const std::string& source, const std::string& pointer) {
  return pointer.empty() ? source : source + ":" + pointer;
}

// Makes errors located in one source.
struct Reader {
  std::string source;
  Error fail(std::string pointer, std::string message, ErrorCode code = ErrorCode::Parse) const {
    return Error{code, std::move(message), located(source, pointer)};
  }
};

// JSON pointers are built with append() rather than "/" + … : GCC 12 warns (-Wrestrict, a known
// false positive) on operator+ with a literal on the left.
inline std::string ptr(std::string_view field) {
  std::string s("/");
  s.append(field);
  return s;
}
inline std::string ptr(std::string_view field, std::size_t i) {
  std::string s = ptr(field);
  s.append("/").append(std::to_string(i));
  return s;
}

// Reads a number; an error names the pointer.
inline Expected<double> read_number(const Reader& r, const json& v, const std::string& pointer) {
  if (!v.is_number()) return r.fail(pointer, "expected a number, got " + std::string(v.type_name()));
  const double d = v.get<double>();
  if (!std::isfinite(d)) return r.fail(pointer, "number is not finite", ErrorCode::NotFinite);
  return d;
}

}  // namespace inbetween::io_detail
