#pragma once
/// Paths along the edges of a mesh or any graph embedded in space (texts 004 §3.4.4–3.4.5).
///
/// - greedy_edge_path: the texts' greedy walk over a surface mesh.  From the current vertex take
///   the edge whose direction is closest to the straight line to the goal — the largest cosine
///   (edge · unit vector to the goal)/|edge| — until the goal is reached.  It is cheap and usually
///   direct, but it can walk into a dead end or around a loop; then it stops with an Error naming
///   the vertex where it would revisit (no silent infinite loop).  Ties go to the lower vertex index.
/// - shortest_graph_path: the shortest path by edge length (A* with the straight-line distance to
///   the goal as heuristic, which never overestimates, so the result is optimal; Dijkstra when the
///   heuristic is zero), the reference the greedy walk can be compared with.
/// Errors name the item: "vertex i" (not finite), "edge i" (index out of range, or a loop from a
/// vertex to itself), "start" / "goal" (out of range), and "goal" for "no path".

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// An undirected graph with vertices in 3-D; edge weights are Euclidean lengths.
template <Real T>
class EdgeGraph {
 public:
  EdgeGraph() = default;  ///< empty graph (no vertices)

  /// From vertices and index pairs; duplicate edges are merged.  Errors in the file comment.
  static Expected<EdgeGraph> build(std::span<const Vec3<T>> vertices, std::span<const std::array<int, 2>> edges) {
    for (std::size_t i = 0; i < vertices.size(); ++i)
      if (!is_finite(vertices[i]))
        return Error{ErrorCode::not_finite, "vertex " + std::to_string(i) + " is not finite", {Element{"vertex", std::size_t(i)}}};
    EdgeGraph g;
    g.vertices_.assign(vertices.begin(), vertices.end());
    g.adjacent_.resize(vertices.size());
    const int n = int(vertices.size());
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [a, b] = edges[e];
      if (a < 0 || b < 0 || a >= n || b >= n)
        return Error{ErrorCode::invalid_argument,
                     "edge joins vertices " + std::to_string(a) + " and " + std::to_string(b) + ", but there are " +
                         std::to_string(n), {Element{"edge", std::size_t(e)}}};
      if (a == b)
        return Error{ErrorCode::invalid_argument, "edge joins vertex " + std::to_string(a) + " to itself", {Element{"edge", std::size_t(e)}}};
      g.adjacent_[std::size_t(a)].push_back(b);
      g.adjacent_[std::size_t(b)].push_back(a);
    }
    for (auto& list : g.adjacent_) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    return g;
  }

  /// From a triangle mesh: the edges of every triangle.  Errors name "triangle i" for an index out
  /// of range or a triangle with a repeated vertex, else as build().
  static Expected<EdgeGraph> from_triangles(std::span<const Vec3<T>> vertices,
                                            std::span<const std::array<int, 3>> triangles) {
    std::vector<std::array<int, 2>> edges;
    const int n = int(vertices.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const auto& tri = triangles[t];
      for (int k = 0; k < 3; ++k) {
        if (tri[std::size_t(k)] < 0 || tri[std::size_t(k)] >= n || tri[std::size_t(k)] == tri[std::size_t((k + 1) % 3)])
          return Error{ErrorCode::invalid_argument, "triangle has a vertex index out of range or repeated", {Element{"triangle", std::size_t(t)}}};
        edges.push_back({tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)]});
      }
    }
    return build(vertices, edges);
  }

  /// Number of vertices.
  int vertex_count() const noexcept { return int(vertices_.size()); }
  /// Position of vertex i (0 ≤ i < vertex_count()).
  const Vec3<T>& vertex(int i) const noexcept { return vertices_[std::size_t(i)]; }
  /// The neighbours of vertex i, ascending.
  std::span<const int> neighbours(int i) const noexcept { return adjacent_[std::size_t(i)]; }

 private:
  std::vector<Vec3<T>> vertices_;
  std::vector<std::vector<int>> adjacent_;
};

/// A path of vertex indices and its length (sum of edge lengths).
template <Real T>
struct GraphPath {
  std::vector<int> vertices;  ///< start … goal
  T length{};                 ///< total Euclidean length
};

namespace detail {
template <Real T>
Expected<void> check_graph_ends(const EdgeGraph<T>& g, int start, int goal) {
  for (const auto& [v, name] : {std::pair{start, "start"}, std::pair{goal, "goal"}})
    if (v < 0 || v >= g.vertex_count())
      return Error{ErrorCode::invalid_argument,
                   std::string(name) + " vertex " + std::to_string(v) + " is not one of the " +
                       std::to_string(g.vertex_count()) + " vertices",
                   {Parameter{name}}};
  return {};
}
}  // namespace detail

/// The texts' greedy edge walk (file comment).  start == goal gives the one-vertex path.
template <Real T>
Expected<GraphPath<T>> greedy_edge_path(const EdgeGraph<T>& graph, int start, int goal) {
  if (auto ok = detail::check_graph_ends(graph, start, goal); !ok) return ok.error();
  GraphPath<T> out{{start}, T(0)};
  std::vector<bool> visited(std::size_t(graph.vertex_count()), false);
  visited[std::size_t(start)] = true;
  int cur = start;
  while (cur != goal) {
    const Vec3<T> to_goal = graph.vertex(goal) - graph.vertex(cur);
    const T dist = norm(to_goal);
    int best = -1;
    T best_cos = -std::numeric_limits<T>::infinity();
    for (int nb : graph.neighbours(cur)) {
      const Vec3<T> edge = graph.vertex(nb) - graph.vertex(cur);
      const T len = norm(edge);
      // A zero-length edge or a vertex at the goal's position: go there if it is the goal.
      const T c = nb == goal ? std::numeric_limits<T>::infinity()
                  : (len > T(0) && dist > T(0)) ? dot(edge, to_goal) / (len * dist) : T(-2);
      if (c > best_cos) {
        best_cos = c;
        best = nb;
      }
    }
    if (best < 0)
      return Error{ErrorCode::invalid_argument,
                   "greedy walk stuck: vertex " + std::to_string(cur) + " has no edges", {Parameter{"goal"}}};
    if (visited[std::size_t(best)])
      return Error{ErrorCode::invalid_argument,
                   "greedy walk would revisit vertex " + std::to_string(best) + " (from vertex " + std::to_string(cur) +
                       "): a dead end or a loop; use shortest_graph_path", {Parameter{"goal"}}};
    visited[std::size_t(best)] = true;
    out.length += distance(graph.vertex(cur), graph.vertex(best));
    out.vertices.push_back(best);
    cur = best;
  }
  return out;
}

/// The shortest path by Euclidean edge length (A*, straight-line heuristic).  Errors in the file
/// comment; "no path" names "goal".
template <Real T>
Expected<GraphPath<T>> shortest_graph_path(const EdgeGraph<T>& graph, int start, int goal) {
  if (auto ok = detail::check_graph_ends(graph, start, goal); !ok) return ok.error();
  const std::size_t n = std::size_t(graph.vertex_count());
  std::vector<T> g(n, std::numeric_limits<T>::infinity());
  std::vector<int> parent(n, -1);
  std::vector<bool> closed(n, false);
  using Entry = std::pair<T, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  g[std::size_t(start)] = T(0);
  open.emplace(distance(graph.vertex(start), graph.vertex(goal)), start);
  while (!open.empty()) {
    const int cur = open.top().second;
    open.pop();
    if (closed[std::size_t(cur)]) continue;
    closed[std::size_t(cur)] = true;
    if (cur == goal) break;
    for (int nb : graph.neighbours(cur)) {
      if (closed[std::size_t(nb)]) continue;
      const T cost = g[std::size_t(cur)] + distance(graph.vertex(cur), graph.vertex(nb));
      if (cost < g[std::size_t(nb)]) {
        g[std::size_t(nb)] = cost;
        parent[std::size_t(nb)] = cur;
        open.emplace(cost + distance(graph.vertex(nb), graph.vertex(goal)), nb);
      }
    }
  }
  if (!closed[std::size_t(goal)])
    return Error{ErrorCode::invalid_argument,
                 "no path from vertex " + std::to_string(start) + " to vertex " + std::to_string(goal) +
                     ": they are not connected", {Parameter{"goal"}}};
  GraphPath<T> out;
  for (int v = goal; v >= 0; v = parent[std::size_t(v)]) out.vertices.push_back(v);
  std::reverse(out.vertices.begin(), out.vertices.end());
  out.length = g[std::size_t(goal)];
  return out;
}

}  // namespace inbetween
