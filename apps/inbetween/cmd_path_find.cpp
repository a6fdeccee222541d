// `inbetween path find ENV.json -o PATH.json [--timing FILE] [--poses FILE]`: path finding among obstacles in 3-D
// (texts 004 §3.4.5).  Reads an environment file (docs/paths.md), plans a collision-free path
// through the static obstacles and the via points, smooths it into a Catmull-Rom curve that still
// clears every grown obstacle, times the motion along it around the moving spheres, and writes the
// curve as a curve file (readable by `inbetween curve sample`) and the timing as JSON (standard
// output unless --timing names a file).  Parsing and formatting only; the maths is
// inbetween/paths/environment.hpp and path_planner.hpp.
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <variant>

#include "command.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/environment_file.hpp"
#include "inbetween/paths/path_planner.hpp"

namespace inbetween::cli {
namespace {

struct Args {
  std::string input, output, timing = "-", poses;
  bool no_steering = false;
};

// A library error located in the environment file; `what` introduces impossible problems.
[[noreturn]] void fail(const Error& e, const std::string& file, const std::string& what = "") {
  Error located = locate_environment_error(e, file);
  located.message.insert(0, what);
  throw CommandError{located.describe()};
}

std::string timing_json(const FoundPath& f, const PathTimingOptions& options, const CapsuleMover& capsule) {
  const PathTiming& t = f.timing;
  nlohmann::json j;
  j["inbetween_timing"] = 1;
  j["avoidance"] = std::string(avoidance_name(f.avoidance));
  j["speed"] = options.speed;
  j["fps"] = options.fps;
  j["length"] = f.arc.length();
  j["duration"] = t.duration;
  j["wait"] = t.wait;
  j["clearance_slack"] = t.clearance_slack;
  nlohmann::json keys = nlohmann::json::array();
  for (const auto& k : t.keys) keys.push_back({k.t, k.s});
  j["keys"] = keys;
  nlohmann::json detours = nlohmann::json::array();
  for (const Detour& d : f.detours)
    detours.push_back({{"obstacle", d.obstacle},
                       {"side", d.front ? "front" : "behind"},
                       {"point", {d.point.x, d.point.y, d.point.z}}});
  j["detours"] = detours;
  if (f.capsule) {
    // The capsule's turns in place, at the polyline's inner vertices.
    nlohmann::json turns = nlohmann::json::array();
    const CapsuleMotion& m = *f.capsule;
    for (std::size_t i = 1; i + 1 < m.points.size(); ++i)
      turns.push_back({{"point", {m.points[i].x, m.points[i].y, m.points[i].z}},
                       {"angle_deg", m.turn_rad[i] * 180 / pi_v<double>},
                       {"t0", m.arrive[i]},
                       {"t1", m.leave[i]}});
    j["mover"] = {{"capsule", {{"half_length", capsule.half_length}, {"turn_rate_deg", capsule.turn_rate_deg}}}};
    j["turns"] = turns;
  } else {
    j["mover"] = {{"sphere", nlohmann::json::object()}};
  }
  const PlannedPolyline& poly = f.polyline;
  j["polyline"] = {{"points", poly.points.size()},       {"length", poly.length},
                   {"lattice_length", poly.lattice_length}, {"cell_size", poly.cell_size},
                   {"margin", poly.margin},                 {"expanded", poly.expanded}};
  j["spline"] = {{"control_points", f.smooth.control_points.size()},
                 {"refinements", f.smooth.refinements},
                 {"polyline_fallback", f.smooth.polyline_fallback},
                 {"sample_step", f.smooth.sample_step}};
  return j.dump(2) + "\n";
}

// The most rows --poses writes.
constexpr double kMaxPoseRows = 1e7;

// The capsule's pose at every frame 0, 1/fps, … and at the end: CSV t,x,y,z,qw,qx,qy,qz.
std::string poses_csv(const CapsuleMotion& m, double fps) {
  std::string out = "t,x,y,z,qw,qx,qy,qz\n";
  const double end = m.arrive.back();
  if (!(end * fps <= kMaxPoseRows))
    throw CommandError{"--poses: " + format_number(end) + " s at " + format_number(fps) + " fps is more than " +
                       format_number(kMaxPoseRows) + " rows; lower fps"};
  auto row = [&](double t) {
    const MoverPose p = capsule_pose_at(m, t);
    for (double v : {t, p.position.x, p.position.y, p.position.z, p.rotation.w, p.rotation.x, p.rotation.y})
      out += format_number(v) + ',';
    out += format_number(p.rotation.z) + '\n';
  };
  long long j = 0;
  for (; double(j) / fps < end; ++j) row(double(j) / fps);
  row(end);
  return out;
}

void setup(CLI::App& root) {
  // `path` may already exist (path fit, path smooth); share it.
  CLI::App* path = nullptr;
  for (CLI::App* sub : root.get_subcommands([](CLI::App* s) { return s->get_name() == "path"; })) path = sub;
  if (path == nullptr) path = root.add_subcommand("path", kPathDescription);
  path->require_subcommand(1);
  auto* find = path->add_subcommand(
      "find",
      "Find a collision-free path among 3-D obstacles for a sphere or a capsule that turns along its path (Parent, "
      "Computer Animation, section 3.4.5) and its timing");
  auto args = std::make_shared<Args>();
  input_file(find->add_option("ENV", args->input, "environment file (JSON, docs/paths.md); - for stdin"))->required();
  output_file(find->add_option("-o,--output", args->output, "output curve file (catmull-rom, readable by `curve sample`)"))
      ->required();
  output_file(find->add_option("--timing", args->timing, "where the timing JSON goes (default: standard output)"))
      ->capture_default_str();
  output_file(find->add_option("--poses", args->poses,
                   "capsule mover: CSV t,x,y,z,qw,qx,qy,qz of the centre and the rotation (local +x = the capsule's axis) "
                   "at every frame (fps of the environment file) and the end"));
  find->add_flag("--no-steering", args->no_steering,
                 "avoid moving spheres by the timing only (no detours in front of or behind them)");
  find->callback([args] {
    const std::string& file = args->input;
    if (args->output == args->timing && args->output != "")
      throw CommandError{"--timing: the timing and the curve cannot both go to " + args->output};
    if (!args->poses.empty() && (args->poses == args->output || args->poses == args->timing))
      throw CommandError{"--poses: the poses cannot go to the same place as the curve or the timing (" + args->poses + ")"};
    const auto parsed = parse_environment_json(read_input(file), file);
    if (!parsed) throw CommandError{parsed.error().describe()};
    if (!args->poses.empty() && !parsed->environment.capsule)
      throw CommandError{"--poses: " + file + " has a spherical mover, which has no orientation; poses are for \"mover\": {\"capsule\": …}"};
    const auto env = Environment::build(parsed->environment);
    if (!env) fail(env.error(), file);
    const auto found = find_path(*env, parsed->ends,
                                 {.planner = parsed->planner, .timing = parsed->timing, .steering = !args->no_steering});
    if (!found) {
      // The first step of the structured place tells the kind: an obstacle (the timing failed), an
      // option of the timing (speed, fps), else a point the planner could not reach.
      const auto& loc = found.error().location;
      const auto* first = loc.empty() ? nullptr : std::get_if<std::string>(&loc.front());
      const bool timing = first && *first == "obstacles";
      const bool option = first && (*first == "fps" || *first == "speed");
      fail(found.error(), file, timing ? "no timing: " : option ? "" : "no path: ");
    }
    const std::string curve = write_curve_json(AnyCurve{CurveKind::catmull_rom, 3, AnyCurveVariant{found->smooth.curve}});
    const std::string report = timing_json(*found, parsed->timing, env->capsule().value_or(CapsuleMover{}));
    const std::string poses = found->capsule ? poses_csv(*found->capsule, parsed->timing.fps) : "";
    write_output(args->output, curve);
    write_output(args->timing, report);
    if (!args->poses.empty()) write_output(args->poses, poses);
  });
}

const RegisterCommand kRegister{{"path find", 64, setup}};

}  // namespace
}  // namespace inbetween::cli
