#pragma once
// Private helpers of the io readers (curve, environment and surface files): errors located by
// {Source{file}, members and indices…} ("<source>:<JSON pointer>") and numbers read with their
// place.  Not installed.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/expected.hpp"

namespace inbetween::io_detail {

using json = nlohmann::json;

// `e` placed in the file `source`: its member names and indices after Source{source}, rendered
// "file:/points/3", or just "file" for the document root.  A place that is not in the file (a
// library call's parameter) is dropped: the file is the place.
inline Error located(Error e, const std::string& source) {
  std::erase_if(e.location, [](const LocationStep& s) { return !is_data_step(s); });
  e.location.insert(e.location.begin(), Source{source});
  return e;
}

// ---- Readers that build Error::location (environment and surface files): the same helpers.

// A place in a file's shape (Error::location).
using Loc = std::vector<LocationStep>;

// Longest member name kept in a location step or a message (a file's odd keys stay bounded).
inline constexpr std::size_t kMaxQuotedKey = 40;

// `base` one member further in; the name cut to kMaxQuotedKey characters with "..." when longer.
inline Loc join(Loc base, std::string_view field) {
  std::string name(field.substr(0, std::min(field.size(), kMaxQuotedKey)));
  if (field.size() > kMaxQuotedKey) name.append("...");
  base.emplace_back(std::move(name));
  return base;
}
// `base` one index further in.
inline Loc join(Loc base, std::size_t i) {
  base.emplace_back(i);
  return base;
}

// An error at `loc`.
inline Error fail(Loc loc, std::string message, ErrorCode code = ErrorCode::parse) {
  return Error{code, std::move(message), std::move(loc)};
}

// Rejects fields other than `known` (so a misspelt "raduis" is not silently ignored).
inline Expected<void> only_fields(const json& obj, const Loc& at, std::initializer_list<std::string_view> known) {
  for (const auto& item : obj.items())
    if (std::find(known.begin(), known.end(), item.key()) == known.end()) return fail(join(at, item.key()), "unknown field");
  return {};
}

// A finite number at `at`.
inline Expected<double> read_number(const json& v, const Loc& at) {
  if (!v.is_number()) return fail(at, "expected a number, got " + std::string(v.type_name()));
  const double d = v.get<double>();
  if (!std::isfinite(d)) return fail(at, "number is not finite", ErrorCode::not_finite);
  return d;
}

}  // namespace inbetween::io_detail
