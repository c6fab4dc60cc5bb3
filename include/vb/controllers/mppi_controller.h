// MPPI baseline (reference_verti_bench.md §7.3): the MPPI core with the kinematic bicycle model
// and the goal + obstacle cost, replanned at 20 Hz towards the observation's local goal (10 m *
// scale ahead on the A* path); steering = the first planned command, held between updates, no
// rate limit; throttle and brake from the fixed-speed controller (4 m/s), as the original, whose
// own speed output is computed but never used. docs/baselines.md: parameters and quirks.
#pragma once

#include <memory>
#include <optional>

#include "vb/controllers/bicycle_model.h"
#include "vb/controllers/controller.h"
#include "vb/controllers/mppi_core.h"
#include "vb/controllers/mppi_front_end.h"
#include "vb/controllers/mppi_goal_cost.h"

namespace vb::controllers {

struct MppiControllerParams {
  MppiParams core;
  BicycleModelParams model;                 // model.scale is set from the episode
  GoalObstacleCostParams cost;
  // The 20 Hz update, the local goal, the near-goal bounds, the fixed-speed throttle.
  MppiFrontEndParams front;
  uint64_t seed_salt = 0x4D505049ull;       // "MPPI": its noise stream differs from other users'
};

// The published behaviour (the intent): costs summed over the horizon, textbook control cost and
// warm start, obstacle map looked up where the rollout is, steps along the heading.
MppiControllerParams MppiIntentParams();
// The original's code: last-step-only cost, |.|/2 control cost, cyclic roll, transposed obstacle
// lookup, sideways step direction, 1e-6 weight floor.
MppiControllerParams MppiOriginalParams();

class MppiController : public Controller {
 public:
  explicit MppiController(const MppiControllerParams& params = MppiIntentParams(),
                          std::string name = "mppi");
  std::string name() const override { return name_; }
  ObservationConfig observation_config() const override;
  void Reset(const EpisodeContext& context) override;
  Command Update(const Observation& obs) override;
  std::unique_ptr<Controller> Clone() const override;

  const MppiCore& core() const { return core_; }
  long updates() const { return front_.updates(); }

 private:
  MppiControllerParams params_;
  std::string name_;
  EpisodeContext context_;
  MppiFrontEnd front_;
  MppiCore core_;
  BicycleModel model_;
  std::optional<GoalObstacleCost> cost_;
  double steering_ = 0.0;
};

}  // namespace vb::controllers
