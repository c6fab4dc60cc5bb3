// The task's rocks and trees as static convex shapes in world coordinates (boxes, or the convex
// hulls of their shapes: obstacle_shape.h), resting on the ground (terrain_physics.h:
// ObstacleBaseHeight), with a uniform-grid broadphase so that a body asks only
// for the obstacles near it. Tags: rock i -> i, tree j -> kTreeTagOffset + j.
#pragma once

#include <cstdint>
#include <vector>

#include "vb/engine/convex_shape.h"
#include "vb/terrain/task.h"
#include "vb/terrain/terrain.h"

namespace vb::terrain {

// Friction of the obstacles' surface (rock, bark): combined with the other body's by the minimum
// (Chrono's NSC rule, as the tires on the ground).
constexpr double kObstacleFriction = 0.8;

// A run of consecutive contact samples of a shape and their bounding box (samples lie along
// edges, so a run's box is tight): a query far from the box skips the run whole.
struct SampleRun {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  int begin = 0, end = 0;  // samples [begin, end)
};

struct Obstacle {
  engine::ConvexShape shape;   // world frame
  int tag = -1;
  double friction = kObstacleFriction;
  std::vector<SampleRun> sample_runs;  // covering shape.samples in order (ObstacleField makes them)
};

class ObstacleField {
 public:
  // sample_spacing_m: spacing of the contact sample points along the obstacles' edges (0.05 m x
  // task.scale keeps a wheel rolling over an edge smooth; docs/architecture.md "Contact").
  explicit ObstacleField(const TaskSpec& task, const Terrain& terrain);
  ObstacleField() = default;

  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  // Indices of the obstacles whose bounding boxes overlap [lo, hi], ascending, into *out
  // (cleared first). No allocation once *out and the internal stamps have their sizes.
  void Overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>* out) const;

 private:
  std::vector<Obstacle> obstacles_;
  double cell_m_ = 8.0;
  double x0_ = 0.0, y0_ = 0.0;     // south-west corner of the grid
  int cols_ = 0, rows_ = 0;
  std::vector<std::vector<int>> cells_;   // obstacle indices per cell, ascending
  mutable std::vector<uint32_t> stamp_;   // per obstacle: last query that reported it
  mutable uint32_t query_ = 0;
};

}  // namespace vb::terrain
