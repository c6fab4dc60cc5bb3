#include "vb/terrain/terrain_physics.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vb::terrain {
namespace {

// Only the chassis touches the terrain mesh (wheel-ground contact is vb's own model), so one
// representative coefficient suffices here; rocks and trees use the same value.
constexpr double kMeshFriction = 0.8;
constexpr double kObstacleFriction = 0.8;

}  // namespace

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

void AddTerrainToPhysics(const TaskSpec& task, const Terrain& terrain,
                         engine::PhysicsWorld* world) {
  std::vector<Vec3> vertices_W;
  std::vector<int> triangles;
  terrain.Mesh(&vertices_W, &triangles);
  world->AddTerrainMesh(vertices_W, triangles, kMeshFriction);

  // rocks and trees rest on the ground: bottom face at the lowest terrain point of the footprint
  // (the original centred rocks on a height read at the wrong place, so they floated or sank by
  // up to ~1 m, reference_verti_bench.md §2.8)
  for (size_t i = 0; i < task.rocks.size(); ++i) {
    const RockSpec& rock = task.rocks[i];
    const Vec3 half_m = 0.5 * RockBoxSize(task, rock);
    Pose pose_W;
    pose_W.position =
        Vec3(rock.x_m, rock.y_m,
             ObstacleBaseHeight(terrain, rock.x_m, rock.y_m, 2.0 * half_m.x()) + half_m.z());
    world->AddStaticBox(pose_W, half_m, kObstacleFriction, static_cast<int>(i));
  }
  const Vec3 tree_half_m = 0.5 * TreeBoxSize(task);
  for (size_t j = 0; j < task.trees.size(); ++j) {
    const TreeSpec& tree = task.trees[j];
    Pose pose_W;
    pose_W.position =
        Vec3(tree.x_m, tree.y_m,
             ObstacleBaseHeight(terrain, tree.x_m, tree.y_m, 2.0 * tree_half_m.x()) +
                 tree_half_m.z());
    world->AddStaticBox(pose_W, tree_half_m, kObstacleFriction,
                        kTreeTagOffset + static_cast<int>(j));
  }
}

}  // namespace vb::terrain
