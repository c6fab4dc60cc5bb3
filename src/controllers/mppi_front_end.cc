// The MPPI family's front end (mppi_front_end.h).
#include "vb/controllers/mppi_front_end.h"

#include <algorithm>

#include "vb/controllers/pid_controller.h"

namespace vb::controllers {

namespace {
// Observation times are k * step_s; the tolerance keeps "t - last >= period" exact in steps.
constexpr double kRateTolerance_s = 1e-9;
}  // namespace

MppiFrontEnd::MppiFrontEnd(const MppiFrontEndParams& params) : params_(params) {}

ObservationConfig MppiFrontEnd::observation_config() const {
  ObservationConfig c;
  c.lookahead_m = params_.lookahead_m;
  c.replan_period_s = params_.replan_period_s;
  return c;
}

void MppiFrontEnd::Reset(double target_speed_mps) {
  target_speed_mps_ = target_speed_mps;
  last_update_s_ = -1e9;
  updates_ = 0;
}

bool MppiFrontEnd::Due(const Observation& obs) {
  if (obs.time_s - last_update_s_ < params_.update_period_s - kRateTolerance_s) return false;
  last_update_s_ = obs.time_s;
  return true;
}

double MppiFrontEnd::Plan(const Observation& obs, double scale, MppiCore& core,
                          const RolloutModel& model, RolloutCost& cost) {
  PlannerState start;
  start.x_m = obs.position_W.x();
  start.y_m = obs.position_W.y();
  start.z_m = obs.position_W.z();
  start.yaw_rad = obs.rpy.yaw_rad;
  start.roll_rad = obs.rpy.roll_rad;
  start.pitch_rad = obs.rpy.pitch_rad;
  const Vec2 to_local_goal = obs.local_goal_m - obs.position_W.head<2>();
  const bool near = params_.widen_near_goal && to_local_goal.norm() < params_.near_goal_m * scale;
  const MppiControl& lo = near ? params_.near_goal_u_min : core.params().u_min;
  const MppiControl& hi = near ? params_.near_goal_u_max : core.params().u_max;
  const MppiControl u = core.Update(start, model, cost, lo, hi);
  ++updates_;
  return std::clamp(u[kMppiSteer], -1.0, 1.0);
}

Command MppiFrontEnd::Drive(const Observation& obs, double steering) const {
  Command command;
  command.steering = steering;
  SpeedControl(target_speed_mps_, obs.forward_speed_mps, params_.speed_kp, &command);
  return command;
}

}  // namespace vb::controllers
