// The mobility systems a trial can name: the controllers of the registry (controllers::
// MakeController, which see only observations) and the privileged expert, which needs the
// episode it drives (oracle.h). The one factory RunTrial, vb_collect and the tools use.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "vb/controllers/controller.h"

namespace vb::runner {

class Episode;

// The paper's systems and their "_original" variants (controllers::ControllerNames), then
// "oracle" (its budget variants "oracle-h..-r..-n..-e.." are valid too; oracle.h).
std::vector<std::string> SystemNames();
// Throws InputError (naming `key`, e.g. the flag) unless `name` can be made.
void ValidateSystemName(const std::string& name, const std::string& key = "system");
// The system `name` driving `episode` (which must outlive it); learned systems load their
// weights through `models` (controllers::MakeController). Throws InputError for an unknown name
// or an invalid oracle budget.
std::unique_ptr<controllers::Controller> MakeSystem(const std::string& name,
                                                    const Episode& episode,
                                                    const nn::ModelStore* models = nullptr);

}  // namespace vb::runner
