// The hybrid baselines (reference_verti_bench.md §7.4-7.7): WMVCT, MPPI-6, TAL and TNT, the MPPI
// core (mppi_core.h) with learned kinodynamic models (hybrid_models.h) and their costs
// (hybrid_cost.h), replanned at 20 Hz towards the observation's local goal like MPPI; throttle and
// brake from the fixed-speed controller (4 m/s). The weights are trained in Python on vb's
// exploration data (docs/learning.md "Hybrid kinodynamic models") and loaded through a
// nn::ModelStore ("models/<system>.safetensors"). docs/baselines.md "Hybrid systems": parameters,
// the original's quirks and what vb does instead.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "vb/controllers/controller.h"
#include "vb/controllers/hybrid_cost.h"
#include "vb/controllers/hybrid_models.h"
#include "vb/controllers/mppi_core.h"
#include "vb/controllers/mppi_front_end.h"
#include "vb/controllers/traversability_map.h"
#include "vb/nn/model_store.h"

namespace vb::controllers {

enum class HybridSystem { kWmvct, kMppi6, kTal, kTnt };

struct HybridControllerParams {
  MppiParams core;
  BicycleModelParams bicycle;               // bicycle.scale is set from the episode
  HybridCostParams cost;
  TraversabilityMapParams trav;
  MppiFrontEndParams front;                 // as MPPI (MPPI-6: no near-goal widening)
  double steering_rate_per_s = 0.0;         // 0: none; MPPI-6: 10 (0.05 per 5 ms, as PID)
  uint64_t seed_salt = 0x485942ull;         // "HYB" (xor the system index)
};

// Each system's parameters (the intent; docs/baselines.md lists the original's values).
HybridControllerParams HybridDefaultParams(HybridSystem system);
const char* HybridSystemName(HybridSystem system);

class HybridController : public Controller {
 public:
  // model: the system's rollout model (WMVCT, MPPI-6, TAL; TNT uses TAL's); trav: TNT's map.
  HybridController(HybridSystem system, const HybridControllerParams& params,
                   HybridRolloutModel model, std::optional<TraversabilityMap> trav,
                   std::string name);
  HybridController(const HybridController& other);
  HybridController& operator=(const HybridController&) = delete;

  std::string name() const override { return name_; }
  ObservationConfig observation_config() const override;
  void Reset(const EpisodeContext& context) override;
  Command Update(const Observation& obs) override;
  std::unique_ptr<Controller> Clone() const override;

  const MppiCore& core() const { return core_; }
  const HybridRolloutModel& model() const { return model_; }
  const TraversabilityMap* traversability() const { return trav_ ? &*trav_ : nullptr; }
  long updates() const { return front_.updates(); }

 private:
  HybridSystem system_;
  HybridControllerParams params_;
  std::string name_;
  EpisodeContext context_;
  MppiFrontEnd front_;
  MppiCore core_;
  HybridRolloutModel model_;
  std::optional<TraversabilityMap> trav_;
  std::optional<HybridCost> cost_;
  double planned_steering_ = 0.0;
  double steering_ = 0.0;
};

// The registry's entry: builds `name` (wmvct, mppi6, tal, tnt) with the weights of
// models/<wmvct|mppi6|tal|tnt>.safetensors (TNT: tnt + tal). Throws InputError without a store or
// when a file does not fit its networks.
std::unique_ptr<Controller> MakeHybridController(HybridSystem system, const std::string& name,
                                                 const nn::ModelStore* models);

}  // namespace vb::controllers
