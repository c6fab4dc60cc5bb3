// The one observation builder (controllers/observation.h): robot state, goal and local goal on the
// global path, and egocentric ground-truth crops, for every consumer of an episode. Its
// navigation state (the current global path, the look-ahead index, the last replanning time) is
// plain copyable data, part of an episode snapshot.
#pragma once

#include <optional>
#include <vector>

#include "vb/controllers/observation.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/gt_maps.h"
#include "vb/vehicles/vehicle.h"

namespace vb::runner {

// Navigation bookkeeping between observations.
struct NavigationState {
  std::vector<Vec2> path_m;
  size_t local_goal_index = 0;
  double last_replan_s = -1e9;
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

  // New episode towards `goal_m`: the planner's cost-to-goal field (computed once per goal; a
  // repeated goal reuses it) and empty navigation state.
  void Reset(const Vec2& goal_m);

  // Fills *obs for the vehicle state at time t_s (replanning the global path when the replan
  // period has passed). No allocation once the crops and the path have their sizes.
  void Build(double t_s, const vehicles::VehicleState& state, controllers::Observation* obs);

  const NavigationState& navigation() const { return nav_; }
  void set_navigation(const NavigationState& nav) { nav_ = nav; }

 private:
  const terrain::GroundTruthMaps& maps_;
  const terrain::OccupancyGrid& inflated_;
  double scale_ = 1.0;
  controllers::ObservationConfig config_;
  Vec2 goal_m_ = Vec2::Zero();
  std::optional<terrain::GoalDistanceField> goal_field_;
  std::optional<Vec2> field_goal_m_;   // goal the field was computed for
  NavigationState nav_;
};

}  // namespace vb::runner
