// The one interface of all mobility systems. A controller sees observations and ground-truth
// maps, never the physics engine. Update() is called once per control period of the episode
// (EpisodeRules::control_period_s; RunTrial uses one physics step, 5 ms, as the original); the
// controller decides internally when to recompute (its own rate).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vb/controllers/observation.h"
#include "vb/engine/types.h"
#include "vb/nn/model_store.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/gt_maps.h"
#include "vb/terrain/task.h"

namespace vb::controllers {

struct Command {
  double throttle = 0.0;   // [0, 1]
  double steering = 0.0;   // [-1, 1], +1 = left
  double braking = 0.0;    // [0, 1]
};

// What a controller knows about the task when an episode starts (ground truth, as the original).
struct EpisodeContext {
  const terrain::TaskSpec* task = nullptr;
  const terrain::OccupancyGrid* inflated_obstacles = nullptr;  // planning grid
  // Whole-world ground-truth layers (elevation, semantics, friction, bare obstacle footprints),
  // for systems that look beyond the observation's crops (e.g. along their rollouts).
  const terrain::GroundTruthMaps* maps = nullptr;
  Vec2 goal_m = Vec2::Zero();
  double scale = 1.0;        // environment scale (look-ahead etc. scale with it)
  double step_s = 0.005;     // physics step
  double control_period_s = 0.005;  // time between two Update calls
  // The speed controller's target (EpisodeRules::target_speed_mps; the original's CLI `speed`).
  double target_speed_mps = 4.0;
  uint64_t seed = 0;         // trial seed: the only source of randomness a controller may use
};

class Controller {
 public:
  virtual ~Controller() = default;
  virtual std::string name() const = 0;
  // What the controller needs in its observations besides the robot state and the navigation
  // (crops); asked once, before the episode starts.
  virtual ObservationConfig observation_config() const { return ObservationConfig(); }
  virtual void Reset(const EpisodeContext& context) = 0;
  virtual Command Update(const Observation& obs) = 0;
  // A copy with the same internal state (what a branching planner or a snapshot of a whole trial
  // needs: the episode's Snapshot covers the world, this the controller).
  virtual std::unique_ptr<Controller> Clone() const = 0;
};

// Names of all available systems, and a factory; nullptr for an unknown name. Learned systems
// load their weights through `models` (the tools pass io::DataDirModelStore); asking for one
// without a store throws InputError.
std::vector<std::string> ControllerNames();
std::unique_ptr<Controller> MakeController(const std::string& name,
                                           const nn::ModelStore* models = nullptr);

}  // namespace vb::controllers
