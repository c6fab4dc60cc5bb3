#include "vb/terrain/terrain_physics.h"

#include <algorithm>
#include <cmath>
#include <vector>

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

}  // namespace vb::terrain
