// The episode, docs/architecture.md "Episode": the static world of a task (built once), the
// per-trial world (physics, vehicle, soil; built by Reset), the physics step in the order the
// vehicle requires (SetInputs -> Synchronize -> soil EndStep -> world Step -> UpdateState), the
// state checks, the success and failure rules, and the bookkeeping (trial_metrics.h). No I/O.
#include "vb/engine/runner/episode.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "trial_metrics.h"
#include "vb/engine/error.h"
#include "vb/engine/physics_world.h"
#include "vb/engine/runner/observation_builder.h"
#include "vb/soil/scm_soil.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/gt_maps.h"
#include "vb/terrain/terrain.h"
#include "vb/terrain/obstacle_field.h"
#include "vb/terrain/terrain_physics.h"

namespace vb::runner {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kRadToDeg = 180.0 / kPi;
// A vehicle on its side or roof cannot recover on its own: the trial may stop there.
constexpr double kTippedOverRoll_rad = 0.5 * kPi;
// Beyond these the state is physically meaningless (10 km away from the world's box, which is
// 128 m wide at scale 1, and the HMMWV tops out near 40 m/s): a numerical blow-up, not driving.
constexpr double kAbsurdDistance_m = 1.0e4;
constexpr double kAbsurdSpeed_mps = 200.0;
// A touch of the same obstacle within this time is the same contact event.
constexpr double kContactGap_s = 0.5;
// The trajectory's storage is reserved for this much simulated time at most; longer trials grow
// it (amortised) rather than reserve gigabytes up front.
constexpr double kTrajectoryReserve_s = 60.0;

bool IsFinite(const Vec3& v) { return v.allFinite(); }

// Short human-readable number for messages (std::to_string prints six fixed decimals).
std::string Fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", x);
  return buf;
}

// Distance of p from the world's box (its rectangle times its height range; 0 inside): the
// divergence test measures how far the vehicle got from the world, not from the origin, so a
// world at 1000 km altitude is not a blow-up (DEF-15 of the probe).
double DistanceFromWorld(const terrain::TaskSpec& task, const Vec3& p) {
  const double hx = 0.5 * task.size_x_m;
  const double hy = 0.5 * task.size_y_m;
  const Vec3 nearest(std::clamp(p.x(), -hx, hx), std::clamp(p.y(), -hy, hy),
                     std::clamp(p.z(), task.min_height_m, task.max_height_m));
  return (p - nearest).norm();
}

// Empty string if the state is usable; otherwise why it is not.
std::string CheckState(const terrain::TaskSpec& task, const vehicles::VehicleState& s) {
  const Vec3& p = s.pose_W.position;
  if (!IsFinite(p) || !IsFinite(s.velocity_W) || !IsFinite(s.angular_velocity_W) ||
      !s.pose_W.rotation.coeffs().allFinite() || !std::isfinite(s.forward_speed_mps)) {
    return "non-finite vehicle state";
  }
  const double away_m = DistanceFromWorld(task, p);
  if (away_m > kAbsurdDistance_m) {
    return "vehicle position diverged (" + Fmt(away_m) + " m away from the world)";
  }
  if (s.velocity_W.norm() > kAbsurdSpeed_mps) {
    return "vehicle speed diverged (" + Fmt(s.velocity_W.norm()) + " m/s)";
  }
  return "";
}

// Times the wheels' soil contact, which the vehicle calls from inside Synchronize, so the step
// breakdown can report all soil work in one bucket. Used only when timings are asked for.
class TimedSoil : public soil::SoilContact {
 public:
  explicit TimedSoil(soil::ScmSoil* soil) : soil_(soil) {}
  soil::WheelSoilOutput WheelContact(const soil::WheelSoilInput& wheel, double dt) override {
    const auto t0 = Clock::now();
    const soil::WheelSoilOutput out = soil_->WheelContact(wheel, dt);
    seconds_ += std::chrono::duration<double>(Clock::now() - t0).count();
    return out;
  }
  soil::TrackSoilOutput TrackContact(const soil::TrackSoilInput& track, double dt) override {
    const auto t0 = Clock::now();
    const soil::TrackSoilOutput out = soil_->TrackContact(track, dt);
    seconds_ += std::chrono::duration<double>(Clock::now() - t0).count();
    return out;
  }
  void EndStep(double dt) override { soil_->EndStep(dt); }
  // Seconds of wheel contact since the last call.
  double TakeSeconds() {
    const double s = seconds_;
    seconds_ = 0.0;
    return s;
  }

 private:
  soil::ScmSoil* soil_;
  double seconds_ = 0.0;
};

bool HasDeformablePatches(const terrain::TaskSpec& task) {
  return std::any_of(task.patches.classes.begin(), task.patches.classes.end(),
                     [](terrain::SurfaceClass c) { return terrain::IsDeformable(c); });
}

// Physics steps per control period; InputError unless the period is a whole number of steps.
int StepsPerControlPeriod(const EpisodeRules& rules) {
  const double ratio = rules.control_period_s / rules.step_s;
  const long n = std::lround(ratio);
  if (!(n >= 1) || std::abs(ratio - static_cast<double>(n)) > 1e-9 * ratio || n > 1000000) {
    throw InputError("", 0, "control_period_s",
                     "must be a whole number (1 to 1e6) of physics steps of " +
                         Fmt(rules.step_s) + " s, got " + Fmt(rules.control_period_s) + " s");
  }
  return static_cast<int>(n);
}

void ValidateRules(const EpisodeRules& rules) {
  if (!(rules.step_s > 0.0) || !(rules.step_s <= 0.1)) {
    throw InputError("", 0, "step_s", "must be in (0, 0.1] s, got " + Fmt(rules.step_s));
  }
  if (!(rules.time_limit_s > 0.0) || !(rules.time_limit_s <= kMaxTimeLimit_s)) {
    throw InputError("", 0, "time_limit_s",
                     "must be in (0, " + Fmt(kMaxTimeLimit_s) + "] s, got " +
                         Fmt(rules.time_limit_s));
  }
  if (!(rules.target_speed_mps > 0.0) || !(rules.target_speed_mps <= kMaxTargetSpeed_mps)) {
    throw InputError("", 0, "target_speed_mps",
                     "must be in (0, " + Fmt(kMaxTargetSpeed_mps) + "] m/s, got " +
                         Fmt(rules.target_speed_mps));
  }
  if (rules.trajectory_every_n_steps < 0) {
    throw InputError("", 0, "trajectory_every_n_steps", "must be >= 0 (0: no trajectory)");
  }
  if (rules.trajectory_every_n_steps > 0) {
    const double samples = rules.time_limit_s / rules.step_s / rules.trajectory_every_n_steps;
    if (samples > static_cast<double>(kMaxTrajectorySamples)) {
      throw InputError("", 0, "trajectory_every_n_steps",
                       "a time limit of " + Fmt(rules.time_limit_s) + " s would keep " +
                           Fmt(samples) + " trajectory samples, at most " +
                           std::to_string(kMaxTrajectorySamples) +
                           " are kept: keep fewer steps (vb_run --traj-every)");
    }
  }
  if (!(rules.stuck_window_s > 0.0) || !(rules.stuck_window_s <= kMaxTimeLimit_s)) {
    throw InputError("", 0, "stuck_window_s", "must be in (0, " + Fmt(kMaxTimeLimit_s) + "] s");
  }
  if (rules.rule_set != RuleSet::kVb && rules.rule_set != RuleSet::kVertiBench) {
    throw InputError("", 0, "rule_set", "unknown rule set; valid: " + RuleSetNames());
  }
  StepsPerControlPeriod(rules);
  ValidatePerception(rules.perception, "perception '" + rules.perception.name + "'");
}

}  // namespace

std::string_view TrialStatusName(TrialStatus s) {
  switch (s) {
    case TrialStatus::kSuccess: return "success";
    case TrialStatus::kRollover: return "rollover";
    case TrialStatus::kStuck: return "stuck";
    case TrialStatus::kTimeout: return "timeout";
    case TrialStatus::kSimError: return "sim_error";
    case TrialStatus::kOutOfBounds: return "out_of_bounds";
  }
  return "unknown";
}

// Where a trial stands: step count, the decision so far, the inputs being applied.
struct Progress {
  long k = 0;                       // physics steps since Reset
  bool done = false;
  bool decided = false;             // status final before the end rules (success, sim_error)
  TrialStatus status = TrialStatus::kTimeout;
  std::string message;
  double traversal_time_s = -1.0;
  double final_goal_distance_m = 0.0;
  vehicles::DriverInputs inputs;    // applied during the last physics step
};

struct Episode::Impl {
  Impl(const terrain::TaskSpec& task_in, const vehicles::VehicleParams& vehicle_in,
       const EpisodeRules& rules_in, const soil::SoilConfig* soil_in)
      : task(task_in),
        vehicle_params(vehicle_in),
        rules(rules_in),
        soil_config(soil_in != nullptr ? std::optional<soil::SoilConfig>(*soil_in) : std::nullopt),
        ground(task),
        inflated(terrain::Inflate(terrain::RasterizeObstacles(task),
                                  terrain::PlannerInflationCells(task))),
        maps(task, /*inflation_cells=*/0),
        obstacles(task, ground),
        builder(maps, inflated, task.scale) {
    builder.SetPerception(rules.perception, rules.step_s);
  }

  // --- static world (per Episode; its own copies of the inputs) ---
  const terrain::TaskSpec task;
  const vehicles::VehicleParams vehicle_params;
  const EpisodeRules rules;
  const std::optional<soil::SoilConfig> soil_config;
  const terrain::Terrain ground;
  // The planning grid as the original: obstacle footprints dilated by 4 m * scale.
  const terrain::OccupancyGrid inflated;
  const terrain::GroundTruthMaps maps;   // bare obstacle footprints
  const terrain::ObstacleField obstacles;
  ObservationBuilder builder;
  int steps_per_period = 1;
  long max_steps = 1;
  // Physics sub-steps per step: a vehicle whose file limits the step (max_step_s, the 1/10-scale
  // Verti-Wheeler) runs the step as that many equal sub-steps with the inputs held.
  int substeps = 1;
  long window_steps = 1;
  long contact_gap_steps = 1;
  double stuck_distance_m = 1.0;
  double slow_step_m = 0.01;   // verti_bench rules: a step that moved less is slow

  // --- per trial (Reset) ---
  bool started = false;
  TrialSpec spec;
  Vec2 goal_m = Vec2::Zero();
  GoalRule goal;
  std::unique_ptr<engine::PhysicsWorld> world;
  std::unique_ptr<vehicles::Vehicle> vehicle;
  std::unique_ptr<soil::ScmSoil> soil;
  std::unique_ptr<TimedSoil> timed_soil;  // only when timings are asked for
  controllers::EpisodeContext context;
  Clock::time_point wall_start;
  Progress progress;
  TrialMetrics metrics;
  controllers::Observation observation;
  bool observation_valid = false;

  double Time() const { return static_cast<double>(progress.k) * rules.step_s; }
  void PhysicsStep();
  void Finish();
  // The stuck condition of the rule set, evaluated on the steps so far.
  bool Stuck() const;
  void Classify(TrialStatus* status, std::string* message) const;
  TrialResult MakeResult() const;
};

// One physics step with progress.inputs, then the checks and the bookkeeping of step k.
void Episode::Impl::PhysicsStep() {
  const double dt = rules.step_s;
  StepTimings* const timings = rules.timings;
  // Optional timing breakdown: a clock read between the stages, only when asked for.
  Clock::time_point mark;
  auto lap = [&](double* bucket) {
    if (timings == nullptr) return;
    const Clock::time_point now = Clock::now();
    *bucket += std::chrono::duration<double>(now - mark).count();
    mark = now;
  };
  if (timings != nullptr) {
    mark = Clock::now();
    ++timings->steps;
  }

  vehicle->SetInputs(progress.inputs);
  const double h = substeps == 1 ? dt : dt / substeps;
  for (int sub = 0; sub < substeps; ++sub) {
    vehicle->Synchronize(h);
    lap(timings != nullptr ? &timings->vehicle_sync_s : nullptr);
    if (soil) {
      soil->EndStep(h);
      lap(timings != nullptr ? &timings->soil_s : nullptr);
    }
    if (timed_soil) {  // the wheels' soil contact ran inside Synchronize: move it to soil_s
      const double contact_s = timed_soil->TakeSeconds();
      timings->vehicle_sync_s -= contact_s;
      timings->soil_s += contact_s;
    }
    world->Step(h);
    lap(timings != nullptr ? &timings->physics_step_s : nullptr);
    vehicle->UpdateState();
    lap(timings != nullptr ? &timings->vehicle_update_s : nullptr);
  }
  ++progress.k;
  const double t = Time();
  const vehicles::VehicleState& s = vehicle->state();
  builder.Record(progress.k, s);

  // Numerical trouble ends the trial as data, never as a crash.
  const std::string trouble =
      world->StateIsFinite() ? CheckState(task, s) : "non-finite physics state";
  if (!trouble.empty()) {
    progress.status = TrialStatus::kSimError;
    progress.message = trouble + " at t = " + Fmt(t) + " s";
    progress.decided = true;
    Finish();
    lap(timings != nullptr ? &timings->bookkeeping_s : nullptr);
    return;
  }

  metrics.AddStep(s, progress.inputs, rules.tipped_roll_rad);
  metrics.AddContacts(progress.k, world->ObstacleContacts(), vehicle->body(), task.rocks.size());
  const int every = rules.trajectory_every_n_steps;
  if (every > 0 && progress.k % every == 0) {
    metrics.trajectory().push_back(MakeSample(t, s, progress.inputs));
  }

  // Success, then the early ends of certain failures, then the time limit.
  const Vec2 xy = s.pose_W.position.head<2>();
  progress.final_goal_distance_m = (goal_m - xy).norm();
  if (rules.goal_ends_trial && goal.Reached(s.pose_W.position)) {
    progress.status = TrialStatus::kSuccess;
    progress.traversal_time_s = t;
    progress.message = rules.rule_set == RuleSet::kVb
                           ? "reached the goal"
                           : "reached the goal marker (" + Fmt(goal.Distance(s.pose_W.position)) +
                                 " m away in 3-D)";
    progress.decided = true;
    Finish();
  } else if (std::abs(xy.x()) > 0.5 * task.size_x_m || std::abs(xy.y()) > 0.5 * task.size_y_m) {
    // Off the edge of the world (the original's RL interface: "fallen off"): a failure of its own.
    progress.status = TrialStatus::kOutOfBounds;
    progress.message = "left the world at (" + Fmt(xy.x()) + ", " + Fmt(xy.y()) + ") m";
    progress.decided = true;
    Finish();
  } else if (rules.end_early && (std::abs(s.rpy.roll_rad) > kTippedOverRoll_rad || Stuck())) {
    Finish();
  } else if (progress.k >= max_steps) {
    Finish();
  }
  lap(timings != nullptr ? &timings->bookkeeping_s : nullptr);
}

bool Episode::Impl::Stuck() const {
  if (rules.rule_set == RuleSet::kVertiBench) {
    return metrics.slow_steps().slow_steps() >= window_steps;
  }
  return metrics.window().Full() && metrics.window().Displacement() <= stuck_distance_m;
}

// Failure type from the current state (architecture §4).
void Episode::Impl::Classify(TrialStatus* status, std::string* message) const {
  const vehicles::VehicleState& s = vehicle->state();
  const double final_roll = std::abs(s.rpy.roll_rad);
  if (final_roll > rules.rollover_roll_rad) {
    *status = TrialStatus::kRollover;
    *message = "rolled over (|roll| = " + Fmt(final_roll * kRadToDeg) + " deg at the end)";
  } else if (Stuck()) {
    *status = TrialStatus::kStuck;
    *message = rules.rule_set == RuleSet::kVb
                   ? "stuck (moved " + Fmt(metrics.window().Displacement()) + " m in the last " +
                         Fmt(rules.stuck_window_s) + " s)"
                   : "stuck (every step of the last " + Fmt(rules.stuck_window_s) +
                         " s below " + Fmt(slow_step_m / rules.step_s) + " m/s)";
  } else {
    *status = TrialStatus::kTimeout;
    *message = "time limit of " + Fmt(rules.time_limit_s) + " s reached";
  }
}

// The trial has ended: the last state closes the trajectory (unless it is the invalid state of a
// sim_error), and an undecided trial gets its failure type.
void Episode::Impl::Finish() {
  progress.done = true;
  observation_valid = false;
  const double t = Time();
  std::vector<TrajectorySample>& trajectory = metrics.trajectory();
  if (progress.status != TrialStatus::kSimError && rules.trajectory_every_n_steps > 0 &&
      (trajectory.empty() || trajectory.back().time_s != t)) {
    trajectory.push_back(MakeSample(t, vehicle->state(), progress.inputs));
  }
  if (!progress.decided) Classify(&progress.status, &progress.message);
  if (rules.timings != nullptr && soil) {
    const soil::ScmStats& st = soil->stats();
    rules.timings->soil_contact_nodes = st.contact_nodes;
    rules.timings->soil_tiles = st.tiles;
    rules.timings->soil_memory_bytes = st.memory_bytes;
  }
}

TrialResult Episode::Impl::MakeResult() const {
  TrialResult r;
  r.spec = spec;
  r.task_name = task.name;
  r.perception = rules.perception.name;
  r.target_speed_mps = rules.target_speed_mps;
  r.rule_set = rules.rule_set;
  r.missed_obstacles = builder.perception().missed_obstacles();
  r.phantom_rocks = builder.perception().phantom_rocks();
  r.status = progress.status;
  r.message = progress.message;
  if (!progress.done) Classify(&r.status, &r.message);
  r.sim_time_s = Time();
  r.traversal_time_s = progress.traversal_time_s;
  r.final_goal_distance_m = progress.final_goal_distance_m;
  metrics.Fill(&r);
  r.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  r.real_time_factor = r.wall_time_s > 0.0 ? r.sim_time_s / r.wall_time_s : 0.0;
  return r;
}

Episode::Episode(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                 const EpisodeRules& rules, const soil::SoilConfig* soil) {
  ValidateRules(rules);
  if (HasDeformablePatches(task) && soil == nullptr) {
    throw InputError(task.source_file, 0, "semantics.classes",
                     "the task has deformable patches (mud/sand/snow) but no soil parameters "
                     "were given (data/soils/*.yaml, vb_run --soil)");
  }
  if (vehicle.axles.size() * 2 > kMaxWheels) {
    throw InputError("", 0, "axles",
                     "vehicle '" + vehicle.name + "' has " + std::to_string(vehicle.axles.size()) +
                         " axles; at most " + std::to_string(kMaxWheels / 2) + " are supported");
  }
  impl_ = std::make_unique<Impl>(task, vehicle, rules, soil);
  Impl& m = *impl_;
  const double dt = rules.step_s;
  m.steps_per_period = StepsPerControlPeriod(rules);
  // Step counts instead of accumulated time: t = k * dt never drifts.
  m.max_steps = std::max(1L, std::lround(rules.time_limit_s / dt));
  m.window_steps = std::max(1L, std::lround(rules.stuck_window_s / dt));
  m.contact_gap_steps = std::lround(kContactGap_s / dt);
  m.stuck_distance_m = rules.stuck_distance_m * task.scale;
  m.slow_step_m = VertiBenchSlowStep_m(dt, task.scale);
}

Episode::~Episode() = default;

void Episode::SetObservationConfig(const controllers::ObservationConfig& config) {
  impl_->builder.SetConfig(config);
  impl_->observation_valid = false;
}

void Episode::Reset(const TrialSpec& spec) {
  Impl& m = *impl_;
  const terrain::TaskSpec& task = m.task;
  const int num_pairs = static_cast<int>(task.pairs.size());
  if (spec.pair_index < 0 || spec.pair_index >= num_pairs) {
    throw InputError(task.source_file, 0, "pair",
                     "pair index " + std::to_string(spec.pair_index) + " out of range; task '" +
                         task.name + "' has " + std::to_string(num_pairs) + " pairs (0.." +
                         std::to_string(num_pairs - 1) + ")");
  }
  m.wall_start = Clock::now();
  m.spec = spec;
  const terrain::StartGoalPair& pair = task.pairs[static_cast<size_t>(spec.pair_index)];
  m.goal_m = pair.goal_m;
  m.goal = GoalRule::Make(m.rules.rule_set, pair.goal_m,
                          m.ground.Height(pair.goal_m.x(), pair.goal_m.y()), task.scale,
                          m.rules.goal_radius_m);

  // The per-trial world: a physics world with just the vehicle (the ground and the obstacles are
  // vb's own contact geometry, built once with the episode), the soil, if any, untouched.
  m.timed_soil.reset();
  m.soil.reset();
  m.vehicle.reset();
  m.world = std::make_unique<engine::PhysicsWorld>();

  // Vehicle facing the goal, dropped from start_height: the highest ground under the reference
  // point and the wheel centres decides the height, so that on a slope no wheel starts inside
  // the terrain (3.4 m wheelbase on a 30 deg slope: ~1 m of height difference). It settles onto
  // the local slope during the first steps. The drop scales with the world, as the original's
  // (terrain + 1.0 * scale factor): a 1/10 vehicle dropped a full-scale 0.5 m fell ten times its
  // share and 12 of the Verti-Wheeler's 14 rollovers in 100 trials were such landings.
  const vehicles::VehicleParams& vp = m.vehicle_params;
  const Vec2 to_goal0 = pair.goal_m - pair.start_m;
  const double yaw0 = std::atan2(to_goal0.y(), to_goal0.x());
  const Eigen::Rotation2Dd yaw_rotation(yaw0);
  double ground_z = m.ground.Height(pair.start_m.x(), pair.start_m.y());
  for (const vehicles::AxleParams& axle : vp.axles) {
    for (double side : {1.0, -1.0}) {
      const Vec2 wheel_xy = pair.start_m + yaw_rotation * Vec2(axle.x_m, side * axle.half_track_m);
      ground_z = std::max(ground_z, m.ground.Height(wheel_xy.x(), wheel_xy.y()));
    }
  }
  Pose start_pose;
  start_pose.position =
      Vec3(pair.start_m.x(), pair.start_m.y(),
           ground_z + vp.wheel.radius_m - (vp.axles.empty() ? 0.0 : vp.axles[0].z_m) +
               m.rules.start_height_m * task.scale);
  start_pose.rotation = FromYaw(yaw0);
  m.vehicle = std::make_unique<vehicles::Vehicle>(vp, m.ground, start_pose, m.world.get());
  if (vp.max_step_s > 0.0 && vp.max_step_s < m.rules.step_s) {
    m.substeps = static_cast<int>(std::ceil(m.rules.step_s / vp.max_step_s - 1e-9));
  }
  m.vehicle->SetObstacles(&m.obstacles);
  // Deformable patches: one SCM grid over the whole world (it only stores what wheels touch);
  // wheels over rigid patches keep the vehicle's rigid tire, rocks stay rigid bodies.
  if (HasDeformablePatches(task)) {
    // A vehicle with small wheels asks for a finer grid than the soil file's (max_soil_grid_m:
    // the 1/10 Verti-Wheeler's 0.041 m tread would fall between 0.05 m nodes; docs/vehicles.md).
    soil::SoilConfig grid_config = *m.soil_config;
    if (vp.max_soil_grid_m > 0.0) {
      grid_config.grid_spacing_m = std::min(grid_config.grid_spacing_m, vp.max_soil_grid_m);
    }
    m.soil = std::make_unique<soil::ScmSoil>(m.ground, grid_config);
    if (m.rules.timings != nullptr) {
      m.timed_soil = std::make_unique<TimedSoil>(m.soil.get());
      m.vehicle->SetSoil(m.timed_soil.get());
    } else {
      m.vehicle->SetSoil(m.soil.get());
    }
  }

  m.context = controllers::EpisodeContext();
  m.context.task = &task;
  m.builder.Reset(pair.goal_m, spec.seed, task);
  m.context.inflated_obstacles = &m.builder.planning_grid();
  m.context.maps = &m.maps;
  m.context.goal_m = pair.goal_m;
  m.context.scale = task.scale;
  m.context.step_s = m.rules.step_s;
  m.context.control_period_s = m.rules.control_period_s;
  m.context.target_speed_mps = m.rules.target_speed_mps;
  m.context.seed = spec.seed;

  const int every = m.rules.trajectory_every_n_steps;
  const long reserve_steps =
      std::min(m.max_steps, std::lround(kTrajectoryReserve_s / m.rules.step_s));
  m.metrics = TrialMetrics(m.window_steps, m.slow_step_m, task.rocks.size() + task.trees.size(),
                           m.contact_gap_steps,
                           every > 0 ? static_cast<size_t>(reserve_steps / every) + 2 : 0);
  m.progress = Progress();
  const vehicles::VehicleState& s = m.vehicle->state();
  m.builder.Record(0, s);
  if (every > 0) m.metrics.trajectory().push_back(MakeSample(0.0, s, m.progress.inputs));
  m.metrics.StartPosition(s.pose_W.position);
  m.progress.final_goal_distance_m = (pair.goal_m - s.pose_W.position.head<2>()).norm();
  m.observation_valid = false;
  m.started = true;
  if (m.rules.timings != nullptr) {
    m.rules.timings->setup_s +=
        std::chrono::duration<double>(Clock::now() - m.wall_start).count();
  }
}

void Episode::Step(const controllers::Command& command) {
  Impl& m = *impl_;
  VB_DEMAND(m.started);
  if (m.progress.done) return;
  m.observation_valid = false;
  if (!std::isfinite(command.throttle) || !std::isfinite(command.steering) ||
      !std::isfinite(command.braking)) {
    m.progress.status = TrialStatus::kSimError;
    m.progress.message = "controller '" + m.spec.system + "' returned a non-finite command";
    m.progress.decided = true;
    m.Finish();
    return;
  }
  m.progress.inputs.throttle = std::clamp(command.throttle, 0.0, 1.0);
  m.progress.inputs.steering = std::clamp(command.steering, -1.0, 1.0);
  m.progress.inputs.braking = std::clamp(command.braking, 0.0, 1.0);
  try {
    for (int i = 0; i < m.steps_per_period && !m.progress.done; ++i) m.PhysicsStep();
  } catch (const std::exception& e) {
    EndWithSimError(std::string("exception during stepping at t = ") + Fmt(m.Time()) +
                    " s: " + e.what());
  }
}

void Episode::EndWithSimError(const std::string& message) {
  Impl& m = *impl_;
  VB_DEMAND(m.started);
  if (m.progress.done) return;
  m.progress.status = TrialStatus::kSimError;
  m.progress.message = message;
  m.progress.decided = true;
  m.Finish();
}

const controllers::Observation& Episode::Observe() {
  Impl& m = *impl_;
  VB_DEMAND(m.started);
  if (!m.observation_valid) {
    m.builder.Build(m.progress.k, m.Time(), m.vehicle->state(), &m.observation);
    m.observation_valid = true;
  }
  return m.observation;
}

bool Episode::Done() const { return impl_->progress.done; }

TrialResult Episode::Result() const {
  VB_DEMAND(impl_->started);
  TrialResult r = impl_->MakeResult();
  r.trajectory = impl_->metrics.trajectory();
  return r;
}

TrialResult Episode::TakeResult() {
  VB_DEMAND(impl_->started);
  TrialResult r = impl_->MakeResult();
  r.trajectory = std::move(impl_->metrics.trajectory());
  impl_->metrics.trajectory().clear();
  return r;
}

struct EpisodeSnapshot::Data {
  TrialSpec spec;
  Progress progress;
  TrialMetrics metrics;
  NavigationState navigation;
  PerceptionState perception;
  controllers::Observation observation;
  bool observation_valid = false;
  vehicles::VehicleSnapshot vehicle;
  std::optional<soil::SoilSnapshot> soil;
  double time_s = 0.0;
};

EpisodeSnapshot::EpisodeSnapshot() = default;
EpisodeSnapshot::~EpisodeSnapshot() = default;
EpisodeSnapshot::EpisodeSnapshot(const EpisodeSnapshot& other)
    : data_(other.data_ ? std::make_unique<Data>(*other.data_) : nullptr) {}
EpisodeSnapshot& EpisodeSnapshot::operator=(const EpisodeSnapshot& other) {
  if (this != &other) data_ = other.data_ ? std::make_unique<Data>(*other.data_) : nullptr;
  return *this;
}
double EpisodeSnapshot::time_s() const { return data_ ? data_->time_s : 0.0; }

EpisodeSnapshot Episode::Snapshot() const {
  const Impl& m = *impl_;
  VB_DEMAND(m.started);
  EpisodeSnapshot snapshot;
  snapshot.data_ = std::make_unique<EpisodeSnapshot::Data>();
  EpisodeSnapshot::Data& d = *snapshot.data_;
  d.spec = m.spec;
  d.progress = m.progress;
  d.metrics = m.metrics;
  d.navigation = m.builder.navigation();
  d.perception = m.builder.perception_state();
  d.observation = m.observation;
  d.observation_valid = m.observation_valid;
  d.vehicle = m.vehicle->Snapshot();
  if (m.soil) d.soil = m.soil->Snapshot();
  d.time_s = m.Time();
  return snapshot;
}

void Episode::Restore(const EpisodeSnapshot& snapshot) {
  VB_DEMAND(snapshot.data_ != nullptr);
  const EpisodeSnapshot::Data& d = *snapshot.data_;
  Impl& m = *impl_;
  // The perception's map errors and perceived obstacles come from the trial seed.
  if (!m.started || m.spec.pair_index != d.spec.pair_index ||
      (m.builder.perception().enabled() && m.spec.seed != d.spec.seed)) {
    Reset(d.spec);
  }
  m.spec = d.spec;
  m.context.seed = d.spec.seed;
  m.progress = d.progress;
  m.metrics = d.metrics;
  m.builder.set_navigation(d.navigation);
  m.builder.set_perception_state(d.perception);
  m.observation = d.observation;
  m.observation.global_path_m = &m.builder.navigation().path_m;
  m.observation_valid = d.observation_valid;
  m.vehicle->Restore(d.vehicle);
  VB_DEMAND(static_cast<bool>(m.soil) == d.soil.has_value());
  if (m.soil) m.soil->Restore(*d.soil);
}

const controllers::EpisodeContext& Episode::context() const { return impl_->context; }
double Episode::time_s() const { return impl_->Time(); }
long Episode::physics_steps() const { return impl_->progress.k; }
int Episode::steps_per_control_period() const { return impl_->steps_per_period; }
const vehicles::VehicleState& Episode::vehicle_state() const {
  VB_DEMAND(impl_->started);
  return impl_->vehicle->state();
}
const EpisodeRules& Episode::rules() const { return impl_->rules; }
const terrain::TaskSpec& Episode::task() const { return impl_->task; }
const vehicles::VehicleParams& Episode::vehicle_params() const { return impl_->vehicle_params; }
const soil::SoilConfig* Episode::soil_config() const {
  return impl_->soil_config ? &*impl_->soil_config : nullptr;
}

}  // namespace vb::runner
