// Registry of the mobility systems: the one place that maps a system name to its implementation.
#include "vb/controllers/controller.h"

#include "vb/controllers/pid_controller.h"

namespace vb::controllers {

std::vector<std::string> ControllerNames() { return {"pid"}; }

std::unique_ptr<Controller> MakeController(const std::string& name) {
  if (name == "pid") return std::make_unique<PidController>();
  return nullptr;
}

}  // namespace vb::controllers
