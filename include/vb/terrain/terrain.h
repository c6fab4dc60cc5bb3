// Terrain: the one query every module uses for the ground (height, normal, material under a
// point). The surface is the triangulated height grid, each cell split along its SW-NE diagonal
// (as Chrono's heightmap mesh), and exactly the same triangles are handed to the physics
// adapter, so what the wheels feel and what the chassis collides with agree.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "vb/engine/types.h"
#include "vb/terrain/surface_class.h"
#include "vb/terrain/task.h"

namespace vb::terrain {

// What kinds of ground a region holds: only rigid patches, only deformable ones, or both (a
// soil/rigid seam runs through it).
enum class GroundMix { kRigid, kDeformable, kMixed };

struct SurfacePoint {
  double height_m = 0.0;
  Vec3 normal_W = Vec3::UnitZ();   // unit, pointing up
  SurfaceClass surface = SurfaceClass::kDirt;
  double friction = 0.8;           // Coulomb coefficient of the patch (rigid classes)
};

class Terrain {
 public:
  // Builds the query structure from a loaded task (heights, patches). Rocks and trees are not
  // part of the surface; see AddTerrainToPhysics.
  explicit Terrain(const TaskSpec& task);

  // Height of the surface at (x, y); points outside the grid are clamped to the border.
  double Height(double x_m, double y_m) const;
  // Upward unit normal of the triangle under (x, y).
  Vec3 Normal(double x_m, double y_m) const;
  // Height, normal and material in one call (the hot path for wheel contact).
  SurfacePoint Query(double x_m, double y_m) const;
  // Patch indices under (x, y), clamped.
  void PatchIndex(double x_m, double y_m, int* row, int* col) const;
  // Material of the patch under (x, y) (the SurfacePoint default without semantics).
  SurfaceClass SurfaceAt(double x_m, double y_m) const;
  // The kinds of ground of the patches overlapping the axis-aligned square of half size
  // `half_m` around (x, y): which contact model(s) a wheel there needs. A few patches at most.
  GroundMix MixAround(double x_m, double y_m, double half_m) const;

  // The triangle mesh of the surface (vertices in world frame, CCW triangles seen from above).
  void Mesh(std::vector<Vec3>* vertices_W, std::vector<int>* triangles) const;

  double size_x_m() const { return size_x_m_; }
  double size_y_m() const { return size_y_m_; }
  double spacing_x_m() const { return dx_; }
  double spacing_y_m() const { return dy_; }
  const HeightGrid& grid() const { return grid_; }
  const PatchGrid& patches() const { return patches_; }

 private:
  HeightGrid grid_;
  PatchGrid patches_;
  double size_x_m_ = 0.0;
  double size_y_m_ = 0.0;
  double half_x_m_ = 0.0;   // 0.5 * size (exact)
  double half_y_m_ = 0.0;
  double dx_ = 1.0;
  double dy_ = 1.0;
};

namespace detail {

// Position of (x, y) in grid coordinates: the cell (row r, col c) whose NW vertex is (r, c), and
// the fractional offsets fu (east, along columns) and fv (south, along rows), both in [0, 1].
struct CellCoords {
  int r;
  int c;
  double fu;
  double fv;
};

inline CellCoords Locate(const HeightGrid& g, double half_x, double half_y, double dx, double dy,
                         double x_m, double y_m) {
  // clamp to the grid first, so points outside read the border (continuous extension)
  double u = std::min(std::max((x_m + half_x) / dx, 0.0), static_cast<double>(g.cols - 1));
  double v = std::min(std::max((half_y - y_m) / dy, 0.0), static_cast<double>(g.rows - 1));
  // NaN passes both clamps, and casting it to int is undefined (it read out of bounds): a
  // non-finite query reads the north-west vertex instead; the caller's state check reports it.
  if (std::isnan(u)) u = 0.0;
  if (std::isnan(v)) v = 0.0;
  // the last row/column belongs to the cell before it (fu or fv = 1 there)
  const int c = std::min(static_cast<int>(u), g.cols - 2);
  const int r = std::min(static_cast<int>(v), g.rows - 2);
  return {r, c, u - c, v - r};
}

// Height and grid-coordinate gradient of the triangle containing the point. The SW-NE diagonal
// is fu + fv = 1: below it (fu + fv <= 1) lies triangle (SW, NE, NW), above it (SW, SE, NE).
// Each branch is the exact plane through its three vertices, so both agree on the diagonal.
inline double PlaneHeight(const HeightGrid& g, const CellCoords& p, double* dh_du, double* dh_dv) {
  const double* row0 = &g.heights_m[static_cast<size_t>(p.r) * g.cols + p.c];
  const double* row1 = row0 + g.cols;
  const double h_nw = row0[0];
  const double h_ne = row0[1];
  const double h_sw = row1[0];
  const double h_se = row1[1];
  if (p.fu + p.fv <= 1.0) {
    *dh_du = h_ne - h_nw;
    *dh_dv = h_sw - h_nw;
    return h_nw + p.fu * (*dh_du) + p.fv * (*dh_dv);
  }
  *dh_du = h_se - h_sw;
  *dh_dv = h_se - h_ne;
  return h_se - (1.0 - p.fu) * (*dh_du) - (1.0 - p.fv) * (*dh_dv);
}

}  // namespace detail

// Inline: the wheels' and the body envelope's contacts ask for ~130 heights per step.
inline double Terrain::Height(double x_m, double y_m) const {
  double dh_du, dh_dv;
  return detail::PlaneHeight(grid_, detail::Locate(grid_, half_x_m_, half_y_m_, dx_, dy_, x_m, y_m),
                             &dh_du, &dh_dv);
}

}  // namespace vb::terrain
