#include "vb/terrain/grid_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "vb/engine/error.h"
#include "vb/terrain/obstacle_shape.h"

namespace vb::terrain {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
// Rock collision box side at scale 1 (RockBoxSize in terrain_physics.h), which sets the footprint.
constexpr double kRockSideM = 4.4;
// Planner inflation at world scale 1: 4 m, the original's int(4 * sf) cells at 1 m cells.
constexpr double kInflationM = 4.0;

// Octile distance: the exact cost of an obstacle-free 8-connected path with diagonal cost
// sqrt(2), so the heuristic is admissible and consistent and A* returns an optimal path.
inline double Octile(int dr, int dc) {
  dr = std::abs(dr);
  dc = std::abs(dc);
  const int lo = std::min(dr, dc);
  const int hi = std::max(dr, dc);
  return (hi - lo) + kSqrt2 * lo;
}

// The 8 neighbour offsets, in the order that breaks ties.
constexpr int kDr[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
constexpr int kDc[8] = {-1, 0, 1, -1, 1, -1, 0, 1};

// Calls visit(neighbour_index, step_cost) for each in-grid, unoccupied 8-neighbour of cell
// `index`, in kDr/kDc order (diagonal steps cost sqrt(2)).
template <typename Visit>
void ForEachFreeNeighbour(const OccupancyGrid& grid, int index, Visit&& visit) {
  const int r = index / grid.cols;
  const int c = index % grid.cols;
  for (int k = 0; k < 8; ++k) {
    const int nr = r + kDr[k];
    const int nc = c + kDc[k];
    if (nr < 0 || nr >= grid.rows || nc < 0 || nc >= grid.cols) continue;
    if (grid.Occupied(nr, nc)) continue;
    visit(nr * grid.cols + nc, (kDr[k] != 0 && kDc[k] != 0) ? kSqrt2 : 1.0);
  }
}

struct OpenEntry {
  double f;
  double h;
  int index;
};

// std::priority_queue pops the largest element; "larger" here means worse, so the best entry
// (lowest f, then lowest h, then lowest row-major index) comes out first.
struct WorseThan {
  bool operator()(const OpenEntry& a, const OpenEntry& b) const {
    if (a.f != b.f) return a.f > b.f;
    if (a.h != b.h) return a.h > b.h;
    return a.index > b.index;
  }
};

void MarkSquare(OccupancyGrid* grid, const Cell& centre, int half) {
  const int r0 = std::max(centre.row - half, 0);
  const int r1 = std::min(centre.row + half, grid->rows - 1);
  const int c0 = std::max(centre.col - half, 0);
  const int c1 = std::min(centre.col + half, grid->cols - 1);
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) grid->occupied[static_cast<size_t>(r) * grid->cols + c] = 1;
  }
}

// The cells whose centres lie inside the outline (local polygon placed at `at`), and the cell
// nearest `at`, so that an obstacle narrower than a cell still blocks one.
void MarkOutline(OccupancyGrid* grid, const Vec2& at, const std::vector<Vec2>& local) {
  MarkSquare(grid, grid->CellOf(at), 0);
  std::vector<Vec2> outline = local;
  Vec2 lo = at, hi = at;
  for (Vec2& p : outline) {
    p += at;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double x0 = -0.5 * grid->size_x_m, y0 = 0.5 * grid->size_y_m;
  const int c0 = std::max(0, static_cast<int>(std::ceil((lo.x() - x0) / grid->cell_m - 1e-9)));
  const int c1 = std::min(grid->cols - 1, static_cast<int>(std::floor((hi.x() - x0) / grid->cell_m + 1e-9)));
  const int r0 = std::max(0, static_cast<int>(std::ceil((y0 - hi.y()) / grid->cell_m - 1e-9)));
  const int r1 = std::min(grid->rows - 1, static_cast<int>(std::floor((y0 - lo.y()) / grid->cell_m + 1e-9)));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      // a relative tolerance keeps a scaled world's footprint equal to the unscaled one
      if (InsideConvexPolygon(outline, grid->CenterOf({r, c}), 1e-9 * grid->cell_m)) {
        grid->occupied[static_cast<size_t>(r) * grid->cols + c] = 1;
      }
    }
  }
}

}  // namespace

Cell OccupancyGrid::CellOf(const Vec2& p_m) const {
  // nearest cell centre; floor(v + 0.5) rounds halves the same way on every platform
  const int c = static_cast<int>(std::floor((p_m.x() + 0.5 * size_x_m) / cell_m + 0.5));
  const int r = static_cast<int>(std::floor((0.5 * size_y_m - p_m.y()) / cell_m + 0.5));
  return {std::min(std::max(r, 0), rows - 1), std::min(std::max(c, 0), cols - 1)};
}

Vec2 OccupancyGrid::CenterOf(const Cell& cell) const {
  return Vec2(-0.5 * size_x_m + cell.col * cell_m, 0.5 * size_y_m - cell.row * cell_m);
}

OccupancyGrid RasterizeObstacles(const TaskSpec& task) {
  VB_DEMAND(task.heights.rows >= 2 && task.heights.cols >= 2);
  OccupancyGrid grid;
  grid.rows = task.heights.rows;
  grid.cols = task.heights.cols;
  grid.cell_m = task.size_x_m / (task.heights.cols - 1);
  grid.size_x_m = task.size_x_m;
  grid.size_y_m = task.size_y_m;
  grid.occupied.assign(static_cast<size_t>(grid.rows) * grid.cols, 0);
  if (task.rock_shape.kind == ObstacleShapeKind::kBox) {
    for (const RockSpec& rock : task.rocks) {
      // side in cells truncated as the original (3, 4, 5 at 1 m); the square [c - w/2, c + w/2]
      // is then 3, 5, 5 cells wide
      // (the tiny epsilon keeps a scaled world's footprint equal to the unscaled one when
      // scale * 4.4 / cell_m is an integer up to rounding)
      const int w = static_cast<int>(kRockSideM * rock.scale * task.scale / grid.cell_m + 1e-9);
      MarkSquare(&grid, grid.CellOf(Vec2(rock.x_m, rock.y_m)), w / 2);
    }
  } else {
    for (const RockSpec& rock : task.rocks) {
      MarkOutline(&grid, Vec2(rock.x_m, rock.y_m), Outline(RockShapePoints(task, rock)));
    }
  }
  if (task.tree_shape.kind == ObstacleShapeKind::kBox) {
    for (const TreeSpec& tree : task.trees) {
      MarkSquare(&grid, grid.CellOf(Vec2(tree.x_m, tree.y_m)), 0);
    }
  } else {
    const std::vector<Vec2> outline = Outline(TreeShapePoints(task));
    for (const TreeSpec& tree : task.trees) MarkOutline(&grid, Vec2(tree.x_m, tree.y_m), outline);
  }
  return grid;
}

int PlannerInflationCells(const TaskSpec& task) {
  VB_DEMAND(task.heights.cols >= 2);
  const double cell_m = task.size_x_m / (task.heights.cols - 1);
  return static_cast<int>(std::floor(kInflationM * task.scale / cell_m + 1e-9));
}

OccupancyGrid Inflate(const OccupancyGrid& grid, int radius_cells) {
  VB_DEMAND(radius_cells >= 0);
  OccupancyGrid out = grid;
  if (radius_cells == 0) return out;
  // a square structuring element is separable: dilate along rows, then along columns
  std::vector<uint8_t> rows_pass(grid.occupied.size(), 0);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      if (!grid.Occupied(r, c)) continue;
      const int c0 = std::max(c - radius_cells, 0);
      const int c1 = std::min(c + radius_cells, grid.cols - 1);
      for (int k = c0; k <= c1; ++k) rows_pass[static_cast<size_t>(r) * grid.cols + k] = 1;
    }
  }
  std::fill(out.occupied.begin(), out.occupied.end(), 0);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      if (!rows_pass[static_cast<size_t>(r) * grid.cols + c]) continue;
      const int r0 = std::max(r - radius_cells, 0);
      const int r1 = std::min(r + radius_cells, grid.rows - 1);
      for (int k = r0; k <= r1; ++k) out.occupied[static_cast<size_t>(k) * grid.cols + c] = 1;
    }
  }
  return out;
}

std::optional<std::vector<Cell>> AStar(const OccupancyGrid& grid, const Cell& start,
                                       const Cell& goal) {
  VB_DEMAND(start.row >= 0 && start.row < grid.rows && start.col >= 0 && start.col < grid.cols);
  VB_DEMAND(goal.row >= 0 && goal.row < grid.rows && goal.col >= 0 && goal.col < grid.cols);
  if (start == goal) return std::vector<Cell>{start};
  // the goal must be free (as the original): a path ending inside an obstacle is no path
  if (grid.Occupied(goal.row, goal.col)) return std::nullopt;

  const int n = grid.rows * grid.cols;
  const int start_index = start.row * grid.cols + start.col;
  const int goal_index = goal.row * grid.cols + goal.col;
  std::vector<double> g(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  std::vector<int> parent(static_cast<size_t>(n), -1);
  std::vector<uint8_t> closed(static_cast<size_t>(n), 0);
  std::priority_queue<OpenEntry, std::vector<OpenEntry>, WorseThan> open;

  const double h_start = Octile(goal.row - start.row, goal.col - start.col);
  g[start_index] = 0.0;
  open.push({h_start, h_start, start_index});

  while (!open.empty()) {
    const OpenEntry top = open.top();
    open.pop();
    // lazy deletion: skip entries superseded by a cheaper push of the same cell
    if (closed[top.index]) continue;
    closed[top.index] = 1;
    if (top.index == goal_index) break;
    ForEachFreeNeighbour(grid, top.index, [&](int ni, double step) {
      if (closed[ni]) return;
      const double ng = g[top.index] + step;
      if (ng < g[ni]) {
        g[ni] = ng;
        parent[ni] = top.index;
        const double h = Octile(goal.row - ni / grid.cols, goal.col - ni % grid.cols);
        open.push({ng + h, h, ni});
      }
    });
  }
  if (!closed[goal_index]) return std::nullopt;

  std::vector<Cell> path;
  for (int i = goal_index; i != -1; i = parent[i]) path.push_back({i / grid.cols, i % grid.cols});
  std::reverse(path.begin(), path.end());
  return path;
}

GoalDistanceField::GoalDistanceField(const OccupancyGrid& grid, const Cell& goal)
    : grid_(&grid), goal_(goal) {
  VB_DEMAND(goal.row >= 0 && goal.row < grid.rows && goal.col >= 0 && goal.col < grid.cols);
  const int n = grid.rows * grid.cols;
  cost_.assign(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  if (grid.Occupied(goal.row, goal.col)) return;  // no path ends inside an obstacle
  // Dijkstra from the goal over free cells; costs are symmetric, so this is the cost *to* it.
  std::priority_queue<OpenEntry, std::vector<OpenEntry>, WorseThan> open;
  const int goal_index = goal.row * grid.cols + goal.col;
  cost_[goal_index] = 0.0;
  open.push({0.0, 0.0, goal_index});
  while (!open.empty()) {
    const OpenEntry top = open.top();
    open.pop();
    if (top.f > cost_[top.index]) continue;  // superseded entry
    ForEachFreeNeighbour(grid, top.index, [&](int ni, double step) {
      const double nd = top.f + step;
      if (nd < cost_[ni]) {
        cost_[ni] = nd;
        open.push({nd, 0.0, ni});
      }
    });
  }
}

double GoalDistanceField::CostToGoal(const Cell& cell) const {
  return cost_[static_cast<size_t>(cell.row) * grid_->cols + cell.col];
}

std::optional<std::vector<Cell>> GoalDistanceField::PathFrom(const Cell& start) const {
  const OccupancyGrid& grid = *grid_;
  VB_DEMAND(start.row >= 0 && start.row < grid.rows && start.col >= 0 && start.col < grid.cols);
  if (start == goal_) return std::vector<Cell>{start};
  if (grid.Occupied(goal_.row, goal_.col)) return std::nullopt;
  std::vector<Cell> path{start};
  Cell at = start;
  // Steepest descent: each step goes to the free neighbour with the least step + cost-to-goal
  // (first in neighbour order on ties). From a free cell that is exactly its own cost, so the
  // path is optimal and the cost falls strictly; the start alone may be occupied (as in AStar).
  while (!(at == goal_)) {
    double best = std::numeric_limits<double>::infinity();
    Cell next = at;
    for (int k = 0; k < 8; ++k) {
      const Cell nb{at.row + kDr[k], at.col + kDc[k]};
      if (nb.row < 0 || nb.row >= grid.rows || nb.col < 0 || nb.col >= grid.cols) continue;
      const double d = ((kDr[k] != 0 && kDc[k] != 0) ? kSqrt2 : 1.0) + CostToGoal(nb);
      if (d < best) {
        best = d;
        next = nb;
      }
    }
    if (!std::isfinite(best)) return std::nullopt;  // cut off from the goal
    path.push_back(next);
    at = next;
  }
  return path;
}

std::optional<std::vector<Vec2>> GoalDistanceField::PathFrom(const Vec2& start_m) const {
  const auto cells = PathFrom(grid_->CellOf(start_m));
  if (!cells) return std::nullopt;
  std::vector<Vec2> path_m;
  path_m.reserve(cells->size());
  for (const Cell& cell : *cells) path_m.push_back(grid_->CenterOf(cell));
  return path_m;
}

std::optional<std::vector<Vec2>> PlanPath(const OccupancyGrid& inflated, const Vec2& start_m,
                                          const Vec2& goal_m) {
  const auto cells = AStar(inflated, inflated.CellOf(start_m), inflated.CellOf(goal_m));
  if (!cells) return std::nullopt;
  std::vector<Vec2> path_m;
  path_m.reserve(cells->size());
  for (const Cell& cell : *cells) path_m.push_back(inflated.CenterOf(cell));
  return path_m;
}

Vec2 LookAheadPoint(const std::vector<Vec2>& path_m, const Vec2& position_m, double yaw_rad,
                    double lookahead_m, size_t* index) {
  VB_DEMAND(!path_m.empty());
  const Vec2 heading(std::cos(yaw_rad), std::sin(yaw_rad));
  for (size_t i = *index; i < path_m.size(); ++i) {
    const Vec2 d = path_m[i] - position_m;
    // bearing within +-90 deg of the heading <=> non-negative projection on the heading
    if (d.norm() >= lookahead_m && d.dot(heading) >= 0.0) {
      *index = i;
      return path_m[i];
    }
  }
  *index = path_m.size() - 1;
  return path_m.back();
}

}  // namespace vb::terrain
