// Recording an episode for a dataset (docs/datasets.md): an Episode is driven by a SamplePolicy
// every physics step (5 ms, as RunTrial), and every `sample_every_steps` a sample is taken: the
// gym interface's observation (state, wheels, egocentric crops), the full robot state, the
// command, wheel contact, sinkage and surface class, and the navigation. Between two samples the
// transition's action, reward (vb_gym's default reward) and termination are kept. No I/O.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "vb/controllers/controller.h"
#include "vb/dataset/episode_record.h"
#include "vb/engine/runner/episode.h"
#include "vb/terrain/gt_maps.h"

namespace vb::dataset {

// An egocentric crop in every sample (gt_maps.h conventions: row 0 farthest ahead, column 0 the
// far left; size x size cells of side resolution_m x the world scale).
struct CropSpec {
  std::string name;   // key in observations/ (e.g. "elevation")
  terrain::MapLayer layer = terrain::MapLayer::kElevation;
  int size_cells = 64;
  double resolution_m = 0.1;
};

struct SampleConfig {
  int sample_every_steps = 20;   // 0.1 s at the 5 ms physics step: vb_gym's control period
  std::vector<CropSpec> crops;   // elevation crops are relative to the chassis height (vb_gym)
};

// vb_gym's two action spaces (docs/gym.md): speed = Box(2): steering, target speed / 4 m/s;
// direct = Box(3): 2 throttle - 1, steering, 2 braking - 1.
enum class ActionKind { kSpeed, kDirect };
int ActionSize(ActionKind kind);
const char* ActionKindName(ActionKind kind);

// What drives the episode.
class SamplePolicy {
 public:
  virtual ~SamplePolicy() = default;
  // The command for the next physics step.
  virtual controllers::Command Step(runner::Episode& episode) = 0;
  virtual ActionKind action_kind() const = 0;
  // kSpeed only: the action held since the last sample (called after the interval's first Step).
  virtual std::vector<double> HeldAction() const { return {}; }
};

// A mobility system (controllers::MakeController) as a policy, called every physics step as
// RunTrial does, so a re-simulated trial is bit-identical to vb_run's and vb_batch's. Its dataset
// action is the mean of the applied commands over the interval (direct space).
class ControllerPolicy : public SamplePolicy {
 public:
  explicit ControllerPolicy(std::unique_ptr<controllers::Controller> controller);
  // Sets the episode's observation config to the controller's and resets the controller; call
  // after Episode::Reset.
  void Start(runner::Episode& episode);
  controllers::Command Step(runner::Episode& episode) override;
  ActionKind action_kind() const override { return ActionKind::kDirect; }

 private:
  std::unique_ptr<controllers::Controller> controller_;
};

// Which physics steps are sampled: step `first_step` and every `sample_every_steps` after it,
// and always the episode's last step (the last interval may be shorter). Steps before
// first_step are driven but not recorded (a failure window). end_step >= 0 stops driving after
// that many physics steps even though the episode is not done (a teleoperated drive that its
// operator stopped): the record ends there with the outcome as it stands (Episode::Result).
struct RecordWindow {
  long first_step = 0;
  long end_step = -1;
};

// Drives `episode` (after Reset, and policy started) to its end and returns the record: columns
// of docs/datasets.md and the attributes status, message, sim_time_s, steps_recorded.
// Outcome rows: terminations at the last transition for success, rollover, out_of_bounds and
// sim_error; truncations for timeout and stuck (vb_gym's convention).
EpisodeRecord RecordEpisode(runner::Episode& episode, SamplePolicy& policy,
                            const SampleConfig& config, const RecordWindow& window = {});

// vb_gym's "state" vector (19 values, vb_gym.core.STATE_NAMES order) of an observation and the
// command applied during the last physics step.
constexpr int kGymStateSize = 19;
void GymState(const controllers::Observation& obs, const controllers::Command& applied,
              float* out);

// vb_gym's default reward of one transition (python/vb_gym/reward.py, RewardWeights defaults):
// dt the transition's length, prev_xy / xy / local_goal_xy the planar positions, status
// "running" or the outcome.
double GymReward(double dt_s, const Vec2& prev_xy, const Vec2& xy, const Vec2& local_goal_xy,
                 double roll_rad, double pitch_rad, const std::string& status,
                 double goal_distance_m);

}  // namespace vb::dataset
