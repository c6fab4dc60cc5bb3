// Ground-truth maps for mobility systems (reference_verti_bench.md §7): whole-world elevation,
// semantics and obstacle-occupancy grids, and egocentric crops of them around a vehicle pose, as
// the original's baselines read them (EH 64 px crops, MPPI 28 px, RL 64 px at 0.1 m).
//
// Conventions (docs/generator.md "Ground-truth maps"):
//  - World grids are aligned with the height grid: cell (r, c) is centred on height vertex (r, c),
//    x = -size_x/2 + c * res, y = +size_y/2 - r * res; row 0 is north, column 0 west (as images).
//  - Egocentric crops are size x size cells of side resolution_m, centred on the vehicle: row 0 is
//    the farthest ahead, the last row the farthest behind; column 0 is the vehicle's far LEFT,
//    the last column its far right (the original's crop after its transpose). Cell (i, j) is at
//      forward = ((size-1)/2 - i) * res,  left = ((size-1)/2 - j) * res
//    in the vehicle frame (x forward, y left), rotated into the world by the yaw (rad, CCW from
//    +x east). So with yaw 0 the crop is the world grid turned 90 deg clockwise (north on the
//    left).
//  - Sampling: elevation on the triangulated surface (Terrain::Height, exact for the physics);
//    semantics and occupancy from the cell/patch containing the point. Outside the world:
//    elevation and semantics clamp to the border, occupancy is 1 (outside is not traversable).
#pragma once

#include <cstdint>
#include <vector>

#include "vb/engine/types.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/task.h"
#include "vb/terrain/terrain.h"

namespace vb::terrain {

// A 2-D grid of values, row-major.
struct GridMap {
  int rows = 0;
  int cols = 0;
  double resolution_m = 1.0;
  std::vector<double> values;
  double At(int r, int c) const { return values[static_cast<size_t>(r) * cols + c]; }
};

enum class MapLayer {
  kElevation,  // terrain height (m)
  kSemantics,  // surface class id (SurfaceClass value, 0..9)
  kOccupancy,  // 1 = obstacle (inflated as configured), 0 = free
  kFriction,   // Coulomb friction of the rigid patch under the point; 0 on mud, sand, snow
};

class GroundTruthMaps {
 public:
  // inflation_cells < 0: the planners' inflation (PlannerInflationCells); 0: bare footprints.
  explicit GroundTruthMaps(const TaskSpec& task, int inflation_cells = 0);

  // Whole-world grid of a layer (height-grid resolution).
  const GridMap& World(MapLayer layer) const;

  // Whole-world grid of a layer at another resolution (e.g. 0.1 m, like the original's 1291 x 1291
  // high-res height map): cell (r, c) at x = -size_x/2 + c * res, y = size_y/2 - r * res, with
  // floor(size / res + 1e-9) + 1 cells per axis.
  GridMap Resampled(MapLayer layer, double resolution_m) const;

  // Value of a layer at a world point (the sampling rules above).
  double Sample(MapLayer layer, const Vec2& p_m) const;

  // Egocentric crop around position_m facing yaw_rad (conventions above).
  GridMap Crop(MapLayer layer, const Vec2& position_m, double yaw_rad, int size_cells,
               double resolution_m) const;
  // The same into *out, reusing its storage (no allocation once it has the size).
  void CropInto(MapLayer layer, const Vec2& position_m, double yaw_rad, int size_cells,
                double resolution_m, GridMap* out) const;

  const Terrain& terrain() const { return terrain_; }

 private:
  Terrain terrain_;
  OccupancyGrid occupancy_;
  GridMap elevation_;
  GridMap semantics_;
  GridMap occupancy_map_;
  GridMap friction_;
};

}  // namespace vb::terrain
