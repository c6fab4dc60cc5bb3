#include "vb/terrain/gt_maps.h"

#include <cmath>

#include "vb/engine/error.h"

namespace vb::terrain {

GroundTruthMaps::GroundTruthMaps(const TaskSpec& task, int inflation_cells)
    : terrain_(task),
      occupancy_(Inflate(RasterizeObstacles(task),
                         inflation_cells < 0 ? PlannerInflationCells(task) : inflation_cells)) {
  const HeightGrid& g = terrain_.grid();
  for (GridMap* m : {&elevation_, &semantics_, &occupancy_map_, &friction_}) {
    m->rows = g.rows;
    m->cols = g.cols;
    m->resolution_m = terrain_.spacing_x_m();
    m->values.resize(static_cast<size_t>(g.rows) * g.cols);
  }
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const size_t i = static_cast<size_t>(r) * g.cols + c;
      const Vec2 p(-0.5 * terrain_.size_x_m() + c * terrain_.spacing_x_m(),
                   0.5 * terrain_.size_y_m() - r * terrain_.spacing_y_m());
      elevation_.values[i] = g.At(r, c);
      semantics_.values[i] = Sample(MapLayer::kSemantics, p);
      occupancy_map_.values[i] = occupancy_.Occupied(r, c) ? 1.0 : 0.0;
      friction_.values[i] = Sample(MapLayer::kFriction, p);
    }
  }
}

const GridMap& GroundTruthMaps::World(MapLayer layer) const {
  switch (layer) {
    case MapLayer::kElevation: return elevation_;
    case MapLayer::kSemantics: return semantics_;
    case MapLayer::kOccupancy: return occupancy_map_;
    case MapLayer::kFriction: return friction_;
  }
  return elevation_;
}

GridMap GroundTruthMaps::Resampled(MapLayer layer, double resolution_m) const {
  VB_DEMAND(resolution_m > 0.0);
  GridMap out;
  out.resolution_m = resolution_m;
  out.cols = static_cast<int>(std::floor(terrain_.size_x_m() / resolution_m + 1e-9)) + 1;
  out.rows = static_cast<int>(std::floor(terrain_.size_y_m() / resolution_m + 1e-9)) + 1;
  out.values.resize(static_cast<size_t>(out.rows) * out.cols);
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) {
      const Vec2 p(-0.5 * terrain_.size_x_m() + c * resolution_m,
                   0.5 * terrain_.size_y_m() - r * resolution_m);
      out.values[static_cast<size_t>(r) * out.cols + c] = Sample(layer, p);
    }
  }
  return out;
}

double GroundTruthMaps::Sample(MapLayer layer, const Vec2& p_m) const {
  switch (layer) {
    case MapLayer::kElevation:
      return terrain_.Height(p_m.x(), p_m.y());
    case MapLayer::kSemantics: {
      if (terrain_.patches().classes.empty()) return static_cast<double>(SurfaceClass::kDirt);
      int r = 0, c = 0;
      terrain_.PatchIndex(p_m.x(), p_m.y(), &r, &c);
      return static_cast<double>(terrain_.patches().ClassAt(r, c));
    }
    case MapLayer::kOccupancy: {
      // outside the world (beyond half a cell past the border vertices) counts as blocked
      const double half = 0.5 * occupancy_.cell_m;
      if (std::abs(p_m.x()) > 0.5 * occupancy_.size_x_m + half ||
          std::abs(p_m.y()) > 0.5 * occupancy_.size_y_m + half) {
        return 1.0;
      }
      const Cell cell = occupancy_.CellOf(p_m);
      return occupancy_.Occupied(cell.row, cell.col) ? 1.0 : 0.0;
    }
    case MapLayer::kFriction: {
      if (terrain_.patches().classes.empty()) return SurfacePoint().friction;
      int r = 0, c = 0;
      terrain_.PatchIndex(p_m.x(), p_m.y(), &r, &c);
      return IsDeformable(terrain_.patches().ClassAt(r, c)) ? 0.0
                                                            : terrain_.patches().FrictionAt(r, c);
    }
  }
  return 0.0;
}

GridMap GroundTruthMaps::Crop(MapLayer layer, const Vec2& position_m, double yaw_rad,
                              int size_cells, double resolution_m) const {
  GridMap out;
  CropInto(layer, position_m, yaw_rad, size_cells, resolution_m, &out);
  return out;
}

void GroundTruthMaps::CropInto(MapLayer layer, const Vec2& position_m, double yaw_rad,
                               int size_cells, double resolution_m, GridMap* out) const {
  VB_DEMAND(size_cells > 0 && resolution_m > 0.0);
  out->rows = size_cells;
  out->cols = size_cells;
  out->resolution_m = resolution_m;
  out->values.resize(static_cast<size_t>(size_cells) * size_cells);
  const double centre = 0.5 * (size_cells - 1);
  const double cos_yaw = std::cos(yaw_rad);
  const double sin_yaw = std::sin(yaw_rad);
  for (int i = 0; i < size_cells; ++i) {
    for (int j = 0; j < size_cells; ++j) {
      const double forward = (centre - i) * resolution_m;
      const double left = (centre - j) * resolution_m;
      const Vec2 p(position_m.x() + cos_yaw * forward - sin_yaw * left,
                   position_m.y() + sin_yaw * forward + cos_yaw * left);
      out->values[static_cast<size_t>(i) * size_cells + j] = Sample(layer, p);
    }
  }
}

}  // namespace vb::terrain
