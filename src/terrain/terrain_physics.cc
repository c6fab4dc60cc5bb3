#include "vb/terrain/terrain_physics.h"

#include <vector>

namespace vb::terrain {
namespace {

// Only the chassis touches the terrain mesh (wheel-ground contact is vb's own model), so one
// representative coefficient suffices here; rocks and trees use the same value.
constexpr double kMeshFriction = 0.8;
constexpr double kObstacleFriction = 0.8;

}  // namespace

void AddTerrainToPhysics(const TaskSpec& task, const Terrain& terrain,
                         engine::PhysicsWorld* world) {
  std::vector<Vec3> vertices_W;
  std::vector<int> triangles;
  terrain.Mesh(&vertices_W, &triangles);
  world->AddTerrainMesh(vertices_W, triangles, kMeshFriction);

  // rocks: box centred on the surface at (x, y), half of it below ground, as the original
  for (size_t i = 0; i < task.rocks.size(); ++i) {
    const RockSpec& rock = task.rocks[i];
    Pose pose_W;
    pose_W.position = Vec3(rock.x_m, rock.y_m, terrain.Height(rock.x_m, rock.y_m));
    world->AddStaticBox(pose_W, 0.5 * RockBoxSize(rock.scale), kObstacleFriction,
                        static_cast<int>(i));
  }
  // trees: box standing on the surface (its bottom face at the terrain height)
  const Vec3 tree_half_m = 0.5 * TreeBoxSize();
  for (size_t j = 0; j < task.trees.size(); ++j) {
    const TreeSpec& tree = task.trees[j];
    Pose pose_W;
    pose_W.position =
        Vec3(tree.x_m, tree.y_m, terrain.Height(tree.x_m, tree.y_m) + tree_half_m.z());
    world->AddStaticBox(pose_W, tree_half_m, kObstacleFriction,
                        kTreeTagOffset + static_cast<int>(j));
  }
}

}  // namespace vb::terrain
