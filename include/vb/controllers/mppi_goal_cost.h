// The MPPI baseline's cost plug-in (reference §7.3): w_goal * d^2 normalised to [0, 1] across
// the samples (min-max) + w_obstacle * [the state lies on an obstacle], d the planar distance to
// the goal of this update (the local goal on the global path). Obstacles are the ground-truth
// obstacle footprints (the original's obs bmp, not inflated); outside the world counts as an
// obstacle.
#pragma once

#include <memory>
#include <vector>

#include "vb/controllers/mppi_core.h"
#include "vb/engine/types.h"
#include "vb/terrain/gt_maps.h"

namespace vb::controllers {

struct GoalObstacleCostParams {
  double goal_weight = 10.0;
  double obstacle_weight = 50.0;
  // The original looks its obstacle map up as [row 64 + x, col 64 - y], i.e. at the world point
  // (-y, -x): the map mirrored about the line y = -x. false: at (x, y) (the intent).
  bool original_transposed_lookup = false;
};

class GoalObstacleCost : public RolloutCost {
 public:
  // `obstacles`: a whole-world occupancy grid (GroundTruthMaps::World(kOccupancy), bare
  // footprints); must outlive the cost. nullptr: no obstacle term.
  GoalObstacleCost(const GoalObstacleCostParams& params, const terrain::GridMap* obstacles,
                   double world_size_x_m, double world_size_y_m);
  void set_goal(const Vec2& goal_m) { goal_m_ = goal_m; }
  const Vec2& goal() const { return goal_m_; }
  // 1 if the world point (x, y) is on an obstacle or outside the world (the lookup rule above).
  double ObstacleAt(double x_m, double y_m) const;

  void Evaluate(int step, const PlannerState* states, const MppiControl* controls, int count,
                double* cost) override;
  std::unique_ptr<RolloutCost> Clone() const override;

 private:
  GoalObstacleCostParams params_;
  const terrain::GridMap* obstacles_;
  double half_x_m_, half_y_m_;
  Vec2 goal_m_ = Vec2::Zero();
  std::vector<double> d2_;   // scratch, one per sample (sized on the first call)
};

}  // namespace vb::controllers
