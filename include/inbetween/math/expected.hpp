#pragma once
/// Error reporting for user data: an Error names what is wrong and where, and Expected<T> carries
/// either a built value or an Error.  (C++20 has no std::expected; this is the small subset used.)

#include <cassert>
#include <cstddef>
#include <initializer_list>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace inbetween {

/// Machine-readable category of a user-data error.  The PascalCase spellings (`InvalidArgument`, …)
/// are deprecated aliases kept for one release (docs/conventions.md, "Deprecation").
enum class ErrorCode {
  invalid_argument,     ///< a value outside its legal domain (negative count, zero-norm quaternion, …)
  not_finite,           ///< NaN or infinity where a finite number is required
  keys_not_increasing,  ///< frames or parameters that must strictly increase do not
  wrong_arity,          ///< the wrong number of components or elements
  too_few_points,       ///< fewer control points or keys than the construction needs
  not_a_rotation,       ///< a matrix that is not orthonormal with determinant +1
  parse,                ///< text or JSON that cannot be read
  io,                   ///< a file that cannot be opened or written
  unsupported,          ///< a request outside what the library implements (named in the message)
  not_monotone,         ///< a timing curve that would run backwards
  budget_exceeded,      ///< an adaptive computation ran out of its work budget before its tolerance

  InvalidArgument [[deprecated("use ErrorCode::invalid_argument")]] = invalid_argument,
  NotFinite [[deprecated("use ErrorCode::not_finite")]] = not_finite,
  KeysNotIncreasing [[deprecated("use ErrorCode::keys_not_increasing")]] = keys_not_increasing,
  WrongArity [[deprecated("use ErrorCode::wrong_arity")]] = wrong_arity,
  TooFewPoints [[deprecated("use ErrorCode::too_few_points")]] = too_few_points,
  NotARotation [[deprecated("use ErrorCode::not_a_rotation")]] = not_a_rotation,
  Parse [[deprecated("use ErrorCode::parse")]] = parse,
  Io [[deprecated("use ErrorCode::io")]] = io,
  Unsupported [[deprecated("use ErrorCode::unsupported")]] = unsupported,
  NotMonotone [[deprecated("use ErrorCode::not_monotone")]] = not_monotone,
  BudgetExceeded [[deprecated("use ErrorCode::budget_exceeded")]] = budget_exceeded,
};

/// One step of a structured error location: a member name (std::string) or an array index
/// (std::size_t).  A builder names its own inputs: the parameter or member it was given ("keys",
/// "distance_factor", "cycles") and the index into a sequence.
using LocationStep = std::variant<std::string, std::size_t>;

/// Renders `location` as a JSON pointer (RFC 6901): "/tracks/2/keys/3/frame", member names with
/// '~' and '/' escaped as "~0" and "~1"; the empty location is the empty pointer "" (the whole
/// document).  The one place where a structured location becomes text.
[[nodiscard]] inline std::string json_pointer(std::span<const LocationStep> location) {
  std::string out;
  for (const LocationStep& step : location) {
    out += '/';
    if (const auto* index = std::get_if<std::size_t>(&step)) {
      out += std::to_string(*index);
      continue;
    }
    for (char ch : std::get<std::string>(step)) {
      if (ch == '~') out += "~0";
      else if (ch == '/') out += "~1";
      else out += ch;
    }
  }
  return out;
}

/// A user-data error: a code, a human message and the place.  The place is either structured
/// (`location`: member names and indices, outermost first, as the data was given, so a builder
/// fed from a document already holds the document path of the offending value) or, for places
/// that are not paths into the data ("line 3, column 5" of a syntax error, "--degree"), the free
/// text `where`.
struct Error {
  ErrorCode code = ErrorCode::invalid_argument;  ///< category
  std::string message;                          ///< what is wrong, in words, including values
  std::string where;                            ///< free-text location ("line 3, column 5"); may be empty
  std::vector<LocationStep> location{};         ///< structured location, outermost first; may be empty

  /// Puts `steps` (outermost first) in front of the location: a caller adds its own context
  /// ({"tracks", 2}) as the error propagates out of a nested builder.  Returns *this.
  Error& prepend(std::initializer_list<LocationStep> steps) {
    location.insert(location.begin(), steps.begin(), steps.end());
    return *this;
  }

  /// "where: message" when `where` is set, else "<JSON pointer of location>: message" when the
  /// location is not empty, else just the message.
  [[nodiscard]] std::string describe() const {
    if (!where.empty()) return where + ": " + message;
    if (!location.empty()) return json_pointer(location) + ": " + message;
    return message;
  }
};

/// `error` with `steps` (outermost first) put in front of its location; see Error::prepend().
[[nodiscard]] inline Error prepended(Error error, std::initializer_list<LocationStep> steps) {
  error.prepend(steps);
  return error;
}

/// Either a value of type T or an Error.  Access the value only after checking has_value().
template <class T>
class Expected {
 public:
  /// A successful result.
  Expected(T value) : data_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  /// A failed result.
  Expected(Error error) : data_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  /// True when a value is held.
  [[nodiscard]] bool has_value() const noexcept { return data_.index() == 0; }
  /// Same as has_value().
  explicit operator bool() const noexcept { return has_value(); }

  /// The value; precondition has_value().
  [[nodiscard]] T& value() & { assert(has_value()); return std::get<0>(data_); }
  /// The value; precondition has_value().
  [[nodiscard]] const T& value() const& { assert(has_value()); return std::get<0>(data_); }
  /// The value, moved out; precondition has_value().
  [[nodiscard]] T&& value() && { assert(has_value()); return std::get<0>(std::move(data_)); }
  /// The error; precondition !has_value().
  [[nodiscard]] const Error& error() const& { assert(!has_value()); return std::get<1>(data_); }

  /// Member access to the value; precondition has_value().
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  /// The value; precondition has_value().
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Error> data_;
};

/// Expected<void>: success or an Error.
template <>
class Expected<void> {
 public:
  /// Success.
  Expected() = default;
  /// Failure.
  Expected(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT(google-explicit-constructor)
  /// True on success.
  [[nodiscard]] bool has_value() const noexcept { return ok_; }
  /// Same as has_value().
  explicit operator bool() const noexcept { return ok_; }
  /// The error; precondition !has_value().
  [[nodiscard]] const Error& error() const& { assert(!ok_); return error_; }

 private:
  Error error_{};
  bool ok_ = true;
};

}  // namespace inbetween
