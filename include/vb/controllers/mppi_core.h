// The sampling planner shared by the MPPI family (reference_verti_bench.md §7.3-7.7: MPPI,
// WMVCT, TAL, TNT, MPPI-6): Model Predictive Path Integral control over a nominal sequence of
// (speed, steering) commands. One update samples K perturbed command sequences (seeded Gaussian
// noise, clamped to the bounds), rolls them out T steps through a pluggable dynamics model,
// scores them with a pluggable cost, weights them by exp(-cost / lambda) and moves the nominal
// sequence by the weighted noise; then the sequence is shifted for the next update (warm start).
// docs/baselines.md explains each choice and the original's variants (the quirks options).
//
// Plug-ins work on whole batches (all K samples of one horizon step per call), so a learned
// model can run one batched network evaluation per step. The core allocates nothing after
// construction.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "vb/engine/rng.h"

namespace vb::controllers {

// A planner command, normalised: [0] speed (the original's 0.45..0.6 unit-less range), [1]
// steering in [-1, 1], + = left (vb's command convention; the original's sign is flipped).
constexpr int kMppiControlDims = 2;
using MppiControl = std::array<double, kMppiControlDims>;
constexpr int kMppiSpeed = 0;
constexpr int kMppiSteer = 1;

// The rollout state every model of the family can fill (the learned ones predict z, roll and
// pitch as well). World frame, metres and radians.
struct PlannerState {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double z_m = 0.0;
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
};

// Dynamics plug-in: advances `count` states by one horizon step under their controls.
class RolloutModel {
 public:
  virtual ~RolloutModel() = default;
  // step: horizon index 0..T-1. states, controls, next: arrays of `count`.
  virtual void Step(int step, const PlannerState* states, const MppiControl* controls, int count,
                    PlannerState* next) const = 0;
  virtual std::unique_ptr<RolloutModel> Clone() const = 0;
};

// Cost plug-in: the state-dependent cost of `count` samples after horizon step `step` (states
// reached by applying `controls`). May normalise across the batch (the original's min-max
// normalised goal distance), which is why it sees all samples at once. Non-const: a cost may
// keep scratch buffers.
class RolloutCost {
 public:
  virtual ~RolloutCost() = default;
  virtual void Evaluate(int step, const PlannerState* states, const MppiControl* controls,
                        int count, double* cost) = 0;
  virtual std::unique_ptr<RolloutCost> Clone() const = 0;
};

// How the per-step costs make a sample's total.
enum class CostAccumulation {
  kSum,        // sum over the horizon (MPPI as published; the intent)
  kLastStep,   // only the last step counts: the original overwrites its running cost each step
};

// The control (importance-sampling) term of a step, per sample: lambda * u^T Sigma^-1 eps.
enum class ControlCostForm {
  kSigned,     // lambda * sum_d u_d eps_d / var_d (standard MPPI)
  kAbsHalf,    // 0.5 * sum_d |lambda * u_d eps_d / var_d| (the original)
};

// What happens to the nominal sequence after its first command has been used.
enum class WarmStart {
  kShiftHoldLast,  // drop the first, repeat the last (standard receding horizon)
  kRollCyclic,     // the original's torch.roll: the used first command moves to the end
};

struct MppiParams {
  int horizon_steps = 20;                 // T
  int samples = 800;                      // K
  double temperature = 0.1;               // lambda
  // Noise covariance diagonal (the original's noise "sigma" (0.2, 0.5) is the covariance of
  // its multivariate normal, as in pytorch_mppi, from which its planners derive).
  MppiControl noise_variance = {0.2, 0.5};
  MppiControl u_min = {0.45, -1.0};
  MppiControl u_max = {0.6, 1.0};
  // Added to every normalised weight (the original adds 1e-6; 0 is textbook MPPI).
  double weight_floor = 0.0;
  CostAccumulation accumulation = CostAccumulation::kSum;
  ControlCostForm control_cost = ControlCostForm::kSigned;
  WarmStart warm_start = WarmStart::kShiftHoldLast;
};

class MppiCore {
 public:
  explicit MppiCore(const MppiParams& params = MppiParams());

  // Nominal sequence back to zeros (the original's start) and the noise stream to `seed`.
  void Reset(uint64_t seed);

  // One MPPI iteration from `start` with bounds [u_min, u_max] for this update (a caller may
  // widen them, as the original does near the goal). Returns the first command of the updated
  // nominal sequence; the sequence is then shifted (warm start).
  MppiControl Update(const PlannerState& start, const RolloutModel& model, RolloutCost& cost,
                     const MppiControl& u_min, const MppiControl& u_max);
  MppiControl Update(const PlannerState& start, const RolloutModel& model, RolloutCost& cost) {
    return Update(start, model, cost, params_.u_min, params_.u_max);
  }

  const MppiParams& params() const { return params_; }
  // The nominal sequence (T commands; after Update: already shifted for the next update).
  const std::vector<MppiControl>& nominal() const { return nominal_; }
  // Of the last update, per sample: total cost and normalised weight.
  const std::vector<double>& costs() const { return total_cost_; }
  const std::vector<double>& weights() const { return weights_; }
  // Of the last update: the sampled commands of sample k at step t (after clamping).
  const MppiControl& sampled(int t, int k) const {
    return controls_[static_cast<size_t>(t) * params_.samples + k];
  }
  // The last state of each sample's rollout (K states).
  const std::vector<PlannerState>& final_states() const { return state_a_; }

  // Sets the nominal sequence (tests; a planner seeding its first guess).
  void SetNominal(const std::vector<MppiControl>& u);

 private:
  MppiParams params_;
  Rng rng_;
  std::vector<MppiControl> nominal_;     // T
  std::vector<MppiControl> controls_;    // T x K (step-major: one batch per step)
  std::vector<MppiControl> noise_;       // T x K, effective noise = control - nominal
  std::vector<PlannerState> state_a_, state_b_;  // K each, current / next
  std::vector<double> stage_cost_;       // K
  std::vector<double> total_cost_;       // K
  std::vector<double> weights_;          // K
};

}  // namespace vb::controllers
