#include "vb/terrain/original_planner.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>

#include "vb/engine/error.h"

namespace vb::terrain {
namespace {

constexpr double kRockSideM = 4.4;     // the original's rock box side at rock scale 1
constexpr double kInflationM = 4.0;    // its int(4 * scale) pixels
constexpr int kBezierSamples = 100;

// numpy.round: half to even (std::nearbyint in the default rounding mode).
int RoundHalfEven(double v) { return static_cast<int>(std::nearbyint(v)); }

// scipy.special.comb(n, k) (exact=False) as scipy computes it: symmetric k, the product formula
// below k = 20, the beta function above (so comb(n, 0) = comb(n, n) = 1 exactly).
double ScipyBinom(int n, int k) {
  if (k > n / 2.0) k = n - k;
  if (k < 20) {
    double num = 1.0, den = 1.0;
    for (int i = 1; i <= k; ++i) {
      num *= i + n - k;
      den *= i;
      if (std::abs(num) > 1e50) {
        num /= den;
        den = 1.0;
      }
    }
    return num / den;
  }
  const double a = 1.0 + n - k, b = 1.0 + k;
  return 1.0 / (n + 1.0) / std::exp(std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b));
}

}  // namespace

OriginalPlannerGrid MakeOriginalPlannerGrid(const TaskSpec& task) {
  VB_DEMAND(task.heights.rows >= 2 && task.heights.cols >= 2);
  OriginalPlannerGrid g;
  g.rows = task.heights.rows;
  g.cols = task.heights.cols;
  g.cell_m = task.size_x_m / (g.cols - 1);
  g.half_x_m = 0.5 * g.cols * g.cell_m;
  g.half_y_m = 0.5 * g.rows * g.cell_m;
  std::vector<uint8_t> marked(static_cast<size_t>(g.rows) * g.cols, 0);
  auto mark = [&](double x_m, double y_m, int side_px) {
    // transform_to_bmp, clipped into the image, then rounded (the original's obstacle map)
    const int c = RoundHalfEven(std::clamp((x_m + g.half_x_m) / g.cell_m, 0.0, g.cols - 1.0));
    const int r = RoundHalfEven(std::clamp((g.half_y_m - y_m) / g.cell_m, 0.0, g.rows - 1.0));
    const int half = side_px / 2;
    for (int rr = std::max(r - half, 0); rr <= std::min(r + half, g.rows - 1); ++rr) {
      for (int cc = std::max(c - half, 0); cc <= std::min(c + half, g.cols - 1); ++cc) {
        marked[static_cast<size_t>(rr) * g.cols + cc] = 1;
      }
    }
  };
  for (const RockSpec& rock : task.rocks) {
    mark(rock.x_m, rock.y_m, static_cast<int>(kRockSideM * rock.scale));
  }
  for (const TreeSpec& tree : task.trees) mark(tree.x_m, tree.y_m, 1);
  // scipy's binary_dilation with a (2r + 1)^2 square of ones, nothing beyond the border
  const int radius = static_cast<int>(kInflationM * task.scale);
  g.occupied.assign(marked.size(), 0);
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      if (!marked[static_cast<size_t>(r) * g.cols + c]) continue;
      for (int rr = std::max(r - radius, 0); rr <= std::min(r + radius, g.rows - 1); ++rr) {
        for (int cc = std::max(c - radius, 0); cc <= std::min(c + radius, g.cols - 1); ++cc) {
          g.occupied[static_cast<size_t>(rr) * g.cols + cc] = 1;
        }
      }
    }
  }
  return g;
}

void OriginalPlannerPixel(const OriginalPlannerGrid& grid, const Vec2& p_m, int* row, int* col) {
  // chrono_to_grid: int() truncates towards zero, then the clamp
  const int c = static_cast<int>((p_m.x() + grid.half_x_m) / grid.cell_m);
  const int r = static_cast<int>((grid.half_y_m - p_m.y()) / grid.cell_m);
  *row = std::min(std::max(r, 0), grid.rows - 1);
  *col = std::min(std::max(c, 0), grid.cols - 1);
}

std::optional<std::vector<std::pair<int, int>>> OriginalAStar(const OriginalPlannerGrid& grid,
                                                              int start_row, int start_col,
                                                              int goal_row, int goal_col) {
  const size_t n = static_cast<size_t>(grid.rows) * grid.cols;
  const double kUnset = std::numeric_limits<double>::infinity();
  std::vector<double> g(n, kUnset);
  std::vector<int> parent(n, -1);
  std::vector<uint8_t> closed(n, 0);
  auto index = [&](int r, int c) { return static_cast<size_t>(r) * grid.cols + c; };
  auto heuristic = [&](int r, int c) {  // ((dr)**2 + (dc)**2)**0.5
    const double dr = r - goal_row, dc = c - goal_col;
    return std::pow(dr * dr + dc * dc, 0.5);
  };
  using Entry = std::tuple<double, int, int>;  // Python's (f, (row, col)) order
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  open.emplace(0.0, start_row, start_col);
  g[index(start_row, start_col)] = 0.0;
  constexpr int kMoves[8][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  while (!open.empty()) {
    const auto [f, r, c] = open.top();
    open.pop();
    const size_t cur = index(r, c);
    if (closed[cur]) continue;
    closed[cur] = 1;
    if (r == goal_row && c == goal_col) {
      std::vector<std::pair<int, int>> path;
      for (int k = static_cast<int>(cur); k >= 0; k = parent[k]) {
        path.emplace_back(k / grid.cols, k % grid.cols);
        if (static_cast<size_t>(k) == index(start_row, start_col)) break;
      }
      std::reverse(path.begin(), path.end());
      return path;
    }
    for (const auto& m : kMoves) {
      const int rr = r + m[0], cc = c + m[1];
      if (rr < 0 || rr >= grid.rows || cc < 0 || cc >= grid.cols || grid.Occupied(rr, cc)) continue;
      const size_t nb = index(rr, cc);
      const double tentative = g[cur] + 1.0;
      if (tentative < g[nb]) {  // "not in g_costs" is g = infinity
        g[nb] = tentative;
        open.emplace(tentative + heuristic(rr, cc), rr, cc);
        parent[nb] = static_cast<int>(cur);
      }
    }
  }
  return std::nullopt;
}

std::vector<std::pair<double, double>> OriginalBezier(
    const std::vector<std::pair<int, int>>& control) {
  VB_DEMAND(control.size() >= 3);
  const int degree = static_cast<int>(control.size()) - 1;
  std::vector<double> binom(degree + 1);
  for (int i = 0; i <= degree; ++i) binom[i] = ScipyBinom(degree, i);
  std::vector<std::pair<double, double>> curve(kBezierSamples, {0.0, 0.0});
  const double step = 1.0 / (kBezierSamples - 1);  // numpy.linspace(0, 1, 100)
  for (int j = 0; j < kBezierSamples; ++j) {
    const double t = j == kBezierSamples - 1 ? 1.0 : j * step;
    double row = 0.0, col = 0.0;
    for (int i = 0; i <= degree; ++i) {
      // comb(n, i) * t**i * (1 - t)**(n - i); where the binomial overflows (past ~1030 cells) or
      // the powers underflow, the product in log space (the ends t = 0, 1 stay exact)
      const double p = std::pow(t, i) * std::pow(1.0 - t, degree - i);
      double w = binom[i] * p;
      const bool interior = t > 0.0 && t < 1.0;
      if (interior && (!std::isfinite(w) || p < 1e-290)) {  // overflow or underflow
        w = std::exp(std::lgamma(degree + 1.0) - std::lgamma(i + 1.0) -
                     std::lgamma(degree - i + 1.0) + i * std::log(t) +
                     (degree - i) * std::log1p(-t));
      }
      row += w * control[i].first;
      col += w * control[i].second;
    }
    curve[j] = {row, col};
  }
  return curve;
}

std::optional<std::vector<Vec2>> OriginalPlanPath(const OriginalPlannerGrid& grid,
                                                  const Vec2& start_m, const Vec2& goal_m) {
  int sr = 0, sc = 0, gr = 0, gc = 0;
  OriginalPlannerPixel(grid, start_m, &sr, &sc);
  OriginalPlannerPixel(grid, goal_m, &gr, &gc);
  std::optional<std::vector<std::pair<int, int>>> cells = OriginalAStar(grid, sr, sc, gr, gc);
  if (!cells) return std::nullopt;
  std::vector<std::pair<double, double>> points;
  if (cells->size() >= 3) {
    points = OriginalBezier(*cells);
  } else {
    for (const auto& [r, c] : *cells) points.emplace_back(r, c);
  }
  std::vector<Vec2> path;
  path.reserve(points.size());
  for (const auto& [r, c] : points) {  // transform_to_chrono of (col, row)
    path.emplace_back(c * grid.cell_m - grid.half_x_m, -(r * grid.cell_m - grid.half_y_m));
  }
  return path;
}

}  // namespace vb::terrain
