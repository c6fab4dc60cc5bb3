// The hybrid baselines' cost plug-in (reference_verti_bench.md §7.4-7.7; docs/baselines.md
// "Hybrid systems"): one weighted sum whose terms each system switches on with its weights:
//   goal_weight      x d^2 to the local goal, min-max normalised across the samples (MPPI, WMVCT,
//                      TAL, TNT)
//   goal_raw_weight  x d^2 in m^2 (MPPI-6)
//   heading_weight   x |bearing of the goal - yaw| / d^2 from the update's start (MPPI-6; the
//                      original compared the yaw with a fixed goal yaw of 0)
//   obstacle_weight  x [on an obstacle footprint or outside the world] (GoalObstacleCost's lookup)
//   roll/pitch_weight x |roll|, |pitch| (normalised: min-max across the samples and 0 below
//                      attitude_threshold_rad, TAL's rule; raw: radians, MPPI-6); the original
//                      MPPI-6 used the signed angles (`signed_attitude`)
//   trav_weight      x (1 - traversability) from TNT's map, min-max normalised
#pragma once

#include <memory>
#include <vector>

#include "vb/controllers/mppi_core.h"
#include "vb/controllers/mppi_goal_cost.h"
#include "vb/controllers/traversability_map.h"
#include "vb/engine/types.h"

namespace vb::controllers {

struct HybridCostParams {
  double goal_weight = 0.0;
  double goal_raw_weight = 0.0;
  double heading_weight = 0.0;
  double obstacle_weight = 0.0;
  double roll_weight = 0.0;
  double pitch_weight = 0.0;
  bool attitude_normalised = true;
  double attitude_threshold_rad = 0.17;
  bool signed_attitude = false;
  double trav_weight = 0.0;
};

class HybridCost : public RolloutCost {
 public:
  // obstacles: the bare obstacle footprints (may be nullptr: no obstacle term possible);
  // trav: TNT's map (nullptr unless trav_weight > 0). Both must outlive the cost.
  HybridCost(const HybridCostParams& params, const terrain::GridMap* obstacles,
             double world_size_x_m, double world_size_y_m, const TraversabilityMap* trav);
  // Per update: the local goal and the start of the rollouts.
  void set_goal(const Vec2& goal_m, const Vec2& start_m);

  void Evaluate(int step, const PlannerState* states, const MppiControl* controls, int count,
                double* cost) override;
  std::unique_ptr<RolloutCost> Clone() const override;
  void set_traversability(const TraversabilityMap* trav) { trav_ = trav; }

 private:
  HybridCostParams params_;
  GoalObstacleCost obstacles_;
  const TraversabilityMap* trav_;
  Vec2 goal_m_ = Vec2::Zero();
  double start_d2_ = 1.0;
  std::vector<double> d2_, roll_, pitch_, trav_cost_;   // scratch, one per sample
};

}  // namespace vb::controllers
