// Kinematic bicycle rollout model, the MPPI baseline's dynamics plug-in (reference §7.3). The
// original integrates a normalised "Ackermann" model in unit-less steps; its numbers reduce to a
// bicycle with an effective wheelbase of 0.32 * 0.583 / 0.0649 = 2.875 m, a wheel angle of
// 0.6 rad per unit steering command and a step length of 0.583 / 0.75 = 0.777 m per unit speed
// command (so 0.35-0.47 m per step for the speed range 0.45-0.6): purely geometric rollouts, ~8 m
// over 20 steps. Lengths are multiplied by the environment scale.
#pragma once

#include <memory>

#include "vb/controllers/mppi_core.h"

namespace vb::controllers {

struct BicycleModelParams {
  double step_length_per_speed_m = 0.0583 * 10.0 / 0.75;   // metres per step per unit speed
  double wheelbase_m = 0.32 * 0.0583 * 10.0 / 0.0649;      // effective wheelbase
  double wheel_angle_per_steer_rad = 0.6;                  // road-wheel angle at steering 1
  // The original moves each step along the *unscaled* normalised heading change (its dx, dy use
  // cos/sin of v'/0.32 tan(delta'), up to 1.7 rad, while the pose turns by 0.0649 of it): at full
  // steering a step goes nearly sideways. false: along the mean heading of the step (the intent).
  bool original_step_direction = false;
  double scale = 1.0;                                      // environment scale
};

class BicycleModel : public RolloutModel {
 public:
  explicit BicycleModel(const BicycleModelParams& params = BicycleModelParams());
  void Step(int step, const PlannerState* states, const MppiControl* controls, int count,
            PlannerState* next) const override;
  std::unique_ptr<RolloutModel> Clone() const override;
  const BicycleModelParams& params() const { return params_; }

 private:
  BicycleModelParams params_;
};

}  // namespace vb::controllers
