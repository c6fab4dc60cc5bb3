#include "vb/terrain/terrain_physics.h"

#include <algorithm>
#include <vector>

namespace vb::terrain {
namespace {

// Only the chassis touches the terrain mesh (wheel-ground contact is vb's own model), so one
// representative coefficient suffices here; rocks and trees use the same value.
constexpr double kMeshFriction = 0.8;
constexpr double kObstacleFriction = 0.8;

}  // namespace

double ObstacleBaseHeight(const Terrain& terrain, double x_m, double y_m, double footprint_m) {
  constexpr int kSamples = 9;  // per side; at 5.3 m (largest rock) a sample every 0.66 m
  double lowest = terrain.Height(x_m, y_m);
  for (int i = 0; i < kSamples; ++i) {
    for (int j = 0; j < kSamples; ++j) {
      const double dx = footprint_m * (static_cast<double>(i) / (kSamples - 1) - 0.5);
      const double dy = footprint_m * (static_cast<double>(j) / (kSamples - 1) - 0.5);
      lowest = std::min(lowest, terrain.Height(x_m + dx, y_m + dy));
    }
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
