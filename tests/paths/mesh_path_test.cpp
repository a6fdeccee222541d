// Triangle meshes and the paths on them (texts 004 §3.4.4, Figs. 3.47 and 3.48).
// References used here, all independent of the code under test:
//   - distance to the mesh: Ericson's closest point on a triangle (Real-Time Collision Detection
//     §5.1.5), minimised over every triangle;
//   - shortest edge paths: Floyd–Warshall over the edge lengths;
//   - closed forms: on a flat mesh the plane and greedy paths are the chord; on the diagonal grid
//     the shortest edge path is h(√2·min + |Δi − Δk|) or h(|Δi| + |Δk|); on a unit-sphere
//     polyhedron with radial normals the plane is a great-circle plane and the section, a convex
//     polygon inside that circle, is no longer than the arc (perimeters are monotone under inclusion
//     of convex sets); the minimum of A·sin x·cos z at (−π/2, 0); a tilted plane's fall line.
#include "inbetween/paths/mesh_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "support/random.hpp"

namespace inbetween {
namespace {

using test::Random;

// ------------------------------------------------------------------------------ test meshes
// A grid of n×n squares of side h in the plane y = f(x, z) (y up), each square split along its
// (+i, +k) diagonal, wound counter-clockwise seen from +y.  Vertex (i, k) has index i(n + 1) + k
// and sits at x = x0 + i·h, z = z0 + k·h.
template <Real T, class F>
RawMesh<T> grid_mesh(int n, T h, T x0, T z0, F f) {
  RawMesh<T> raw;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const T x = x0 + T(i) * h, z = z0 + T(k) * h;
      raw.vertices.push_back({x, T(f(x, z)), z});
    }
  const auto id = [n](int i, int k) { return i * (n + 1) + k; };
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      raw.triangles.push_back({id(i, k), id(i, k + 1), id(i + 1, k + 1)});
      raw.triangles.push_back({id(i, k), id(i + 1, k + 1), id(i + 1, k)});
    }
  return raw;
}

template <Real T>
RawMesh<T> flat_grid(int n, T h = T(1)) {
  return grid_mesh<T>(n, h, T(0), T(0), [](T, T) { return T(0); });
}

constexpr double kBump = 0.3;  // amplitude of the bumpy field y = A sin x cos z
RawMesh<double> bumpy_grid(int n) {
  return grid_mesh<double>(n, 4.0 / n, -2.0, -2.0, [](double x, double z) { return kBump * std::sin(x) * std::cos(z); });
}

// An icosahedron subdivided `levels` times, vertices pushed onto the unit sphere.
RawMesh<double> icosphere(int levels, bool radial_normals) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  RawMesh<double> raw;
  for (Vec3d p : std::vector<Vec3d>{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}})
    raw.vertices.push_back(p / norm(p));
  raw.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                   {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      const Vec3d m = (raw.vertices[std::size_t(a)] + raw.vertices[std::size_t(b)]) * 0.5;
      raw.vertices.push_back(m / norm(m));
      return mid[key] = int(raw.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& [a, b, c] : raw.triangles) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    raw.triangles = next;
  }
  if (radial_normals) raw.normals = raw.vertices;
  return raw;
}

// ------------------------------------------------------------------------------ references
// Ericson's closest point on triangle abc to p.
Vec3d closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3d bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3d cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

template <Real T>
double distance_to_mesh(const RawMesh<T>& raw, const Vec3<T>& pt) {
  const Vec3d p = pt.template cast<double>();
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b, c] : raw.triangles)
    best = std::min(best, distance(p, closest_on_triangle(p, raw.vertices[std::size_t(a)].template cast<double>(),
                                                          raw.vertices[std::size_t(b)].template cast<double>(),
                                                          raw.vertices[std::size_t(c)].template cast<double>())));
  return best;
}

// All-pairs shortest edge lengths (Floyd–Warshall).
std::vector<std::vector<double>> floyd_warshall(const RawMesh<double>& raw) {
  const std::size_t n = raw.vertices.size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> d(n, std::vector<double>(n, inf));
  for (std::size_t i = 0; i < n; ++i) d[i][i] = 0;
  for (const auto& t : raw.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto a = std::size_t(t[std::size_t(k)]), b = std::size_t(t[std::size_t((k + 1) % 3)]);
      d[a][b] = d[b][a] = distance(raw.vertices[a], raw.vertices[b]);
    }
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) d[i][j] = std::min(d[i][j], d[i][k] + d[k][j]);
  return d;
}

// The bound for "lies on the mesh" and "in its plane" (double, meshes of size ~1).
constexpr double kOnMesh = 1e-9;

void expect_joins_on_mesh(const RawMesh<double>& raw, const std::vector<Vec3d>& path, int from, int to) {
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(path.front(), raw.vertices[std::size_t(from)]);
  EXPECT_EQ(path.back(), raw.vertices[std::size_t(to)]);
  for (std::size_t i = 0; i < path.size(); ++i) EXPECT_LE(distance_to_mesh(raw, path[i]), kOnMesh) << "point " << i;
  // Segments lie on the mesh too: sample their midpoints (each segment crosses one face).
  for (std::size_t i = 1; i < path.size(); ++i)
    EXPECT_LE(distance_to_mesh(raw, Vec3d((path[i - 1] + path[i]) * 0.5)), kOnMesh) << "segment " << i;
}

// ------------------------------------------------------------------------------ the builder
TEST(TriangleMesh, AdjacencyOfAClosedAndAnOpenMesh) {
  const auto sphere = build_triangle_mesh(icosphere(1, false));
  ASSERT_TRUE(sphere) << sphere.error().describe();
  EXPECT_EQ(sphere->vertex_count(), 42);  // 12 + 30 edge midpoints
  EXPECT_EQ(sphere->face_count(), 80);
  for (int f = 0; f < sphere->face_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int g = sphere->face_across(f, k);
      ASSERT_GE(g, 0) << "closed: no boundary";
      const auto& t = sphere->face(f);
      EXPECT_EQ(sphere->face_across_edge(g, t[std::size_t(k)], t[std::size_t((k + 1) % 3)]), f);
    }
  const auto grid = build_triangle_mesh(flat_grid<double>(4));
  ASSERT_TRUE(grid);
  int boundary = 0;
  for (int f = 0; f < grid->face_count(); ++f)
    for (int k = 0; k < 3; ++k) boundary += grid->face_across(f, k) < 0;
  EXPECT_EQ(boundary, 16);  // 4 sides of 4 edges
  EXPECT_EQ(grid->faces_around(0).size(), 2u);   // corner (0, 0): both triangles of its square
  EXPECT_EQ(grid->faces_around(12).size(), 6u);  // interior vertex (2, 2)
  EXPECT_EQ(std::vector<int>(grid->neighbours(12).begin(), grid->neighbours(12).end()),
            (std::vector<int>{6, 7, 11, 13, 17, 18}));
}

TEST(TriangleMesh, ComputedNormals) {
  // Flat grid: every normal is +y exactly (all cross products are (0, h², 0)).
  const auto grid = build_triangle_mesh(flat_grid<double>(3));
  ASSERT_TRUE(grid);
  EXPECT_FALSE(grid->has_given_normals());
  for (int v = 0; v < grid->vertex_count(); ++v) EXPECT_EQ(grid->normal(v), (Vec3d{0, 1, 0}));
  // Icosahedron: by its symmetry the area-weighted normal of a vertex is radial.
  const auto ico = build_triangle_mesh(icosphere(0, false));
  ASSERT_TRUE(ico);
  for (int v = 0; v < ico->vertex_count(); ++v) EXPECT_LE(distance(ico->normal(v), ico->vertex(v)), 1e-15) << v;
}

TEST(TriangleMesh, BadInputIsNamed) {
  const auto where = [](const RawMesh<double>& raw) {
    auto m = build_triangle_mesh(raw);
    return m ? std::string("built") : m.error().where;
  };
  RawMesh<double> raw = flat_grid<double>(1);  // 4 vertices, 2 faces
  EXPECT_EQ(where(RawMesh<double>{}), "vertices");
  EXPECT_EQ(where(RawMesh<double>{raw.vertices, {}, {}}), "triangles");
  auto bad = raw;
  bad.triangles[1][2] = 4;
  EXPECT_EQ(where(bad), "face 1");
  bad = raw;
  bad.triangles[1][2] = -1;
  EXPECT_EQ(where(bad), "face 1");
  bad = raw;
  bad.triangles[0] = {0, 1, 1};
  EXPECT_EQ(where(bad), "face 0");
  bad = raw;
  bad.vertices[2].y = std::nan("");
  EXPECT_EQ(where(bad), "vertex 2");
  bad = raw;
  bad.vertices[3] = bad.vertices[0] + (bad.vertices[2] - bad.vertices[0]) * 0.5;  // collinear with 0 and 2
  EXPECT_EQ(where(bad), "face 1");
  bad = raw;
  bad.vertices.push_back({0, 1, 0});
  bad.triangles.push_back({0, 3, 4});  // a third face on the diagonal edge 0-3
  EXPECT_EQ(where(bad), "face 2");
  bad = raw;
  bad.normals = {{0, 1, 0}};
  EXPECT_EQ(where(bad), "normals");
  bad.normals = {{0, 1, 0}, {0, 1, 0}, {0, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(where(bad), "normal 2");
  // A caller's names for the places (a reader's lines, say): member and index, never parsed text.
  const MeshPlaceNamer place = [](std::string_view member, std::size_t index) {
    return std::string(member) + (index == kWholeMeshMember ? "" : "[" + std::to_string(index) + "]");
  };
  EXPECT_EQ(build_triangle_mesh(bad, place).error().where, "normals[2]");
  bad = raw;
  bad.triangles[1][2] = 4;
  EXPECT_EQ(build_triangle_mesh(bad, place).error().where, "triangles[1]");
  EXPECT_EQ(build_triangle_mesh(RawMesh<double>{}, place).error().where, "vertices");
}

// ------------------------------------------------------------------------------ flat meshes
TEST(MeshPath, FlatGridPlaneAndGreedyAreTheChordEdgesTheClosedForm) {
  const int n = 6;
  const double h = 0.5;
  const RawMesh<double> raw = flat_grid<double>(n, h);
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  const auto fw = floyd_warshall(raw);
  Random rng(test::seed_for(1301));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 40; ++trial) {
    const int i1 = rng.integer(0, n), k1 = rng.integer(0, n), i2 = rng.integer(0, n), k2 = rng.integer(0, n);
    const int from = i1 * (n + 1) + k1, to = i2 * (n + 1) + k2;
    SCOPED_TRACE("from " + std::to_string(from) + " to " + std::to_string(to));
    const double chord = distance(raw.vertices[std::size_t(from)], raw.vertices[std::size_t(to)]);
    auto plane = plane_mesh_path(*mesh, from, to);
    auto greedy = greedy_mesh_path(*mesh, from, to);
    auto edges = edge_mesh_path(*mesh, from, to);
    ASSERT_TRUE(plane) << plane.error().describe();
    ASSERT_TRUE(greedy) << greedy.error().describe();
    ASSERT_TRUE(edges) << edges.error().describe();
    expect_joins_on_mesh(raw, *plane, from, to);
    expect_joins_on_mesh(raw, *greedy, from, to);
    expect_joins_on_mesh(raw, *edges, from, to);
    // Flat: the plane meets the mesh in the straight line, and the projected direction to the goal
    // is the direction to the goal, so both are the chord (to rounding: 1e-12 of a length ~3).
    EXPECT_NEAR(polyline_length(*plane), chord, 1e-12);
    EXPECT_NEAR(polyline_length(*greedy), chord, 1e-12);
    const int di = std::abs(i2 - i1), dk = std::abs(k2 - k1);
    const double closed = (i2 - i1) * (k2 - k1) >= 0 ? h * (std::sqrt(2.0) * std::min(di, dk) + std::abs(di - dk))
                                                     : h * (di + dk);
    EXPECT_NEAR(polyline_length(*edges), closed, 1e-12);
    EXPECT_NEAR(polyline_length(*edges), fw[std::size_t(from)][std::size_t(to)], 1e-12);
    EXPECT_LE(polyline_length(*plane), polyline_length(*edges) + 1e-12);  // the chord is the shortest
  }
}

template <class T>
class MeshPathTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(MeshPathTyped, Scalars);

TYPED_TEST(MeshPathTyped, PlanePathLiesInItsPlaneOnATiltedGrid) {
  using T = TypeParam;
  // Tilted plane y = 0.5x + 0.2z over [0, 3]²: the plane path is the chord here too.  Tolerance:
  // the walk's own snapping (kMeshWalkTolerance · scale) plus a few ulp of coordinates ~3.
  const RawMesh<T> raw = grid_mesh<T>(6, T(0.5), T(0), T(0), [](T x, T z) { return T(0.5) * x + T(0.2) * z; });
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  const T tol = T(16) * kMeshWalkTolerance<T> * mesh->scale();
  Random rng(test::seed_for(1302));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 30; ++trial) {
    const int from = rng.integer(0, mesh->vertex_count() - 1), to = rng.integer(0, mesh->vertex_count() - 1);
    if (from == to) continue;
    SCOPED_TRACE("from " + std::to_string(from) + " to " + std::to_string(to));
    auto plane = plane_mesh_path(*mesh, from, to);
    ASSERT_TRUE(plane) << plane.error().describe();
    const Vec3<T> p0 = mesh->vertex(from), p1 = mesh->vertex(to);
    const Vec3<T> m = normalized(cross(Vec3<T>(p1 - p0), Vec3<T>(mesh->normal(from) + mesh->normal(to))), Vec3<T>{});
    for (const Vec3<T>& p : *plane) {
      EXPECT_LE(std::abs(dot(m, Vec3<T>(p - p0))), tol);
      EXPECT_LE(distance_to_mesh(raw, p), double(tol));
    }
    EXPECT_NEAR(polyline_length(*plane), distance(p0, p1), tol);
    auto greedy = greedy_mesh_path(*mesh, from, to);
    ASSERT_TRUE(greedy) << greedy.error().describe();
    EXPECT_NEAR(polyline_length(*greedy), distance(p0, p1), tol);
  }
}

TEST(MeshPath, DownhillOnATiltedPlaneIsTheFallLine) {
  // y = 0.5x + 0.2z: −∇ in the ground plane is −(0.5, 0.2); the fall line from any vertex is that
  // direction, lifted onto the plane, until the boundary x = 0 or z = 0.
  const RawMesh<double> raw = grid_mesh<double>(8, 0.5, 0, 0, [](double x, double z) { return 0.5 * x + 0.2 * z; });
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  const Vec3d fall = normalized(Vec3d{-0.5, -(0.25 + 0.04), -0.2}, Vec3d{});  // (dx, dy, dz) with dy = 0.5dx + 0.2dz
  for (int start : {80, 44, 60, 70}) {
    SCOPED_TRACE("start " + std::to_string(start));
    auto down = downhill_mesh_path(*mesh, start);
    ASSERT_TRUE(down) << down.error().describe();
    EXPECT_EQ(down->stop, DownhillStop::boundary);
    const Vec3d p0 = mesh->vertex(start);
    for (const Vec3d& p : down->points) {
      EXPECT_LE(norm(cross(Vec3d(p - p0), fall)), 1e-12);  // on the fall line
      EXPECT_LE(distance_to_mesh(raw, p), kOnMesh);
    }
    const Vec3d end = down->points.back();
    EXPECT_LE(std::min(end.x, end.z), 1e-12);  // on the boundary x = 0 or z = 0
    EXPECT_GT(down->points.size(), 1u);
  }
}

// ------------------------------------------------------------------------------ a sphere
TEST(MeshPath, IcospherePlanePathIsNoLongerThanTheGreatCircleArc) {
  const RawMesh<double> raw = icosphere(2, true);  // radial normals: the plane holds the centre
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  Random rng(test::seed_for(1303));
  SCOPED_TRACE(rng.trace());
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int from = rng.integer(0, mesh->vertex_count() - 1), to = rng.integer(0, mesh->vertex_count() - 1);
    const Vec3d a = mesh->vertex(from), b = mesh->vertex(to);
    const double arc = std::acos(std::clamp(dot(a, b), -1.0, 1.0));
    if (from == to || arc > 0.9 * std::numbers::pi) continue;  // near-antipodal: the short side is ambiguous
    SCOPED_TRACE("from " + std::to_string(from) + " to " + std::to_string(to));
    auto plane = plane_mesh_path(*mesh, from, to);
    ASSERT_TRUE(plane) << plane.error().describe();
    expect_joins_on_mesh(raw, *plane, from, to);
    const Vec3d m = normalized(cross(Vec3d(b - a), Vec3d(mesh->normal(from) + mesh->normal(to))), Vec3d{});
    for (const Vec3d& p : *plane) EXPECT_LE(std::abs(dot(m, Vec3d(p - a))), kOnMesh);
    const double len = polyline_length(*plane);
    EXPECT_LE(len, arc + 1e-12);
    EXPECT_GE(len, distance(a, b) - 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(MeshPath, IcosphereGreedyAndEdgesAgainstFloydWarshall) {
  const RawMesh<double> raw = icosphere(1, false);
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  const auto fw = floyd_warshall(raw);
  for (int from = 0; from < mesh->vertex_count(); from += 5)
    for (int to = 0; to < mesh->vertex_count(); to += 3) {
      SCOPED_TRACE("from " + std::to_string(from) + " to " + std::to_string(to));
      auto edges = edge_mesh_path(*mesh, from, to);
      ASSERT_TRUE(edges) << edges.error().describe();
      expect_joins_on_mesh(raw, *edges, from, to);
      EXPECT_NEAR(polyline_length(*edges), fw[std::size_t(from)][std::size_t(to)], 1e-12);
      auto greedy = greedy_mesh_path(*mesh, from, to);
      ASSERT_TRUE(greedy) << greedy.error().describe();
      expect_joins_on_mesh(raw, *greedy, from, to);
      EXPECT_GE(polyline_length(*greedy), distance(mesh->vertex(from), mesh->vertex(to)) - 1e-12);
    }
}

// ------------------------------------------------------------------------------ a bumpy field
TEST(MeshPath, BumpyFieldAllMethodsJoinOnTheMesh) {
  const RawMesh<double> raw = bumpy_grid(10);
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  const auto fw = floyd_warshall(raw);
  Random rng(test::seed_for(1304));
  SCOPED_TRACE(rng.trace());
  for (int trial = 0; trial < 30; ++trial) {
    // Interior vertices, so that the plane's section stays over the grid.
    const int from = rng.integer(1, 9) * 11 + rng.integer(1, 9), to = rng.integer(1, 9) * 11 + rng.integer(1, 9);
    SCOPED_TRACE("from " + std::to_string(from) + " to " + std::to_string(to));
    const Vec3d a = mesh->vertex(from), b = mesh->vertex(to);
    auto edges = edge_mesh_path(*mesh, from, to);
    ASSERT_TRUE(edges);
    EXPECT_NEAR(polyline_length(*edges), fw[std::size_t(from)][std::size_t(to)], 1e-12);
    auto greedy = greedy_mesh_path(*mesh, from, to);
    ASSERT_TRUE(greedy) << greedy.error().describe();
    expect_joins_on_mesh(raw, *greedy, from, to);
    // Interior pairs on these gentle bumps (slopes ≤ 0.3): the section stays over the grid, so the
    // plane walk must succeed (measured: 30 of 30 for seeds 1 to 5 and 1304).
    auto plane = plane_mesh_path(*mesh, from, to);
    ASSERT_TRUE(plane) << plane.error().describe();
    expect_joins_on_mesh(raw, *plane, from, to);
    if (from == to) continue;
    const Vec3d m = normalized(cross(Vec3d(b - a), Vec3d(mesh->normal(from) + mesh->normal(to))), Vec3d{});
    for (const Vec3d& p : *plane) EXPECT_LE(std::abs(dot(m, Vec3d(p - a))), kOnMesh);
    for (const auto* path : {&*plane, &*greedy, &*edges}) EXPECT_GE(polyline_length(*path), distance(a, b) - 1e-12);
  }
}

TEST(MeshPath, DownhillNeverGoesUpAndFindsTheValley) {
  const RawMesh<double> raw = bumpy_grid(24);
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  for (int start = 0; start < mesh->vertex_count(); start += 7) {
    SCOPED_TRACE("start " + std::to_string(start));
    auto down = downhill_mesh_path(*mesh, start);
    ASSERT_TRUE(down) << down.error().describe();
    for (std::size_t i = 1; i < down->points.size(); ++i) EXPECT_LT(down->points[i].y, down->points[i - 1].y) << i;
    for (const Vec3d& p : down->points) EXPECT_LE(distance_to_mesh(raw, p), kOnMesh);
    if (down->stop == DownhillStop::boundary) {
      const Vec3d e = down->points.back();
      EXPECT_NEAR(std::max(std::abs(e.x), std::abs(e.z)), 2.0, 1e-12);
    }
  }
  // From near (−1.2, 0.3) the fall ends at the bowl of A sin x cos z around (−π/2, 0), y = −A:
  // within a grid step (h = 1/6) of it, the mesh's vertices sampling the bowl that finely.
  const int start = int(std::lround((-1.2 + 2) * 6)) * 25 + int(std::lround((0.3 + 2) * 6));
  auto down = downhill_mesh_path(*mesh, start);
  ASSERT_TRUE(down);
  EXPECT_EQ(down->stop, DownhillStop::minimum);
  const Vec3d end = down->points.back();
  EXPECT_LE(std::hypot(end.x + std::numbers::pi / 2, end.z), 1.0 / 6);
  // Every mesh point interpolates samples ≥ −A; the end's face has its corners within h + h√2 < 3h
  // of the minimum, where A sin x cos z ≤ −A + A(dx² + dz²)/2 ≤ −A + 4.5·A·h².
  const double h = 1.0 / 6;
  EXPECT_GE(end.y, -kBump);
  EXPECT_LE(end.y, -kBump + 4.5 * kBump * h * h);
}

TYPED_TEST(MeshPathTyped, RandomBumpyFieldsEveryResultHoldsItsGuarantees) {
  // Random fields y = Σ a sin(ωx x + φ) cos(ωz z + ψ) on random grids, random pairs (boundary
  // vertices included): every method returns either an Error with a reason, or a path that starts
  // and ends at the vertices, has finite points on the mesh (within 64 ulp of the box diagonal: the
  // rounding of one interpolation, with room) and, for downhill, strictly falls.
  using T = TypeParam;
  Random rng(test::seed_for(1305));
  SCOPED_TRACE(rng.trace());
  int succeeded = 0, failed = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const int n = rng.integer(3, 12);
    const T a1 = rng.uniform<T>(T(0), T(0.6)), a2 = rng.uniform<T>(T(0), T(0.3)), w1 = rng.uniform<T>(T(0.5), T(2.5)),
            w2 = rng.uniform<T>(T(0.5), T(4)), ph = rng.uniform<T>(T(0), T(3));
    const RawMesh<T> raw = grid_mesh<T>(n, T(4) / T(n), T(-2), T(-2), [&](T x, T z) {
      return a1 * std::sin(w1 * x + ph) * std::cos(w1 * z) + a2 * std::sin(w2 * z) * std::cos(w2 * x - ph);
    });
    const auto mesh = build_triangle_mesh(raw);
    ASSERT_TRUE(mesh);
    const double tol = 64 * double(std::numeric_limits<T>::epsilon()) * double(mesh->scale());
    for (int pair = 0; pair < 8; ++pair) {
      const int from = rng.integer(0, mesh->vertex_count() - 1), to = rng.integer(0, mesh->vertex_count() - 1);
      SCOPED_TRACE("trial " + std::to_string(trial) + " from " + std::to_string(from) + " to " + std::to_string(to));
      for (int method = 0; method < 3; ++method) {
        auto path = method == 0 ? plane_mesh_path(*mesh, from, to)
                    : method == 1 ? greedy_mesh_path(*mesh, from, to)
                                  : edge_mesh_path(*mesh, from, to);
        if (!path) {
          EXPECT_FALSE(path.error().message.empty());
          EXPECT_FALSE(path.error().where.empty());
          EXPECT_NE(method, 2);  // a grid is connected
          ++failed;
          continue;
        }
        ++succeeded;
        EXPECT_EQ(path->front(), mesh->vertex(from));
        EXPECT_EQ(path->back(), mesh->vertex(to));
        for (const Vec3<T>& p : *path) {
          EXPECT_TRUE(is_finite(p));
          EXPECT_LE(distance_to_mesh(raw, p), tol);
        }
      }
      auto down = downhill_mesh_path(*mesh, from);
      ASSERT_TRUE(down);
      for (std::size_t i = 1; i < down->points.size(); ++i) {
        EXPECT_LT(down->points[i].y, down->points[i - 1].y);
        EXPECT_LE(distance_to_mesh(raw, down->points[i]), tol);
      }
    }
  }
  EXPECT_GT(succeeded, 5 * failed);  // the walks are meant to work on fields like these
}

TEST(MeshPath, HugeAndTinyMeshesGiveTheSamePathsScaled) {
  // Scaling every coordinate by a power of two is exact, and every decision of the walks is
  // relative (tolerances in units of the mesh's size, bases in units of their edges, cosines of
  // unit vectors), so the paths on the scaled mesh are the paths on the unit mesh scaled, exactly:
  // at 2^996 ≈ 6.7e299 (where a squared length would overflow) and 2^-900 ≈ 1.2e-271 (where a 4th
  // power would underflow).
  const RawMesh<double> unit = bumpy_grid(8);
  const auto base = build_triangle_mesh(unit);
  ASSERT_TRUE(base);
  for (const int e : {996, -900}) {
    SCOPED_TRACE("2^" + std::to_string(e));
    RawMesh<double> raw = unit;
    for (Vec3d& p : raw.vertices) p = Vec3d{std::ldexp(p.x, e), std::ldexp(p.y, e), std::ldexp(p.z, e)};
    const auto mesh = build_triangle_mesh(raw);
    ASSERT_TRUE(mesh) << mesh.error().describe();
    for (int v = 0; v < mesh->vertex_count(); ++v) EXPECT_EQ(mesh->normal(v), base->normal(v));
    const auto scaled = [e](std::vector<Vec3d> pts) {
      for (Vec3d& p : pts) p = Vec3d{std::ldexp(p.x, e), std::ldexp(p.y, e), std::ldexp(p.z, e)};
      return pts;
    };
    for (const auto& [from, to] : std::vector<std::pair<int, int>>{{10, 70}, {0, 80}, {31, 44}, {72, 8}}) {
      SCOPED_TRACE(std::to_string(from) + " to " + std::to_string(to));
      auto p0 = plane_mesh_path(*base, from, to), p1 = plane_mesh_path(*mesh, from, to);
      ASSERT_EQ(p0.has_value(), p1.has_value());
      if (p0) EXPECT_EQ(*p1, scaled(*p0));
      auto g0 = greedy_mesh_path(*base, from, to), g1 = greedy_mesh_path(*mesh, from, to);
      ASSERT_TRUE(g0 && g1);
      EXPECT_EQ(*g1, scaled(*g0));
      auto e0 = edge_mesh_path(*base, from, to), e1 = edge_mesh_path(*mesh, from, to);
      ASSERT_TRUE(e0 && e1);
      EXPECT_EQ(*e1, scaled(*e0));
      auto d0 = downhill_mesh_path(*base, from), d1 = downhill_mesh_path(*mesh, from);
      ASSERT_TRUE(d0 && d1);
      EXPECT_EQ(d1->points, scaled(d0->points));
      EXPECT_EQ(d1->stop, d0->stop);
    }
  }
  // Beyond an eighth of the largest double a coordinate is refused, naming the vertex.
  RawMesh<double> too_big = unit;
  too_big.vertices[5].x = 1e308;
  EXPECT_EQ(build_triangle_mesh(too_big).error().where, "vertex 5");
}

TEST(MeshPath, ANotchTrapsTheGreedyAndPlaneWalksButNotTheEdgePath) {
  // A flat 6 × 6 grid with the squares i = 3, k = 0..3 removed: a notch from the side k = 0 into
  // the middle.  From (1, 0) to (5, 0) the straight line runs across the notch.
  const int n = 6;
  RawMesh<double> raw = flat_grid<double>(n);
  std::vector<std::array<int, 3>> kept;
  for (std::size_t t = 0; t < raw.triangles.size(); ++t) {
    const int square = int(t / 2), i = square / n, k = square % n;  // grid_mesh's order: i outer, k inner
    if (!(i == 3 && k <= 3)) kept.push_back(raw.triangles[t]);
  }
  raw.triangles = kept;
  const auto mesh = build_triangle_mesh(raw);
  ASSERT_TRUE(mesh);
  const int from = 1 * (n + 1), to = 5 * (n + 1);
  auto plane = plane_mesh_path(*mesh, from, to);
  ASSERT_FALSE(plane);  // the plane (normal +y, through both) is z = 0, the boundary; it leaves at the notch
  EXPECT_EQ(plane.error().describe(), "vertex 21: the plane leaves the mesh at vertex 21 (boundary)");
  auto greedy = greedy_mesh_path(*mesh, from, to);
  ASSERT_FALSE(greedy);  // it reaches the notch's corner (3, 0) = vertex 21, and would come back to it
  EXPECT_EQ(greedy.error().describe(), "vertex 21: the greedy walk would return to vertex 21 (a trap)");
  auto edges = edge_mesh_path(*mesh, from, to);
  ASSERT_TRUE(edges);
  expect_joins_on_mesh(raw, *edges, from, to);
  // Around the notch: (1, 0) → (3, 4) is 2√2 + 2 (the grid's closed form), across the top 1, and
  // (4, 4) → (5, 0) with opposite steps 1 + 4: 8 + 2√2 in all; and Floyd–Warshall agrees.
  EXPECT_NEAR(polyline_length(*edges), 8 + 2 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(polyline_length(*edges), floyd_warshall(raw)[std::size_t(from)][std::size_t(to)], 1e-12);
}

TEST(MeshPath, ErrorsNameTheArgumentOrThePlace) {
  const auto mesh = build_triangle_mesh(flat_grid<double>(3));
  ASSERT_TRUE(mesh);
  EXPECT_EQ(plane_mesh_path(*mesh, 0, 16).error().where, "to");
  EXPECT_EQ(greedy_mesh_path(*mesh, -1, 3).error().where, "from");
  EXPECT_EQ(edge_mesh_path(*mesh, 0, 99).error().where, "to");
  EXPECT_EQ(downhill_mesh_path(*mesh, 16).error().where, "start");
  EXPECT_EQ(downhill_mesh_path(*mesh, 0, Vec3d{}).error().where, "up");
  // A flat mesh with up = +y: every vertex is a minimum, the path is the vertex alone.
  auto level = downhill_mesh_path(*mesh, 5);
  ASSERT_TRUE(level);
  EXPECT_EQ(level->points.size(), 1u);
  // Two separate triangles: no edge path, and the plane and greedy walks fail with a place.
  RawMesh<double> two{{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {5, 0, 0}, {6, 0, 0}, {5, 0, 1}}, {{0, 2, 1}, {3, 5, 4}}, {}};
  const auto apart = build_triangle_mesh(two);
  ASSERT_TRUE(apart);
  auto e = edge_mesh_path(*apart, 0, 4);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("not connected"), std::string::npos);
  auto p = plane_mesh_path(*apart, 0, 4);
  ASSERT_FALSE(p);
  EXPECT_NE(p.error().message.find("leaves the mesh"), std::string::npos) << p.error().describe();
  auto g = greedy_mesh_path(*apart, 0, 4);
  ASSERT_FALSE(g);
  // A plane that cannot be formed: normals along the chord.
  RawMesh<double> tri{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, {{1, 0, 0}, {1, 0, 0}, {0, 0, 1}}};
  const auto bad_plane = build_triangle_mesh(tri);
  ASSERT_TRUE(bad_plane);
  auto q = plane_mesh_path(*bad_plane, 0, 1);
  ASSERT_FALSE(q);
  EXPECT_NE(q.error().message.find("no plane"), std::string::npos);
}

}  // namespace
}  // namespace inbetween
