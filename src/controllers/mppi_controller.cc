// MPPI baseline controller (mppi_controller.h).
#include "vb/controllers/mppi_controller.h"

namespace vb::controllers {

MppiControllerParams MppiIntentParams() { return MppiControllerParams(); }

MppiControllerParams MppiOriginalParams() {
  MppiControllerParams p;
  p.core.accumulation = CostAccumulation::kLastStep;
  p.core.control_cost = ControlCostForm::kAbsHalf;
  p.core.warm_start = WarmStart::kRollCyclic;
  p.core.weight_floor = 1e-6;
  p.model.original_step_direction = true;
  p.cost.original_transposed_lookup = true;
  return p;
}

MppiController::MppiController(const MppiControllerParams& params, std::string name)
    : params_(params),
      name_(std::move(name)),
      front_(params.front),
      core_(params.core),
      model_(params.model) {}

ObservationConfig MppiController::observation_config() const { return front_.observation_config(); }

void MppiController::Reset(const EpisodeContext& context) {
  context_ = context;
  BicycleModelParams model = params_.model;
  model.scale = context.scale;
  model_ = BicycleModel(model);
  const terrain::GridMap* obstacles =
      context.maps != nullptr ? &context.maps->World(terrain::MapLayer::kOccupancy) : nullptr;
  const double size_x = context.task != nullptr ? context.task->size_x_m : 0.0;
  const double size_y = context.task != nullptr ? context.task->size_y_m : 0.0;
  cost_.emplace(params_.cost, obstacles, size_x, size_y);
  core_.Reset(context.seed ^ params_.seed_salt);
  front_.Reset(context.target_speed_mps);
  steering_ = 0.0;
}

Command MppiController::Update(const Observation& obs) {
  if (front_.Due(obs)) {
    cost_->set_goal(obs.local_goal_m);
    steering_ = front_.Plan(obs, context_.scale, core_, model_, *cost_);
  }
  return front_.Drive(obs, steering_);
}

std::unique_ptr<Controller> MppiController::Clone() const {
  return std::make_unique<MppiController>(*this);
}

}  // namespace vb::controllers
