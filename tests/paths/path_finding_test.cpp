// A* path finding on grids (texts 004 §3.4.5) and the smoothed curve through the found path.
#include "inbetween/paths/path_finding.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>

#include "support/random.hpp"

namespace inbetween {
namespace {

const double kSqrt2 = std::sqrt(2.0);

OccupancyGrid grid_of(std::vector<std::string> rows) {
  auto g = OccupancyGrid::from_rows(rows);
  EXPECT_TRUE(g) << g.error().describe();
  return *g;
}

// Independent implementation for 4-moves: breadth-first search distances (all moves cost 1).
int bfs_distance(const OccupancyGrid& g, GridCell s, GridCell t) {
  std::vector<int> d(std::size_t(g.width() * g.height()), -1);
  std::deque<GridCell> q{s};
  d[std::size_t(s.y * g.width() + s.x)] = 0;
  while (!q.empty()) {
    const GridCell c = q.front();
    q.pop_front();
    for (auto [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
      const GridCell n{c.x + dx, c.y + dy};
      if (g.blocked(n) || d[std::size_t(n.y * g.width() + n.x)] >= 0) continue;
      d[std::size_t(n.y * g.width() + n.x)] = d[std::size_t(c.y * g.width() + c.x)] + 1;
      q.push_back(n);
    }
  }
  return d[std::size_t(t.y * g.width() + t.x)];
}

// Independent implementation for 8-moves: Dijkstra by repeated linear minimum search (O(n²)), with
// the same move rules (diagonal allowed only when both side cells are free).
double dijkstra_distance(const OccupancyGrid& g, GridCell s, GridCell t) {
  const int w = g.width(), n = g.width() * g.height();
  std::vector<double> d(std::size_t(n), INFINITY);
  std::vector<bool> done(std::size_t(n), false);
  d[std::size_t(s.y * w + s.x)] = 0;
  for (;;) {
    int best = -1;
    for (int i = 0; i < n; ++i)
      if (!done[std::size_t(i)] && std::isfinite(d[std::size_t(i)]) && (best < 0 || d[std::size_t(i)] < d[std::size_t(best)]))
        best = i;
    if (best < 0) break;
    done[std::size_t(best)] = true;
    const GridCell c{best % w, best / w};
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const GridCell m{c.x + dx, c.y + dy};
        if ((dx == 0 && dy == 0) || g.blocked(m)) continue;
        if (dx != 0 && dy != 0 && (g.blocked({c.x + dx, c.y}) || g.blocked({c.x, c.y + dy}))) continue;
        const double nd = d[std::size_t(best)] + (dx != 0 && dy != 0 ? kSqrt2 : 1.0);
        d[std::size_t(m.y * w + m.x)] = std::min(d[std::size_t(m.y * w + m.x)], nd);
      }
  }
  return d[std::size_t(t.y * w + t.x)];
}

void expect_valid_moves(const GridPath& p, const OccupancyGrid& g, GridCell s, GridCell t) {
  ASSERT_FALSE(p.cells.empty());
  EXPECT_EQ(p.cells.front(), s);
  EXPECT_EQ(p.cells.back(), t);
  double length = 0;
  for (std::size_t i = 0; i < p.cells.size(); ++i) {
    EXPECT_FALSE(g.blocked(p.cells[i]));
    if (i == 0) continue;
    const int dx = std::abs(p.cells[i].x - p.cells[i - 1].x), dy = std::abs(p.cells[i].y - p.cells[i - 1].y);
    ASSERT_TRUE(dx <= 1 && dy <= 1 && dx + dy >= 1);
    length += dx + dy == 2 ? kSqrt2 : 1.0;
  }
  EXPECT_NEAR(p.length, length, 1e-12);
}

TEST(PathFinding, EmptyGridOptima) {
  auto g = OccupancyGrid::build(5, 5, std::vector<bool>(25, false));
  ASSERT_TRUE(g);
  // 4 moves: Manhattan distance 4 + 4 = 8.  8 moves: four diagonals, 4√2.
  auto four = find_grid_path(*g, {0, 0}, {4, 4}, {.moves = GridMoves::four});
  auto eight = find_grid_path(*g, {0, 0}, {4, 4});
  ASSERT_TRUE(four && eight);
  EXPECT_DOUBLE_EQ(four->length, 8.0);
  EXPECT_NEAR(eight->length, 4 * kSqrt2, 1e-14);
  EXPECT_EQ(eight->cells.size(), 5u);
  expect_valid_moves(*four, *g, {0, 0}, {4, 4});
  expect_valid_moves(*eight, *g, {0, 0}, {4, 4});
}

TEST(PathFinding, WallWithAGap) {
  const auto g = grid_of({".....",
                          "###.#",
                          "....."});
  // Only way down is the gap at x = 3.  4 moves: 3 right, 2 down, 3 left = 8.
  auto four = find_grid_path(g, {0, 0}, {0, 2}, {.moves = GridMoves::four});
  ASSERT_TRUE(four);
  EXPECT_DOUBLE_EQ(four->length, 8.0);
  // 8 moves without corner cutting: both diagonals into and out of the gap pass the blocked cell
  // (2, 1), so the length is 8 again.  With corner cutting: 2 + √2 + √2 + 2 = 4 + 2√2.
  auto no_cut = find_grid_path(g, {0, 0}, {0, 2});
  auto cut = find_grid_path(g, {0, 0}, {0, 2}, {.cut_corners = true});
  ASSERT_TRUE(no_cut && cut);
  EXPECT_DOUBLE_EQ(no_cut->length, 8.0);
  EXPECT_NEAR(cut->length, 4 + 2 * kSqrt2, 1e-14);
  expect_valid_moves(*cut, g, {0, 0}, {0, 2});
  // Never squeeze between two blocked cells, even with cut_corners.
  const auto diag = grid_of({".#",
                             "#."});
  auto none = find_grid_path(diag, {0, 0}, {1, 1}, {.cut_corners = true});
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().where, "goal");
}

TEST(PathFinding, MatchesBreadthFirstSearchOnRandomGrids) {
  test::Random rng(test::seed_for(2024));
  SCOPED_TRACE(rng.trace());
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int w = rng.integer(2, 14), h = rng.integer(2, 14);
    std::vector<bool> cells(std::size_t(w * h));
    for (auto&& c : cells) c = rng.uniform(0.0, 1.0) < 0.3;
    auto g = OccupancyGrid::build(w, h, cells);
    ASSERT_TRUE(g);
    const GridCell s{rng.integer(0, w - 1), rng.integer(0, h - 1)}, t{rng.integer(0, w - 1), rng.integer(0, h - 1)};
    if (g->blocked(s) || g->blocked(t)) continue;
    const int want = bfs_distance(*g, s, t);
    auto p = find_grid_path(*g, s, t, {.moves = GridMoves::four});
    if (want < 0) {
      ASSERT_FALSE(p);
      EXPECT_NE(p.error().message.find("no path"), std::string::npos);
      continue;
    }
    ASSERT_TRUE(p);
    EXPECT_DOUBLE_EQ(p->length, double(want));
    expect_valid_moves(*p, *g, s, t);
    auto p8 = find_grid_path(*g, s, t);
    const double want8 = dijkstra_distance(*g, s, t);
    ASSERT_EQ(bool(p8), std::isfinite(want8));
    if (p8) {
      EXPECT_NEAR(p8->length, want8, 1e-12);  // sums of at most ~30 terms 1 and √2
      expect_valid_moves(*p8, *g, s, t);
    }
    ++compared;
  }
  EXPECT_GT(compared, 50);
}

TEST(PathFinding, ErrorsNameTheCell) {
  const auto g = grid_of({"..#",
                          "###",
                          "..."});
  auto walled = find_grid_path(g, {0, 0}, {2, 2});
  ASSERT_FALSE(walled);
  EXPECT_EQ(walled.error().where, "goal");
  EXPECT_NE(walled.error().message.find("no path from (0, 0) to (2, 2)"), std::string::npos);
  auto blocked = find_grid_path(g, {2, 0}, {0, 0});
  ASSERT_FALSE(blocked);
  EXPECT_EQ(blocked.error().where, "start");
  auto outside = find_grid_path(g, {0, 0}, {3, 0});
  ASSERT_FALSE(outside);
  EXPECT_EQ(outside.error().where, "goal");
  auto same = find_grid_path(g, {1, 2}, {1, 2});
  ASSERT_TRUE(same);
  EXPECT_EQ(same->cells.size(), 1u);
  EXPECT_EQ(same->length, 0.0);
  const std::vector<std::string> bad{"..", ".x"};
  auto parse = OccupancyGrid::from_rows(bad);
  ASSERT_FALSE(parse);
  EXPECT_EQ(parse.error().where, "row 1, column 1");
  auto size = OccupancyGrid::build(2, 2, std::vector<bool>(3));
  ASSERT_FALSE(size);
}

TEST(PathFinding, InflationGrowsObstaclesByARadius) {
  const auto g = grid_of({".....",
                          ".....",
                          "..#..",
                          ".....",
                          "....."});
  // Radius 1: the 4 neighbours (distance 1); radius 1.5: also the diagonals (√2 ≤ 1.5); radius 2:
  // also the cells 2 away along the axes.
  EXPECT_TRUE(g.inflated(1.0).blocked({3, 2}));
  EXPECT_FALSE(g.inflated(1.0).blocked({3, 3}));
  EXPECT_TRUE(g.inflated(1.5).blocked({3, 3}));
  EXPECT_FALSE(g.inflated(1.5).blocked({4, 2}));
  EXPECT_TRUE(g.inflated(2.0).blocked({4, 2}));
  EXPECT_FALSE(g.inflated(2.0).blocked({4, 3}));  // √5 > 2
  EXPECT_FALSE(g.inflated(0.0).blocked({3, 2}));
}

TEST(PathFinding, SmoothedPathPassesThroughTheWaypoints) {
  const auto g = grid_of({"........",
                          ".######.",
                          "......#.",
                          "#####.#.",
                          "........"});
  auto p = find_grid_path(g, {0, 0}, {0, 4}, {.moves = GridMoves::four});
  ASSERT_TRUE(p);
  const GridSmoothingOptions<double> opt{.origin = {10, 20}, .cell_size = 0.5};
  const auto way = grid_path_waypoints(*p, opt);
  auto curve = smooth_grid_path(*p, opt);
  ASSERT_TRUE(curve) << curve.error().describe();
  ASSERT_EQ(way.size(), std::size_t(curve->segment_count() + 1));
  for (int i = 0; i < int(way.size()); ++i) {
    const double u = i < curve->segment_count() ? curve->segment_domain(i).lo : curve->domain().hi;
    EXPECT_NEAR(distance(curve->point(u), way[std::size_t(i)]), 0.0, 1e-12) << i;
  }
  // Corners only: the start, the goal and each turn; consecutive waypoints differ.
  EXPECT_EQ(way.front(), (Vec2d{10, 20}));
  EXPECT_EQ(way.back(), (Vec2d{10, 22}));
  for (std::size_t i = 1; i < way.size(); ++i) EXPECT_GT(distance(way[i], way[i - 1]), 0.0);
  // One-cell path: a curve of length zero at the cell (documented fallback).
  auto one = find_grid_path(g, {3, 0}, {3, 0});
  ASSERT_TRUE(one);
  auto c1 = smooth_grid_path<double>(*one);
  ASSERT_TRUE(c1);
  EXPECT_EQ(c1->point(0.5), (Vec2d{3, 0}));
  auto empty = smooth_grid_path<double>(GridPath{});
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().where, "path");
}

TEST(PathFinding, CornersOfAStraightRunAreItsEnds) {
  const std::vector<GridCell> run{{0, 0}, {1, 0}, {2, 0}, {3, 1}, {4, 2}, {4, 3}};
  const auto c = grid_path_corners(run);
  EXPECT_EQ(c, (std::vector<GridCell>{{0, 0}, {2, 0}, {4, 2}, {4, 3}}));
}

}  // namespace
}  // namespace inbetween
