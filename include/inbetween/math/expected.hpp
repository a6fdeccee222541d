#pragma once
/// Error reporting for user data: an Error names what is wrong and where, and Expected<T> carries
/// either a built value or an Error.  (C++20 has no std::expected; this is the small subset used.)

#include <cassert>
#include <cstddef>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
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

/// A named parameter, option or command-line argument as the caller gave it ("to", "options",
/// "--scale"): the place of an error in a value that is not a path into data.  Renders as its name.
struct Parameter {
  std::string name;  ///< the parameter's or option's name
  bool operator==(const Parameter&) const = default;
};

/// A file or stream by the name the user gave ("scene.json", "mesh.obj", "<stdin>").  Renders as its
/// name; a JSON pointer after it follows a ':' ("scene.json:/tracks/0"), any other place ": "
/// ("mesh.obj: line 3").
struct Source {
  std::string name;  ///< the file's name as given
  bool operator==(const Source&) const = default;
};

/// A line (1-based) of a text and, when known, a column (1-based; 0 = none): "line 3",
/// "line 3, column 5".
struct TextLine {
  std::size_t line = 0;    ///< 1-based line
  std::size_t column = 0;  ///< 1-based column, 0 when the place is the whole line
  bool operator==(const TextLine&) const = default;
};

/// A numbered element of a structure that is not a JSON document, by its kind and index ("vertex 3",
/// "face 7", "row 2", "segment 0"); an edge names both ends ("edge 3-7": `index` 3, `to` 7).
struct Element {
  std::string kind;        ///< singular noun: "vertex", "face", "row", "column", "segment", "edge", …
  std::size_t index = 0;   ///< the element's number (0-based unless the kind says otherwise)
  std::size_t to = npos;   ///< second end of a pair (an edge), npos for none
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);  ///< "no second index"
  bool operator==(const Element&) const = default;
};

/// One step of a structured error location: a member name (std::string) or an array index
/// (std::size_t) of the data as given, or, for places that are not paths into data, a parameter,
/// a source file, a line of a text or a numbered element.  A builder names its own inputs: the
/// parameter or member it was given ("keys", "distance_factor", "cycles") and the index into a
/// sequence.
using LocationStep = std::variant<std::string, std::size_t, Parameter, Source, TextLine, Element>;

/// True for the steps of a JSON pointer: member names and array indices.
[[nodiscard]] inline bool is_data_step(const LocationStep& step) noexcept {
  return std::holds_alternative<std::string>(step) || std::holds_alternative<std::size_t>(step);
}

/// Renders the member names and indices of `location` as a JSON pointer (RFC 6901):
/// "/tracks/2/keys/3/frame", member names with '~' and '/' escaped as "~0" and "~1"; the empty
/// location is the empty pointer "" (the whole document).  Steps of the other kinds are not part of
/// a pointer and are skipped (place() renders them).
[[nodiscard]] inline std::string json_pointer(std::span<const LocationStep> location) {
  std::string out;
  for (const LocationStep& step : location) {
    if (const auto* index = std::get_if<std::size_t>(&step)) {
      out += '/';
      out += std::to_string(*index);
      continue;
    }
    const auto* member = std::get_if<std::string>(&step);
    if (member == nullptr) continue;
    out += '/';
    for (char ch : *member) {
      if (ch == '~') out += "~0";
      else if (ch == '/') out += "~1";
      else out += ch;
    }
  }
  return out;
}

/// Renders a whole location for a message, outermost first: runs of member names and indices as
/// one JSON pointer, a Source as its name (then ':' before a pointer, ": " before anything else),
/// a Parameter as its name, a TextLine as "line 3" or "line 3, column 5", an Element as "vertex 3"
/// or "edge 3-7"; other neighbours are joined by ", " ("row 2, column 4").  The empty location
/// renders as "".  With json_pointer() the only place where a structured location becomes text.
[[nodiscard]] inline std::string render_location(std::span<const LocationStep> location) {
  std::string out;
  bool after_source = false;
  for (std::size_t i = 0; i < location.size();) {
    std::string piece;
    bool pointer = false, source = false;
    if (is_data_step(location[i])) {
      std::size_t j = i;
      while (j < location.size() && is_data_step(location[j])) ++j;
      piece = json_pointer(location.subspan(i, j - i));
      pointer = true;
      i = j;
    } else {
      const LocationStep& step = location[i++];
      if (const auto* p = std::get_if<Parameter>(&step)) {
        piece = p->name;
      } else if (const auto* f = std::get_if<Source>(&step)) {
        piece = f->name;
        source = true;
      } else if (const auto* l = std::get_if<TextLine>(&step)) {
        piece = "line " + std::to_string(l->line);
        if (l->column != 0) piece += ", column " + std::to_string(l->column);
      } else if (const auto* e = std::get_if<Element>(&step)) {
        piece = e->kind + " " + std::to_string(e->index);
        if (e->to != Element::npos) piece += "-" + std::to_string(e->to);
      }
    }
    if (!out.empty()) out += after_source ? (pointer ? ":" : ": ") : ", ";
    out += piece;
    after_source = source;
  }
  return out;
}

/// A user-data error: a code, a human message and the place, `location`: member names and indices,
/// outermost first, as the data was given (so a builder fed from a document already holds the
/// document path of the offending value), or, for places that are not paths into data, a parameter
/// ({Parameter{"to"}}), a file and a line ({Source{"mesh.obj"}, TextLine{3}}) or an element
/// ({Element{"vertex", 2}}).  One field for the place (the free-text `where` of 0.1 is gone:
/// `place()` renders it).
struct Error {
  ErrorCode code = ErrorCode::invalid_argument;  ///< category
  std::string message;                           ///< what is wrong, in words, including values
  std::vector<LocationStep> location{};          ///< the place, outermost first; may be empty

  /// Puts `steps` (outermost first) in front of the location: a caller adds its own context
  /// ({"tracks", 2}) as the error propagates out of a nested builder.  Returns *this.
  Error& prepend(std::initializer_list<LocationStep> steps) {
    location.insert(location.begin(), steps.begin(), steps.end());
    return *this;
  }
  /// Same, with the steps of another location.
  Error& prepend(std::span<const LocationStep> steps) {
    location.insert(location.begin(), steps.begin(), steps.end());
    return *this;
  }

  /// The place as text (render_location(location)); "" when the location is empty.
  [[nodiscard]] std::string place() const { return render_location(location); }

  /// "<place>: message", or just the message when the location is empty.
  [[nodiscard]] std::string describe() const {
    if (location.empty()) return message;
    return place() + ": " + message;
  }
};

/// The location of `error` without a leading Source{source} step: the place within the file a
/// caller already names ("scene.json: /tracks/0: …", not "scene.json: scene.json:/tracks/0: …").
[[nodiscard]] inline std::span<const LocationStep> location_within(const Error& error, std::string_view source) {
  std::span<const LocationStep> steps(error.location);
  if (!steps.empty()) {
    if (const auto* file = std::get_if<Source>(&steps.front()); file != nullptr && file->name == source) {
      return steps.subspan(1);
    }
  }
  return steps;
}

/// "source: place: message", the one line of the tool and of the Python module for an error in
/// the file or stream `source`: the place is render_location(location_within(error, source)),
/// `empty_place` when that is empty ("/" for a scene document's root), left out when both are.
[[nodiscard]] inline std::string describe_in(const Error& error, std::string_view source,
                                             std::string_view empty_place = {}) {
  std::string place = render_location(location_within(error, source));
  if (place.empty()) place = empty_place;
  std::string out(source);
  if (!out.empty()) out += ": ";
  if (!place.empty()) out += place + ": ";
  return out + error.message;
}

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
