// The hybrid baselines' controller (hybrid_controller.h).
#include "vb/controllers/hybrid_controller.h"

#include <algorithm>
#include <cmath>

#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"

namespace vb::controllers {

const char* HybridSystemName(HybridSystem system) {
  switch (system) {
    case HybridSystem::kWmvct: return "wmvct";
    case HybridSystem::kMppi6: return "mppi6";
    case HybridSystem::kTal: return "tal";
    case HybridSystem::kTnt: return "tnt";
  }
  return "?";
}

HybridControllerParams HybridDefaultParams(HybridSystem system) {
  HybridControllerParams p;   // core: T 20, K 800, lambda 0.1, costs summed, textbook MPPI
  HybridCostParams& c = p.cost;
  switch (system) {
    case HybridSystem::kWmvct:
      // MPPI's cost, plus TAL's attitude terms on the learned roll and pitch (the original
      // computes them and never uses them)
      c.goal_weight = 10.0;
      c.obstacle_weight = 50.0;
      c.roll_weight = 2.0;
      c.pitch_weight = 1.0;
      break;
    case HybridSystem::kTal:
      c.goal_weight = 5.0;
      c.obstacle_weight = 4.0;
      c.roll_weight = 2.0;
      c.pitch_weight = 1.0;
      break;
    case HybridSystem::kTnt:
      c.goal_weight = 5.0;
      c.obstacle_weight = 4.0;
      c.trav_weight = 3.0;
      break;
    case HybridSystem::kMppi6:
      p.core.samples = 600;
      p.front.widen_near_goal = false;
      p.steering_rate_per_s = 10.0;
      // ackermann_bench: step = speed command in metres (0.45-0.6 m), wheelbase 3.4 m; the wheel
      // angle of MPPI's bicycle (0.6 rad at full steering; the original turned its wheels 1 rad)
      p.bicycle.step_length_per_speed_m = 1.0;
      p.bicycle.wheelbase_m = 3.4;
      c.goal_raw_weight = 1.0;
      c.heading_weight = 30.0;
      c.roll_weight = 1.0;
      c.pitch_weight = 0.5;
      c.attitude_normalised = false;
      break;
  }
  p.seed_salt ^= static_cast<uint64_t>(system) + 1;
  return p;
}

HybridController::HybridController(HybridSystem system, const HybridControllerParams& params,
                                   HybridRolloutModel model,
                                   std::optional<TraversabilityMap> trav, std::string name)
    : system_(system),
      params_(params),
      name_(std::move(name)),
      front_(params.front),
      core_(params.core),
      model_(std::move(model)),
      trav_(std::move(trav)) {}

HybridController::HybridController(const HybridController& other)
    : system_(other.system_),
      params_(other.params_),
      name_(other.name_),
      context_(other.context_),
      front_(other.front_),
      core_(other.core_),
      model_(other.model_),
      trav_(other.trav_),
      cost_(other.cost_),
      planned_steering_(other.planned_steering_),
      steering_(other.steering_) {
  if (cost_) cost_->set_traversability(trav_ ? &*trav_ : nullptr);   // point at our own map
}

ObservationConfig HybridController::observation_config() const {
  return front_.observation_config();
}

void HybridController::Reset(const EpisodeContext& context) {
  context_ = context;
  if (context.maps == nullptr) {
    throw InputError("", 0, name_, "the hybrid systems need the ground-truth maps (EpisodeContext::maps)");
  }
  BicycleModelParams bicycle = params_.bicycle;
  bicycle.scale = context.scale;
  model_.set_bicycle(bicycle);
  model_.set_terrain(&context.maps->terrain());
  const terrain::GridMap* obstacles = &context.maps->World(terrain::MapLayer::kOccupancy);
  const double size_x = context.task != nullptr ? context.task->size_x_m : 0.0;
  const double size_y = context.task != nullptr ? context.task->size_y_m : 0.0;
  cost_.emplace(params_.cost, obstacles, size_x, size_y, trav_ ? &*trav_ : nullptr);
  core_.Reset(context.seed ^ params_.seed_salt);
  front_.Reset(context.target_speed_mps);
  planned_steering_ = 0.0;
  steering_ = 0.0;
}

Command HybridController::Update(const Observation& obs) {
  if (front_.Due(obs)) {
    // the traversability map once per update, at the vehicle's heading
    if (trav_) trav_->Update(*context_.maps, obs.position_W.head<2>(), obs.rpy.yaw_rad);
    cost_->set_goal(obs.local_goal_m, obs.position_W.head<2>());
    planned_steering_ = front_.Plan(obs, context_.scale, core_, model_, *cost_);
  }
  if (params_.steering_rate_per_s > 0.0) {
    steering_ = RateLimitedSteering(planned_steering_, steering_,
                                    params_.steering_rate_per_s * context_.control_period_s);
  } else {
    steering_ = planned_steering_;
  }
  return front_.Drive(obs, steering_);
}

std::unique_ptr<Controller> HybridController::Clone() const {
  return std::make_unique<HybridController>(*this);
}

std::unique_ptr<Controller> MakeHybridController(HybridSystem system, const std::string& name,
                                                 const nn::ModelStore* models) {
  if (models == nullptr) {
    throw InputError("", 0, name, "system '" + name + "' needs its model weights (data/models/)");
  }
  const HybridControllerParams params = HybridDefaultParams(system);
  std::optional<TraversabilityMap> trav;
  switch (system) {
    case HybridSystem::kWmvct:
      return std::make_unique<HybridController>(
          system, params,
          HybridRolloutModel(params.bicycle, WmvctNetworks(models->Load("models/wmvct.safetensors"))),
          std::nullopt, name);
    case HybridSystem::kMppi6:
      return std::make_unique<HybridController>(
          system, params,
          HybridRolloutModel(params.bicycle, Mppi6Networks(models->Load("models/mppi6.safetensors"))),
          std::nullopt, name);
    case HybridSystem::kTnt:
      trav.emplace(models->Load("models/tnt.safetensors"), params.trav);
      [[fallthrough]];
    case HybridSystem::kTal:
      return std::make_unique<HybridController>(
          system, params,
          HybridRolloutModel(params.bicycle, TalNetworks(models->Load("models/tal.safetensors"))),
          std::move(trav), name);
  }
  return nullptr;
}

}  // namespace vb::controllers
