// EH, the elevation-heuristic baseline (reference_verti_bench.md §7.2): the PID path follower
// whose steering blends in a terrain target. Every decision it compares the ground-truth height
// under the vehicle (a square region of 6.4 m, the original's 64 px of its 0.1 m map) with five
// regions of the same size in a row ahead of it (centres 6.4 m ahead, -12.8..12.8 m to the side),
// picks the region whose mean height is closest to the one under the vehicle (ties: the smaller
// height variance, i.e. the flatter), and aims at its centre:
//   steering = rate_limit(0.2 * heading error to that region + 0.8 * heading error to the
//                         local goal on the A* path), clamped to [-1, 1];
// throttle and brake from the fixed-speed controller (4 m/s). Lengths scale with the environment.
// docs/baselines.md: parameters and the original's left-lying "front" regions.
#pragma once

#include <array>
#include <memory>

#include "vb/controllers/controller.h"

namespace vb::controllers {

struct EhParams {
  double region_size_m = 6.4;         // side of every region (original: 64 px of 0.0999 m)
  int num_regions = 5;                // candidate regions in the row ahead (odd)
  // Height sampling inside a region: the original averages 64 x 64 samples of its 0.1 m map,
  // which interpolates the 1 m grid; 16 x 16 samples (0.4 m) give the same mean and variance to
  // ~1 cm / ~2 % on the benchmark's surfaces (eh_controller_test) at 1/16 of the cost.
  double sample_spacing_m = 0.4;
  double terrain_weight = 0.2;
  double path_weight = 0.8;
  double steering_kp = 1.0;
  double steering_rate_per_s = 10.0;  // 0.05 per 5 ms step, as PID
  double speed_kp = 1.0;
  double lookahead_m = 10.0;          // multiplied by the environment scale
  double replan_period_s = 0.1;
  // The original cuts its five "front" regions from the strip that lies to the vehicle's left
  // (centres 6.4 m left, 12.8 m ahead .. 12.8 m behind) but aims as if they were ahead.
  bool original_left_regions = false;
};

// What one decision saw (for tests and traces).
struct EhDecision {
  int chosen = -1;                      // region index, 0 = leftmost (largest lateral offset)
  double under_mean_m = 0.0, under_var_m2 = 0.0;
  std::array<double, 9> mean_m{}, var_m2{};   // per region (num_regions <= 9)
  Vec2 target_m = Vec2::Zero();
  double terrain_error_rad = 0.0;
};

// The original's choice: the region minimising (|mean - under_mean|, variance) in lexicographic
// order; the first such region in index order on an exact tie.
int EhChooseRegion(const double* mean_m, const double* var_m2, int count, double under_mean_m);

class EhController : public Controller {
 public:
  explicit EhController(const EhParams& params = EhParams(), std::string name = "eh");
  std::string name() const override { return name_; }
  ObservationConfig observation_config() const override;
  void Reset(const EpisodeContext& context) override;
  Command Update(const Observation& obs) override;
  std::unique_ptr<Controller> Clone() const override;

  // The region choice for a vehicle at `position_m` heading `yaw_rad` (no state change).
  EhDecision Decide(const Vec2& position_m, double yaw_rad) const;
  const EhDecision& last_decision() const { return last_; }

 private:
  // Mean and population variance of the height over a region centred (forward, left) metres from
  // the vehicle in its frame.
  void RegionStats(const Vec2& position_m, double cos_yaw, double sin_yaw, double forward_m,
                   double left_m, double* mean, double* var) const;

  EhParams params_;
  std::string name_;
  EpisodeContext context_;
  double steering_ = 0.0;
  EhDecision last_;
};

}  // namespace vb::controllers
