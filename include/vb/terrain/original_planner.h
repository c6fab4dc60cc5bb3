// The original benchmark's global planner as its code runs it (reference_verti_bench.md §4.6),
// for the path followers' `*_original` variants (docs/baselines.md): vb's own planner
// (grid_planner.h) is optimal A* without smoothing, which is what the paper describes; this one
// reproduces the routes the original's vehicles actually drove.
//
// What the original does, and this does the same:
//  - grid: its obstacle map, one pixel per height vertex but addressed with a 129 m span over the
//    128 m world (quirk 1: pixel (r, c) stands for x = c - 64.5, y = 64.5 - r at scale 1); a rock
//    marks int(4.4 * rock scale) pixels square around the pixel nearest its position (numpy's
//    round half to even, clipped into the image), a tree one pixel; inflated by a square of
//    2 int(4 * scale) + 1 pixels (0 below scale 1/4, as the original);
//  - the start and goal pixels by truncation, clamped into the image;
//  - A*: 8-connected, every move costs 1 (diagonals too), Euclidean heuristic, a binary heap of
//    (f, row, col) so that ties break on f, then row, then column; the start is expanded even if
//    occupied; no path if the goal is unreachable;
//  - smoothing: a path of 3 or more cells is the control polygon of one Bezier curve of degree
//    n - 1, sampled at 100 parameters 0, 1/99, ..., 1 (it cuts corners, even into obstacles);
//  - points in world coordinates by the same 129 m transform.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "vb/engine/types.h"
#include "vb/terrain/task.h"

namespace vb::terrain {

struct OriginalPlannerGrid {
  int rows = 0;
  int cols = 0;
  double cell_m = 1.0;        // world metres per pixel (the task's scale at 1 m vertices)
  double half_x_m = 64.5;     // the original's half lengths: (cols * cell) / 2
  double half_y_m = 64.5;
  std::vector<uint8_t> occupied;  // inflated, row-major, 1 = blocked
  bool Occupied(int r, int c) const { return occupied[static_cast<size_t>(r) * cols + c] != 0; }
};

// The inflated obstacle map of a task with a height grid of at least 2 x 2 vertices.
OriginalPlannerGrid MakeOriginalPlannerGrid(const TaskSpec& task);

// The pixel (row, col) the original plans from for a world position (truncation, clamped).
void OriginalPlannerPixel(const OriginalPlannerGrid& grid, const Vec2& p_m, int* row, int* col);

// A* as the original (unit-cost moves, its heap's tie-breaking): the pixel path including both
// ends, or nullopt if the goal is unreachable.
std::optional<std::vector<std::pair<int, int>>> OriginalAStar(const OriginalPlannerGrid& grid,
                                                              int start_row, int start_col,
                                                              int goal_row, int goal_col);

// The 100-point Bezier curve through a control polygon of (row, col) points (3 or more).
std::vector<std::pair<double, double>> OriginalBezier(
    const std::vector<std::pair<int, int>>& control);

// The whole plan: A*, smoothing (3 or more cells), world coordinates; nullopt if unreachable.
std::optional<std::vector<Vec2>> OriginalPlanPath(const OriginalPlannerGrid& grid,
                                                  const Vec2& start_m, const Vec2& goal_m);

}  // namespace vb::terrain
