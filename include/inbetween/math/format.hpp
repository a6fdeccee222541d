#pragma once
/// Number formatting for messages and output: the shortest decimal text that reads back to the same
/// value, so error messages and CSV never lose or invent digits.

#include <charconv>
#include <string>

#include "inbetween/math/scalar.hpp"

namespace inbetween {

/// Shortest round-trip text of v in its own precision ("0.1", "2", "1e-300", "inf", "nan");
/// a float prints as the shortest text that reads back to that float.
template <Real T>
std::string shortest_text(T v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

}  // namespace inbetween
