#pragma once
/// Paths on a triangle mesh between two vertices, and downhill from a vertex (texts 004 §3.4.4,
/// Figs. 3.47 and 3.48).  Each returns a polyline of points on the mesh: vertices, or points on
/// edges computed as a + (b − a)·w with w in [0, 1], so every point lies on a triangle up to the
/// rounding of that one interpolation.
///
/// - plane_mesh_path (Fig. 3.47): the plane through vertices I and J that contains the average of
///   their normals (normal m = (P_J − P_I) × (n_I + n_J)), intersected with the faces and walked face
///   to face from I, in the direction whose first step points towards J, until J.  Every point lies
///   in the plane.  Fails (with the reason) when there is no such plane (the chord is parallel to the
///   average normal, or the normals cancel), when the walk reaches the boundary, or when it would
///   enter a face or vertex a second time (the section closes without meeting J).
/// - greedy_mesh_path (the texts' improved greedy walk): from the current point, the direction to
///   J projected on the current face's plane is followed straight across the face to an edge, into
///   the face beyond, and so on.  At a vertex the face whose corner contains that direction is taken;
///   when none does (a ridge, a saddle, the boundary), the texts' edge rule takes the edge with the
///   largest cosine to J.  When the direction in a face points back across the edge just crossed
///   (a crease between the two faces), or the edge is on the boundary, the walk follows the edge to
///   its end nearer J.  Fails when it would revisit a face or a vertex (a trap) — it never loops.
/// - edge_mesh_path: the shortest path along edges (Dijkstra/A*, beyond the texts), the reference
///   the other two can be compared with.  Fails when I and J are not connected.
/// - downhill_mesh_path (Fig. 3.48): in each face D = −up + n (n · up), the projection of −up on the
///   face plane, which equals the texts' n × (n × up); followed across faces like the greedy walk,
///   along a valley edge where both faces' D point at it, until a vertex or edge with no lower
///   way out (a minimum), a level face, or the boundary (an edge with one face, or a vertex on one,
///   reached after the start: the start itself may be on the boundary).  Heights (p · up) strictly decrease along
///   the path; a step that would not descend ends it.
/// Lengths: every path is at least the chord |P_J − P_I|; on a flat mesh the plane and greedy paths
/// are the straight segment, the chord itself, and so no longer than the edge path.  In general no
/// order holds between the three (the tests derive the ones that do per mesh).
/// Errors name the argument ("from", "to", "start") for a bad index, and the place on the mesh
/// ("vertex v", "edge a-b", "face f") for a walk that fails.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"
#include "inbetween/paths/graph_path.hpp"
#include "inbetween/paths/triangle_mesh.hpp"

namespace inbetween {

/// Snapping tolerance of the walks, relative to TriangleMesh::scale(): a signed distance or an
/// along-edge weight this close to zero counts as zero (the plane passes through the vertex, the
/// walk reaches the corner).  About 1000 ulp of T: far above the rounding of one dot product of
/// coordinates of size `scale`, far below any feature of a mesh that is meant to be walked.
template <Real T>
inline constexpr T kMeshWalkTolerance = T(1024) * std::numeric_limits<T>::epsilon();

/// Why a downhill walk stopped.
enum class DownhillStop {
  minimum,   ///< no way down: a vertex or valley edge with no lower neighbour, or a level face
  boundary,  ///< the walk left the mesh across a boundary edge (the last point is on it)
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Minimum [[deprecated("use DownhillStop::minimum")]] = minimum,
  Boundary [[deprecated("use DownhillStop::boundary")]] = boundary,
};

/// A downhill path and why it ended.
template <Real T>
struct DownhillPath {
  std::vector<Vec3<T>> points;              ///< from the start vertex, heights strictly decreasing
  DownhillStop stop = DownhillStop::minimum; ///< why it ended
};

/// Total length of a polyline (0 for fewer than two points).
template <Real T>
T polyline_length(const std::vector<Vec3<T>>& points) noexcept {
  T s{};
  for (std::size_t i = 1; i < points.size(); ++i) s += distance(points[i - 1], points[i]);
  return s;
}

namespace detail {

/// An Error naming `name` unless v is a vertex of the mesh that belongs to a face.
template <Real T>
Expected<void> check_mesh_vertex(const TriangleMesh<T>& mesh, int v, const char* name) {
  if (v < 0 || v >= mesh.vertex_count())
    return Error{ErrorCode::InvalidArgument,
                 "vertex " + std::to_string(v) + " is not one of the mesh's " + std::to_string(mesh.vertex_count()) +
                     " vertices (0 to " + std::to_string(mesh.vertex_count() - 1) + ")",
                 name};
  if (mesh.faces_around(v).empty())
    return Error{ErrorCode::InvalidArgument, "vertex " + std::to_string(v) + " belongs to no face", name};
  return {};
}

/// "edge a-b", smaller index first.
inline std::string edge_name(int a, int b) { return "edge " + std::to_string(std::min(a, b)) + "-" + std::to_string(std::max(a, b)); }

/// The corners of face f other than v, in the face's order after v.
template <Real T>
std::array<int, 2> other_corners(const TriangleMesh<T>& mesh, int f, int v) noexcept {
  const auto& t = mesh.face(f);
  const int k = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
  return {t[std::size_t((k + 1) % 3)], t[std::size_t((k + 2) % 3)]};
}

/// The corner of face f that is neither a nor b.
template <Real T>
int third_corner(const TriangleMesh<T>& mesh, int f, int a, int b) noexcept {
  for (int v : mesh.face(f))
    if (v != a && v != b) return v;
  return -1;
}

/// Coordinates (α, β) of the in-plane part of d in the basis (e1, e2): least squares through the
/// 2×2 Gram system (e1, e2 independent: faces are not degenerate).  Solved in units of the longer
/// of e1 and e2, so that the Gram determinant (4th powers of lengths) neither overflows nor
/// underflows.
template <Real T>
std::array<T, 2> in_basis(Vec3<T> e1, Vec3<T> e2, Vec3<T> d) noexcept {
  const T unit = std::max(norm(e1), norm(e2));
  e1 /= unit;
  e2 /= unit;
  d /= unit;
  const T g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
  const T r1 = dot(e1, d), r2 = dot(e2, d);
  const T det = g11 * g22 - g12 * g12;
  return {(r1 * g22 - r2 * g12) / det, (r2 * g11 - r1 * g12) / det};
}

/// Where a walk is: at a vertex, or on the edge (a, b) at lerp(P_a, P_b, w) having come from face
/// `from` (−1 at the start).
struct MeshSpot {
  int vertex = -1;     ///< ≥ 0 when at a vertex
  int a = -1, b = -1;  ///< the edge, when not at a vertex
  double w = 0;        ///< weight of b on the edge
  int from = -1;       ///< the face just left
};

/// The result of crossing a face from an edge point along a direction.
enum class CrossKind {
  back,    ///< the direction does not enter the face
  edge,    ///< leaves through an edge
  vertex,  ///< leaves through a corner
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Back [[deprecated("use CrossKind::back")]] = back,
  Edge [[deprecated("use CrossKind::edge")]] = edge,
  Vertex [[deprecated("use CrossKind::vertex")]] = vertex,
};

/// Where a straight walk across one face leaves it.
template <Real T>
struct FaceCross {
  CrossKind kind = CrossKind::back;  ///< back out, through an edge, or through a corner
  int a = -1, b = -1;  ///< exit edge (Edge), or a = the vertex (Vertex)
  T w{};               ///< weight of b on the exit edge
};

/// Crossing face f, entered on its edge (a, b) at weight w of b, along direction d (in the face's
/// plane): Back when d does not point into the face (within tolerance), else the exit edge or
/// the far corner.
template <Real T>
FaceCross<T> cross_face_from_edge(const TriangleMesh<T>& mesh, int f, int a, int b, T w, const Vec3<T>& d) {
  const int c = third_corner(mesh, f, a, b);
  const Vec3<T>& pa = mesh.vertex(a);
  const Vec3<T>& pb = mesh.vertex(b);
  const Vec3<T>& pc = mesh.vertex(c);
  const auto [da, db] = in_basis(Vec3<T>(pa - pc), Vec3<T>(pb - pc), d);
  const T dc = -da - db;
  const T tol = kMeshWalkTolerance<T>;
  // In barycentric units the direction's size is about |d|/|edge|; compare with that scale.
  const T size = std::max({std::abs(da), std::abs(db), std::abs(dc)});
  if (!(dc > tol * size)) return {};
  const T la = T(1) - w, lb = w;
  const T ta = da < T(0) ? la / -da : std::numeric_limits<T>::infinity();
  const T tb = db < T(0) ? lb / -db : std::numeric_limits<T>::infinity();
  const T t = std::min(ta, tb);
  // Exit weights, renormalised on the exit edge.
  T lc = std::clamp(t * dc, T(0), T(1));
  if (!std::isfinite(t) || lc >= T(1) - tol) return {CrossKind::vertex, c, -1, T(0)};
  if (ta <= tb) {  // λa reaches 0 first: exit through edge (b, c)
    const T lbx = std::clamp(lb + t * db, T(0), T(1));
    if (std::abs(ta - tb) <= tol * t) return {CrossKind::vertex, c, -1, T(0)};
    lc = T(1) - lbx;
    if (lc <= tol) return {CrossKind::vertex, b, -1, T(0)};
    return {CrossKind::edge, b, c, lc};
  }
  const T lax = std::clamp(la + t * da, T(0), T(1));
  lc = T(1) - lax;
  if (lc <= tol) return {CrossKind::vertex, a, -1, T(0)};
  return {CrossKind::edge, a, c, lc};
}

/// Leaving vertex v through face f along d: Back when d is outside the face's corner at v (within
/// tolerance), else the point where it meets the opposite edge, or a corner when it runs along an
/// edge.
template <Real T>
FaceCross<T> cross_face_from_vertex(const TriangleMesh<T>& mesh, int f, int v, const Vec3<T>& d) {
  const auto [a, b] = other_corners(mesh, f, v);
  const Vec3<T>& pv = mesh.vertex(v);
  const auto [al, be] = in_basis(Vec3<T>(mesh.vertex(a) - pv), Vec3<T>(mesh.vertex(b) - pv), d);
  const T sum = al + be;
  const T tol = kMeshWalkTolerance<T>;
  const T size = std::max(std::abs(al), std::abs(be));
  if (!(sum > T(0)) || al < -tol * size || be < -tol * size) return {};
  const T wb = std::clamp(be / sum, T(0), T(1));
  if (wb <= tol) return {CrossKind::vertex, a, -1, T(0)};
  if (wb >= T(1) - tol) return {CrossKind::vertex, b, -1, T(0)};
  return {CrossKind::edge, a, b, wb};
}

/// d with its component along face f's normal removed.
template <Real T>
Vec3<T> on_plane_of(const TriangleMesh<T>& mesh, int f, const Vec3<T>& d) noexcept {
  const Vec3<T>& n = mesh.face_normal(f);
  return d - n * dot(n, d);
}

}  // namespace detail

/// The texts' plane-intersection path from vertex `from` to vertex `to` (file comment, Fig. 3.47).
template <Real T>
Expected<std::vector<Vec3<T>>> plane_mesh_path(const TriangleMesh<T>& mesh, int from, int to) {
  using V = Vec3<T>;
  if (auto ok = detail::check_mesh_vertex(mesh, from, "from"); !ok) return ok.error();
  if (auto ok = detail::check_mesh_vertex(mesh, to, "to"); !ok) return ok.error();
  const V p0 = mesh.vertex(from), p1 = mesh.vertex(to);
  std::vector<V> out{p0};
  if (from == to) return out;
  const V chord = p1 - p0;
  const V n_avg = (mesh.normal(from) + mesh.normal(to)) * T(0.5);
  const V m_raw = cross(chord, n_avg);
  // Unit vectors' cross product below 1e-9 means the chord and the average normal are parallel to
  // within 1e-9 rad (or the normals cancel): no plane is defined.
  if (!(norm(m_raw) > T(1e-9) * norm(chord)))
    return Error{ErrorCode::InvalidArgument,
                 "no plane: the line from vertex " + std::to_string(from) + " to vertex " + std::to_string(to) +
                     " is parallel to the average of their normals (or the normals cancel)",
                 "to"};
  const V m = m_raw / norm(m_raw);
  const T tol = kMeshWalkTolerance<T> * mesh.scale();
  const auto sd = [&](int v) { return dot(m, V(mesh.vertex(v) - p0)); };
  const auto side = [&](int v) {
    const T s = sd(v);
    return s > tol ? 1 : (s < -tol ? -1 : 0);
  };
  const auto cut = [&](int a, int b) {  // point of the plane on edge (a, b), sides opposite
    const T sa = sd(a), sb = sd(b);
    return lerp(mesh.vertex(a), mesh.vertex(b), std::clamp(sa / (sa - sb), T(0), T(1)));
  };
  std::vector<char> face_seen(std::size_t(mesh.face_count()), 0), vertex_seen(std::size_t(mesh.vertex_count()), 0);
  vertex_seen[std::size_t(from)] = 1;
  V forward = chord;
  detail::MeshSpot spot{.vertex = from};
  const int max_steps = 2 * (mesh.face_count() + mesh.vertex_count()) + 4;
  for (int step = 0; step < max_steps; ++step) {
    if (spot.vertex == to) return out;
    if (spot.vertex >= 0) {
      const int v = spot.vertex;
      const V pv = mesh.vertex(v);
      // Candidate continuations: an edge of v lying in the plane, or a face whose opposite edge the
      // plane cuts.  The best points most along the current travel direction.
      struct Cand { int vertex; int face; int a; int b; V p; };
      std::vector<Cand> cands;
      bool blocked = false;
      for (int f : mesh.faces_around(v)) {
        const auto [a, b] = detail::other_corners(mesh, f, v);
        const int sa = side(a), sb = side(b);
        for (int x : {a, b})
          if (side(x) == 0) {
            if (x == to) {  // the plane runs along the edge v-J
              out.push_back(p1);
              return out;
            }
            if (vertex_seen[std::size_t(x)]) blocked = true;
            else cands.push_back({x, -1, -1, -1, mesh.vertex(x)});
          }
        if (sa * sb < 0) {
          if (face_seen[std::size_t(f)]) blocked = true;
          else cands.push_back({-1, f, a, b, cut(a, b)});
        }
      }
      const Cand* best = nullptr;
      T best_dot = -std::numeric_limits<T>::infinity();
      for (const Cand& c : cands) {
        const T d = dot(normalized(V(c.p - pv), V{}), forward);
        if (d > best_dot) best_dot = d, best = &c;
      }
      if (best == nullptr)
        return Error{ErrorCode::InvalidArgument,
                     blocked && !mesh.on_boundary(v)
                         ? "the plane walk returns to where it has been without meeting vertex " + std::to_string(to)
                         : "the plane leaves the mesh at vertex " + std::to_string(v) + " (boundary)",
                     "vertex " + std::to_string(v)};
      forward = normalized(V(best->p - pv), forward);
      out.push_back(best->p);
      if (best->vertex >= 0) {
        vertex_seen[std::size_t(best->vertex)] = 1;
        spot = {.vertex = best->vertex};
      } else {
        face_seen[std::size_t(best->face)] = 1;
        spot = {.vertex = -1, .a = best->a, .b = best->b, .from = best->face};
      }
      continue;
    }
    // On edge (a, b): into the face beyond.
    const int f = mesh.face_across_edge(spot.from, spot.a, spot.b);
    if (f < 0)
      return Error{ErrorCode::InvalidArgument, "the plane leaves the mesh across a boundary edge",
                   detail::edge_name(spot.a, spot.b)};
    if (face_seen[std::size_t(f)])
      return Error{ErrorCode::InvalidArgument,
                   "the plane walk enters face " + std::to_string(f) + " a second time without meeting vertex " +
                       std::to_string(to),
                   "face " + std::to_string(f)};
    face_seen[std::size_t(f)] = 1;
    const int c = detail::third_corner(mesh, f, spot.a, spot.b);
    const V prev = out.back();
    const int sc = side(c);
    if (c == to || sc == 0) {
      if (c != to && vertex_seen[std::size_t(c)])
        return Error{ErrorCode::InvalidArgument, "the plane walk returns to vertex " + std::to_string(c),
                     "vertex " + std::to_string(c)};
      out.push_back(mesh.vertex(c));
      vertex_seen[std::size_t(c)] = 1;
      spot = {.vertex = c};
    } else {
      const int other = side(spot.a) * sc < 0 ? spot.a : spot.b;  // the corner across the plane from c
      out.push_back(cut(other, c));
      spot = {.vertex = -1, .a = other, .b = c, .from = f};
    }
    forward = normalized(V(out.back() - prev), forward);
  }
  return Error{ErrorCode::InvalidArgument, "the plane walk did not reach vertex " + std::to_string(to), "to"};
}

/// The greedy walk across faces from vertex `from` to vertex `to` (file comment).
template <Real T>
Expected<std::vector<Vec3<T>>> greedy_mesh_path(const TriangleMesh<T>& mesh, int from, int to) {
  using V = Vec3<T>;
  if (auto ok = detail::check_mesh_vertex(mesh, from, "from"); !ok) return ok.error();
  if (auto ok = detail::check_mesh_vertex(mesh, to, "to"); !ok) return ok.error();
  const V target = mesh.vertex(to);
  std::vector<V> out{mesh.vertex(from)};
  std::vector<char> face_seen(std::size_t(mesh.face_count()), 0), vertex_seen(std::size_t(mesh.vertex_count()), 0);
  vertex_seen[std::size_t(from)] = 1;
  detail::MeshSpot spot{.vertex = from};
  const auto go_vertex = [&](int v) -> Expected<void> {
    if (vertex_seen[std::size_t(v)])
      return Error{ErrorCode::InvalidArgument,
                   "the greedy walk would return to vertex " + std::to_string(v) + " (a trap)",
                   "vertex " + std::to_string(v)};
    vertex_seen[std::size_t(v)] = 1;
    out.push_back(mesh.vertex(v));
    spot = {.vertex = v};
    return {};
  };
  const int max_steps = 2 * (mesh.face_count() + mesh.vertex_count()) + 4;
  for (int step = 0; step < max_steps; ++step) {
    if (spot.vertex == to) return out;
    if (spot.vertex >= 0) {
      const int v = spot.vertex;
      const V pv = mesh.vertex(v);
      const V to_goal = target - pv;
      if (to_goal == V{}) {  // another vertex at J's position: J is reached (exact test: a squared norm underflows)
        out.push_back(target);
        return out;
      }
      // A face with J as a corner: straight to J.
      for (int f : mesh.faces_around(v))
        for (int x : mesh.face(f))
          if (x == to) {
            out.push_back(target);
            return out;
          }
      int best_face = -1;
      detail::FaceCross<T> best_cross{};
      T best_cos = -std::numeric_limits<T>::infinity();
      for (int f : mesh.faces_around(v)) {
        if (face_seen[std::size_t(f)]) continue;
        const V d = detail::on_plane_of(mesh, f, to_goal);
        const auto cr = detail::cross_face_from_vertex(mesh, f, v, d);
        if (cr.kind == detail::CrossKind::back) continue;
        const T c = dot(normalized(d, V{}), normalized(to_goal, V{}));
        if (c > best_cos) best_cos = c, best_face = f, best_cross = cr;
      }
      if (best_face >= 0) {
        face_seen[std::size_t(best_face)] = 1;
        if (best_cross.kind == detail::CrossKind::vertex) {
          if (auto ok = go_vertex(best_cross.a); !ok) return ok.error();
        } else {
          out.push_back(lerp(mesh.vertex(best_cross.a), mesh.vertex(best_cross.b), best_cross.w));
          spot = {.vertex = -1, .a = best_cross.a, .b = best_cross.b, .w = double(best_cross.w), .from = best_face};
        }
        continue;
      }
      // The texts' edge rule: the edge with the largest cosine to the goal.
      int best = -1;
      best_cos = -std::numeric_limits<T>::infinity();
      for (int nb : mesh.neighbours(v)) {
        const T c = dot(normalized(V(mesh.vertex(nb) - pv), V{}), normalized(to_goal, V{}));
        if (c > best_cos) best_cos = c, best = nb;
      }
      if (best < 0)  // cannot happen: a vertex in a face has neighbours, and their cosines are finite
        return Error{ErrorCode::InvalidArgument, "the greedy walk is stuck at vertex " + std::to_string(v),
                     "vertex " + std::to_string(v)};
      if (auto ok = go_vertex(best); !ok) return ok.error();
      continue;
    }
    const int f = mesh.face_across_edge(spot.from, spot.a, spot.b);
    const V q = out.back();
    if (f >= 0 && face_seen[std::size_t(f)])
      return Error{ErrorCode::InvalidArgument,
                   "the greedy walk would enter face " + std::to_string(f) + " again (a trap)",
                   "face " + std::to_string(f)};
    detail::FaceCross<T> cr{};
    if (f >= 0) {
      if (detail::third_corner(mesh, f, spot.a, spot.b) == to) {
        out.push_back(target);
        return out;
      }
      cr = detail::cross_face_from_edge(mesh, f, spot.a, spot.b, T(spot.w),
                                        detail::on_plane_of(mesh, f, V(target - q)));
    }
    if (cr.kind == detail::CrossKind::back) {
      // Boundary, or a crease: follow the edge to its end nearer the goal.
      const int end = distance(mesh.vertex(spot.a), target) <= distance(mesh.vertex(spot.b), target) ? spot.a : spot.b;
      if (auto ok = go_vertex(end); !ok) return ok.error();
      continue;
    }
    face_seen[std::size_t(f)] = 1;
    if (cr.kind == detail::CrossKind::vertex) {
      if (auto ok = go_vertex(cr.a); !ok) return ok.error();
    } else {
      out.push_back(lerp(mesh.vertex(cr.a), mesh.vertex(cr.b), cr.w));
      spot = {.vertex = -1, .a = cr.a, .b = cr.b, .w = double(cr.w), .from = f};
    }
  }
  return Error{ErrorCode::InvalidArgument, "the greedy walk did not reach vertex " + std::to_string(to), "to"};
}

/// The shortest path along edges from vertex `from` to vertex `to` (Dijkstra/A*; graph_path.hpp).
template <Real T>
Expected<std::vector<Vec3<T>>> edge_mesh_path(const TriangleMesh<T>& mesh, int from, int to) {
  if (auto ok = detail::check_mesh_vertex(mesh, from, "from"); !ok) return ok.error();
  if (auto ok = detail::check_mesh_vertex(mesh, to, "to"); !ok) return ok.error();
  auto graph = EdgeGraph<T>::from_triangles(mesh.vertices(), mesh.faces());
  if (!graph) return graph.error();  // cannot happen: the mesh was validated
  auto path = shortest_graph_path(*graph, from, to);
  if (!path) return Error{ErrorCode::InvalidArgument, path.error().message, "to"};
  std::vector<Vec3<T>> out;
  out.reserve(path->vertices.size());
  for (int v : path->vertices) out.push_back(mesh.vertex(v));
  return out;
}

/// The downhill path from vertex `start` (file comment, Fig. 3.48); `up` is the world's up
/// direction (any non-zero length).  Errors: "start" (index, or a vertex in no face), "up" (zero
/// or not finite).
template <Real T>
Expected<DownhillPath<T>> downhill_mesh_path(const TriangleMesh<T>& mesh, int start,
                                             const Vec3<T>& up = {T(0), T(1), T(0)}) {
  using V = Vec3<T>;
  if (auto ok = detail::check_mesh_vertex(mesh, start, "start"); !ok) return ok.error();
  const V u = normalized(up, V{});
  if (!is_finite(up) || squared_norm(u) == T(0))
    return Error{ErrorCode::InvalidArgument, "up must be a non-zero finite vector", "up"};
  DownhillPath<T> out{{mesh.vertex(start)}, DownhillStop::minimum};
  const auto height = [&](const V& p) { return dot(p, u); };
  const auto downhill = [&](int f) {  // D = −up + n (n · up)
    const V& n = mesh.face_normal(f);
    return V(n * dot(n, u) - u);
  };
  // A face is level when its downhill vector is shorter than 1e-12 (|D| = sin of its slope angle):
  // then there is no downhill in it.
  constexpr T kLevel = T(sizeof(T) <= 4 ? 1e-6 : 1e-12);
  detail::MeshSpot spot{.vertex = start};
  const auto push = [&](const V& p) {
    if (!(height(p) < height(out.points.back()))) return false;  // not lower: stop here
    out.points.push_back(p);
    return true;
  };
  const int max_steps = 2 * (mesh.face_count() + mesh.vertex_count()) + 4;
  for (int step = 0; step < max_steps; ++step) {
    if (spot.vertex >= 0) {
      const int v = spot.vertex;
      const V pv = mesh.vertex(v);
      if (v != start && mesh.on_boundary(v)) {  // reached the boundary (at a vertex)
        out.stop = DownhillStop::boundary;
        return out;
      }
      // Steepest way down: a face whose corner at v holds its D, or an edge to a lower neighbour;
      // slope = height lost per unit length.
      T best_slope = T(0);
      int best_face = -1, best_vertex = -1;
      detail::FaceCross<T> best_cross{};
      for (int f : mesh.faces_around(v)) {
        const V d = downhill(f);
        if (!(norm(d) > kLevel)) continue;
        const auto cr = detail::cross_face_from_vertex(mesh, f, v, d);
        if (cr.kind == detail::CrossKind::back) continue;
        const T slope = -dot(normalized(d, V{}), u);
        if (slope > best_slope) best_slope = slope, best_face = f, best_cross = cr;
      }
      for (int nb : mesh.neighbours(v)) {
        const T slope = -dot(normalized(V(mesh.vertex(nb) - pv), V{}), u);
        if (slope > best_slope) best_slope = slope, best_face = -1, best_vertex = nb;
      }
      if (best_face < 0 && best_vertex < 0) return out;  // a minimum
      if (best_face < 0 || best_cross.kind == detail::CrossKind::vertex) {
        const int next = best_face < 0 ? best_vertex : best_cross.a;
        if (!push(mesh.vertex(next))) return out;
        spot = {.vertex = next};
      } else {
        if (!push(lerp(mesh.vertex(best_cross.a), mesh.vertex(best_cross.b), best_cross.w))) return out;
        spot = {.vertex = -1, .a = best_cross.a, .b = best_cross.b, .w = double(best_cross.w), .from = best_face};
      }
      continue;
    }
    const int f = mesh.face_across_edge(spot.from, spot.a, spot.b);
    if (f < 0) {
      out.stop = DownhillStop::boundary;
      return out;
    }
    const V d = downhill(f);
    detail::FaceCross<T> cr{};
    if (norm(d) > kLevel) cr = detail::cross_face_from_edge(mesh, f, spot.a, spot.b, T(spot.w), d);
    if (cr.kind == detail::CrossKind::back) {
      // A valley along the edge (or a level face beyond): down the edge to its lower end.
      const int low = height(mesh.vertex(spot.a)) <= height(mesh.vertex(spot.b)) ? spot.a : spot.b;
      if (!push(mesh.vertex(low))) return out;
      spot = {.vertex = low};
      continue;
    }
    if (cr.kind == detail::CrossKind::vertex) {
      if (!push(mesh.vertex(cr.a))) return out;
      spot = {.vertex = cr.a};
    } else {
      if (!push(lerp(mesh.vertex(cr.a), mesh.vertex(cr.b), cr.w))) return out;
      spot = {.vertex = -1, .a = cr.a, .b = cr.b, .w = double(cr.w), .from = f};
    }
  }
  return out;  // cannot happen: heights strictly decrease and each step enters a new face or vertex
}

}  // namespace inbetween
