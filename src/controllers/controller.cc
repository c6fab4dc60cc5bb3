// Registry of the mobility systems: the one place that maps a system name to its implementation.
// "<system>_original" variants reproduce the original's code where it departs from the paper
// (docs/baselines.md lists each difference).
#include "vb/controllers/controller.h"

#include "vb/controllers/eh_controller.h"
#include "vb/controllers/mppi_controller.h"
#include "vb/controllers/pid_controller.h"

namespace vb::controllers {

std::vector<std::string> ControllerNames() {
  return {"pid", "eh", "mppi", "eh_original", "mppi_original"};
}

std::unique_ptr<Controller> MakeController(const std::string& name, const nn::ModelStore* models) {
  (void)models;   // no learned system registered yet
  if (name == "pid") return std::make_unique<PidController>();
  if (name == "eh") return std::make_unique<EhController>();
  if (name == "mppi") return std::make_unique<MppiController>();
  if (name == "eh_original") {
    EhParams p;
    p.original_left_regions = true;
    return std::make_unique<EhController>(p, name);
  }
  if (name == "mppi_original") return std::make_unique<MppiController>(MppiOriginalParams(), name);
  return nullptr;
}

}  // namespace vb::controllers
