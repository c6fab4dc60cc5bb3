// One trial: task + pair + vehicle + system + seed -> status, metrics and a trajectory.
// Episode rules (docs/architecture.md §4): success when the reference point is within
// 10 m * scale (planar) of the goal before 60 s; otherwise at the end: rollover (|roll| > 30 deg),
// stuck (moved <= 1 m * scale in the last 10 s), timeout, or sim_error (numerical trouble).
// The core does no I/O: results come back as data; tools/io writes them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/controllers/controller.h"
#include "vb/soil/soil_params.h"
#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::runner {

enum class TrialStatus { kSuccess, kRollover, kStuck, kTimeout, kSimError };
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

struct EpisodeRules {
  double step_s = 0.005;               // physics step (as the original)
  double time_limit_s = 60.0;
  double goal_radius_m = 10.0;         // scaled by task.scale
  double rollover_roll_rad = 30.0 * kPi / 180.0;
  double stuck_window_s = 10.0;
  double stuck_distance_m = 1.0;       // scaled by task.scale
  double start_height_m = 0.5;         // drop height of the wheel bottoms above the terrain
  bool end_early = true;               // stop once the failure is certain
  int trajectory_every_n_steps = 1;    // trajectory decimation
  StepTimings* timings = nullptr;      // if set, the loop adds its wall-clock breakdown here
};

struct TrialSpec {
  int pair_index = 0;
  uint64_t seed = 0;
  std::string system = "pid";
  std::string vehicle = "hmmwv";
};

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
  std::vector<int> wheel_surface;       // SurfaceClass id under each wheel, -1 if airborne
  std::vector<double> wheel_sinkage_m;
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
  TrialStatus status = TrialStatus::kTimeout;
  std::string message;                 // why it ended (sim_error details)
  double sim_time_s = 0.0;             // simulated time when the trial ended
  double traversal_time_s = -1.0;      // time to goal for successes, -1 otherwise
  double final_goal_distance_m = 0.0;
  double path_length_m = 0.0;          // driven planar distance
  int obstacle_contacts = 0;           // contact events with rocks/trees (re-touch within 0.5 s: same event)
  SignalStats roll_deg, pitch_deg, abs_roll_deg, abs_pitch_deg;
  SignalStats throttle, steering, abs_steering;
  double wall_time_s = 0.0;
  double real_time_factor = 0.0;       // sim_time / wall_time
  std::vector<TrajectorySample> trajectory;
};

// Runs one trial. Never throws for numerical trouble (that is kSimError); throws InputError only
// for a trial that cannot be set up (pair index out of range, unknown system, a task with
// deformable patches but no soil parameters). `soil` (loaded by io::LoadSoil) is needed only
// when the task has mud, sand or snow patches.
TrialResult RunTrial(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                     const TrialSpec& spec, const EpisodeRules& rules = EpisodeRules(),
                     const soil::SoilConfig* soil = nullptr);

}  // namespace vb::runner
