// Terrain: the one query every module uses for the ground (height, normal, material under a
// point). The surface is the triangulated height grid, each cell split along its SW-NE diagonal
// (as Chrono's heightmap mesh), and exactly the same triangles are handed to the physics
// adapter, so what the wheels feel and what the chassis collides with agree.
#pragma once

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
  double dx_ = 1.0;
  double dy_ = 1.0;
};

}  // namespace vb::terrain
