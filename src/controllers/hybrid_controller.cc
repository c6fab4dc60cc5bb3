// The hybrid baselines' controller (hybrid_controller.h).
#include "vb/controllers/hybrid_controller.h"

#include <algorithm>
#include <cmath>

#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"

namespace vb::controllers {

namespace {
constexpr double kRateTolerance_s = 1e-9;
}  // namespace

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
      p.widen_near_goal = false;
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
      core_(params.core),
      model_(std::move(model)),
      trav_(std::move(trav)) {}

HybridController::HybridController(const HybridController& other)
    : system_(other.system_),
      params_(other.params_),
      name_(other.name_),
      context_(other.context_),
      core_(other.core_),
      model_(other.model_),
      trav_(other.trav_),
      cost_(other.cost_),
      last_update_s_(other.last_update_s_),
      planned_steering_(other.planned_steering_),
      steering_(other.steering_),
      updates_(other.updates_) {
  if (cost_) cost_->set_traversability(trav_ ? &*trav_ : nullptr);   // point at our own map
}

ObservationConfig HybridController::observation_config() const {
  ObservationConfig c;
  c.lookahead_m = params_.lookahead_m;
  c.replan_period_s = params_.replan_period_s;
  return c;
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
  last_update_s_ = -1e9;
  planned_steering_ = 0.0;
  steering_ = 0.0;
  updates_ = 0;
}

Command HybridController::Update(const Observation& obs) {
  if (obs.time_s - last_update_s_ >= params_.update_period_s - kRateTolerance_s) {
    last_update_s_ = obs.time_s;
    PlannerState start;
    start.x_m = obs.position_W.x();
    start.y_m = obs.position_W.y();
    start.z_m = obs.position_W.z();
    start.yaw_rad = obs.rpy.yaw_rad;
    start.roll_rad = obs.rpy.roll_rad;
    start.pitch_rad = obs.rpy.pitch_rad;
    // the traversability map once per update, at the vehicle's heading
    if (trav_) trav_->Update(*context_.maps, obs.position_W.head<2>(), obs.rpy.yaw_rad);
    cost_->set_goal(obs.local_goal_m, obs.position_W.head<2>());
    const Vec2 to_local_goal = obs.local_goal_m - obs.position_W.head<2>();
    const bool near = params_.widen_near_goal &&
                      to_local_goal.norm() < params_.near_goal_m * context_.scale;
    const MppiControl& lo = near ? params_.near_goal_u_min : params_.core.u_min;
    const MppiControl& hi = near ? params_.near_goal_u_max : params_.core.u_max;
    const MppiControl u = core_.Update(start, model_, *cost_, lo, hi);
    planned_steering_ = std::clamp(u[kMppiSteer], -1.0, 1.0);
    ++updates_;
  }
  if (params_.steering_rate_per_s > 0.0) {
    steering_ = RateLimitedSteering(planned_steering_, steering_,
                                    params_.steering_rate_per_s * context_.control_period_s);
  } else {
    steering_ = planned_steering_;
  }
  Command command;
  command.steering = steering_;
  SpeedControl(params_.target_speed_mps, obs.forward_speed_mps, params_.speed_kp, &command);
  return command;
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
