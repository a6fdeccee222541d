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
#include "rotation_text.hpp"
#include "inbetween/math/euler.hpp"
#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/math/transform.hpp"

namespace inbetween::cli {
namespace {

struct ConvertArgs {
  std::string from, to;
  bool degrees = false;
};

void run_convert(const ConvertArgs& args) {
  std::string why;
  const auto from = parse_rotation_format(args.from, why);
  if (!from) throw CommandError{"--from: " + why};
  const auto to = parse_rotation_format(args.to, why);
  if (!to) throw CommandError{"--to: " + why};
  const std::string input = read_input("-");
  std::ostringstream out;
  std::vector<std::string> warnings;
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
    bool gimbal = false;
    const std::vector<double> result = convert_rotation_line(*from, *to, line, args.degrees, where, gimbal);
    if (gimbal)
      warnings.push_back(where + ": gimbal lock in " + to->sequence.name() +
                         ": only the sum or difference of the first and third angles is well determined (they "
                         "still give this rotation; at lock itself the third angle is set to 0)");
    for (std::size_t k = 0; k < result.size(); ++k) out << (k ? " " : "") << format_number(result[k]);
    out << '\n';
    if (end == input.size()) break;
  }
  for (const auto& w : warnings) tool_err() << "inbetween: warning: " << w << "\n";
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
  convert->add_option("--from", args->from, std::string("Input format: ") + kRotationFormatHelp)->required();
  convert->add_option("--to", args->to, std::string("Output format: ") + kRotationFormatHelp)->required();
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
