// MPPI baseline controller (mppi_controller.h).
#include "vb/controllers/mppi_controller.h"

#include <algorithm>
#include <cmath>

#include "vb/controllers/pid_controller.h"

namespace vb::controllers {

namespace {
// Observation times are k * step_s; the tolerance keeps "t - last >= period" exact in steps.
constexpr double kRateTolerance_s = 1e-9;
}  // namespace

MppiControllerParams MppiIntentParams() { return MppiControllerParams(); }

MppiControllerParams MppiOriginalParams() {
  MppiControllerParams p;
  p.core.accumulation = CostAccumulation::kLastStep;
  p.core.control_cost = ControlCostForm::kAbsHalf;
  p.core.warm_start = WarmStart::kRollCyclic;
  p.core.weight_floor = 1e-6;
  p.model.original_step_direction = true;
  p.cost.original_transposed_lookup = true;
  return p;
}

MppiController::MppiController(const MppiControllerParams& params, std::string name)
    : params_(params), name_(std::move(name)), core_(params.core), model_(params.model) {}

ObservationConfig MppiController::observation_config() const {
  ObservationConfig c;
  c.lookahead_m = params_.lookahead_m;
  c.replan_period_s = params_.replan_period_s;
  return c;
}

void MppiController::Reset(const EpisodeContext& context) {
  context_ = context;
  BicycleModelParams model = params_.model;
  model.scale = context.scale;
  model_ = BicycleModel(model);
  const terrain::GridMap* obstacles =
      context.maps != nullptr ? &context.maps->World(terrain::MapLayer::kOccupancy) : nullptr;
  const double size_x = context.task != nullptr ? context.task->size_x_m : 0.0;
  const double size_y = context.task != nullptr ? context.task->size_y_m : 0.0;
  cost_.emplace(params_.cost, obstacles, size_x, size_y);
  core_.Reset(context.seed ^ params_.seed_salt);
  last_update_s_ = -1e9;
  steering_ = 0.0;
  updates_ = 0;
}

Command MppiController::Update(const Observation& obs) {
  if (obs.time_s - last_update_s_ >= params_.update_period_s - kRateTolerance_s) {
    last_update_s_ = obs.time_s;
    PlannerState start;
    start.x_m = obs.position_W.x();
    start.y_m = obs.position_W.y();
    start.z_m = obs.position_W.z();
    start.yaw_rad = obs.rpy.yaw_rad;
    start.roll_rad = obs.rpy.roll_rad;
    start.pitch_rad = obs.rpy.pitch_rad;
    cost_->set_goal(obs.local_goal_m);
    const Vec2 to_local_goal = obs.local_goal_m - obs.position_W.head<2>();
    const bool near = to_local_goal.norm() < params_.near_goal_m * context_.scale;
    const MppiControl& lo = near ? params_.near_goal_u_min : params_.core.u_min;
    const MppiControl& hi = near ? params_.near_goal_u_max : params_.core.u_max;
    const MppiControl u = core_.Update(start, model_, *cost_, lo, hi);
    steering_ = std::clamp(u[kMppiSteer], -1.0, 1.0);
    ++updates_;
  }
  Command command;
  command.steering = steering_;
  SpeedControl(params_.target_speed_mps, obs.forward_speed_mps, params_.speed_kp, &command);
  return command;
}

std::unique_ptr<Controller> MppiController::Clone() const {
  return std::make_unique<MppiController>(*this);
}

}  // namespace vb::controllers
