// vb's learned baselines RL, MCL and ACL (reference_verti_bench.md §7.8, docs/learning.md): a
// PPO policy trained in vb (python/vb_gym/train) on generated worlds, run here without torch.
// Every 0.1 s of observation time the policy maps the 76 learned features
// (learned_features.h) to an action in [-1, 1]^2: steering, held until the next decision, and a
// target speed x 4 m/s for the speed controller (kp 1), which runs at every Update as in the gym
// (the same commands as vb_gym with action "speed" and control_period_s 0.1).
//
// Weights: a safetensors file with the Sequential "policy" (Linear layers 0, 2, 4 of
// [out, in] float32; metadata "format" = "vb-policy-1" and "policy.activations", one activation
// per Linear layer, e.g. "tanh,tanh,none"), loaded by the registry through nn::ModelStore from
// data/policies/<system>.safetensors.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "vb/controllers/controller.h"
#include "vb/controllers/learned_features.h"
#include "vb/nn/mlp.h"
#include "vb/nn/tensor_set.h"

namespace vb::controllers {

class LearnedController : public Controller {
 public:
  // Throws InputError (file, tensor or metadata key) when the weights do not fit.
  LearnedController(const std::string& name, const nn::TensorSet& weights);
  std::string name() const override { return name_; }
  ObservationConfig observation_config() const override;
  void Reset(const EpisodeContext& context) override;
  Command Update(const Observation& obs) override;
  std::unique_ptr<Controller> Clone() const override;

  // The features and the action (clipped) of the last decision (tests, diagnostics).
  const std::array<float, kLearnedFeatures>& last_features() const { return features_; }
  const std::array<float, 2>& last_action() const { return action_; }
  int decisions() const { return decisions_; }
  // The policy's action mean (the network's output) and the action (clipped to [-1, 1]) for a
  // feature vector of kLearnedFeatures values.
  std::array<float, 2> Mean(const float* features) const;
  std::array<float, 2> Act(const float* features) const;

 private:
  std::string name_;
  nn::Mlp policy_;
  EpisodeContext context_;
  int steps_per_decision_ = 20;
  long calls_ = 0;
  int decisions_ = 0;
  double steering_ = 0.0;        // command held since the last decision
  double target_speed_mps_ = 0.0;
  std::array<float, kLearnedFeatures> features_{};
  std::array<float, 2> action_{};
};

}  // namespace vb::controllers
