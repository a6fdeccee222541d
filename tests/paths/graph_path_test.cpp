// Greedy edge walks and shortest paths on meshes (texts 004 §3.4.4–3.4.5).
#include "inbetween/paths/graph_path.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/random.hpp"

namespace inbetween {
namespace {

const double kSqrt2 = std::sqrt(2.0);

// (n+1)² vertices of a unit grid in the plane z = 0, each square split along its (+1, +1)
// diagonal.  Vertex (i, j) has index j(n + 1) + i.
EdgeGraph<double> triangulated_grid(int n) {
  std::vector<Vec3d> v;
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back({double(i), double(j), 0});
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return *EdgeGraph<double>::from_triangles(v, t);
}

TEST(GraphPath, DiagonalAcrossATriangulatedGrid) {
  const auto g = triangulated_grid(5);
  // Corner to corner along the diagonals: 5√2, both greedy (every step is exactly towards the
  // goal, cosine 1) and shortest.
  auto greedy = greedy_edge_path(g, 0, 35);
  auto best = shortest_graph_path(g, 0, 35);
  ASSERT_TRUE(greedy && best);
  EXPECT_NEAR(greedy->length, 5 * kSqrt2, 1e-14);
  EXPECT_NEAR(best->length, 5 * kSqrt2, 1e-14);
  EXPECT_EQ(greedy->vertices, (std::vector<int>{0, 7, 14, 21, 28, 35}));
  // Against the diagonals, (5, 0) → (0, 5) has no diagonal edges: the shortest edge path is
  // 5 + 5 = 10 (any monotone staircase).
  auto anti = shortest_graph_path(g, 5, 30);
  ASSERT_TRUE(anti);
  EXPECT_NEAR(anti->length, 10.0, 1e-14);
}

TEST(GraphPath, OctahedronPoleToPole) {
  // Vertices ±x, ±y, ±z, edges between non-opposite vertices (length √2): +x to −x takes two edges,
  // 2√2; greedy ties (every neighbour has cosine 1/√2) go to the lowest index.
  const std::vector<Vec3d> v{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const std::vector<std::array<int, 3>> t{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                          {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  auto g = EdgeGraph<double>::from_triangles(v, t);
  ASSERT_TRUE(g);
  auto greedy = greedy_edge_path(*g, 0, 1);
  auto best = shortest_graph_path(*g, 0, 1);
  ASSERT_TRUE(greedy && best);
  EXPECT_EQ(greedy->vertices, (std::vector<int>{0, 2, 1}));
  EXPECT_NEAR(greedy->length, 2 * kSqrt2, 1e-15);
  EXPECT_NEAR(best->length, 2 * kSqrt2, 1e-15);
}

TEST(GraphPath, GreedyDeadEndIsAnErrorAndShortestGoesAround) {
  // S(0,0) — A(1,0) is a dead end pointing at the goal G(2,0); the way round is S — B(0,1) —
  // C(2,1) — G.  Greedy takes A (cosine 1), then could only go back: Error.  Shortest: 1 + 2 + 1.
  const std::vector<Vec3d> v{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 1, 0}, {2, 0, 0}};
  const std::vector<std::array<int, 2>> e{{0, 1}, {0, 2}, {2, 3}, {3, 4}};
  auto g = EdgeGraph<double>::build(v, e);
  ASSERT_TRUE(g);
  auto greedy = greedy_edge_path(*g, 0, 4);
  ASSERT_FALSE(greedy);
  EXPECT_EQ(greedy.error().place(), "goal");
  EXPECT_NE(greedy.error().message.find("revisit vertex 0"), std::string::npos) << greedy.error().message;
  auto best = shortest_graph_path(*g, 0, 4);
  ASSERT_TRUE(best);
  EXPECT_EQ(best->vertices, (std::vector<int>{0, 2, 3, 4}));
  EXPECT_DOUBLE_EQ(best->length, 4.0);
}

TEST(GraphPath, GreedyIsNeverShorterThanShortest) {
  test::Random rng(test::seed_for(99));
  SCOPED_TRACE(rng.trace());
  const auto g = triangulated_grid(8);
  int compared = 0;
  for (int k = 0; k < 100; ++k) {
    const int a = rng.integer(0, 80), b = rng.integer(0, 80);
    auto best = shortest_graph_path(g, a, b);
    ASSERT_TRUE(best);
    // Lower bound: the straight line.  Upper bound: the staircase of axis edges, |dx| + |dy| ≤ √2·line
    // (Cauchy–Schwarz), is always available.
    const double line = distance(g.vertex(a), g.vertex(b));
    EXPECT_GE(best->length, line - 1e-12);
    EXPECT_LE(best->length, kSqrt2 * line + 1e-12);
    auto greedy = greedy_edge_path(g, a, b);
    if (!greedy) continue;
    EXPECT_GE(greedy->length, best->length - 1e-12);
    ++compared;
  }
  EXPECT_GT(compared, 50);
}

TEST(GraphPath, BadInputIsNamed) {
  const std::vector<Vec3d> v{{0, 0, 0}, {1, 0, 0}, {std::nan(""), 0, 0}};
  const std::vector<std::array<int, 2>> e{{0, 1}};
  auto nan = EdgeGraph<double>::build(v, e);
  ASSERT_FALSE(nan);
  EXPECT_EQ(nan.error().place(), "vertex 2");
  const std::vector<Vec3d> ok{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<std::array<int, 2>> bad{{0, 1}, {1, 3}};
  auto range = EdgeGraph<double>::build(ok, bad);
  ASSERT_FALSE(range);
  EXPECT_EQ(range.error().place(), "edge 1");
  const std::vector<std::array<int, 2>> loop{{1, 1}};
  EXPECT_EQ(EdgeGraph<double>::build(ok, loop).error().place(), "edge 0");
  const std::vector<std::array<int, 3>> tri{{0, 1, 1}};
  EXPECT_EQ(EdgeGraph<double>::from_triangles(ok, tri).error().place(), "triangle 0");
  // Vertex 2 is isolated: no path; out-of-range ends are named.
  const std::vector<std::array<int, 2>> one{{0, 1}};
  auto g = EdgeGraph<double>::build(ok, one);
  ASSERT_TRUE(g);
  auto none = shortest_graph_path(*g, 0, 2);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().place(), "goal");
  EXPECT_NE(none.error().message.find("no path"), std::string::npos);
  EXPECT_FALSE(greedy_edge_path(*g, 0, 2));
  EXPECT_EQ(shortest_graph_path(*g, -1, 0).error().place(), "start");
  EXPECT_EQ(greedy_edge_path(*g, 0, 3).error().place(), "goal");
  auto same = shortest_graph_path(*g, 1, 1);
  ASSERT_TRUE(same);
  EXPECT_EQ(same->vertices, std::vector<int>{1});
}

}  // namespace
}  // namespace inbetween
