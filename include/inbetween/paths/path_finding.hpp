#pragma once
/// Path finding (texts 004 §3.4.5): A* search on an occupancy grid among static obstacles, obstacle
/// growth for a moving sphere ("increasing the size of the obstacles by the size of the
/// approximating sphere"), and the found polyline turned into a smooth curve.
///
/// Grid: cells (x, y) with 0 ≤ x < width, 0 ≤ y < height; a move goes to one of the 4 (GridMoves::four)
/// or 8 (GridMoves::eight) neighbours, costing 1 straight and √2 diagonally.  A diagonal move may
/// not squeeze between two blocked cells; unless `cut_corners` is set it may not pass any blocked
/// corner cell either.  The heuristic (Manhattan for 4 moves, octile for 8) never overestimates,
/// so the path found is a shortest one; ties are broken deterministically.
///
/// Smoothing: smooth_grid_path keeps the start, the goal and the cells where the direction of travel
/// changes, maps them to points (origin + cell·cell_size) and runs a centripetal Catmull-Rom spline
/// (curves/catmull_rom.hpp) through them; the curve passes through every waypoint.  It may cut
/// corners of obstacles between waypoints (the grid path does not); inflate the obstacles first
/// when clearance matters.

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/vec.hpp"

namespace inbetween {

/// A grid cell (column x, row y).
struct GridCell {
  int x = 0;  ///< column, 0 ≤ x < width
  int y = 0;  ///< row, 0 ≤ y < height
  friend constexpr bool operator==(const GridCell&, const GridCell&) = default;
};

/// A width × height grid of free and blocked cells.
class OccupancyGrid {
 public:
  /// An empty 0 × 0 grid (every cell counts as blocked); use build() or from_rows().
  OccupancyGrid() = default;

  /// From a row-major list of width·height flags (true = blocked).  Errors: width or height < 1,
  /// or a list of the wrong size (InvalidArgument).
  static Expected<OccupancyGrid> build(int width, int height, std::vector<bool> blocked);
  /// From text rows, row 0 first: '#' blocked, '.' free; all rows the same length.  Errors name
  /// "row r" or "row r, column c".
  static Expected<OccupancyGrid> from_rows(std::span<const std::string> rows);

  /// Number of columns.
  int width() const noexcept { return width_; }
  /// Number of rows.
  int height() const noexcept { return height_; }
  /// True when c lies on the grid.
  bool contains(GridCell c) const noexcept { return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_; }
  /// True when c is blocked; cells off the grid count as blocked.
  bool blocked(GridCell c) const noexcept {
    return !contains(c) || blocked_[std::size_t(c.y) * std::size_t(width_) + std::size_t(c.x)];
  }
  /// The grid with every cell within Euclidean distance `radius_cells` (centre to centre) of a
  /// blocked cell blocked too; radius ≤ 0 or NaN returns a copy.
  OccupancyGrid inflated(double radius_cells) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<bool> blocked_;
};

/// Neighbourhood of a move.
enum class GridMoves {
  four,   ///< up, down, left, right (cost 1)
  eight,  ///< also the diagonals (cost √2)
  /// Deprecated PascalCase spellings, kept for one release (docs/conventions.md, "Enumerators").
  Four [[deprecated("use GridMoves::four")]] = four,
  Eight [[deprecated("use GridMoves::eight")]] = eight,
};

/// Options of find_grid_path().
struct GridPathOptions {
  GridMoves moves = GridMoves::eight;  ///< neighbourhood
  bool cut_corners = false;            ///< allow a diagonal past one blocked corner cell
};

/// A path of cells from start to goal and its length in cell units.
struct GridPath {
  std::vector<GridCell> cells;  ///< start … goal, each a move from the previous one
  double length = 0;            ///< sum of move costs (1 or √2)
  int expanded = 0;             ///< cells taken from the open list (a measure of search effort)
};

/// A* from start to goal.  Errors (InvalidArgument, `where` "start" or "goal"): a cell off the grid
/// or blocked, and — where "goal" — "no path" when the goal cannot be reached.  start == goal
/// gives the one-cell path of length 0.
Expected<GridPath> find_grid_path(const OccupancyGrid& grid, GridCell start, GridCell goal,
                                  const GridPathOptions& options = {});

/// The start, the goal and the cells where the move direction changes (the polyline's corners).
std::vector<GridCell> grid_path_corners(std::span<const GridCell> cells);

/// Options of smooth_grid_path().
template <Real T>
struct GridSmoothingOptions {
  Vec2<T> origin{};          ///< world position of cell (0, 0)
  T cell_size = T(1);        ///< > 0, world size of a cell
  bool corners_only = true;  ///< true: waypoints are grid_path_corners(); false: every cell
  T alpha = T(0.5);          ///< Catmull-Rom knot exponent (0.5 centripetal: no cusps or loops)
};

/// The waypoints of `path` in world coordinates (see GridSmoothingOptions).
template <Real T>
std::vector<Vec2<T>> grid_path_waypoints(const GridPath& path, const GridSmoothingOptions<T>& options = {}) {
  const std::vector<GridCell> cells = options.corners_only ? grid_path_corners(path.cells) : path.cells;
  std::vector<Vec2<T>> out;
  for (const GridCell& c : cells) out.push_back(options.origin + Vec2<T>{T(c.x), T(c.y)} * options.cell_size);
  return out;
}

/// A Catmull-Rom spline through the waypoints (file comment).  A one-cell path gives a curve of
/// length zero through two copies of the cell (documented fallback).  Errors: an empty path
/// (TooFewPoints, "path"), cell_size not finite and positive ("cell_size"), and the spline
/// builder's errors.
template <Real T>
Expected<CatmullRomSpline<Vec2<T>>> smooth_grid_path(const GridPath& path, const GridSmoothingOptions<T>& options = {}) {
  if (path.cells.empty()) return Error{ErrorCode::TooFewPoints, "the grid path has no cells", "path"};
  if (!(options.cell_size > T(0)) || !std::isfinite(options.cell_size))
    return Error{ErrorCode::InvalidArgument, "cell_size must be finite and > 0", "cell_size"};
  std::vector<Vec2<T>> pts = grid_path_waypoints(path, options);
  if (pts.size() == 1) pts.push_back(pts[0]);
  return build_catmull_rom(pts, {.alpha = options.alpha});
}

}  // namespace inbetween
