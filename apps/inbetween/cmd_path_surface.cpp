// `inbetween path surface FILE …`: paths on surfaces (texts 004 §3.4.4), written as CSV rows.
//   MESH.obj --from I --to J [--method plane|greedy|edges]     a path on a triangle mesh
//   MESH.obj --downhill I [--up X Y Z]                         downhill on the mesh (or --method downhill --from I)
//   SURFACE.json --from U V --to U V [--count N]              the straight (u, v) line mapped onto a named surface
//   SURFACE.json --downhill U V | X Y Z [--step S] [--max-steps N] [--up X Y Z]   downhill on its implicit form
// Mesh vertices count from 0 in the order of the OBJ file's `v` lines; a surface file is JSON
// (io/surface_file.hpp, docs/paths.md).  Parsing and formatting only; the maths is
// inbetween/paths/mesh_path.hpp, surface_path.hpp and surface_shapes.hpp.
#include <cmath>
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/obj.hpp"
#include "inbetween/io/surface_file.hpp"
#include "inbetween/paths/mesh_path.hpp"
#include "inbetween/paths/surface_path.hpp"

namespace inbetween::cli {
namespace {

// Walk defaults on a surface file: the step is the surface's scale() / kStepsPerScale.
constexpr double kStepsPerScale = 20;
constexpr int kDefaultMaxSteps = 100000;
constexpr int kDefaultCount = 33;
constexpr int kMaxCount = 10'000'000;

struct Args {
  std::string input, output = "-", method = "plane", curve;
  std::vector<double> from, to, downhill;
  std::vector<double> up{0, 1, 0};
  int count = kDefaultCount;
  double step = 0;
  int max_steps = kDefaultMaxSteps;
};

// The options as the user wrote them ("--from 0.5 1").
std::string spelled(const std::string& name, const std::vector<double>& v) {
  std::string s = name;
  for (double d : v) s += ' ' + format_number(d);
  return s;
}

// A vertex index from an option of one whole number.
int vertex_of(const std::string& name, const std::vector<double>& v) {
  if (v.size() != 1)
    throw CommandError{spelled(name, v) + ": on a mesh " + name + " takes one vertex index (two or three numbers are for a surface file)"};
  if (!(v[0] == std::floor(v[0])) || std::abs(v[0]) > 2e9)
    throw CommandError{spelled(name, v) + ": a vertex index is a whole number"};
  return int(v[0]);
}

// A path error naming a parameter of the library call (Parameter{"to"}) is placed at the option
// that gave it, as the user spelled it; a place on the mesh or surface stays, after the file.
[[noreturn]] void fail(const Error& e, const Args& a) {
  const auto* arg = e.location.size() == 1 ? std::get_if<Parameter>(&e.location.front()) : nullptr;
  const std::string name = arg != nullptr ? arg->name : std::string();
  std::string option;
  if (name == "from") option = spelled("--from", a.from);
  else if (name == "to") option = spelled("--to", a.to);
  else if (name == "start") option = spelled("--downhill", a.downhill);
  else if (name == "up") option = "--up";
  else if (name == "step") option = "--step";
  else if (name == "max_steps") option = "--max-steps";
  if (!option.empty()) throw CommandError{option + ": " + e.message};
  throw CommandError{describe_in(e, a.input)};
}

std::string xyz_rows(const std::vector<Vec3d>& points) {
  std::string text = "x,y,z\n";
  for (const Vec3d& p : points)
    text += format_number(p.x) + ',' + format_number(p.y) + ',' + format_number(p.z) + '\n';
  return text;
}

// The centripetal Catmull-Rom curve file through the path's points (repeated points dropped), for
// --curve; it passes through every point.
std::string curve_through(const std::vector<Vec3d>& points) {
  std::vector<Vec3d> kept;
  for (const Vec3d& p : points)
    if (kept.empty() || distance(kept.back(), p) > 0) kept.push_back(p);
  if (kept.size() < 2) throw CommandError{"--curve: the path is a single point; there is no curve through it"};
  auto spline = build_catmull_rom(kept, CatmullRomOptions<double>{.alpha = 0.5});
  if (!spline) throw CommandError{"--curve: " + spline.error().describe()};
  return write_curve_json(AnyCurve{CurveKind::catmull_rom, 3, AnyCurveVariant{std::move(*spline)}});
}

// Writes the CSV and, with --curve, the curve file (both checked before either is written).
void write_results(const Args& a, const std::string& csv, const std::vector<Vec3d>& points) {
  const std::string curve = a.curve.empty() ? "" : curve_through(points);
  write_output(a.output, csv);
  if (!a.curve.empty()) write_output(a.curve, curve);
}

// A surface file is JSON: its first non-blank character is '{' (an OBJ line never starts so).
bool is_surface_file(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  return first != std::string::npos && text[first] == '{';
}

// Which options the user gave.
struct Given {
  bool by_method = false;  // --method downhill
  bool method = false, from = false, to = false, downhill = false, count = false, step = false, max_steps = false;
};

// --from/--to (uv line) or --downhill (walk) on a surface file.
std::pair<std::string, std::vector<Vec3d>> surface_paths(const Args& a, const std::string& text, const Given& given) {
  auto surface = parse_surface_json(text, a.input);
  if (!surface) {
    // A JSON file of another kind inbetween reads: say so and name the command that reads it.
    const std::string kind = json_file_kind(text);
    if (kind == "scene" || kind == "curve")
      throw CommandError{a.input + ": a " + kind + " file, not a surface file (\"inbetween_surface\": 1, docs/paths.md); " +
                         (kind == "scene" ? "scene files are read by inbetween bake, plot, view and convert"
                                          : "curve files are read by inbetween curve info, curve sample and curve plot")};
    if (text.find("\"inbetween_env\"") != std::string::npos && text.find("\"inbetween_surface\"") == std::string::npos)
      throw CommandError{a.input + ": an environment file, not a surface file (\"inbetween_surface\": 1, docs/paths.md); "
                                   "environment files are read by inbetween path find"};
    throw CommandError{surface.error().describe()};
  }
  if (given.method && a.method != "uv" && a.method != "downhill")
    throw CommandError{"--method " + a.method + ": a surface file takes --method uv (the (u, v) line) or downhill"};
  const bool downhill = given.by_method || given.downhill;
  if (!downhill) {
    if (!given.from || !given.to) throw CommandError{"give --from U V and --to U V, or --downhill U V"};
    if (a.from.size() != 2) throw CommandError{spelled("--from", a.from) + ": on a surface file --from takes two numbers U V"};
    if (a.to.size() != 2) throw CommandError{spelled("--to", a.to) + ": on a surface file --to takes two numbers U V"};
    if (given.step || given.max_steps) throw CommandError{"--step and --max-steps are for --downhill; the (u, v) line takes --count"};
    if (a.count < 2 || a.count > kMaxCount)
      throw CommandError{"--count " + std::to_string(a.count) + ": must be 2 … " + std::to_string(kMaxCount)};
    const auto points = parametric_surface_path<double>(
        [&](double u, double v) { return surface->point(u, v); }, Vec2d{a.from[0], a.from[1]}, Vec2d{a.to[0], a.to[1]},
        a.count);
    for (const Vec3d& p : points)
      if (!is_finite(p))
        throw CommandError{spelled("--from", a.from) + " " + spelled("--to", a.to) +
                           ": the (u, v) line leaves the range of finite numbers on this surface"};
    std::string out = "u,v,x,y,z\n";
    for (int i = 0; i < a.count; ++i) {
      const Vec2d uv = lerp(Vec2d{a.from[0], a.from[1]}, Vec2d{a.to[0], a.to[1]}, double(i) / double(a.count - 1));
      const Vec3d& p = points[std::size_t(i)];
      out += format_number(uv.x) + ',' + format_number(uv.y) + ',' + format_number(p.x) + ',' + format_number(p.y) + ',' +
             format_number(p.z) + '\n';
    }
    return {out, points};
  }
  if (given.count) throw CommandError{"--count is for the (u, v) line; --downhill takes --step and --max-steps"};
  const std::vector<double>& start = a.downhill;
  if (start.size() != 2 && start.size() != 3)
    throw CommandError{spelled("--downhill", start) + ": on a surface file the start is U V or a point X Y Z"};
  if (!surface->has_implicit())
    throw CommandError{a.input + ": a " + std::string(surface->kind()) +
                       " has no implicit form to walk on; downhill takes a plane, sphere, torus or height_field"};
  const Vec3d from = start.size() == 2 ? surface->point(start[0], start[1]) : Vec3d{start[0], start[1], start[2]};
  SurfaceWalkOptions<double> options;
  options.mode = SurfaceWalk::downhill;
  options.up = {a.up[0], a.up[1], a.up[2]};
  options.step = a.step == 0 ? surface->scale() / kStepsPerScale : a.step;
  options.max_steps = a.max_steps;
  auto path = walk_on_surface(*surface, from, options);
  if (!path) fail(path.error(), a);
  return {xyz_rows(*path), *path};
}

void setup(CLI::App& root) {
  CLI::App* path = nullptr;
  for (CLI::App* sub : root.get_subcommands([](CLI::App* s) { return s->get_name() == "path"; })) path = sub;
  if (path == nullptr) path = root.add_subcommand("path", kPathDescription);
  path->require_subcommand(1);
  auto* surface = path->add_subcommand(
      "surface",
      "A path on a triangle mesh (OBJ) or a named surface (JSON: plane, sphere, torus, height_field, bezier_patch), as CSV "
      "rows (Parent, Computer Animation, section 3.4.4)");
  auto args = std::make_shared<Args>();
  input_file(surface->add_option("FILE", args->input,
                      "OBJ mesh (v, vn, f lines; polygons are triangulated) or surface file (JSON, docs/paths.md); - for stdin"))
      ->required();
  auto* from = surface->add_option(
      "--from", args->from,
      "start: a mesh vertex I (counting from 0 in the order of the v lines) or surface parameters U V "
      "(needed, with --to, unless --downhill is given)")
      ->expected(1, 3);
  auto* to = surface->add_option("--to", args->to, "end: a mesh vertex J or surface parameters U V (needed unless downhill)")
                 ->expected(1, 3);
  auto* method = surface->add_option("--method", args->method,
                                     "mesh: plane (Fig. 3.47), greedy (across faces toward J), edges (shortest along edges); "
                                     "surface file: uv (the straight (u, v) line, its default); both: downhill (from --from; "
                                     "the same as --downhill)")
                     ->check(CLI::IsMember({"plane", "greedy", "edges", "uv", "downhill"}))
                     ->capture_default_str();
  auto* downhill = surface->add_option(
                       "--downhill", args->downhill,
                       "downhill path (Fig. 3.48) from a mesh vertex I, or on a surface file from S(U, V) or the point X Y Z "
                       "pulled onto the surface (or --method downhill --from …)")
                       ->expected(1, 3);
  surface->add_option("--up", args->up, "world up for downhill (three numbers)")->expected(3)->capture_default_str();
  auto* count = surface->add_option("--count", args->count, "surface file: points on the (u, v) line, 2 or more")
                    ->capture_default_str();
  auto* step = surface->add_option("--step", args->step,
                                   "surface file, downhill: distance per step; 0: the surface's scale / 20 (sphere radius, torus "
                                   "minor radius, grid spacing, plane axis)")
                    ->capture_default_str();
  auto* max_steps = surface->add_option("--max-steps", args->max_steps, "surface file, downhill: steps at most")
                        ->capture_default_str();
  output_file(surface->add_option("-o,--output", args->output, "output CSV (default: standard output)"));
  output_file(surface->add_option("--curve", args->curve,
                      "also write a curve file (centripetal catmull-rom through the points, readable by `curve sample`)"));
  surface->callback([args, from, to, method, downhill, count, step, max_steps] {
    // --method downhill --from … is --downhill ….
    const bool by_method = args->method == "downhill";
    if (by_method) {
      if (downhill->count() > 0) throw CommandError{"--method downhill starts at --from; --downhill is the same, give one"};
      if (to->count() > 0) throw CommandError{"--method downhill takes no --to (the path ends where it cannot descend)"};
      if (from->count() == 0) throw CommandError{"--method downhill needs --from, the start"};
      args->downhill = args->from;
    }
    if (!args->curve.empty() && args->curve == args->output)
      throw CommandError{"--curve: the curve and the CSV cannot both go to " + args->curve};
    const std::string text = read_input(args->input);
    if (is_surface_file(text)) {
      if (!by_method && downhill->count() > 0 && (from->count() > 0 || to->count() > 0 || method->count() > 0))
        throw CommandError{"--downhill takes no --from, --to or --method"};
      const Given given{by_method,          method->count() > 0, from->count() > 0,  to->count() > 0,
                        downhill->count() > 0, count->count() > 0,  step->count() > 0, max_steps->count() > 0};
      const auto [csv, points] = surface_paths(*args, text, given);
      write_results(*args, csv, points);
      return;
    }
    if (method->count() > 0 && args->method == "uv")
      throw CommandError{"--method uv is for a surface file; a mesh takes plane, greedy, edges or downhill"};
    if (count->count() > 0 || step->count() > 0 || max_steps->count() > 0)
      throw CommandError{"--count, --step and --max-steps are for a surface file, not a mesh"};
    const bool pair = from->count() > 0 || to->count() > 0;
    if (!by_method && downhill->count() > 0 && (pair || method->count() > 0))
      throw CommandError{"--downhill takes no --from, --to or --method"};
    if (!by_method && downhill->count() == 0 && (from->count() == 0 || to->count() == 0))
      throw CommandError{"give --from I and --to J, or --downhill I"};
    auto mesh = parse_obj(text, args->input);
    if (!mesh) throw CommandError{mesh.error().describe()};
    Expected<std::vector<Vec3d>> points = Error{};
    if (by_method || downhill->count() > 0) {
      auto d = downhill_mesh_path(*mesh, vertex_of("--downhill", args->downhill), Vec3d{args->up[0], args->up[1], args->up[2]});
      if (!d) fail(d.error(), *args);
      points = std::move(d->points);
    } else {
      const int i = vertex_of("--from", args->from), j = vertex_of("--to", args->to);
      if (args->method == "plane") points = plane_mesh_path(*mesh, i, j);
      else if (args->method == "greedy") points = greedy_mesh_path(*mesh, i, j);
      else points = edge_mesh_path(*mesh, i, j);
    }
    if (!points) fail(points.error(), *args);
    write_results(*args, xyz_rows(*points), *points);
  });
}

const RegisterCommand kRegister{{"path surface", 62, setup}};

}  // namespace
}  // namespace inbetween::cli
