// `inbetween rotation convert --from FORMAT --to FORMAT [--degrees]`: the rotation calculator, and
// the "rotations" section of `inbetween demo`.  Parsing and formatting only; the conversions are
// the library's (rotation.hpp, euler.hpp, orientation_interp.hpp).
#include <charconv>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "command.hpp"
#include "inbetween/math/euler.hpp"
#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/math/transform.hpp"

namespace inbetween::cli {
namespace {

enum class FormatKind { Quat, QuatXyzw, Matrix, AxisAngle, RotVec, Euler };

struct Format {
  FormatKind kind = FormatKind::Quat;
  EulerSequence sequence{};  // for Euler
  std::string name;

  [[nodiscard]] std::size_t arity() const {
    switch (kind) {
      case FormatKind::Quat:
      case FormatKind::QuatXyzw:
      case FormatKind::AxisAngle: return 4;
      case FormatKind::Matrix: return 9;
      case FormatKind::RotVec:
      case FormatKind::Euler: return 3;
    }
    return 0;
  }
  [[nodiscard]] std::string layout() const {
    switch (kind) {
      case FormatKind::Quat: return "w x y z";
      case FormatKind::QuatXyzw: return "x y z w";
      case FormatKind::Matrix: return "9 entries, row-major";
      case FormatKind::AxisAngle: return "x y z angle";
      case FormatKind::RotVec: return "x y z";
      case FormatKind::Euler: return "three angles in the order of " + sequence.name();
    }
    return {};
  }
};

const char* const kFormatHelp =
    "quat (w x y z), quat-xyzw (x y z w), matrix (9 numbers, row-major, v' = R v), "
    "axis-angle (x y z angle), rotvec (x y z, axis times angle), euler:SEQ (SEQ as in SciPy: "
    "XYZ intrinsic, xyz extrinsic, any of the 24)";

std::optional<Format> parse_format(const std::string& text, std::string& why) {
  Format f;
  f.name = text;
  if (text == "quat") f.kind = FormatKind::Quat;
  else if (text == "quat-xyzw") f.kind = FormatKind::QuatXyzw;
  else if (text == "matrix") f.kind = FormatKind::Matrix;
  else if (text == "axis-angle") f.kind = FormatKind::AxisAngle;
  else if (text == "rotvec") f.kind = FormatKind::RotVec;
  else if (text.rfind("euler:", 0) == 0) {
    auto seq = parse_euler_sequence(std::string_view(text).substr(6));
    if (!seq) {
      why = seq.error().message;
      return std::nullopt;
    }
    f.kind = FormatKind::Euler;
    f.sequence = *seq;
  } else {
    why = "unknown format '" + text + "'; expected one of: " + kFormatHelp;
    return std::nullopt;
  }
  return f;
}

/// Splits a data line into numbers: separators are runs of blanks holding at most one comma.
/// Returns an error message (empty on success).
std::string split_numbers(std::string_view line, std::vector<double>& out) {
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

double angle_in(double v, bool degrees) { return degrees ? deg_to_rad(v) : v; }
double angle_out(double v, bool degrees) { return degrees ? rad_to_deg(v) : v; }

/// Reads one rotation; throws CommandError naming the line.
Quatd read_rotation(const Format& f, const std::vector<double>& v, bool degrees, const std::string& where) {
  switch (f.kind) {
    case FormatKind::Quat:
    case FormatKind::QuatXyzw: {
      const Quatd q = f.kind == FormatKind::Quat ? Quatd::from_wxyz(v[0], v[1], v[2], v[3])
                                                 : Quatd::from_xyzw(v[0], v[1], v[2], v[3]);
      if (!(norm(q) > 0)) throw CommandError{where + ": a zero quaternion is not a rotation"};
      return normalized(q);
    }
    case FormatKind::Matrix: {
      const Mat3d r{{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}}};
      auto q = quat_from_rotation_matrix_checked(r);
      if (!q) throw CommandError{where + ": not a rotation matrix within 1e-6: " + q.error().message};
      return *q;
    }
    case FormatKind::AxisAngle: {
      const Vec3d axis{v[0], v[1], v[2]};
      if (!(norm(axis) > 0)) throw CommandError{where + ": the axis (0, 0, 0) has no direction"};
      return Quatd::from_axis_angle(axis, angle_in(v[3], degrees));
    }
    case FormatKind::RotVec: {
      const Vec3d r{v[0], v[1], v[2]};
      return quat_from_rotation_vector(degrees ? r * (pi_v<double> / 180) : r);
    }
    case FormatKind::Euler:
      return quat_from_euler(f.sequence, EulerTriple<double>{angle_in(v[0], degrees), angle_in(v[1], degrees),
                                                             angle_in(v[2], degrees)});
  }
  return {};
}

/// Writes one rotation as numbers; reports gimbal lock through `gimbal`.
std::vector<double> write_rotation(const Format& f, const Quatd& q_in, bool degrees, bool& gimbal) {
  gimbal = false;
  const Quatd q = canonical(q_in);
  switch (f.kind) {
    case FormatKind::Quat: return {q.w, q.x, q.y, q.z};
    case FormatKind::QuatXyzw: return {q.x, q.y, q.z, q.w};
    case FormatKind::Matrix: {
      const Mat3d r = matrix_from_quat(q);
      return {r.m[0][0], r.m[0][1], r.m[0][2], r.m[1][0], r.m[1][1], r.m[1][2], r.m[2][0], r.m[2][1], r.m[2][2]};
    }
    case FormatKind::AxisAngle: {
      const AxisAngled aa = axis_angle_from_quat(q);
      return {aa.axis.x, aa.axis.y, aa.axis.z, angle_out(aa.angle_rad, degrees)};
    }
    case FormatKind::RotVec: {
      const Vec3d r = rotation_vector_from_quat(q) * (degrees ? 180 / pi_v<double> : 1.0);
      return {r.x, r.y, r.z};
    }
    case FormatKind::Euler: {
      const EulerAngles<double> e = euler_from_quat(f.sequence, q);
      gimbal = e.gimbal_lock;
      return {angle_out(e.angles_rad[0], degrees), angle_out(e.angles_rad[1], degrees),
              angle_out(e.angles_rad[2], degrees)};
    }
  }
  return {};
}

struct ConvertArgs {
  std::string from, to;
  bool degrees = false;
};

void run_convert(const ConvertArgs& args) {
  std::string why;
  const auto from = parse_format(args.from, why);
  if (!from) throw CommandError{"--from: " + why};
  const auto to = parse_format(args.to, why);
  if (!to) throw CommandError{"--to: " + why};
  const std::string input = read_input("-");
  std::ostringstream out;
  std::vector<std::string> warnings;
  std::vector<double> numbers;
  std::size_t line_no = 0, start = 0;
  while (start <= input.size()) {
    std::size_t end = input.find('\n', start);
    if (end == std::string::npos) end = input.size();
    const std::string_view line = std::string_view(input).substr(start, end - start);
    start = end + 1;
    ++line_no;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') {
      if (end == input.size()) break;
      continue;
    }
    const std::string where = "line " + std::to_string(line_no);
    const std::string err = split_numbers(line, numbers);
    if (!err.empty()) throw CommandError{where + ": " + err};
    if (numbers.size() != from->arity())
      throw CommandError{where + ": " + from->name + " needs " + std::to_string(from->arity()) + " numbers (" +
                         from->layout() + "), got " + std::to_string(numbers.size())};
    const Quatd q = read_rotation(*from, numbers, args.degrees, where);
    bool gimbal = false;
    const std::vector<double> result = write_rotation(*to, q, args.degrees, gimbal);
    if (gimbal)
      warnings.push_back(where + ": gimbal lock in " + to->sequence.name() +
                         ": only the sum or difference of the first and third angles is well determined (they "
                         "still give this rotation; at lock itself the third angle is set to 0)");
    for (std::size_t k = 0; k < result.size(); ++k) out << (k ? " " : "") << format_number(result[k]);
    out << '\n';
    if (end == input.size()) break;
  }
  for (const auto& w : warnings) std::cerr << "inbetween: warning: " << w << "\n";
  write_output("-", out.str());
}

void setup_rotation(CLI::App& root) {
  auto* rotation = root.add_subcommand("rotation", "Rotation tools: convert between representations");
  rotation->require_subcommand(1);
  auto args = std::make_shared<ConvertArgs>();
  auto* convert = rotation->add_subcommand(
      "convert",
      "Read one rotation per line on standard input (numbers separated by spaces or commas; blank lines and "
      "# lines skipped) and write it in another representation, one line each, shortest round-trip numbers");
  convert->add_option("--from", args->from, std::string("Input format: ") + kFormatHelp)->required();
  convert->add_option("--to", args->to, std::string("Output format: ") + kFormatHelp)->required();
  convert->add_flag("--degrees", args->degrees, "Angles in degrees instead of radians (input and output)");
  convert->callback([args] { run_convert(*args); });
}

const RegisterCommand kRegisterRotation{{"rotation", 10, setup_rotation}};

// ---------------------------------------------------------------- demo
std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", std::abs(v) < 5e-5 ? 0.0 : v);
  return buf;
}
std::string fmt_quat(const Quatd& q) {
  const Quatd c = canonical(q);
  return "(" + fmt(c.w) + ", " + fmt(c.x) + ", " + fmt(c.y) + ", " + fmt(c.z) + ")";
}
std::string fmt_deg(const EulerTriple<double>& a) {
  return "(" + fmt(rad_to_deg(a[0])) + ", " + fmt(rad_to_deg(a[1])) + ", " + fmt(rad_to_deg(a[2])) + ") deg";
}

void demo_rotations(std::ostream& out) {
  const auto deg = [](double d) { return deg_to_rad(d); };
  const EulerSequence euler_xyz = *parse_euler_sequence("XYZ");
  const EulerSequence fixed_zyx = *parse_euler_sequence("zyx");
  out << "Euler angles XYZ (30, 45, 60) deg vs fixed angles ZYX (60, 45, 30) deg, as quaternions (w x y z):\n"
      << "  Euler XYZ: " << fmt_quat(quat_from_euler(euler_xyz, EulerTriple<double>{deg(30), deg(45), deg(60)}))
      << "\n  fixed zyx: " << fmt_quat(quat_from_euler(fixed_zyx, EulerTriple<double>{deg(60), deg(45), deg(30)}))
      << "   (the same rotation)\n";

  const Mat3d r_plus = rotation_z(deg(90)).linear(), r_minus = rotation_z(deg(-90)).linear();
  const Mat3d half = matrix_lerp(r_plus, r_minus, 0.5);
  out << "\nElement-wise lerp of R_z(90) and R_z(-90) at u = 0.5 (the texts' warning):\n";
  for (int r = 0; r < 3; ++r)
    out << "  [" << fmt(half.m[r][0]) << " " << fmt(half.m[r][1]) << " " << fmt(half.m[r][2]) << "]\n";
  out << "  determinant " << fmt(determinant(half)) << ": it flattens everything onto the z axis; slerp gives "
      << fmt_quat(slerp(quat_from_matrix(r_plus), quat_from_matrix(r_minus), 0.5)) << " = the identity\n";

  const EulerTriple<double> e0{0, 0, 0}, e1{deg(90), deg(60), deg(-45)};
  const Quatd q0 = quat_from_euler(euler_xyz, e0), q1 = quat_from_euler(euler_xyz, e1);
  const double total = angle_between(q0, q1);
  out << "\nFrom identity to Euler XYZ (90, 60, -45) deg (" << fmt(rad_to_deg(total))
      << " deg apart): angle turned from the start at u = 0.25 / 0.5, and distance from the slerp midpoint\n";
  const Quatd mid = slerp(q0, q1, 0.5);
  const auto row = [&](const char* name, const Quatd& quarter, const Quatd& halfway) {
    out << "  " << name << fmt(rad_to_deg(angle_between(q0, quarter))) << " / " << fmt(rad_to_deg(angle_between(q0, halfway)))
        << " deg, off the slerp midpoint by " << fmt(rad_to_deg(angle_between(halfway, mid))) << " deg\n";
  };
  row("slerp      ", slerp(q0, q1, 0.25), mid);
  row("nlerp      ", nlerp(q0, q1, 0.25), nlerp(q0, q1, 0.5));
  row("Euler lerp ", quat_from_euler(euler_xyz, euler_lerp(e0, e1, 0.25)),
      quat_from_euler(euler_xyz, euler_lerp(e0, e1, 0.5)));
  const AxisAngled a0 = axis_angle_from_quat(q0), a1 = axis_angle_from_quat(q1);
  row("axis-angle ", quat_from_axis_angle(axis_angle_interp(a0, a1, 0.25)),
      quat_from_axis_angle(axis_angle_interp(a0, a1, 0.5)));
  out << "  (slerp turns at constant speed: 0.25 and 0.5 of " << fmt(rad_to_deg(total)) << " deg)\n";

  const EulerSequence xyz = *parse_euler_sequence("xyz");
  const EulerTriple<double> locked_in{deg(30), deg(90), deg(40)};
  const EulerAngles<double> locked = euler_from_quat(xyz, quat_from_euler(xyz, locked_in));
  out << "\nGimbal lock: fixed angles xyz " << fmt_deg(locked_in) << " extracted back as " << fmt_deg(locked.angles_rad)
      << ", gimbal_lock = " << (locked.gimbal_lock ? "true" : "false")
      << "\n  (with the middle angle at 90 deg only x - z is determined; the third angle is set to 0)\n";
  const EulerTriple<double> filtered = euler_filter(xyz, locked_in, locked.angles_rad);
  out << "  the Euler filter, given the previous key " << fmt_deg(locked_in) << ", returns " << fmt_deg(filtered) << "\n";
}

const RegisterDemo kRegisterRotationDemo{{"rotations", 10, demo_rotations}};

}  // namespace
}  // namespace inbetween::cli
