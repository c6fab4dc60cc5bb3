// Registry of the mobility systems: the one place that maps a system name to its implementation.
// "<system>_original" variants reproduce the original's code where it departs from the paper
// (docs/baselines.md lists each difference).
#include "vb/controllers/controller.h"

#include "vb/controllers/eh_controller.h"
#include "vb/controllers/learned_controller.h"
#include "vb/controllers/hybrid_controller.h"
#include "vb/controllers/mppi_controller.h"
#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"

namespace vb::controllers {

std::vector<std::string> ControllerNames() {
  return {"pid", "eh", "mppi", "rl", "mcl", "acl", "wmvct", "mppi6", "tal", "tnt",
          "pid_original", "eh_original", "mppi_original", "straight"};
}

std::unique_ptr<Controller> MakeController(const std::string& name, const nn::ModelStore* models) {
  if (name == "pid") return std::make_unique<PidController>();
  if (name == "eh") return std::make_unique<EhController>();
  if (name == "mppi") return std::make_unique<MppiController>();
  if (name == "wmvct") return MakeHybridController(HybridSystem::kWmvct, name, models);
  if (name == "mppi6") return MakeHybridController(HybridSystem::kMppi6, name, models);
  if (name == "tal") return MakeHybridController(HybridSystem::kTal, name, models);
  if (name == "tnt") return MakeHybridController(HybridSystem::kTnt, name, models);
  if (name == "pid_original") {
    PidParams p;
    p.original_planner = true;
    return std::make_unique<PidController>(p, name);
  }
  if (name == "eh_original") {
    EhParams p;
    p.original_left_regions = true;
    return std::make_unique<EhController>(p, name);
  }
  if (name == "mppi_original") return std::make_unique<MppiController>(MppiOriginalParams(), name);
  if (name == "straight") {
    PidParams p;
    p.straight_to_goal = true;
    return std::make_unique<PidController>(p, name);
  }
  if (name == "rl" || name == "mcl" || name == "acl") {
    // The policies trained in vb (docs/learning.md), data/policies/<name>.safetensors.
    if (models == nullptr) {
      throw InputError("", 0, "system",
                       "'" + name + "' is a learned system: it needs a model store for its weights");
    }
    return std::make_unique<LearnedController>(name,
                                               models->Load("policies/" + name + ".safetensors"));
  }
  return nullptr;
}

}  // namespace vb::controllers
