// The part of a controller of the MPPI family (MPPI, WMVCT, MPPI-6, TAL, TNT) around the core:
// the 20 Hz update gate, the start state from the observation, the local goal 10 m ahead on the A*
// path (replanned at 10 Hz, asked for through the observation config), the speed bounds widened
// to [-1, 1] within 2 m of the local goal (the original's rule), the planned steering clamped to
// [-1, 1] and held between updates, and the fixed-speed throttle controller (the episode's target
// speed, 4 m/s by default; the planners' own speed output is unused, as the original). docs/baselines.md "MPPI".
#pragma once

#include "vb/controllers/controller.h"
#include "vb/controllers/mppi_core.h"

namespace vb::controllers {

struct MppiFrontEndParams {
  double update_period_s = 0.05;            // 20 Hz
  // Within near_goal_m (x the environment scale) of the local goal the speed bounds widen (the
  // local goal is 10 m ahead except at the end of the path). MPPI-6 does not widen.
  bool widen_near_goal = true;
  double near_goal_m = 2.0;
  MppiControl near_goal_u_min = {-1.0, -1.0};
  MppiControl near_goal_u_max = {1.0, 1.0};
  double speed_kp = 1.0;
  double lookahead_m = 10.0;                // multiplied by the environment scale
  double replan_period_s = 0.1;
};

class MppiFrontEnd {
 public:
  explicit MppiFrontEnd(const MppiFrontEndParams& params = MppiFrontEndParams());

  ObservationConfig observation_config() const;
  // A new episode; `target_speed_mps` is its speed controller's target (EpisodeContext).
  void Reset(double target_speed_mps);
  // True when an update is due at obs.time_s; the update is then counted as done at that time.
  bool Due(const Observation& obs);
  // One core update from the observed pose with this update's bounds; returns the first planned
  // steering, clamped to [-1, 1]. The caller has set the cost's goal (obs.local_goal_m).
  double Plan(const Observation& obs, double scale, MppiCore& core, const RolloutModel& model,
              RolloutCost& cost);
  // Throttle and brake of the fixed-speed controller, with the given steering.
  Command Drive(const Observation& obs, double steering) const;

  const MppiFrontEndParams& params() const { return params_; }
  long updates() const { return updates_; }

 private:
  MppiFrontEndParams params_;
  double target_speed_mps_ = 4.0;
  double last_update_s_ = -1e9;
  long updates_ = 0;
};

}  // namespace vb::controllers
