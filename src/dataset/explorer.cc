// The random explorer (explorer.h).
#include "vb/dataset/explorer.h"

#include <cmath>

#include "vb/controllers/pid_controller.h"
#include "vb/engine/rng.h"

namespace vb::dataset {

ExplorerParams DrawExplorerParams(uint64_t seed) {
  // A stream of its own (not the trial seed's first draws, which other code may use).
  Rng rng(seed ^ 0x6578706c6f726572ull);   // "explorer"
  ExplorerParams p;
  p.amplitude = rng.Uniform(kExplorerMinAmplitude, kExplorerMaxAmplitude);
  p.period_s = rng.Uniform(kExplorerMinPeriod_s, kExplorerMaxPeriod_s);
  p.phase_rad = rng.Uniform(0.0, 2.0 * kPi);
  return p;
}

ExplorerPolicy::ExplorerPolicy(const ExplorerParams& params, int sample_every_steps)
    : p_(params), every_(sample_every_steps) {}

controllers::Command ExplorerPolicy::Step(runner::Episode& episode) {
  const long k = episode.physics_steps();
  if (k % every_ == 0) {
    const double t0 = static_cast<double>(k) * episode.rules().step_s;
    steering_ = p_.amplitude * std::sin(2.0 * kPi * t0 / p_.period_s + p_.phase_rad);
  }
  controllers::Command c;
  c.steering = steering_;
  controllers::SpeedControl(p_.target_speed_mps, episode.vehicle_state().forward_speed_mps,
                            p_.speed_kp, &c);
  return c;
}

std::vector<double> ExplorerPolicy::HeldAction() const {
  return {steering_, p_.target_speed_mps / p_.max_speed_mps};
}

}  // namespace vb::dataset
