// The one observation builder (controllers/observation.h): robot state, goal and local goal on the
// global path, and egocentric ground-truth crops, for every consumer of an episode. Its
// navigation state (the current global path, the look-ahead index, the last replanning time) is
// plain copyable data, part of an episode snapshot.
#pragma once

#include <optional>
#include <vector>

#include "vb/controllers/observation.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/perception.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/original_planner.h"
#include "vb/terrain/gt_maps.h"
#include "vb/vehicles/vehicle.h"

namespace vb::runner {

// Navigation bookkeeping between observations.
struct NavigationState {
  std::vector<Vec2> path_m;
  size_t local_goal_index = 0;
  double last_replan_s = -1e9;
  double last_crop_s = -1e9;   // observation time of the crops in the last Observation built
  int replan_count = 0;   // planner calls since Reset (successful or not)
};

class ObservationBuilder {
 public:
  // `maps` (crops) and `inflated` (planning grid) must outlive the builder. scale: the
  // environment scale (look-ahead and crop resolutions scale with it).
  ObservationBuilder(const terrain::GroundTruthMaps& maps, const terrain::OccupancyGrid& inflated,
                     double scale);

  void SetConfig(const controllers::ObservationConfig& config);
  const controllers::ObservationConfig& config() const { return config_; }
  // Imperfect perception (perception.h); default: none (ground truth). step_s: physics step.
  void SetPerception(const PerceptionParams& params, double step_s);
  const PerceptionModel& perception() const { return perception_; }

  // New episode towards `goal_m` with the trial seed (perception errors) of `task`: the
  // planner's cost-to-goal field (computed once per goal and planning grid; a repeated goal
  // reuses it) and empty navigation state.
  void Reset(const Vec2& goal_m, uint64_t trial_seed, const terrain::TaskSpec& task);
  // The same without perception errors (ground truth only).
  void Reset(const Vec2& goal_m) {
    VB_DEMAND(!perception_.enabled());
    Reset(goal_m, 0, terrain::TaskSpec());
  }

  // The vehicle state after physics step k (k = 0: the start); needed only when
  // perception().needs_history() (latency, mapping delay).
  void Record(long k, const vehicles::VehicleState& state) { perception_.Record(k, state); }

  // Fills *obs for the vehicle state at physics step k, time t_s (replanning the global path
  // when the replan period has passed). No allocation once the crops and the path have their
  // sizes.
  void Build(long k, double t_s, const vehicles::VehicleState& state,
             controllers::Observation* obs);
  // The same for ground truth (no perception errors: the step index is not needed).
  void Build(double t_s, const vehicles::VehicleState& state, controllers::Observation* obs) {
    VB_DEMAND(!perception_.enabled());
    Build(0, t_s, state, obs);
  }

  // The planning grid of this trial: the ground truth's, or the perceived obstacles' one.
  const terrain::OccupancyGrid& planning_grid() const {
    return perception_.params().HasObstacleErrors() ? perception_.perceived_inflated() : inflated_;
  }

  const NavigationState& navigation() const { return nav_; }
  void set_navigation(const NavigationState& nav) { nav_ = nav; }
  const PerceptionState& perception_state() const { return perception_.state(); }
  void set_perception_state(const PerceptionState& s) { perception_.set_state(s); }

 private:
  const terrain::GroundTruthMaps& maps_;
  const terrain::OccupancyGrid& inflated_;
  double scale_ = 1.0;
  controllers::ObservationConfig config_;
  Vec2 goal_m_ = Vec2::Zero();
  std::optional<terrain::GoalDistanceField> goal_field_;
  std::optional<Vec2> field_goal_m_;   // goal the field was computed for
  // ObservationConfig::original_planner: the original's obstacle map of the task planned on
  // (built on the first Reset with that task).
  std::optional<terrain::OriginalPlannerGrid> original_grid_;
  const terrain::TaskSpec* original_grid_task_ = nullptr;
  NavigationState nav_;
  PerceptionModel perception_;
  terrain::GridMap semantics_scratch_;  // true semantics under a friction crop (perception)
};

}  // namespace vb::runner
