#pragma once
// The text side of `inbetween rotation convert`: format names, the number splitter of a data line
// and the conversion of one line.  A library of the tool (inbetween_cli_text) so the rotation fuzz
// target (fuzz/rotation_line_fuzz.cpp) runs exactly this code without the tool's main.  Errors are
// CommandErrors naming the line.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "inbetween/math/euler.hpp"
#include "inbetween/math/quat.hpp"

namespace inbetween::cli {

/// The representations `rotation convert` reads and writes.
enum class RotationFormatKind { quat, quat_xyzw, matrix, axis_angle, rotvec, euler };

/// A parsed --from/--to format.
struct RotationFormat {
  RotationFormatKind kind = RotationFormatKind::quat;  ///< the representation
  EulerSequence sequence{};                            ///< the axis sequence, for Euler
  std::string name;                                    ///< the text given, for messages

  /// Numbers per line: 4 (quaternions, axis-angle), 9 (matrix) or 3 (rotation vector, Euler).
  [[nodiscard]] std::size_t arity() const;
  /// The layout of a line in words, for messages ("w x y z").
  [[nodiscard]] std::string layout() const;
};

/// Help text listing the formats.
extern const char* const kRotationFormatHelp;

/// Parses a format name ("quat", "matrix", "euler:XYZ", …); on failure returns nothing and sets `why`.
std::optional<RotationFormat> parse_rotation_format(const std::string& text, std::string& why);

/// Splits a data line into finite numbers: separators are runs of blanks holding at most one comma.
/// Returns an error message (empty on success).
std::string split_rotation_numbers(std::string_view line, std::vector<double>& out);

/// Reads one rotation from `v` (arity() numbers, finite); throws CommandError prefixed by `where`.
Quatd read_rotation(const RotationFormat& f, const std::vector<double>& v, bool degrees, const std::string& where);

/// Writes one rotation as arity() numbers; sets `gimbal` when an Euler decomposition is at gimbal lock.
std::vector<double> write_rotation(const RotationFormat& f, const Quatd& q_in, bool degrees, bool& gimbal);

/// One data line of `rotation convert`: split, check the count, read in `from`, write in `to`.
/// Throws CommandError prefixed by `where` ("line 3").
std::vector<double> convert_rotation_line(const RotationFormat& from, const RotationFormat& to, std::string_view line,
                                          bool degrees, const std::string& where, bool& gimbal);

}  // namespace inbetween::cli
