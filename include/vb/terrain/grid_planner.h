// Global planning on the obstacle occupancy grid: rasterising obstacles, inflating, A* with
// 8-connected moves (diagonal cost sqrt(2), octile heuristic, so paths are optimal; the original
// used unit diagonal cost), and the look-ahead point the path followers steer to.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "vb/engine/types.h"
#include "vb/terrain/task.h"

namespace vb::terrain {

struct Cell {
  int row = 0;
  int col = 0;
  bool operator==(const Cell& o) const { return row == o.row && col == o.col; }
};

// Occupancy grid aligned with the height grid: cell (r, c) is centred on height vertex (r, c),
// x = -size_x/2 + c*cell_m, y = size_y/2 - r*cell_m.
struct OccupancyGrid {
  int rows = 0;
  int cols = 0;
  double cell_m = 1.0;
  double size_x_m = 0.0;
  double size_y_m = 0.0;
  std::vector<uint8_t> occupied;  // row-major, 1 = blocked
  bool Occupied(int r, int c) const { return occupied[static_cast<size_t>(r) * cols + c] != 0; }
  Cell CellOf(const Vec2& p_m) const;       // nearest cell, clamped into the grid
  Vec2 CenterOf(const Cell& cell) const;    // world x, y of a cell centre
};

// Obstacle footprints. Boxes as the original (reference_verti_bench.md §4.4): a rock covers a
// square of side int(4.4*scale*task.scale/cell) cells (odd-widened as [c - w/2, c + w/2]); a
// tree one cell. Other shapes (obstacle_shape.h): the cells whose centres lie inside the shape's
// outline (its projection on the ground), plus the cell nearest the obstacle's position.
OccupancyGrid RasterizeObstacles(const TaskSpec& task);
// Inflation radius of the global planners in cells: 4 m * task.scale (the original's int(4 * sf)
// cells at 1 m cells; in a scaled world the cells shrink with it, so this stays 4 cells, where the
// original's int(4 * sf) drops to 0 for sf < 1/4).
int PlannerInflationCells(const TaskSpec& task);
// Binary dilation with a (2r+1)^2 square.
OccupancyGrid Inflate(const OccupancyGrid& grid, int radius_cells);

// A* from start to goal; returns the cell sequence including both ends, or nullopt if the goal
// is unreachable. The start cell is expanded even if occupied (the vehicle may stand in the
// inflated margin). Deterministic tie-breaking (f, then h, then row-major cell index).
std::optional<std::vector<Cell>> AStar(const OccupancyGrid& grid, const Cell& start,
                                       const Cell& goal);

// Cost-to-goal of every cell (8-connected, diagonal sqrt(2): A*'s metric), computed once by
// Dijkstra from the goal. The path followers replan at 10 Hz from wherever the vehicle is to a
// fixed goal over a static grid; reading a path off this field by steepest descent is as optimal
// as an A* search but costs O(path length) instead of a search (profiled: A* was up to a quarter
// of the step time on dense worlds). Equal-cost routes may be broken differently than AStar's.
// The grid must outlive the field.
class GoalDistanceField {
 public:
  GoalDistanceField(const OccupancyGrid& grid, const Cell& goal);
  // Infinity for occupied cells and cells cut off from the goal.
  double CostToGoal(const Cell& cell) const;
  // The same contract as AStar(grid, start, goal): both ends included, nullopt if unreachable,
  // an occupied start may step to a free neighbour.
  std::optional<std::vector<Cell>> PathFrom(const Cell& start) const;
  // World coordinates (cell centres), as PlanPath.
  std::optional<std::vector<Vec2>> PathFrom(const Vec2& start_m) const;

 private:
  const OccupancyGrid* grid_;
  Cell goal_;
  std::vector<double> cost_;  // row-major
};

// Convenience: plan in world coordinates; path points are cell centres, start to goal.
std::optional<std::vector<Vec2>> PlanPath(const OccupancyGrid& inflated, const Vec2& start_m,
                                          const Vec2& goal_m);

// Look-ahead point (original find_local_goal): scanning from *index, the first path point at
// planar distance >= lookahead_m whose bearing is within +-90 deg of the heading; else the last
// point. *index is advanced to the chosen point.
Vec2 LookAheadPoint(const std::vector<Vec2>& path_m, const Vec2& position_m, double yaw_rad,
                    double lookahead_m, size_t* index);

}  // namespace vb::terrain
