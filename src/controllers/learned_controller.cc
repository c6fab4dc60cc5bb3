// The learned baselines' controller: features -> MLP (Eigen, float32) -> steering + target speed.
#include "vb/controllers/learned_controller.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"

namespace vb::controllers {

namespace {

std::vector<nn::Activation> Activations(const nn::TensorSet& weights) {
  std::vector<nn::Activation> out;
  std::stringstream list(weights.meta("policy.activations"));
  std::string item;
  while (std::getline(list, item, ',')) {
    try {
      out.push_back(nn::ParseActivation(item));
    } catch (const InputError& e) {
      throw InputError(weights.source, 0, "policy.activations", e.what());
    }
  }
  return out;
}

}  // namespace

LearnedController::LearnedController(const std::string& name, const nn::TensorSet& weights)
    : name_(name) {
  if (weights.meta("format") != "vb-policy-1") {
    throw InputError(weights.source, 0, "format",
                     "expected 'vb-policy-1', got '" + weights.meta("format") + "'");
  }
  policy_ = nn::Mlp(weights, "policy", Activations(weights));
  if (policy_.input_size() != kLearnedFeatures || policy_.output_size() != 2) {
    throw InputError(weights.source, 0, "policy",
                     "expected " + std::to_string(kLearnedFeatures) + " inputs and 2 outputs, got " +
                         std::to_string(policy_.input_size()) + " and " +
                         std::to_string(policy_.output_size()));
  }
}

ObservationConfig LearnedController::observation_config() const {
  return LearnedObservationConfig();
}

void LearnedController::Reset(const EpisodeContext& context) {
  context_ = context;
  const double ratio = kLearnedDecisionPeriod_s / context.control_period_s;
  steps_per_decision_ = std::max(1, static_cast<int>(std::lround(ratio)));
  calls_ = 0;
  decisions_ = 0;
  steering_ = 0.0;
  target_speed_mps_ = 0.0;
  features_.fill(0.0f);
  action_.fill(0.0f);
}

std::array<float, 2> LearnedController::Mean(const float* features) const {
  std::array<float, 2> a{};
  policy_.Forward(features, a.data());
  return a;
}

std::array<float, 2> LearnedController::Act(const float* features) const {
  std::array<float, 2> a = Mean(features);
  for (float& v : a) v = std::clamp(v, -1.0f, 1.0f);
  return a;
}

Command LearnedController::Update(const Observation& obs) {
  if (calls_ % steps_per_decision_ == 0) {
    // The gym reports the steering applied in the last physics step: the held command, clamped.
    LearnedFeatures(obs, std::clamp(steering_, -1.0, 1.0), features_.data(),
                    context_.target_speed_mps);
    action_ = Act(features_.data());
    steering_ = static_cast<double>(action_[0]);
    target_speed_mps_ = static_cast<double>(action_[1]) * context_.target_speed_mps;
    ++decisions_;
  }
  ++calls_;
  Command command;
  command.steering = steering_;
  SpeedControl(target_speed_mps_, obs.forward_speed_mps, 1.0, &command);
  return command;
}

std::unique_ptr<Controller> LearnedController::Clone() const {
  return std::make_unique<LearnedController>(*this);
}

}  // namespace vb::controllers
