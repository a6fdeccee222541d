// `inbetween path surface MESH.obj --from I --to J [--method plane|greedy|edges] [-o FILE]` and
// `inbetween path surface MESH.obj --downhill I [--up X Y Z] [-o FILE]`: a path on a triangle mesh
// read from an OBJ file (texts 004 §3.4.4), written as CSV rows x,y,z.  I and J count vertices from
// 0 in the order of the file's `v` lines.  Parsing and formatting only; the maths is
// inbetween/paths/mesh_path.hpp, the reading inbetween/io/obj.hpp.
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "inbetween/io/obj.hpp"
#include "inbetween/paths/mesh_path.hpp"

namespace inbetween::cli {
namespace {

struct Args {
  std::string input, output = "-", method = "plane";
  int from = -1, to = -1, downhill = -1;
  std::vector<double> up{0, 1, 0};
};

// A path error naming an argument becomes the option's spelling; a place on the mesh stays.
[[noreturn]] void fail(Error e, const Args& a) {
  if (e.where == "from") e.where = "--from " + std::to_string(a.from);
  else if (e.where == "to") e.where = "--to " + std::to_string(a.to);
  else if (e.where == "start") e.where = "--downhill " + std::to_string(a.downhill);
  else if (e.where == "up") e.where = "--up";
  else e.where = a.input + ": " + e.where;
  throw CommandError{e.describe()};
}

void setup(CLI::App& root) {
  CLI::App* path = nullptr;
  for (CLI::App* sub : root.get_subcommands([](CLI::App* s) { return s->get_name() == "path"; })) path = sub;
  if (path == nullptr) path = root.add_subcommand("path", kPathDescription);
  path->require_subcommand(1);
  auto* surface = path->add_subcommand(
      "surface", "A path on a triangle mesh from an OBJ file, as CSV rows x,y,z (Parent, Computer Animation, section 3.4.4)");
  auto args = std::make_shared<Args>();
  surface->add_option("MESH", args->input, "OBJ file (v, vn, f lines; polygons are triangulated); - for stdin")
      ->required();
  auto* from = surface->add_option(
      "--from", args->from,
      "start vertex, counting from 0 in the order of the v lines (needed, with --to, unless --downhill I is given)");
  auto* to = surface->add_option("--to", args->to, "end vertex, counting from 0 (needed unless downhill)");
  auto* method = surface->add_option("--method", args->method,
                                     "plane (Fig. 3.47), greedy (across faces toward J), edges (shortest along edges), "
                                     "downhill (from --from; the same as --downhill I)")
                     ->check(CLI::IsMember({"plane", "greedy", "edges", "downhill"}))
                     ->capture_default_str();
  auto* downhill = surface->add_option("--downhill", args->downhill,
                                       "downhill path from this vertex (Fig. 3.48; or --method downhill --from I)");
  surface->add_option("--up", args->up, "world up for --downhill (three numbers)")->expected(3)->capture_default_str();
  surface->add_option("-o,--output", args->output, "output CSV (default: standard output)");
  surface->callback([args, from, to, method, downhill] {
    // --method downhill --from I is --downhill I.
    const bool by_method = args->method == "downhill";
    if (by_method) {
      if (downhill->count() > 0) throw CommandError{"--method downhill starts at --from I; --downhill I is the same, give one"};
      if (to->count() > 0) throw CommandError{"--method downhill takes no --to (the path ends where no neighbour is lower)"};
      if (from->count() == 0) throw CommandError{"--method downhill needs --from I, the start vertex"};
      args->downhill = args->from;
    }
    const bool pair = from->count() > 0 || to->count() > 0;
    if (!by_method && downhill->count() > 0 && (pair || method->count() > 0))
      throw CommandError{"--downhill takes no --from, --to or --method"};
    if (!by_method && downhill->count() == 0 && (from->count() == 0 || to->count() == 0))
      throw CommandError{"give --from I and --to J, or --downhill I"};
    auto mesh = parse_obj(read_input(args->input), args->input);
    if (!mesh) throw CommandError{mesh.error().describe()};
    Expected<std::vector<Vec3d>> points = Error{};
    if (by_method || downhill->count() > 0) {
      auto d = downhill_mesh_path(*mesh, args->downhill, Vec3d{args->up[0], args->up[1], args->up[2]});
      if (!d) fail(d.error(), *args);
      points = std::move(d->points);
    } else if (args->method == "plane") {
      points = plane_mesh_path(*mesh, args->from, args->to);
    } else if (args->method == "greedy") {
      points = greedy_mesh_path(*mesh, args->from, args->to);
    } else {
      points = edge_mesh_path(*mesh, args->from, args->to);
    }
    if (!points) fail(points.error(), *args);
    std::string text = "x,y,z\n";
    for (const Vec3d& p : *points)
      text += format_number(p.x) + ',' + format_number(p.y) + ',' + format_number(p.z) + '\n';
    write_output(args->output, text);
  });
}

const RegisterCommand kRegister{{"path surface", 62, setup}};

}  // namespace
}  // namespace inbetween::cli
