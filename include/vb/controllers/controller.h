// The one interface of all mobility systems. A controller sees observations and ground-truth
// maps, never the physics engine. Update() is called every physics step; the controller decides
// internally when to recompute (its own rate).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vb/engine/types.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/task.h"

namespace vb::controllers {

struct Observation {
  double time_s = 0.0;
  Vec3 position_W = Vec3::Zero();     // chassis reference point
  Rpy rpy;
  Vec3 velocity_W = Vec3::Zero();
  double forward_speed_mps = 0.0;
};

struct Command {
  double throttle = 0.0;   // [0, 1]
  double steering = 0.0;   // [-1, 1], +1 = left
  double braking = 0.0;    // [0, 1]
};

// What a controller knows about the task when an episode starts (ground truth, as the original).
struct EpisodeContext {
  const terrain::TaskSpec* task = nullptr;
  const terrain::OccupancyGrid* inflated_obstacles = nullptr;  // planning grid
  Vec2 goal_m = Vec2::Zero();
  double scale = 1.0;        // environment scale (look-ahead etc. scale with it)
  double step_s = 0.005;     // physics step
  uint64_t seed = 0;         // trial seed: the only source of randomness a controller may use
};

class Controller {
 public:
  virtual ~Controller() = default;
  virtual std::string name() const = 0;
  virtual void Reset(const EpisodeContext& context) = 0;
  virtual Command Update(const Observation& obs) = 0;
};

// Names of all available systems, and a factory; nullptr for an unknown name.
std::vector<std::string> ControllerNames();
std::unique_ptr<Controller> MakeController(const std::string& name);

}  // namespace vb::controllers
