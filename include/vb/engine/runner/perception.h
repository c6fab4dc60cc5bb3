// Imperfect perception (docs/perception.md): errors applied to what the mobility systems see,
// in the observation builder only; the physics and the outcome rules never see them.
//
// What is modelled, each drawn from the trial seed (deterministic):
//  - pose estimate: a constant bias per trial, a random walk (drift) and a first-order
//    Gauss-Markov noise (white when its correlation time is 0) on position and yaw; noise on
//    roll and pitch; white noise on the linear and angular velocities;
//  - elevation map: a per-cell error fixed for the trial (the map the vehicle built), square holes
//    (NaN: unknown), and a mapping delay (the crops are registered at the pose of that long ago);
//  - semantics: each map cell's class replaced through a confusion matrix (row: true class,
//    column: perceived), fixed for the trial; the friction a system reads follows the perceived
//    class;
//  - obstacles: each rock and tree missed with a probability, phantom rocks at a rate per
//    hectare; the planning grid and the occupancy crops are built from what is perceived;
//  - latency: the whole observation describes the state of that long ago.
// The map errors are fields over world cells of side map_cell_m (hashed from the trial seed and
// the cell index, so they cost no storage and agree between observations and layers).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "vb/controllers/observation.h"
#include "vb/engine/rng.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/gt_maps.h"
#include "vb/terrain/surface_class.h"
#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle.h"

namespace vb::runner {

// Row: true class, column: perceived class; rows sum to 1.
using ConfusionMatrix =
    std::array<std::array<double, terrain::kNumSurfaceClasses>, terrain::kNumSurfaceClasses>;

// The classes each class is mistaken for, with equal shares of its error rate (by appearance:
// bare soils among themselves, hard surfaces among themselves, snow for pale hard ground).
ConfusionMatrix ConfusionFromErrorRate(double error_rate);

struct PerceptionParams {
  std::string name = "none";          // preset or file name (provenance, file names)

  // --- pose estimate (world frame; per axis) ---
  double position_bias_sd_m = 0.0;         // x, y: constant per trial
  double position_drift_m_per_sqrt_s = 0.0;  // x, y: random walk intensity
  double position_noise_sd_m = 0.0;        // x, y, z: Gauss-Markov, stationary standard deviation
  double yaw_bias_sd_rad = 0.0;
  double yaw_drift_rad_per_sqrt_s = 0.0;
  double yaw_noise_sd_rad = 0.0;
  double attitude_noise_sd_rad = 0.0;      // roll, pitch (Gauss-Markov)
  double noise_correlation_s = 0.0;        // of the Gauss-Markov noises; 0: white per observation
  double velocity_noise_sd_mps = 0.0;      // each axis of the velocity; white
  double angular_velocity_noise_sd_radps = 0.0;  // each axis; white

  // --- maps ---
  double map_cell_m = 0.1;                 // cell of the map error fields (times the env scale)
  double elevation_noise_sd_m = 0.0;       // per cell, fixed per trial (times the env scale)
  double elevation_hole_fraction = 0.0;    // of the map area, in square holes
  double elevation_hole_size_m = 1.0;      // side of a hole (times the env scale)
  double mapping_delay_s = 0.0;            // crops at the pose of this long ago
  ConfusionMatrix semantics_confusion = ConfusionFromErrorRate(0.0);

  // --- obstacles ---
  double obstacle_miss_probability = 0.0;  // per rock and per tree, per trial
  double phantom_rocks_per_ha = 0.0;       // phantom rocks per 10 000 m^2 of (scaled) world

  // --- the whole observation ---
  double latency_s = 0.0;

  // True when any error is configured (`none` is exactly ground truth).
  bool Enabled() const;
  bool HasObstacleErrors() const {
    return obstacle_miss_probability > 0.0 || phantom_rocks_per_ha > 0.0;
  }
  bool HasSemanticErrors() const;
};

// Throws InputError(source, 0, key, ...) for out-of-range values (the loader in tools/io names
// the line; this check is the one place the ranges live).
void ValidatePerception(const PerceptionParams& p, const std::string& source);

// Errors of the pose estimate at one time (world frame).
struct PoseError {
  Vec3 position_m = Vec3::Zero();
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;
};

// Everything of the model that changes during a trial: part of an episode snapshot.
struct PerceptionState {
  Rng rng{0};
  double last_update_s = 0.0;
  Vec2 position_bias_m = Vec2::Zero();
  Vec2 position_drift_m = Vec2::Zero();
  Vec3 position_noise_m = Vec3::Zero();
  double yaw_bias_rad = 0.0;
  double yaw_drift_rad = 0.0;
  double yaw_noise_rad = 0.0;
  double roll_noise_rad = 0.0;
  double pitch_noise_rad = 0.0;
  // Vehicle states of the last history_size physics steps (for latency and mapping delay):
  // state of step k at history[k % size].
  std::vector<vehicles::VehicleState> history;
  long last_recorded_step = -1;
};

class PerceptionModel {
 public:
  PerceptionModel() = default;
  // `step_s`: the physics step (the history is per physics step).
  PerceptionModel(const PerceptionParams& params, double step_s);

  const PerceptionParams& params() const { return params_; }
  bool enabled() const { return enabled_; }
  bool needs_history() const { return history_steps_ > 0; }
  double step_s() const { return step_s_; }

  // New trial with `trial_seed`: draws the bias, clears drift, noise and history, and builds the
  // perceived obstacles of `task` (misses, phantoms) into the perceived grids.
  void Reset(uint64_t trial_seed, const terrain::TaskSpec& task);

  // Records the vehicle state after physics step k (k = 0: the start state).
  void Record(long k, const vehicles::VehicleState& s);
  // The state the observation at step k describes (latency), and the one its crops are
  // registered at (latency + mapping delay); the current one without history.
  const vehicles::VehicleState& Delayed(long k, long delay_steps,
                                        const vehicles::VehicleState& current) const;
  long latency_steps() const { return latency_steps_; }
  long crop_delay_steps() const { return latency_steps_ + mapping_delay_steps_; }

  // Advances the pose errors to time t_s (non-decreasing) and returns them.
  PoseError AdvanceTo(double t_s);
  // Velocity noises of one observation (white).
  Vec3 VelocityNoise();
  Vec3 AngularVelocityNoise();

  // Applies the map errors to a crop of `layer` centred at position_m facing yaw_rad (the crop
  // conventions of gt_maps.h). Elevation: the cell error and holes; semantics: confusion;
  // friction: the perceived class's mean friction where the class was confused; occupancy: the
  // perceived obstacles (replaces the values). A friction crop needs the true semantics crop of
  // the same pose and size (`true_semantics`; unused for the other layers).
  void ApplyToCrop(terrain::MapLayer layer, const Vec2& position_m, double yaw_rad,
                   const terrain::GridMap* true_semantics, terrain::GridMap* crop) const;

  // The perceived obstacles of this trial (valid after Reset; only with obstacle errors).
  const terrain::OccupancyGrid& perceived_bare() const { return perceived_bare_; }
  const terrain::OccupancyGrid& perceived_inflated() const { return perceived_inflated_; }
  int missed_obstacles() const { return missed_; }
  int phantom_rocks() const { return phantoms_; }

  // Map error fields at a world point (exposed for tests and pictures).
  double ElevationError(const Vec2& p_m) const;
  bool IsHole(const Vec2& p_m) const;
  int PerceivedClass(int true_class, const Vec2& p_m) const;

  const PerceptionState& state() const { return state_; }
  void set_state(const PerceptionState& s) { state_ = s; }

 private:
  uint64_t CellHash(uint64_t salt, double cell_m, const Vec2& p_m) const;

  PerceptionParams params_;
  bool enabled_ = false;
  double step_s_ = 0.005;
  double scale_ = 1.0;
  long latency_steps_ = 0;
  long mapping_delay_steps_ = 0;
  long history_steps_ = 0;
  uint64_t map_seed_ = 0;
  PerceptionState state_;
  terrain::OccupancyGrid perceived_bare_;
  terrain::OccupancyGrid perceived_inflated_;
  int missed_ = 0;
  int phantoms_ = 0;
};

}  // namespace vb::runner
