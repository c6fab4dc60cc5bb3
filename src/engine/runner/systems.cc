// System names -> implementations: the controller registry plus the oracle (systems.h).
#include "vb/engine/runner/systems.h"

#include <algorithm>

#include "vb/engine/error.h"
#include "vb/engine/runner/oracle.h"

namespace vb::runner {

std::vector<std::string> SystemNames() {
  std::vector<std::string> names = controllers::ControllerNames();
  names.push_back("oracle");
  return names;
}

void ValidateSystemName(const std::string& name, const std::string& key) {
  if (IsOracleName(name)) {
    ParseOracleName(name, key);  // throws for a bad budget
    return;
  }
  const std::vector<std::string> registry = controllers::ControllerNames();
  if (std::find(registry.begin(), registry.end(), name) != registry.end()) return;
  std::string valid;
  for (const std::string& n : SystemNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("", 0, key, "unknown system '" + name + "'; valid: " + valid);
}

std::unique_ptr<controllers::Controller> MakeSystem(const std::string& name,
                                                    const Episode& episode,
                                                    const nn::ModelStore* models) {
  if (IsOracleName(name)) {
    return std::make_unique<OracleController>(&episode, ParseOracleName(name), name);
  }
  ValidateSystemName(name);
  return controllers::MakeController(name, models);
}

}  // namespace vb::runner
