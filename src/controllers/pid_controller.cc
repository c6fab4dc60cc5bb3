// PID baseline, reference_verti_bench.md §7.1 (steering) on the observation's local goal (§4.6
// global planning, in the observation builder), with the architecture's fixes: optimal A* without
// the Bezier smoothing, an explicit [-1, 1] clamp.
#include "vb/controllers/pid_controller.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vb::controllers {

double RateLimitedSteering(double target, double previous, double max_change) {
  return std::clamp(std::clamp(target, previous - max_change, previous + max_change), -1.0, 1.0);
}

void SpeedControl(double target_mps, double speed_mps, double kp, Command* command) {
  const double out = std::clamp(kp * (target_mps - speed_mps), -1.0, 1.0);
  if (out > 0.0) {
    command->throttle = out;
    command->braking = 0.0;
  } else {
    command->throttle = 0.0;
    command->braking = -out;
  }
}

PidController::PidController(const PidParams& params, std::string name)
    : params_(params), name_(std::move(name)) {}

ObservationConfig PidController::observation_config() const {
  ObservationConfig c;
  c.lookahead_m = params_.lookahead_m;
  c.replan_period_s = params_.replan_period_s;
  c.original_planner = params_.original_planner;
  return c;
}

void PidController::Reset(const EpisodeContext& context) {
  context_ = context;
  steering_ = 0.0;
}

Command PidController::Update(const Observation& obs) {
  // Steering: proportional to the heading error to the look-ahead point, rate limited per call,
  // then clamped to the command range.
  double error = obs.heading_error_rad;
  if (params_.straight_to_goal) {
    const Vec2 d = obs.goal_m - obs.position_W.head<2>();
    error = WrapAngle(std::atan2(d.y(), d.x()) - obs.rpy.yaw_rad);
  }
  steering_ = RateLimitedSteering(params_.steering_kp * error, steering_,
                                  params_.steering_rate_per_s * context_.control_period_s);
  Command command;
  command.steering = steering_;
  SpeedControl(context_.target_speed_mps, obs.forward_speed_mps, params_.speed_kp, &command);
  return command;
}

std::unique_ptr<Controller> PidController::Clone() const {
  return std::make_unique<PidController>(*this);
}

}  // namespace vb::controllers
