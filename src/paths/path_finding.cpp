// A* on an occupancy grid (texts 004 §3.4.5); see include/inbetween/paths/path_finding.hpp.
#include "inbetween/paths/path_finding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <tuple>

namespace inbetween {
namespace {

// Built with append(): GCC 12 gives a false -Wrestrict warning for "(" + std::to_string(…).
std::string cell_text(GridCell c) {
  std::string s("(");
  s.append(std::to_string(c.x)).append(", ").append(std::to_string(c.y)).append(")");
  return s;
}

constexpr double kSqrt2 = 1.4142135623730951;

double heuristic(GridCell a, GridCell b, GridMoves moves) {
  const double dx = std::abs(a.x - b.x), dy = std::abs(a.y - b.y);
  if (moves == GridMoves::four) return dx + dy;
  return std::max(dx, dy) + (kSqrt2 - 1) * std::min(dx, dy);  // octile distance
}

}  // namespace

Expected<OccupancyGrid> OccupancyGrid::build(int width, int height, std::vector<bool> blocked) {
  if (width < 1 || height < 1)
    return Error{ErrorCode::InvalidArgument,
                 "grid must be at least 1 x 1, got " + std::to_string(width) + " x " + std::to_string(height), "size"};
  if (blocked.size() != std::size_t(width) * std::size_t(height))
    return Error{ErrorCode::WrongArity,
                 "expected " + std::to_string(std::size_t(width) * std::size_t(height)) + " cells, got " +
                     std::to_string(blocked.size()),
                 "cells"};
  OccupancyGrid g;
  g.width_ = width;
  g.height_ = height;
  g.blocked_ = std::move(blocked);
  return g;
}

Expected<OccupancyGrid> OccupancyGrid::from_rows(std::span<const std::string> rows) {
  if (rows.empty()) return Error{ErrorCode::TooFewPoints, "the grid has no rows", "rows"};
  const std::size_t w = rows[0].size();
  std::vector<bool> cells;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].size() != w || w == 0)
      return Error{ErrorCode::WrongArity,
                   "row has " + std::to_string(rows[r].size()) + " cells, row 0 has " + std::to_string(w),
                   "row " + std::to_string(r)};
    for (std::size_t c = 0; c < w; ++c) {
      const char ch = rows[r][c];
      if (ch != '#' && ch != '.')
        return Error{ErrorCode::Parse, std::string("expected '#' or '.', got '") + ch + "'",
                     "row " + std::to_string(r) + ", column " + std::to_string(c)};
      cells.push_back(ch == '#');
    }
  }
  return build(int(w), int(rows.size()), std::move(cells));
}

OccupancyGrid OccupancyGrid::inflated(double radius_cells) const {
  OccupancyGrid out = *this;
  if (!(radius_cells > 0)) return out;
  const int reach = int(std::floor(std::min(radius_cells, double(width_ + height_))));
  const double r2 = radius_cells * radius_cells;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      if (!blocked({x, y})) continue;
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const GridCell c{x + dx, y + dy};
          if (double(dx * dx + dy * dy) <= r2 && out.contains(c))
            out.blocked_[std::size_t(c.y) * std::size_t(width_) + std::size_t(c.x)] = true;
        }
    }
  return out;
}

Expected<GridPath> find_grid_path(const OccupancyGrid& grid, GridCell start, GridCell goal,
                                  const GridPathOptions& options) {
  for (const auto& [cell, name] : {std::pair{start, "start"}, std::pair{goal, "goal"}}) {
    if (!grid.contains(cell))
      return Error{ErrorCode::InvalidArgument,
                   std::string(name) + " cell " + cell_text(cell) + " is outside the " + std::to_string(grid.width()) +
                       " x " + std::to_string(grid.height()) + " grid",
                   name};
    if (grid.blocked(cell))
      return Error{ErrorCode::InvalidArgument, std::string(name) + " cell " + cell_text(cell) + " is blocked", name};
  }
  const int w = grid.width();
  const std::size_t n = std::size_t(w) * std::size_t(grid.height());
  auto index = [w](GridCell c) { return std::size_t(c.y) * std::size_t(w) + std::size_t(c.x); };
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> g(n, inf);
  std::vector<std::int64_t> parent(n, -1);
  std::vector<bool> closed(n, false);
  // Open list ordered by f, then by larger g (deeper first), then by insertion order.
  using Entry = std::tuple<double, double, std::uint64_t, int, int>;  // f, −g, order, x, y
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  std::uint64_t order = 0;
  g[index(start)] = 0;
  open.emplace(heuristic(start, goal, options.moves), -0.0, order++, start.x, start.y);
  static constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  static constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  const int moves = options.moves == GridMoves::four ? 4 : 8;
  GridPath out;
  while (!open.empty()) {
    const auto [f, neg_g, ord, cx, cy] = open.top();
    open.pop();
    const GridCell cur{cx, cy};
    const std::size_t ci = index(cur);
    if (closed[ci]) continue;
    closed[ci] = true;
    ++out.expanded;
    if (cur == goal) break;
    for (int m = 0; m < moves; ++m) {
      const GridCell next{cx + kDx[m], cy + kDy[m]};
      if (grid.blocked(next)) continue;
      const bool diagonal = m >= 4;
      if (diagonal) {
        const bool a = grid.blocked({cx + kDx[m], cy}), b = grid.blocked({cx, cy + kDy[m]});
        if ((a && b) || (!options.cut_corners && (a || b))) continue;
      }
      const std::size_t ni = index(next);
      if (closed[ni]) continue;
      const double cost = g[ci] + (diagonal ? kSqrt2 : 1.0);
      if (cost < g[ni]) {
        g[ni] = cost;
        parent[ni] = std::int64_t(ci);
        open.emplace(cost + heuristic(next, goal, options.moves), -cost, order++, next.x, next.y);
      }
    }
  }
  if (!closed[index(goal)])
    return Error{ErrorCode::InvalidArgument,
                 "no path from " + cell_text(start) + " to " + cell_text(goal) + ": the goal cannot be reached (" +
                     std::to_string(out.expanded) + " cells explored)",
                 "goal"};
  for (std::int64_t i = std::int64_t(index(goal)); i >= 0; i = parent[std::size_t(i)])
    out.cells.push_back({int(i % w), int(i / w)});
  std::reverse(out.cells.begin(), out.cells.end());
  out.length = g[index(goal)];
  return out;
}

std::vector<GridCell> grid_path_corners(std::span<const GridCell> cells) {
  std::vector<GridCell> out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i == 0 || i + 1 == cells.size()) {
      out.push_back(cells[i]);
      continue;
    }
    const int ax = cells[i].x - cells[i - 1].x, ay = cells[i].y - cells[i - 1].y;
    const int bx = cells[i + 1].x - cells[i].x, by = cells[i + 1].y - cells[i].y;
    if (ax != bx || ay != by) out.push_back(cells[i]);
  }
  return out;
}

}  // namespace inbetween
