// libFuzzer target: the OBJ reader and the paths on a mesh (texts 004 §3.4.4).  A mesh that reads is
// walked by every method between a few vertex pairs and downhill from a few vertices; every path
// must start and end where it says, hold only finite points, and a downhill path must never go up.
// An error is a fine answer, but it must say something.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_check.hpp"
#include "inbetween/io/obj.hpp"
#include "inbetween/paths/mesh_path.hpp"

namespace {

using namespace inbetween;

void check_error(const Error& e) {
  if (e.message.empty()) fuzz::fail("an error without a message");
}

void check_polyline(const std::vector<Vec3d>& path, const Vec3d& from, const Vec3d& to, bool ends_known) {
  if (path.empty()) fuzz::fail("an empty path without an error");
  for (std::size_t i = 0; i < path.size(); ++i) fuzz::require_finite(path[i], "path point", double(i));
  if (ends_known && (path.front() != from || path.back() != to)) fuzz::fail("a path that does not join its vertices");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 8192) return 0;  // a few hundred faces at most: the walks stay fast
  const auto mesh = parse_obj(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.obj");
  if (!mesh) {
    check_error(mesh.error());
    return 0;
  }
  if (mesh->face_count() > 256) return 0;
  const int n = mesh->vertex_count();
  const int picks[] = {0, n / 2, n - 1};
  for (const int a : picks) {
    for (const int b : picks) {
      if (a == b) continue;
      for (auto method : {plane_mesh_path<double>, greedy_mesh_path<double>, edge_mesh_path<double>}) {
        const auto path = method(*mesh, a, b);
        if (path) check_polyline(*path, mesh->vertex(a), mesh->vertex(b), true);
        else check_error(path.error());
      }
    }
    const auto down = downhill_mesh_path(*mesh, a);
    if (!down) {
      check_error(down.error());
      continue;
    }
    const auto& points = down->points;
    check_polyline(points, mesh->vertex(a), {}, false);
    for (std::size_t i = 1; i < points.size(); ++i) {
      if (points[i].y > points[i - 1].y) fuzz::fail("a downhill path that goes up");
    }
  }
  return 0;
}
