// Obstacle geometry of a task: the box sizes of rocks and trees and their resting height (the
// obstacles themselves are terrain::ObstacleField; tags: rock i -> i, tree j -> 1000 + j).
#pragma once

#include <vector>

#include "vb/terrain/task.h"
#include "vb/terrain/terrain.h"

namespace vb::terrain {

constexpr int kTreeTagOffset = 1000;
// Rock box full size (m) for a rock scale (0.7-1.2) and tree box full size (m), as the original
// benchmark, at world scale 1. A scaled world (task.scale != 1) multiplies both by task.scale,
// as the original's scale_factor does (rock.scale is the rock's shape scale, not a length).
inline Vec3 RockBoxSize(double scale) { return Vec3(4.4, 4.4, 3.8) * scale; }
inline Vec3 TreeBoxSize() { return Vec3(1.0, 1.0, 5.0); }
inline Vec3 RockBoxSize(const TaskSpec& task, const RockSpec& rock) {
  return RockBoxSize(rock.scale) * task.scale;
}
inline Vec3 TreeBoxSize(const TaskSpec& task) { return TreeBoxSize() * task.scale; }

// Height of an obstacle's bottom face so that it rests on the ground: the lowest terrain height
// under its footprint (a square of full side footprint_m centred at (x, y), axis-aligned as the
// boxes are). The box then touches the ground at its lowest point and nowhere hangs above it.
double ObstacleBaseHeight(const Terrain& terrain, double x_m, double y_m, double footprint_m);
// The same over a convex footprint polygon (world x, y, counter-clockwise: the outline of a
// boulder, trunk or mesh, obstacle_shape.h): the lowest terrain height at a grid vertex inside it
// or on its boundary (sampled at 1/32 of the grid spacing). A shape whose lowest point is there
// touches the ground at that point and nowhere hangs above it.
double ObstacleBaseHeight(const Terrain& terrain, const std::vector<Vec2>& footprint_W);

}  // namespace vb::terrain
