#pragma once
/// Error reporting for user data: an Error names what is wrong and where, and Expected<T> carries
/// either a built value or an Error.  (C++20 has no std::expected; this is the small subset used.)

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace inbetween {

/// Machine-readable category of a user-data error.
enum class ErrorCode {
  InvalidArgument,    ///< a value outside its legal domain (negative count, zero-norm quaternion, …)
  NotFinite,          ///< NaN or infinity where a finite number is required
  KeysNotIncreasing,  ///< frames or parameters that must strictly increase do not
  WrongArity,         ///< the wrong number of components or elements
  TooFewPoints,       ///< fewer control points or keys than the construction needs
  NotARotation,       ///< a matrix that is not orthonormal with determinant +1
  Parse,              ///< text or JSON that cannot be read
  Io,                 ///< a file that cannot be opened or written
  Unsupported,        ///< a request outside what the library implements (named in the message)
  NotMonotone,        ///< a timing curve that would run backwards
  BudgetExceeded,     ///< an adaptive computation ran out of its work budget before its tolerance
};

/// A user-data error: a code, a human message and the place (JSON pointer, "line 3", "key 4", …).
struct Error {
  ErrorCode code = ErrorCode::InvalidArgument;  ///< category
  std::string message;                          ///< what is wrong, in words, including values
  std::string where;                            ///< location: JSON pointer, row, key index; may be empty

  /// "where: message", or just the message when there is no location.
  [[nodiscard]] std::string describe() const { return where.empty() ? message : where + ": " + message; }
};

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
