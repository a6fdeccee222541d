// `inbetween path find ENV.json -o PATH.json [--timing FILE]`: path finding among obstacles in 3-D
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
  std::string input, output, timing = "-";
  bool no_steering = false;
};

// A library error located in the environment file; `what` introduces impossible problems.
[[noreturn]] void fail(const Error& e, const std::string& file, const std::string& what = "") {
  Error located = locate_environment_error(e, file);
  located.message.insert(0, what);
  throw CommandError{located.describe()};
}

std::string timing_json(const FoundPath& f, const PathTimingOptions& options) {
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

void setup(CLI::App& root) {
  // `path` may already exist (path fit, path smooth); share it.
  CLI::App* path = nullptr;
  for (CLI::App* sub : root.get_subcommands([](CLI::App* s) { return s->get_name() == "path"; })) path = sub;
  if (path == nullptr) path = root.add_subcommand("path", kPathDescription);
  path->require_subcommand(1);
  auto* find = path->add_subcommand(
      "find", "Find a collision-free path among 3-D obstacles (Parent, Computer Animation, section 3.4.5) and its timing");
  auto args = std::make_shared<Args>();
  find->add_option("ENV", args->input, "environment file (JSON, docs/paths.md); - for stdin")->required();
  find->add_option("-o,--output", args->output, "output curve file (catmull-rom, readable by `curve sample`)")
      ->required();
  find->add_option("--timing", args->timing, "where the timing JSON goes (default: standard output)")
      ->capture_default_str();
  find->add_flag("--no-steering", args->no_steering,
                 "avoid moving spheres by the timing only (no detours in front of or behind them)");
  find->callback([args] {
    const std::string& file = args->input;
    if (args->output == args->timing && args->output != "")
      throw CommandError{"--timing: the timing and the curve cannot both go to " + args->output};
    const auto parsed = parse_environment_json(read_input(file), file);
    if (!parsed) throw CommandError{parsed.error().describe()};
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
    const std::string curve = write_curve_json(AnyCurve{CurveKind::CatmullRom, 3, AnyCurveVariant{found->smooth.curve}});
    const std::string report = timing_json(*found, parsed->timing);
    write_output(args->output, curve);
    write_output(args->timing, report);
  });
}

const RegisterCommand kRegister{{"path find", 64, setup}};

}  // namespace
}  // namespace inbetween::cli
