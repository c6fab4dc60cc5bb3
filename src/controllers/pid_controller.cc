// PID baseline, reference_verti_bench.md §7.1 (steering) and §4.6 (global planning), with the
// architecture's fixes: optimal A* without the Bezier smoothing, an explicit [-1, 1] clamp.
#include "vb/controllers/pid_controller.h"

#include <algorithm>
#include <cmath>

#include "vb/terrain/grid_planner.h"

namespace vb::controllers {

namespace {

// Observation times are k * step_s, so "t - last >= 0.1" can miss by one ulp and replan one step
// late (21 steps instead of 20). The tolerance makes the period exact in steps.
constexpr double kReplanTimeTolerance_s = 1e-9;

}  // namespace

PidController::PidController(const PidParams& params) : params_(params) {}

void PidController::Reset(const EpisodeContext& context) {
  context_ = context;
  path_m_.clear();
  local_goal_index_ = 0;
  last_replan_s_ = -1e9;
  steering_ = 0.0;
  replan_count_ = 0;
  goal_field_.reset();
  if (context.inflated_obstacles != nullptr) {
    goal_field_.emplace(*context.inflated_obstacles,
                        context.inflated_obstacles->CellOf(context.goal_m));
  }
}

Command PidController::Update(const Observation& obs) {
  const Vec2 position_m = obs.position_W.head<2>();

  // Global plan from the current position, every replan period of observation time; a failed
  // plan keeps the previous path (the original's behaviour).
  if (obs.time_s - last_replan_s_ >= params_.replan_period_s - kReplanTimeTolerance_s) {
    last_replan_s_ = obs.time_s;
    if (goal_field_) {
      ++replan_count_;
      std::optional<std::vector<Vec2>> plan = goal_field_->PathFrom(position_m);
      if (plan && !plan->empty()) {
        path_m_ = std::move(*plan);
        local_goal_index_ = 0;
      }
    }
  }
  // Without any path (no planning grid, or the goal was unreachable from the first position),
  // head straight for the goal rather than stand still.
  if (path_m_.empty()) {
    path_m_.push_back(context_.goal_m);
    local_goal_index_ = 0;
  }

  // Steering: proportional to the heading error to the look-ahead point, rate limited per call,
  // then clamped to the command range.
  const Vec2 local_goal = terrain::LookAheadPoint(path_m_, position_m, obs.rpy.yaw_rad,
                                                  params_.lookahead_m * context_.scale,
                                                  &local_goal_index_);
  const Vec2 to_goal = local_goal - position_m;
  const double heading_error =
      WrapAngle(std::atan2(to_goal.y(), to_goal.x()) - obs.rpy.yaw_rad);
  const double max_change = params_.steering_rate_per_s * context_.step_s;
  steering_ = std::clamp(params_.steering_kp * heading_error, steering_ - max_change,
                         steering_ + max_change);
  steering_ = std::clamp(steering_, -1.0, 1.0);

  // Speed: Chrono's ChSpeedController with (Kp, Ki, Kd) = (kp, 0, 0), output split into throttle
  // and brake.
  const double out = std::clamp(
      params_.speed_kp * (params_.target_speed_mps - obs.forward_speed_mps), -1.0, 1.0);
  Command command;
  command.steering = steering_;
  if (out > 0.0) {
    command.throttle = out;
    command.braking = 0.0;
  } else {
    command.throttle = 0.0;
    command.braking = -out;
  }
  return command;
}

}  // namespace vb::controllers
