// Observation builder: the navigation follows the original's path followers (reference
// §4.6, §7.1): A* on the inflated grid from the current position every 0.1 s (read off the
// cost-to-goal field, as optimal as a search), a failed plan keeps the previous path, and the
// local goal is the look-ahead point (terrain::LookAheadPoint). ObservationConfig::original_planner
// plans as the original's code instead (terrain/original_planner.h).
#include "vb/engine/runner/observation_builder.h"

#include <algorithm>
#include <cmath>

namespace vb::runner {

namespace {

// Observation times are k * step_s, so "t - last >= 0.1" can miss by one ulp and replan one step
// late (21 steps instead of 20). The tolerance makes the period exact in steps.
constexpr double kReplanTimeTolerance_s = 1e-9;

}  // namespace

ObservationBuilder::ObservationBuilder(const terrain::GroundTruthMaps& maps,
                                       const terrain::OccupancyGrid& inflated, double scale)
    : maps_(maps), inflated_(inflated), scale_(scale) {}

void ObservationBuilder::SetConfig(const controllers::ObservationConfig& config) {
  config_ = config;
}

void ObservationBuilder::SetPerception(const PerceptionParams& params, double step_s) {
  perception_ = PerceptionModel(params, step_s);
  goal_field_.reset();
  field_goal_m_.reset();
}

void ObservationBuilder::Reset(const Vec2& goal_m, uint64_t trial_seed,
                               const terrain::TaskSpec& task) {
  goal_m_ = goal_m;
  perception_.Reset(trial_seed, task);
  // Perceived obstacles differ per trial: their planning grid needs its own field every time.
  const bool per_trial_grid = perception_.params().HasObstacleErrors();
  if (per_trial_grid || !field_goal_m_ || *field_goal_m_ != goal_m) {
    goal_field_.reset();
    const terrain::OccupancyGrid& grid = planning_grid();
    if (grid.rows > 0) goal_field_.emplace(grid, grid.CellOf(goal_m));
    field_goal_m_ = goal_m;
  }
  if (config_.original_planner && original_grid_task_ != &task) {
    if (task.heights.rows < 2 || task.heights.cols < 2) {
      throw InputError(task.source_file, 0, "system",
                       "the original's planner needs the task's height grid (obstacle map size)");
    }
    original_grid_ = terrain::MakeOriginalPlannerGrid(task);
    original_grid_task_ = &task;
  }
  nav_.path_m.clear();
  nav_.local_goal_index = 0;
  nav_.last_replan_s = -1e9;
  nav_.last_crop_s = -1e9;
  nav_.replan_count = 0;
}

void ObservationBuilder::Build(long k, double t_now_s, const vehicles::VehicleState& current,
                               controllers::Observation* obs) {
  // With perception: the state the (late) observation describes, and the estimate's errors.
  const bool perceived = perception_.enabled();
  const long latency = perceived ? perception_.latency_steps() : 0;
  const vehicles::VehicleState& s = perception_.Delayed(k, latency, current);
  const double t_s = latency > 0
                         ? static_cast<double>(std::max(0L, k - latency)) * perception_.step_s()
                         : t_now_s;
  PoseError error;
  Vec3 velocity_noise = Vec3::Zero();
  Vec3 rate_noise = Vec3::Zero();
  if (perceived) {
    error = perception_.AdvanceTo(t_s);
    velocity_noise = perception_.VelocityNoise();
    rate_noise = perception_.AngularVelocityNoise();
  }

  // Robot state (as estimated).
  obs->time_s = t_s;
  obs->position_W = s.pose_W.position + error.position_m;
  obs->rpy = s.rpy;
  if (perceived) {
    obs->rpy.roll_rad += error.roll_rad;
    obs->rpy.pitch_rad += error.pitch_rad;
    obs->rpy.yaw_rad = WrapAngle(s.rpy.yaw_rad + error.yaw_rad);
  }
  obs->velocity_W = s.velocity_W + velocity_noise;
  obs->angular_velocity_B = s.pose_W.rotation.conjugate() * s.angular_velocity_W + rate_noise;
  obs->forward_speed_mps = s.forward_speed_mps + velocity_noise.x();
  obs->gear = s.gear;
  obs->engine_speed_radps = s.engine_speed_radps;
  obs->wheels.resize(s.wheels.size());
  for (size_t i = 0; i < s.wheels.size(); ++i) {
    const vehicles::WheelState& w = s.wheels[i];
    controllers::WheelObservation& o = obs->wheels[i];
    o.in_contact = w.in_contact;
    o.surface = w.in_contact ? static_cast<int>(w.surface) : -1;
    o.normal_force_n = w.normal_force_n;
    o.sinkage_m = w.sinkage_m;
    o.spin_radps = w.spin_radps;
    o.slip = w.longitudinal_slip;
  }

  // Navigation: the global path from the current position every replan period; a failed plan
  // keeps the previous path (the original's behaviour).
  const Vec2 position_m = obs->position_W.head<2>();
  const double yaw_rad = obs->rpy.yaw_rad;
  if (t_s - nav_.last_replan_s >= config_.replan_period_s - kReplanTimeTolerance_s) {
    nav_.last_replan_s = t_s;
    // The original's planner's grid is built by Reset with the task (a config set after it is a
    // caller's error, not a reason to drive without a plan).
    VB_DEMAND(!config_.original_planner || original_grid_.has_value());
    if (config_.original_planner || goal_field_) {
      ++nav_.replan_count;
      std::optional<std::vector<Vec2>> plan =
          config_.original_planner ? terrain::OriginalPlanPath(*original_grid_, position_m, goal_m_)
                                   : goal_field_->PathFrom(position_m);
      if (plan && !plan->empty()) {
        nav_.path_m = std::move(*plan);
        nav_.local_goal_index = 0;
      }
    }
  }
  // Without any path (no planning grid, or the goal unreachable from the first position), the
  // goal itself is the path: head straight for it rather than stand still.
  if (nav_.path_m.empty()) {
    nav_.path_m.push_back(goal_m_);
    nav_.local_goal_index = 0;
  }
  obs->goal_m = goal_m_;
  obs->goal_distance_m = (goal_m_ - position_m).norm();
  obs->local_goal_m = terrain::LookAheadPoint(nav_.path_m, position_m, yaw_rad,
                                              config_.lookahead_m * scale_,
                                              &nav_.local_goal_index);
  const Vec2 to_goal = obs->local_goal_m - position_m;
  obs->heading_error_rad = WrapAngle(std::atan2(to_goal.y(), to_goal.x()) - yaw_rad);
  obs->global_path_m = &nav_.path_m;

  // Maps: registered at the estimated pose (of the mapping delay ago, with perception), every
  // crop period; an Observation without crops of the configured sizes is always given fresh ones.
  bool crops_current = obs->crops.size() == config_.crops.size() &&
                       t_s - nav_.last_crop_s < config_.crop_period_s - kReplanTimeTolerance_s;
  for (size_t i = 0; crops_current && i < config_.crops.size(); ++i) {
    crops_current = obs->crops[i].rows == config_.crops[i].size_cells;
  }
  if (crops_current) return;
  nav_.last_crop_s = t_s;
  obs->crops.resize(config_.crops.size());
  Vec2 crop_position_m = position_m;
  double crop_yaw_rad = yaw_rad;
  if (perceived && perception_.crop_delay_steps() > latency) {
    const vehicles::VehicleState& mapped =
        perception_.Delayed(k, perception_.crop_delay_steps(), current);
    crop_position_m = mapped.pose_W.position.head<2>() + error.position_m.head<2>();
    crop_yaw_rad = WrapAngle(mapped.rpy.yaw_rad + error.yaw_rad);
  }
  for (size_t i = 0; i < config_.crops.size(); ++i) {
    const controllers::CropSpec& c = config_.crops[i];
    const double res = c.resolution_m * scale_;
    maps_.CropInto(c.layer, crop_position_m, crop_yaw_rad, c.size_cells, res, &obs->crops[i]);
    if (!perceived) continue;
    const terrain::GridMap* truth = nullptr;
    if (c.layer == terrain::MapLayer::kFriction && perception_.params().HasSemanticErrors()) {
      maps_.CropInto(terrain::MapLayer::kSemantics, crop_position_m, crop_yaw_rad, c.size_cells,
                     res, &semantics_scratch_);
      truth = &semantics_scratch_;
    }
    perception_.ApplyToCrop(c.layer, crop_position_m, crop_yaw_rad, truth, &obs->crops[i]);
  }
}

}  // namespace vb::runner
