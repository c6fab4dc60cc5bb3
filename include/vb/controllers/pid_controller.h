// PID baseline (reference_verti_bench.md §7.1): steering = heading error to the local goal (the
// look-ahead point 10 m * scale ahead on the A* path replanned every 0.1 s, which the observation
// builder provides) with kp 1, rate-limited to 0.05 per 5 ms and clamped to [-1, 1]; throttle
// and brake from a proportional speed controller (kp 1, 4 m/s).
#pragma once

#include <memory>
#include <string>

#include "vb/controllers/controller.h"

namespace vb::controllers {

struct PidParams {
  double steering_kp = 1.0;
  double steering_rate_per_s = 10.0;     // 0.05 per 5 ms step
  double speed_kp = 1.0;
  double lookahead_m = 10.0;             // multiplied by the environment scale
  double replan_period_s = 0.1;          // global path replanning (observation builder)
  // Steer at the final goal instead of the local goal on the A* path (the "straight" reference
  // system: what a policy must beat to have learned anything about the terrain or obstacles).
  bool straight_to_goal = false;
  // Follow the path the original's code plans (ObservationConfig::original_planner): the
  // `pid_original` system.
  bool original_planner = false;
};

// The speed controller shared by the path followers (Chrono's ChSpeedController with
// (Kp, Ki, Kd) = (kp, 0, 0)): output kp * (target - speed) in [-1, 1], positive as throttle,
// negative as brake. Writes throttle and braking of *command.
void SpeedControl(double target_mps, double speed_mps, double kp, Command* command);

// The steering shared by the path followers: `target` moved towards by at most `max_change`
// from `previous` (the rate limit per control call), then clamped to the command range [-1, 1].
double RateLimitedSteering(double target, double previous, double max_change);

class PidController : public Controller {
 public:
  explicit PidController(const PidParams& params = PidParams(), std::string name = "pid");
  std::string name() const override { return name_; }
  ObservationConfig observation_config() const override;
  void Reset(const EpisodeContext& context) override;
  Command Update(const Observation& obs) override;
  std::unique_ptr<Controller> Clone() const override;

 private:
  PidParams params_;
  std::string name_;
  EpisodeContext context_;
  double steering_ = 0.0;
};

}  // namespace vb::controllers
