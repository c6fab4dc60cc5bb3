#include "vb/terrain/terrain_physics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "vb/engine/error.h"
#include "vb/terrain/obstacle_shape.h"

namespace vb::terrain {
double ObstacleBaseHeight(const Terrain& terrain, double x_m, double y_m, double footprint_m) {
  // The surface is piecewise linear, so its minimum over the square lies at a grid vertex inside
  // the square or on the square's boundary: take every inside vertex exactly and the boundary at
  // 1/32 of the grid spacing (a few mm at the benchmark's slopes).
  const double half = 0.5 * footprint_m;
  const double dx = terrain.spacing_x_m();
  const double dy = terrain.spacing_y_m();
  const double west_m = -0.5 * terrain.size_x_m();
  const double north_m = 0.5 * terrain.size_y_m();
  const HeightGrid& g = terrain.grid();
  const int c0 = std::max(0, static_cast<int>(std::ceil((x_m - half - west_m) / dx)));
  const int c1 = std::min(g.cols - 1, static_cast<int>(std::floor((x_m + half - west_m) / dx)));
  const int r0 = std::max(0, static_cast<int>(std::ceil((north_m - y_m - half) / dy)));
  const int r1 = std::min(g.rows - 1, static_cast<int>(std::floor((north_m - y_m + half) / dy)));
  double lowest = terrain.Height(x_m, y_m);
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) lowest = std::min(lowest, g.At(r, c));
  }
  const double step_m = std::min(dx, dy) / 32.0;
  const int steps = std::max(1, static_cast<int>(std::ceil(footprint_m / step_m)));
  for (int k = 0; k <= steps; ++k) {
    const double t = -half + footprint_m * k / steps;
    lowest = std::min({lowest, terrain.Height(x_m + t, y_m - half),
                       terrain.Height(x_m + t, y_m + half), terrain.Height(x_m - half, y_m + t),
                       terrain.Height(x_m + half, y_m + t)});
  }
  return lowest;
}

double ObstacleBaseHeight(const Terrain& terrain, const std::vector<Vec2>& footprint_W) {
  VB_DEMAND(footprint_W.size() >= 3);
  const double dx = terrain.spacing_x_m();
  const double dy = terrain.spacing_y_m();
  const double west_m = -0.5 * terrain.size_x_m();
  const double north_m = 0.5 * terrain.size_y_m();
  const HeightGrid& g = terrain.grid();
  Vec2 lo = footprint_W[0], hi = footprint_W[0];
  for (const Vec2& p : footprint_W) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  double lowest = terrain.Height(footprint_W[0].x(), footprint_W[0].y());
  const int c0 = std::max(0, static_cast<int>(std::ceil((lo.x() - west_m) / dx)));
  const int c1 = std::min(g.cols - 1, static_cast<int>(std::floor((hi.x() - west_m) / dx)));
  const int r0 = std::max(0, static_cast<int>(std::ceil((north_m - hi.y()) / dy)));
  const int r1 = std::min(g.rows - 1, static_cast<int>(std::floor((north_m - lo.y()) / dy)));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (InsideConvexPolygon(footprint_W, Vec2(west_m + c * dx, north_m - r * dy), 1e-9)) {
        lowest = std::min(lowest, g.At(r, c));
      }
    }
  }
  const double step_m = std::min(dx, dy) / 32.0;
  for (size_t i = 0; i < footprint_W.size(); ++i) {
    const Vec2& a = footprint_W[i];
    const Vec2& b = footprint_W[(i + 1) % footprint_W.size()];
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_m)));
    for (int k = 0; k < steps; ++k) {
      const Vec2 p = a + (b - a) * (static_cast<double>(k) / steps);
      lowest = std::min(lowest, terrain.Height(p.x(), p.y()));
    }
  }
  return lowest;
}

}  // namespace vb::terrain
