// PID baseline (reference_verti_bench.md §7.1): A* global path replanned every 0.1 s, look-ahead
// point 10 m (scaled), steering = heading error (kp 1) rate-limited to 0.05 per 5 ms step and
// clamped to [-1, 1]; throttle/brake from a proportional speed controller (kp 1, 4 m/s).
#pragma once

#include <optional>
#include <vector>

#include "vb/controllers/controller.h"
#include "vb/terrain/grid_planner.h"

namespace vb::controllers {

struct PidParams {
  double steering_kp = 1.0;
  double steering_rate_per_s = 10.0;     // 0.05 per 5 ms step
  double target_speed_mps = 4.0;
  double speed_kp = 1.0;
  double lookahead_m = 10.0;             // multiplied by the environment scale
  double replan_period_s = 0.1;
};

class PidController : public Controller {
 public:
  explicit PidController(const PidParams& params = PidParams());
  std::string name() const override { return "pid"; }
  void Reset(const EpisodeContext& context) override;
  Command Update(const Observation& obs) override;

  // Introspection for tests and diagnostics: the path being followed (world x, y) and the number
  // of planner calls since Reset (successful or not).
  const std::vector<Vec2>& path() const { return path_m_; }
  int replan_count() const { return replan_count_; }

 private:
  PidParams params_;
  EpisodeContext context_;
  std::optional<terrain::GoalDistanceField> goal_field_;  // the trial's planner (static goal)
  std::vector<Vec2> path_m_;
  size_t local_goal_index_ = 0;
  double last_replan_s_ = -1e9;
  double steering_ = 0.0;
  int replan_count_ = 0;
};

}  // namespace vb::controllers
