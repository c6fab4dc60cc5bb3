// Puts a task's static world into the physics adapter: the terrain mesh and one box per rock and
// tree (tags: rock i -> i, tree j -> 1000 + j).
#pragma once

#include "vb/engine/physics_world.h"
#include "vb/terrain/task.h"
#include "vb/terrain/terrain.h"

namespace vb::terrain {

constexpr int kTreeTagOffset = 1000;
// Rock box full size (m) at scale 1 and tree box full size (m), as the original benchmark.
inline Vec3 RockBoxSize(double scale) { return Vec3(4.4, 4.4, 3.8) * scale; }
inline Vec3 TreeBoxSize() { return Vec3(1.0, 1.0, 5.0); }

void AddTerrainToPhysics(const TaskSpec& task, const Terrain& terrain, engine::PhysicsWorld* world);

}  // namespace vb::terrain
