#pragma once
/// Triangle meshes for paths on a surface (texts 004 §3.4.4): RawMesh (what a file or a program
/// gives) → build_triangle_mesh → TriangleMesh, an immutable mesh with unit vertex normals and the
/// adjacency the surface walks need (faces around a vertex, the face across each edge).
///
/// What the builder accepts (everything else is an Error whose location names the item, in the
/// builder's words below or through a MeshPlaceNamer):
///   - at least one vertex ("vertices") and one triangle ("triangles");
///   - finite vertex coordinates of magnitude at most kMeshMaxCoordinate ("vertex i"), so that
///     every difference of two vertices, and its length, is finite;
///   - triangles whose three indices are in range and distinct ("face f");
///   - no zero-area triangle ("face f"): |(b − a) × (c − a)| ≤ kMeshAreaTolerance · (longest edge)²
///     is rejected, not dropped, because dropping it would silently cut the surface there;
///   - every edge shared by at most two triangles ("face f", naming the third one): the walks cross
///     an edge into *the* face on its other side, which a non-manifold edge does not have;
///   - normals: none (then area-weighted ones are computed), or one finite non-zero vector per
///     vertex ("normal i"), normalised.
/// Face orientation is not checked; computed normals assume consistently wound triangles (as every
/// modelling tool writes them).  A vertex in no triangle is legal (a path from it is an Error) and
/// gets a zero computed normal; so does a vertex whose area-weighted normals cancel.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// Relative area below which a triangle counts as degenerate: |cross| ≤ this · (longest edge)²,
/// i.e. the triangle's smallest height is below about this fraction of its longest edge.  A few
/// hundred ulp of T, so that rounding in the cross product of a thin but genuine triangle never trips it.
template <Real T>
inline constexpr T kMeshAreaTolerance = T(256) * std::numeric_limits<T>::epsilon();

/// Largest accepted |coordinate|: an eighth of the largest finite T, so that a difference of two
/// vertices (at most a quarter) and its length (at most √3/4 of the maximum) never overflow.  The
/// walks compute in scaled units beyond that, so any mesh within this range works (tested at 1e300
/// and 1e-300).
template <Real T>
inline constexpr T kMeshMaxCoordinate = std::numeric_limits<T>::max() / T(8);

/// A mesh as given: positions, triangles as vertex indices (counter-clockwise seen from outside, for
/// computed normals), and optionally one normal per vertex.
template <Real T>
struct RawMesh {
  std::vector<Vec3<T>> vertices;              ///< positions, any units
  std::vector<std::array<int, 3>> triangles;  ///< indices into vertices, from 0
  std::vector<Vec3<T>> normals;               ///< empty, or one per vertex (need not be unit)
};

template <Real T>
class TriangleMesh;

/// Index passed to a MeshPlaceNamer for an error about a whole member (an empty mesh, a normal
/// count that does not match).
inline constexpr std::size_t kWholeMeshMember = static_cast<std::size_t>(-1);

/// Names the place of a builder error from the RawMesh member ("vertices", "triangles" or
/// "normals") and the index in it (or kWholeMeshMember) as an Error location, so that a reader can
/// say "line 12" of its file ({Source{"mesh.obj"}, TextLine{12}}) without parsing a place back out
/// of text.  Empty: default_mesh_place.
using MeshPlaceNamer = std::function<std::vector<LocationStep>(std::string_view member, std::size_t index)>;

/// The builder's own names: {Element{"vertex", i}} ("vertex i"), "face f", "normal i", or the
/// member's name for the whole ({Parameter{"vertices"}}).
inline std::vector<LocationStep> default_mesh_place(std::string_view member, std::size_t index) {
  if (index == kWholeMeshMember) return {Parameter{std::string(member)}};
  const char* item = member == "vertices" ? "vertex" : (member == "triangles" ? "face" : "normal");
  return {Element{item, index}};
}

/// Checks `raw` (file comment) and builds the mesh with its adjacency; errors name their place
/// through `place` (default_mesh_place when empty).
template <Real T>
Expected<TriangleMesh<T>> build_triangle_mesh(const RawMesh<T>& raw, const MeshPlaceNamer& place = {});

/// An immutable, valid triangle mesh (see the file comment for what valid means).
template <Real T>
class TriangleMesh {
 public:
  /// Number of vertices.
  [[nodiscard]] int vertex_count() const noexcept { return int(vertices_.size()); }
  /// Number of triangles.
  [[nodiscard]] int face_count() const noexcept { return int(faces_.size()); }
  /// Position of vertex v, 0 ≤ v < vertex_count().
  [[nodiscard]] const Vec3<T>& vertex(int v) const noexcept { return vertices_[std::size_t(v)]; }
  /// All positions, in index order.
  [[nodiscard]] std::span<const Vec3<T>> vertices() const noexcept { return vertices_; }
  /// Unit normal of vertex v (given, or area-weighted); zero for a vertex in no face or whose face
  /// normals cancel.
  [[nodiscard]] const Vec3<T>& normal(int v) const noexcept { return normals_[std::size_t(v)]; }
  /// True when the normals came from the raw mesh, false when they were computed.
  [[nodiscard]] bool has_given_normals() const noexcept { return given_normals_; }
  /// The vertex indices of face f, 0 ≤ f < face_count().
  [[nodiscard]] const std::array<int, 3>& face(int f) const noexcept { return faces_[std::size_t(f)]; }
  /// All faces.
  [[nodiscard]] std::span<const std::array<int, 3>> faces() const noexcept { return faces_; }
  /// Unit normal of face f, (b − a) × (c − a) normalised (never zero: no face is degenerate).
  [[nodiscard]] const Vec3<T>& face_normal(int f) const noexcept { return face_normals_[std::size_t(f)]; }
  /// The face across edge k of face f (the edge from corner k to corner (k + 1) % 3), or −1 on the
  /// boundary.
  [[nodiscard]] int face_across(int f, int k) const noexcept { return across_[std::size_t(f)][std::size_t(k)]; }
  /// The face on the other side of the edge (a, b) of face f, or −1 on the boundary (or when (a, b)
  /// is not an edge of f).
  [[nodiscard]] int face_across_edge(int f, int a, int b) const noexcept {
    const auto& t = faces_[std::size_t(f)];
    for (int k = 0; k < 3; ++k) {
      const int p = t[std::size_t(k)], q = t[std::size_t((k + 1) % 3)];
      if ((p == a && q == b) || (p == b && q == a)) return face_across(f, k);
    }
    return -1;
  }
  /// The faces that have vertex v as a corner, ascending.
  [[nodiscard]] std::span<const int> faces_around(int v) const noexcept {
    return std::span<const int>(vertex_faces_).subspan(std::size_t(vertex_face_start_[std::size_t(v)]),
                                                       std::size_t(vertex_face_start_[std::size_t(v) + 1] -
                                                                   vertex_face_start_[std::size_t(v)]));
  }
  /// True when vertex v is an end of a boundary edge (an edge with one face).
  [[nodiscard]] bool on_boundary(int v) const noexcept { return boundary_[std::size_t(v)] != 0; }
  /// The vertices joined to v by an edge, ascending.
  [[nodiscard]] std::span<const int> neighbours(int v) const noexcept { return neighbours_[std::size_t(v)]; }
  /// Length of the bounding box's diagonal (> 0 unless every vertex coincides); the scale of the
  /// walks' snapping tolerance.
  [[nodiscard]] T scale() const noexcept { return scale_; }

 private:
  TriangleMesh() = default;
  friend Expected<TriangleMesh<T>> build_triangle_mesh<T>(const RawMesh<T>& raw, const MeshPlaceNamer& place);

  std::vector<Vec3<T>> vertices_;
  std::vector<Vec3<T>> normals_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<Vec3<T>> face_normals_;
  std::vector<std::array<int, 3>> across_;
  std::vector<int> vertex_face_start_;
  std::vector<int> vertex_faces_;
  std::vector<std::vector<int>> neighbours_;
  std::vector<char> boundary_;
  T scale_{};
  bool given_normals_ = false;
};

template <Real T>
Expected<TriangleMesh<T>> build_triangle_mesh(const RawMesh<T>& raw, const MeshPlaceNamer& place) {
  using V = Vec3<T>;
  const auto name = [&](std::string_view member, std::size_t index) {
    return place ? place(member, index) : default_mesh_place(member, index);
  };
  const auto face_name = [&](std::size_t f) { return name("triangles", f); };
  if (raw.vertices.empty())
    return Error{ErrorCode::too_few_points, "the mesh has no vertices", name("vertices", kWholeMeshMember)};
  if (raw.triangles.empty())
    return Error{ErrorCode::too_few_points, "the mesh has no faces", name("triangles", kWholeMeshMember)};
  const int n = int(raw.vertices.size());
  T extent{};  // the largest |coordinate|: area weights are computed in units of it
  for (std::size_t i = 0; i < raw.vertices.size(); ++i) {
    if (!is_finite(raw.vertices[i]))
      return Error{ErrorCode::not_finite, "vertex " + std::to_string(i) + " has a coordinate that is not finite",
                   name("vertices", i)};
    const T big = std::max({std::abs(raw.vertices[i].x), std::abs(raw.vertices[i].y), std::abs(raw.vertices[i].z)});
    if (big > kMeshMaxCoordinate<T>)
      return Error{ErrorCode::invalid_argument,
                   "vertex " + std::to_string(i) + " has a coordinate of magnitude " + shortest_text(double(big)) +
                       ", beyond the mesh limit " + shortest_text(double(kMeshMaxCoordinate<T>)),
                   name("vertices", i)};
    extent = std::max(extent, big);
  }
  const T unit = extent > T(0) ? extent : T(1);
  TriangleMesh<T> mesh;
  mesh.vertices_ = raw.vertices;
  mesh.faces_ = raw.triangles;
  mesh.face_normals_.resize(raw.triangles.size());
  std::vector<V> area_normals(raw.vertices.size(), V{});
  for (std::size_t f = 0; f < raw.triangles.size(); ++f) {
    const auto& t = raw.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const int v = t[std::size_t(k)];
      if (v < 0 || v >= n)
        return Error{ErrorCode::invalid_argument,
                     "face uses vertex " + std::to_string(v) + ", but the mesh has " + std::to_string(n) +
                         " vertices (0 to " + std::to_string(n - 1) + ")",
                     face_name(f)};
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      return Error{ErrorCode::invalid_argument,
                   "face repeats a vertex (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                       std::to_string(t[2]) + ")",
                   face_name(f)};
    const V& a = raw.vertices[std::size_t(t[0])];
    const V& b = raw.vertices[std::size_t(t[1])];
    const V& c = raw.vertices[std::size_t(t[2])];
    // The degeneracy test in units of the longest edge, so that it neither overflows nor underflows.
    const T longest = std::max({norm(V(b - a)), norm(V(c - b)), norm(V(a - c))});
    const V rel = longest > T(0) ? cross(V((b - a) / longest), V((c - a) / longest)) : V{};
    const T rel_norm = norm(rel);
    if (!(rel_norm > kMeshAreaTolerance<T>))
      return Error{ErrorCode::invalid_argument,
                   "face (vertices " + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                       std::to_string(t[2]) + ") has zero area",
                   face_name(f)};
    mesh.face_normals_[f] = rel / rel_norm;
    // Twice the area times the unit normal, in units of the mesh's extent (differences ≤ 2, no
    // overflow); a face below ~1e-154 of the extent underflows to weight 0.
    const V area2 = cross(V((b - a) / unit), V((c - a) / unit));
    for (int v : t) area_normals[std::size_t(v)] += area2;
  }
  // Edges: (low, high, face, corner) sorted, so the faces of an edge are adjacent entries.
  std::vector<std::array<int, 4>> edges;
  edges.reserve(raw.triangles.size() * 3);
  for (std::size_t f = 0; f < raw.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int p = raw.triangles[f][std::size_t(k)], q = raw.triangles[f][std::size_t((k + 1) % 3)];
      edges.push_back({std::min(p, q), std::max(p, q), int(f), k});
    }
  std::sort(edges.begin(), edges.end());
  mesh.across_.assign(raw.triangles.size(), {-1, -1, -1});
  mesh.neighbours_.resize(raw.vertices.size());
  mesh.boundary_.assign(raw.vertices.size(), 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    if (j - i > 2)
      return Error{ErrorCode::invalid_argument,
                   "edge (" + std::to_string(edges[i][0]) + ", " + std::to_string(edges[i][1]) +
                       ") is shared by faces " + std::to_string(edges[i][2]) + ", " + std::to_string(edges[i + 1][2]) +
                       " and " + std::to_string(edges[i + 2][2]) + "; a surface allows two",
                   face_name(std::size_t(edges[i + 2][2]))};
    if (j - i == 2) {
      if (edges[i][2] == edges[i + 1][2])  // cannot happen: faces repeat no vertex
        return Error{ErrorCode::invalid_argument, "face uses an edge twice", face_name(std::size_t(edges[i][2]))};
      mesh.across_[std::size_t(edges[i][2])][std::size_t(edges[i][3])] = edges[i + 1][2];
      mesh.across_[std::size_t(edges[i + 1][2])][std::size_t(edges[i + 1][3])] = edges[i][2];
    }
    if (j - i == 1) mesh.boundary_[std::size_t(edges[i][0])] = mesh.boundary_[std::size_t(edges[i][1])] = 1;
    mesh.neighbours_[std::size_t(edges[i][0])].push_back(edges[i][1]);
    mesh.neighbours_[std::size_t(edges[i][1])].push_back(edges[i][0]);
    i = j;
  }
  for (auto& list : mesh.neighbours_) std::sort(list.begin(), list.end());
  // Faces around each vertex (compressed rows).
  mesh.vertex_face_start_.assign(raw.vertices.size() + 1, 0);
  for (const auto& t : raw.triangles)
    for (int v : t) ++mesh.vertex_face_start_[std::size_t(v) + 1];
  for (std::size_t v = 0; v < raw.vertices.size(); ++v) mesh.vertex_face_start_[v + 1] += mesh.vertex_face_start_[v];
  mesh.vertex_faces_.resize(raw.triangles.size() * 3);
  std::vector<int> fill(mesh.vertex_face_start_.begin(), mesh.vertex_face_start_.end() - 1);
  for (std::size_t f = 0; f < raw.triangles.size(); ++f)
    for (int v : raw.triangles[f]) mesh.vertex_faces_[std::size_t(fill[std::size_t(v)]++)] = int(f);
  // Normals.
  if (!raw.normals.empty()) {
    if (raw.normals.size() != raw.vertices.size())
      return Error{ErrorCode::wrong_arity,
                   "there are " + std::to_string(raw.normals.size()) + " normals for " + std::to_string(n) +
                       " vertices; give one per vertex or none",
                   name("normals", kWholeMeshMember)};
    mesh.normals_.resize(raw.normals.size());
    for (std::size_t i = 0; i < raw.normals.size(); ++i) {
      const T len = norm(raw.normals[i]);
      if (!is_finite(raw.normals[i]) || !(len > T(0)))
        return Error{is_finite(raw.normals[i]) ? ErrorCode::invalid_argument : ErrorCode::not_finite,
                     "the normal of vertex " + std::to_string(i) + " is zero or not finite", name("normals", i)};
      mesh.normals_[i] = raw.normals[i] / len;
    }
    mesh.given_normals_ = true;
  } else {
    mesh.normals_.resize(raw.vertices.size());
    for (std::size_t i = 0; i < raw.vertices.size(); ++i) mesh.normals_[i] = normalized(area_normals[i], V{});
  }
  V lo = raw.vertices[0], hi = raw.vertices[0];
  for (const V& p : raw.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  mesh.scale_ = norm(V(hi - lo));
  return mesh;
}

}  // namespace inbetween
