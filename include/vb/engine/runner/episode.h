// The episode: one trial of a task + pair + vehicle + system + seed, as an object that can be
// stepped, observed, snapshotted and restored (docs/architecture.md "Episode"); RunTrial is a
// short loop over it with a controller.
// Episode rules (docs/architecture.md §4): success when the reference point is within
// 10 m * scale (planar) of the goal before 60 s; out_of_bounds as soon as it leaves the world;
// otherwise at the end: rollover (|roll| > 30 deg), stuck (moved <= 1 m * scale in the last
// 10 s), timeout, or sim_error (numerical trouble). EpisodeRules::rule_set = kVertiBench
// decides success and stuck by the original's rules instead (outcome_rules.h).
// The core does no I/O: results come back as data; tools/io writes them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vb/controllers/controller.h"
#include "vb/engine/fixed_vector.h"
#include "vb/engine/runner/outcome_rules.h"
#include "vb/engine/runner/perception.h"
#include "vb/soil/soil_params.h"
#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::runner {

enum class TrialStatus { kSuccess, kRollover, kStuck, kTimeout, kSimError, kOutOfBounds };
constexpr int kNumTrialStatuses = 6;
std::string_view TrialStatusName(TrialStatus s);

// Optional wall-clock breakdown of the stepping loop (benchmarks only; timing never feeds back
// into the simulation, so results stay bit-identical with or without it). Seconds, summed.
struct StepTimings {
  double controller_s = 0.0;      // controller->Update
  double vehicle_sync_s = 0.0;    // SetInputs + Synchronize (suspension, powertrain, tires),
                                  // without the time spent in the soil
  double soil_s = 0.0;            // all time in the soil solver: the wheels' soil contact (called
                                  // from Synchronize) and EndStep; 0 on rigid worlds
  double physics_step_s = 0.0;    // Bullet multibody step (incl. chassis/obstacle collisions)
  double vehicle_update_s = 0.0;  // UpdateState (post-step read-out)
  double bookkeeping_s = 0.0;     // state checks, metrics, trajectory, success/failure rules
  double setup_s = 0.0;           // world, terrain mesh, planner grid, vehicle construction
  long steps = 0;
  // Soil solver counters of the last trial (zero on rigid worlds).
  long soil_contact_nodes = 0;    // node contacts summed over all wheel queries
  long soil_tiles = 0;            // grid tiles allocated
  size_t soil_memory_bytes = 0;   // tiles + tile index
};

// Longest time limit of a trial: one simulated hour (a benchmark trial is 60 s). It bounds the
// step counter and, with kMaxTrajectorySamples, the memory of a trajectory; tools check their
// --time-limit against it so the message names the flag.
constexpr double kMaxTimeLimit_s = 3600.0;
// Most samples a trajectory may keep (about 330 MB): time_limit / (step * every) must not exceed it.
constexpr long kMaxTrajectorySamples = 1000000;
// The benchmark's target speed (the original's CLI default) and the largest one a tool accepts.
constexpr double kDefaultTargetSpeed_mps = 4.0;
constexpr double kMaxTargetSpeed_mps = 40.0;

struct EpisodeRules {
  double step_s = 0.005;               // physics step (as the original)
  // Time one Episode::Step advances with its command held: a whole number of physics steps.
  // RunTrial calls its controller every physics step (the original's 200 Hz loop; controllers
  // keep their own slower rates inside); the gym interface defaults to 0.1 s.
  double control_period_s = 0.005;
  double time_limit_s = 60.0;
  // Target of the systems' speed controller (the original's CLI `speed`, default 4 m/s, the same
  // at every scale; the learned systems' speed action and speed observation are scaled by it).
  double target_speed_mps = kDefaultTargetSpeed_mps;
  // Which success and stuck rules decide the trial (outcome_rules.h): vb's (goal_radius_m,
  // stuck_distance_m over stuck_window_s) or the original's (8 m to the goal marker in 3-D, every
  // step below 2 m/s for stuck_window_s; both x task.scale). Default vb.
  RuleSet rule_set = RuleSet::kVb;
  double goal_radius_m = 10.0;         // scaled by task.scale
  double rollover_roll_rad = 30.0 * kPi / 180.0;
  double tipped_roll_rad = 45.0 * kPi / 180.0;  // TrialResult::tipped: |roll| ever above this
  double stuck_window_s = 10.0;
  double stuck_distance_m = 1.0;       // scaled by task.scale
  double start_height_m = 0.5;         // drop height of the wheel bottoms above the terrain at
                                       // scale 1 (times the task's scale)
  bool end_early = true;               // stop once the failure is certain
  // Reaching the goal radius ends the trial as success. Off only for data collection that is
  // not about the goal (random exploration, docs/datasets.md): it drives until a failure.
  bool goal_ends_trial = true;
  int trajectory_every_n_steps = 1;    // trajectory decimation; 0: no trajectory at all
  // What the mobility system sees (docs/perception.md); default: ground truth.
  PerceptionParams perception;
  StepTimings* timings = nullptr;      // if set, the loop adds its wall-clock breakdown here
};

struct TrialSpec {
  int pair_index = 0;
  uint64_t seed = 0;
  std::string system = "pid";
  std::string vehicle = "hmmwv";
};

// Most wheels (or road wheels) a vehicle may have: per-step wheel records are stored inline.
constexpr size_t kMaxWheels = 20;   // the M113: 2 x 5 road wheels

// One row of the per-step trajectory.
struct TrajectorySample {
  double time_s = 0.0;
  Vec3 position_W = Vec3::Zero();
  Vec3 velocity_W = Vec3::Zero();
  double speed_mps = 0.0;
  Rpy rpy;
  double throttle = 0.0;
  double steering = 0.0;
  double braking = 0.0;
  int gear = 0;
  FixedVector<int, kMaxWheels> wheel_surface;        // SurfaceClass id under each wheel, -1 airborne
  FixedVector<double, kMaxWheels> wheel_sinkage_m;
};

// Aggregates of a signal over the trial (all steps).
struct SignalStats {
  double mean = 0.0;
  double var = 0.0;        // population variance
  double max = 0.0;
};

struct TrialResult {
  TrialSpec spec;
  std::string task_name;
  std::string perception = "none";     // perception preset (docs/perception.md)
  double target_speed_mps = kDefaultTargetSpeed_mps;  // EpisodeRules::target_speed_mps
  RuleSet rule_set = RuleSet::kVb;     // EpisodeRules::rule_set
  int missed_obstacles = 0;            // rocks and trees the perception missed this trial
  int phantom_rocks = 0;               // rocks it saw that are not there
  TrialStatus status = TrialStatus::kTimeout;
  std::string message;                 // why it ended (sim_error details)
  double sim_time_s = 0.0;             // simulated time when the trial ended
  double traversal_time_s = -1.0;      // time to goal for successes, -1 otherwise
  double final_goal_distance_m = 0.0;  // planar, under either rule set
  double path_length_m = 0.0;          // driven planar distance
  int obstacle_contacts = 0;           // contact events with rocks/trees (re-touch within 0.5 s: same event)
  // |roll| went above 45 deg at some step (a vehicle that rolls past it and falls back is not a
  // rollover by the paper's end-of-trial rule, but it tipped); the peaks are abs_*_deg.max.
  bool tipped = false;
  SignalStats roll_deg, pitch_deg, abs_roll_deg, abs_pitch_deg;
  SignalStats throttle, steering, abs_steering;
  double wall_time_s = 0.0;
  double real_time_factor = 0.0;       // sim_time / wall_time
  std::vector<TrajectorySample> trajectory;
};

// The mutable state of a running episode: vehicle multibody and internal states (tires,
// powertrain), soil deformation (touched tiles only), navigation, bookkeeping and the trajectory
// so far. Copyable, opaque. Made by Episode::Snapshot; restored by Episode::Restore into the same
// episode or another one built from the same task, vehicle, soil and rules (a planner that
// branches). The controller is not part of it: Controller::Clone copies one.
class EpisodeSnapshot {
 public:
  EpisodeSnapshot();
  ~EpisodeSnapshot();
  EpisodeSnapshot(const EpisodeSnapshot& other);
  EpisodeSnapshot& operator=(const EpisodeSnapshot& other);
  double time_s() const;

 private:
  friend class Episode;
  struct Data;
  std::unique_ptr<Data> data_;
};

class Episode {
 public:
  // Builds the static world of `task` (terrain, ground-truth maps, planning grid, obstacles),
  // keeping its own copies of the task, vehicle parameters and soil configuration. Throws
  // InputError for what cannot run: bad rules, a task with deformable patches but no soil
  // parameters, more wheels than kMaxWheels.
  Episode(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
          const EpisodeRules& rules = EpisodeRules(), const soil::SoilConfig* soil = nullptr);
  ~Episode();
  Episode(const Episode&) = delete;
  Episode& operator=(const Episode&) = delete;

  // What Observe() builds besides the robot state and navigation (crops); keeps across Reset.
  void SetObservationConfig(const controllers::ObservationConfig& config);

  // Starts a trial of pair spec.pair_index with spec.seed: the vehicle facing the goal, dropped
  // from the start height; time 0. Throws InputError for a pair index out of range.
  void Reset(const TrialSpec& spec);

  // Applies `command` (clamped to its ranges) for one control period, or until the episode ends
  // within it. A non-finite command ends the trial as sim_error. No effect once Done().
  void Step(const controllers::Command& command);

  // The observation of the current state (built on first call after Reset/Step/Restore).
  const controllers::Observation& Observe();

  bool Done() const;
  // The trial as it stands: when Done(), its final result; before, the outcome it would have if
  // it ended now. Wall time and real-time factor count from Reset.
  TrialResult Result() const;
  // As Result(), but moves the trajectory out (the episode's own is left empty): the cheap way
  // to end a trial.
  TrialResult TakeResult();

  EpisodeSnapshot Snapshot() const;
  // Continues from `snapshot` as if the steps since it never happened: stepping the same
  // commands gives the same bits. Rebuilds the per-trial world first if this episode has not
  // started the snapshot's pair.
  void Restore(const EpisodeSnapshot& snapshot);

  // Ends the trial now as sim_error with `message` (e.g. the controller failed).
  void EndWithSimError(const std::string& message);

  // What a controller knows when the trial starts (valid after Reset).
  const controllers::EpisodeContext& context() const;
  double time_s() const;
  long physics_steps() const;
  int steps_per_control_period() const;
  const vehicles::VehicleState& vehicle_state() const;
  const EpisodeRules& rules() const;
  const terrain::TaskSpec& task() const;
  const vehicles::VehicleParams& vehicle_params() const;
  // The soil parameters given at construction, nullptr if none.
  const soil::SoilConfig* soil_config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Runs one trial: RunTrial = Episode + the controller named by spec.system, stepped every physics
// step until the trial is decided. Never throws for numerical trouble (that is kSimError); throws
// InputError only for a trial that cannot be set up (pair index out of range, unknown system, a
// task with deformable patches but no soil parameters). `soil` (loaded by io::LoadSoil) is needed
// only when the task has mud, sand or snow patches; `models` (io::DataDirModelStore) only for
// learned systems, which load their weights through it.
TrialResult RunTrial(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                     const TrialSpec& spec, const EpisodeRules& rules = EpisodeRules(),
                     const soil::SoilConfig* soil = nullptr,
                     const nn::ModelStore* models = nullptr);

// The same trial on an episode built beforehand from the task, vehicle, rules and soil: the
// identical result (bit for bit; the episode's static world does not change with trials), without
// building the static world again. vb_batch builds it once per world in the parent process and
// lets every forked trial of that world inherit it. Wall time counts from this call.
TrialResult RunTrial(Episode* episode, const TrialSpec& spec,
                     const nn::ModelStore* models = nullptr);

}  // namespace vb::runner
