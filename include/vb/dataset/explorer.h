// The random explorer of the exploration dataset (Verti-Bench paper §III-G): sinusoidal steering
// at a 2 m/s target speed, the steering amplitude, period and phase drawn per episode from its
// seed. Throttle and brake come from the gym interface's speed controller (kp 1, every physics
// step), so an explorer step is exactly a `speed` action of vb_gym held for the sample period.
#pragma once

#include <cstdint>

#include "vb/dataset/recorder.h"

namespace vb::dataset {

struct ExplorerParams {
  double amplitude = 0.5;       // steering fraction in [min_amplitude, max_amplitude]
  double period_s = 4.0;        // in [min_period_s, max_period_s]
  double phase_rad = 0.0;       // in [0, 2 pi)
  double target_speed_mps = 2.0;
  double speed_kp = 1.0;        // vb_gym's speed controller gain
  double max_speed_mps = 4.0;   // vb_gym's action scale: speed action = target / max_speed
};

// Ranges of the draws (documented in docs/datasets.md).
constexpr double kExplorerMinAmplitude = 0.2;
constexpr double kExplorerMaxAmplitude = 1.0;
constexpr double kExplorerMinPeriod_s = 2.0;
constexpr double kExplorerMaxPeriod_s = 10.0;

// The parameters of episode `seed` (vb::Rng; platform independent).
ExplorerParams DrawExplorerParams(uint64_t seed);

// Steering held over each sample period: amplitude * sin(2 pi t0 / period + phase), t0 the start
// of the period; the speed controller runs every physics step.
class ExplorerPolicy : public SamplePolicy {
 public:
  ExplorerPolicy(const ExplorerParams& params, int sample_every_steps);
  controllers::Command Step(runner::Episode& episode) override;
  ActionKind action_kind() const override { return ActionKind::kSpeed; }
  std::vector<double> HeldAction() const override;

 private:
  ExplorerParams p_;
  int every_;
  double steering_ = 0.0;
};

}  // namespace vb::dataset
