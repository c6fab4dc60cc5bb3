// The shapes of a task's obstacles (task.h ObstacleShapeSpec): for each rock and tree the points
// whose convex hull is its collision shape, in a local frame (x, y centred on the obstacle's
// position, z = 0 at its lowest point), and its outline on the ground (the shape's projection,
// a convex polygon). One definition for everything that needs an obstacle's shape: the physics
// (ObstacleField), the occupancy grid (RasterizeObstacles: planners, ground-truth maps, top-down
// pictures) and the viewer's scene. Geometry only; no I/O (meshes are loaded by tools/io).
//
// Boulder family (docs/generator.md "Obstacle shapes"): a sphere with a few seeded bumps and a
// little seeded jitter, sampled at 30 near-uniform directions, cut by a plane below its equator
// (the ground: a dome that widens to its base, as a half-buried boulder), and stretched so that
// its bounding box is exactly the original's rock box, (4.4, 4.4, 3.8) m * rock scale * world
// scale (reference_verti_bench.md §2.8 and §4.4). Trunks: a 12-sided prism 1 m across and 5 m
// high * world scale (the original's tree box, 1 x 1 x 5 m).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "vb/terrain/task.h"

namespace vb::terrain {

std::string_view ObstacleShapeKindName(ObstacleShapeKind kind);   // box boulder trunk mesh
bool ParseObstacleShapeKind(std::string_view name, ObstacleShapeKind* kind);

// Sets every rock's shape_seed from the task's generator seed and the rock's index (a fixed
// mix: the same task file gives the same boulders on every machine).
void AssignShapeSeeds(TaskSpec* task);

// Boulder points for `seed` whose bounding box is exactly box_m (x, y centred on 0, z in
// [0, box_m.z()]).
std::vector<Vec3> BoulderPoints(uint64_t seed, const Vec3& box_m);
// A prism of `sides` vertices on a circle of diameter diameter_m (one at angle 0, so the
// bounding box is diameter x diameter for sides divisible by 4), z in [0, height_m].
std::vector<Vec3> PrismPoints(int sides, double diameter_m, double height_m);
// The 8 corners of a box of full size box_m, z in [0, box_m.z()].
std::vector<Vec3> BoxPoints(const Vec3& box_m);

// Local shape points of rock `rock` / of every tree of `task` (frame above).
std::vector<Vec3> RockShapePoints(const TaskSpec& task, const RockSpec& rock);
std::vector<Vec3> TreeShapePoints(const TaskSpec& task);

// Convex hull of the points' (x, y), counter-clockwise, no collinear vertices.
std::vector<Vec2> Outline(const std::vector<Vec3>& points);
// True if p is inside the convex counter-clockwise polygon (or within tol_m outside an edge).
bool InsideConvexPolygon(const std::vector<Vec2>& polygon, const Vec2& p, double tol_m = 0.0);
// Area of a simple polygon (positive when counter-clockwise).
double PolygonArea(const std::vector<Vec2>& polygon);

}  // namespace vb::terrain
