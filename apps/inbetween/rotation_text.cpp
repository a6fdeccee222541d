// The text side of `inbetween rotation convert` (rotation_text.hpp), moved out of cmd_rotation.cpp
// unchanged so the rotation fuzz target can run it.
#include "rotation_text.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include "command.hpp"
#include "inbetween/math/rotation.hpp"

namespace inbetween::cli {
namespace {

using FormatKind = RotationFormatKind;

double angle_in(double v, bool degrees) { return degrees ? deg_to_rad(v) : v; }
double angle_out(double v, bool degrees) { return degrees ? rad_to_deg(v) : v; }

}  // namespace

std::size_t RotationFormat::arity() const {
  switch (kind) {
    case FormatKind::quat:
    case FormatKind::quat_xyzw:
    case FormatKind::axis_angle: return 4;
    case FormatKind::matrix: return 9;
    case FormatKind::rotvec:
    case FormatKind::euler: return 3;
  }
  return 0;
}

std::string RotationFormat::layout() const {
  switch (kind) {
    case FormatKind::quat: return "w x y z";
    case FormatKind::quat_xyzw: return "x y z w";
    case FormatKind::matrix: return "9 entries, row-major";
    case FormatKind::axis_angle: return "x y z angle";
    case FormatKind::rotvec: return "x y z";
    case FormatKind::euler: return "three angles in the order of " + sequence.name();
  }
  return {};
}

const char* const kRotationFormatHelp =
    "quat (w x y z), quat-xyzw (x y z w), matrix (9 numbers, row-major, v' = R v), "
    "axis-angle (x y z angle), rotvec (x y z, axis times angle), euler:SEQ (SEQ as in SciPy: "
    "XYZ intrinsic, xyz extrinsic, any of the 24)";

std::optional<RotationFormat> parse_rotation_format(const std::string& text, std::string& why) {
  RotationFormat f;
  f.name = text;
  if (text == "quat") f.kind = FormatKind::quat;
  else if (text == "quat-xyzw") f.kind = FormatKind::quat_xyzw;
  else if (text == "matrix") f.kind = FormatKind::matrix;
  else if (text == "axis-angle") f.kind = FormatKind::axis_angle;
  else if (text == "rotvec") f.kind = FormatKind::rotvec;
  else if (text.rfind("euler:", 0) == 0) {
    auto seq = parse_euler_sequence(std::string_view(text).substr(6));
    if (!seq) {
      why = seq.error().message;
      return std::nullopt;
    }
    f.kind = FormatKind::euler;
    f.sequence = *seq;
  } else {
    why = "unknown format '" + text + "'; expected one of: " + kRotationFormatHelp;
    return std::nullopt;
  }
  return f;
}

// Splits a data line into numbers: separators are runs of blanks holding at most one comma.
// Returns an error message (empty on success).
std::string split_rotation_numbers(std::string_view line, std::vector<double>& out) {
  out.clear();
  std::size_t i = 0;
  const auto is_blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  bool need_number = true;  // at the start, and after a comma
  bool after_comma = false;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    if (i >= line.size()) break;
    if (line[i] == ',') {
      if (need_number) return after_comma ? "two commas in a row" : "a comma before the first number";
      need_number = true;
      after_comma = true;
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < line.size() && !is_blank(line[j]) && line[j] != ',') ++j;
    std::string_view token = line.substr(i, j - i);
    std::string_view digits = token;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    double v = 0;
    const auto res = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (res.ec != std::errc() || res.ptr != digits.data() + digits.size() || digits.empty())
      return "'" + std::string(token) + "' is not a number";
    if (!std::isfinite(v)) return "'" + std::string(token) + "' is not a finite number";
    out.push_back(v);
    need_number = false;
    after_comma = false;
    i = j;
  }
  if (after_comma) return "a comma after the last number";
  return {};
}

// Reads one rotation; throws CommandError naming the line.
Quatd read_rotation(const RotationFormat& f, const std::vector<double>& v, bool degrees, const std::string& where) {
  switch (f.kind) {
    case FormatKind::quat:
    case FormatKind::quat_xyzw: {
      const Quatd q = f.kind == FormatKind::quat ? Quatd::from_wxyz(v[0], v[1], v[2], v[3])
                                                 : Quatd::from_xyzw(v[0], v[1], v[2], v[3]);
      if (!(norm(q) > 0)) throw CommandError{where + ": a zero quaternion is not a rotation"};
      return normalized(q);
    }
    case FormatKind::matrix: {
      const Mat3d r{{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}}};
      auto q = quat_from_rotation_matrix_checked(r);
      if (!q) throw CommandError{where + ": not a rotation matrix within 1e-6: " + q.error().message};
      return *q;
    }
    case FormatKind::axis_angle: {
      const Vec3d axis{v[0], v[1], v[2]};
      if (!(norm(axis) > 0)) throw CommandError{where + ": the axis (0, 0, 0) has no direction"};
      return Quatd::from_axis_angle(axis, angle_in(v[3], degrees));
    }
    case FormatKind::rotvec: {
      const Vec3d r{v[0], v[1], v[2]};
      return quat_from_rotation_vector(degrees ? r * (pi_v<double> / 180) : r);
    }
    case FormatKind::euler:
      return quat_from_euler(f.sequence, EulerTriple<double>{angle_in(v[0], degrees), angle_in(v[1], degrees),
                                                             angle_in(v[2], degrees)});
  }
  return {};
}

// Writes one rotation as numbers; reports gimbal lock through `gimbal`.
std::vector<double> write_rotation(const RotationFormat& f, const Quatd& q_in, bool degrees, bool& gimbal) {
  gimbal = false;
  const Quatd q = canonical(q_in);
  switch (f.kind) {
    case FormatKind::quat: return {q.w, q.x, q.y, q.z};
    case FormatKind::quat_xyzw: return {q.x, q.y, q.z, q.w};
    case FormatKind::matrix: {
      const Mat3d r = matrix_from_quat(q);
      return {r.m[0][0], r.m[0][1], r.m[0][2], r.m[1][0], r.m[1][1], r.m[1][2], r.m[2][0], r.m[2][1], r.m[2][2]};
    }
    case FormatKind::axis_angle: {
      const AxisAngled aa = axis_angle_from_quat(q);
      return {aa.axis.x, aa.axis.y, aa.axis.z, angle_out(aa.angle_rad, degrees)};
    }
    case FormatKind::rotvec: {
      const Vec3d r = rotation_vector_from_quat(q) * (degrees ? 180 / pi_v<double> : 1.0);
      return {r.x, r.y, r.z};
    }
    case FormatKind::euler: {
      const EulerAngles<double> e = euler_from_quat(f.sequence, q);
      gimbal = e.gimbal_lock;
      return {angle_out(e.angles_rad[0], degrees), angle_out(e.angles_rad[1], degrees),
              angle_out(e.angles_rad[2], degrees)};
    }
  }
  return {};
}

std::vector<double> convert_rotation_line(const RotationFormat& from, const RotationFormat& to, std::string_view line,
                                          bool degrees, const std::string& where, bool& gimbal) {
  std::vector<double> numbers;
  const std::string err = split_rotation_numbers(line, numbers);
  if (!err.empty()) throw CommandError{where + ": " + err};
  if (numbers.size() != from.arity())
    throw CommandError{where + ": " + from.name + " needs " + std::to_string(from.arity()) + " numbers (" +
                       from.layout() + "), got " + std::to_string(numbers.size())};
  const Quatd q = read_rotation(from, numbers, degrees, where);
  return write_rotation(to, q, degrees, gimbal);
}

}  // namespace inbetween::cli
