// One trial, docs/architecture.md §4: world assembly from the task, the fixed-step loop in the
// order the vehicle requires (controller -> SetInputs -> Synchronize -> Step -> UpdateState),
// success and failure rules, metrics and the trajectory. No I/O.
#include "vb/engine/runner/episode.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "vb/engine/error.h"
#include "vb/engine/physics_world.h"
#include "vb/soil/scm_soil.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/terrain.h"
#include "vb/terrain/terrain_physics.h"
#include "vb/vehicles/vehicle.h"

namespace vb::runner {

namespace {

constexpr double kRadToDeg = 180.0 / kPi;
// A vehicle on its side or roof cannot recover on its own: the trial may stop there.
constexpr double kTippedOverRoll_rad = 0.5 * kPi;
// Beyond these the state is physically meaningless (the world is 128 m wide at scale 1 and the
// HMMWV tops out near 40 m/s): treat as a numerical blow-up, not as driving.
constexpr double kAbsurdDistance_m = 1.0e4;
constexpr double kAbsurdSpeed_mps = 200.0;

// Welford's running mean and population variance plus the maximum; numerically stable over the
// 12000 steps of a trial and independent of the signal's offset.
class RunningStats {
 public:
  void Add(double x) {
    ++n_;
    const double delta = x - mean_;
    mean_ += delta / static_cast<double>(n_);
    m2_ += delta * (x - mean_);
    max_ = n_ == 1 ? x : std::max(max_, x);
  }
  SignalStats Get() const {
    SignalStats s;
    if (n_ == 0) return s;
    s.mean = mean_;
    s.var = m2_ / static_cast<double>(n_);
    s.max = max_;
    return s;
  }

 private:
  long n_ = 0;
  double mean_ = 0.0;
  double m2_ = 0.0;
  double max_ = 0.0;
};

// Planar positions of the last `window_steps` steps in a ring, so the stuck test ("moved no more
// than d during the last window") is O(1) per step without allocation.
class PositionWindow {
 public:
  explicit PositionWindow(long window_steps)
      : ring_(static_cast<size_t>(window_steps) + 1, Vec2::Zero()) {}
  void Push(const Vec2& p) {
    ring_[head_] = p;
    head_ = (head_ + 1) % ring_.size();
    if (count_ < ring_.size()) ++count_;
  }
  bool Full() const { return count_ == ring_.size(); }
  // Planar displacement between the newest sample and the one `window_steps` steps before it.
  double Displacement() const {
    const Vec2& newest = ring_[(head_ + ring_.size() - 1) % ring_.size()];
    const Vec2& oldest = ring_[head_ % ring_.size()];
    return (newest - oldest).norm();
  }

 private:
  std::vector<Vec2> ring_;
  size_t head_ = 0;
  size_t count_ = 0;
};

bool IsFinite(const Vec3& v) { return v.allFinite(); }

// Short human-readable number for messages (std::to_string prints six fixed decimals).
std::string Fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", x);
  return buf;
}

// Empty string if the state is usable; otherwise why it is not.
std::string CheckState(const vehicles::VehicleState& s) {
  const Vec3& p = s.pose_W.position;
  if (!IsFinite(p) || !IsFinite(s.velocity_W) || !IsFinite(s.angular_velocity_W) ||
      !s.pose_W.rotation.coeffs().allFinite() || !std::isfinite(s.forward_speed_mps)) {
    return "non-finite vehicle state";
  }
  if (p.norm() > kAbsurdDistance_m) {
    return "vehicle position diverged (|p| = " + Fmt(p.norm()) + " m)";
  }
  if (s.velocity_W.norm() > kAbsurdSpeed_mps) {
    return "vehicle speed diverged (" + Fmt(s.velocity_W.norm()) + " m/s)";
  }
  return "";
}

TrajectorySample MakeSample(double t, const vehicles::VehicleState& s,
                            const vehicles::DriverInputs& in) {
  TrajectorySample out;
  out.time_s = t;
  out.position_W = s.pose_W.position;
  out.velocity_W = s.velocity_W;
  out.speed_mps = s.velocity_W.norm();
  out.rpy = s.rpy;
  out.throttle = in.throttle;
  out.steering = in.steering;
  out.braking = in.braking;
  out.gear = s.gear;
  out.wheel_surface.reserve(s.wheels.size());
  out.wheel_sinkage_m.reserve(s.wheels.size());
  for (const vehicles::WheelState& w : s.wheels) {
    out.wheel_surface.push_back(w.in_contact ? static_cast<int>(w.surface) : -1);
    out.wheel_sinkage_m.push_back(w.sinkage_m);
  }
  return out;
}

// Times the wheels' soil contact, which the vehicle calls from inside Synchronize, so the step
// breakdown can report all soil work in one bucket. Used only when timings are asked for.
class TimedSoil : public soil::SoilContact {
 public:
  explicit TimedSoil(soil::ScmSoil* soil) : soil_(soil) {}
  soil::WheelSoilOutput WheelContact(const soil::WheelSoilInput& wheel, double dt) override {
    const auto t0 = std::chrono::steady_clock::now();
    const soil::WheelSoilOutput out = soil_->WheelContact(wheel, dt);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

void ValidateSetup(const terrain::TaskSpec& task, const TrialSpec& spec,
                   const EpisodeRules& rules, const soil::SoilConfig* soil) {
  const int num_pairs = static_cast<int>(task.pairs.size());
  if (spec.pair_index < 0 || spec.pair_index >= num_pairs) {
    throw InputError(task.source_file, 0, "pair",
                     "pair index " + std::to_string(spec.pair_index) + " out of range; task '" +
                         task.name + "' has " + std::to_string(num_pairs) + " pairs (0.." +
                         std::to_string(num_pairs - 1) + ")");
  }
  if (HasDeformablePatches(task) && soil == nullptr) {
    throw InputError(task.source_file, 0, "semantics.classes",
                     "the task has deformable patches (mud/sand/snow) but no soil parameters "
                     "were given (data/soils/*.yaml, vb_run --soil)");
  }
  if (!(rules.step_s > 0.0)) throw InputError("", 0, "step_s", "must be > 0");
  if (!(rules.time_limit_s > 0.0)) throw InputError("", 0, "time_limit_s", "must be > 0");
  if (rules.trajectory_every_n_steps < 1) {
    throw InputError("", 0, "trajectory_every_n_steps", "must be >= 1");
  }
}

std::unique_ptr<controllers::Controller> MakeSystem(const std::string& name) {
  std::unique_ptr<controllers::Controller> c = controllers::MakeController(name);
  if (c) return c;
  std::string valid;
  for (const std::string& n : controllers::ControllerNames()) {
    valid += (valid.empty() ? "" : ", ") + n;
  }
  throw InputError("", 0, "system", "unknown system '" + name + "'; valid: " + valid);
}

}  // namespace

std::string_view TrialStatusName(TrialStatus s) {
  switch (s) {
    case TrialStatus::kSuccess: return "success";
    case TrialStatus::kRollover: return "rollover";
    case TrialStatus::kStuck: return "stuck";
    case TrialStatus::kTimeout: return "timeout";
    case TrialStatus::kSimError: return "sim_error";
  }
  return "unknown";
}

TrialResult RunTrial(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle_params,
                     const TrialSpec& spec, const EpisodeRules& rules,
                     const soil::SoilConfig* soil_config) {
  ValidateSetup(task, spec, rules, soil_config);
  std::unique_ptr<controllers::Controller> controller = MakeSystem(spec.system);
  const auto wall_start = std::chrono::steady_clock::now();

  TrialResult result;
  result.spec = spec;
  result.task_name = task.name;

  // Static world, and the planning grid as the original: obstacles dilated by 4 m * scale.
  const terrain::StartGoalPair& pair = task.pairs[static_cast<size_t>(spec.pair_index)];
  const double scale = task.scale;
  const terrain::Terrain ground(task);
  engine::PhysicsWorld world;
  terrain::AddTerrainToPhysics(task, ground, &world);
  const terrain::OccupancyGrid inflated = terrain::Inflate(
      terrain::RasterizeObstacles(task), terrain::PlannerInflationCells(task));

  // Vehicle facing the goal, dropped from start_height: the highest ground under the reference
  // point and the wheel centres decides the height, so that on a slope no wheel starts inside
  // the terrain (3.4 m wheelbase on a 30 deg slope: ~1 m of height difference). It settles onto
  // the local slope during the first steps.
  const Vec2 to_goal0 = pair.goal_m - pair.start_m;
  const double yaw0 = std::atan2(to_goal0.y(), to_goal0.x());
  const Eigen::Rotation2Dd yaw_rotation(yaw0);
  double ground_z = ground.Height(pair.start_m.x(), pair.start_m.y());
  for (const vehicles::AxleParams& axle : vehicle_params.axles) {
    for (double side : {1.0, -1.0}) {
      const Vec2 wheel_xy = pair.start_m + yaw_rotation * Vec2(axle.x_m, side * axle.half_track_m);
      ground_z = std::max(ground_z, ground.Height(wheel_xy.x(), wheel_xy.y()));
    }
  }
  Pose start_pose;
  start_pose.position =
      Vec3(pair.start_m.x(), pair.start_m.y(),
           ground_z + vehicle_params.wheel.radius_m -
               (vehicle_params.axles.empty() ? 0.0 : vehicle_params.axles[0].z_m) +
               rules.start_height_m);
  start_pose.rotation = FromYaw(yaw0);
  vehicles::Vehicle vehicle(vehicle_params, ground, start_pose, &world);
  // Deformable patches: one SCM grid over the whole world (it only stores what wheels touch);
  // wheels over rigid patches keep the vehicle's rigid tire, rocks stay rigid bodies.
  std::unique_ptr<soil::ScmSoil> soil;
  std::unique_ptr<TimedSoil> timed_soil;  // only when timings are asked for
  if (HasDeformablePatches(task)) {
    soil = std::make_unique<soil::ScmSoil>(ground, *soil_config);
    if (rules.timings != nullptr) {
      timed_soil = std::make_unique<TimedSoil>(soil.get());
      vehicle.SetSoil(timed_soil.get());
    } else {
      vehicle.SetSoil(soil.get());
    }
  }

  controllers::EpisodeContext context;
  context.task = &task;
  context.inflated_obstacles = &inflated;
  context.goal_m = pair.goal_m;
  context.scale = scale;
  context.step_s = rules.step_s;
  context.seed = spec.seed;
  controller->Reset(context);

  // Optional timing breakdown: a clock read between the stages, only when asked for.
  using Clock = std::chrono::steady_clock;
  StepTimings* const timings = rules.timings;
  Clock::time_point mark = Clock::now();
  auto lap = [&](double* bucket) {
    if (timings == nullptr) return;
    const Clock::time_point now = Clock::now();
    *bucket += std::chrono::duration<double>(now - mark).count();
    mark = now;
  };
  if (timings != nullptr) {
    timings->setup_s += std::chrono::duration<double>(mark - wall_start).count();
  }

  // Step counts instead of accumulated time: t = k * dt never drifts.
  const double dt = rules.step_s;
  const long max_steps = std::max(1L, std::lround(rules.time_limit_s / dt));
  const long window_steps = std::max(1L, std::lround(rules.stuck_window_s / dt));
  const double goal_radius_m = rules.goal_radius_m * scale;
  const double stuck_distance_m = rules.stuck_distance_m * scale;
  const int every = rules.trajectory_every_n_steps;

  RunningStats roll, pitch, abs_roll, abs_pitch, throttle, steering, abs_steering;
  PositionWindow window(window_steps);
  // Step of the last touch per obstacle (rocks first, then trees); a touch starts a new contact
  // event only after kContactGapS out of contact, so a wheel bouncing on a rock face counts once.
  constexpr double kContactGapS = 0.5;
  const long contact_gap_steps = std::lround(kContactGapS / rules.step_s);
  std::vector<long> last_touch_step(task.rocks.size() + task.trees.size(), -contact_gap_steps - 1);
  result.trajectory.reserve(static_cast<size_t>(max_steps / every) + 2);

  vehicles::DriverInputs inputs;
  result.trajectory.push_back(MakeSample(0.0, vehicle.state(), inputs));
  window.Push(vehicle.state().pose_W.position.head<2>());
  Vec2 last_xy = vehicle.state().pose_W.position.head<2>();
  result.final_goal_distance_m = (pair.goal_m - last_xy).norm();
  bool decided = false;  // status already final (success or sim_error)
  long k = 0;
  try {
    while (true) {
      if (timings != nullptr) {  // the previous step's checks, metrics and rules
        lap(&timings->bookkeeping_s);
        ++timings->steps;
      }
      // Controller on the current observation.
      const vehicles::VehicleState& s0 = vehicle.state();
      controllers::Observation obs;
      obs.time_s = static_cast<double>(k) * dt;
      obs.position_W = s0.pose_W.position;
      obs.rpy = s0.rpy;
      obs.velocity_W = s0.velocity_W;
      obs.forward_speed_mps = s0.forward_speed_mps;
      const controllers::Command cmd = controller->Update(obs);
      if (timings != nullptr) lap(&timings->controller_s);
      if (!std::isfinite(cmd.throttle) || !std::isfinite(cmd.steering) ||
          !std::isfinite(cmd.braking)) {
        result.status = TrialStatus::kSimError;
        result.message = "controller '" + spec.system + "' returned a non-finite command";
        decided = true;
        break;
      }
      inputs.throttle = std::clamp(cmd.throttle, 0.0, 1.0);
      inputs.steering = std::clamp(cmd.steering, -1.0, 1.0);
      inputs.braking = std::clamp(cmd.braking, 0.0, 1.0);

      // One physics step.
      vehicle.SetInputs(inputs);
      vehicle.Synchronize(dt);
      if (timings != nullptr) lap(&timings->vehicle_sync_s);
      if (soil) {
        soil->EndStep(dt);
        if (timings != nullptr) lap(&timings->soil_s);
      }
      if (timed_soil) {  // the wheels' soil contact ran inside Synchronize: move it to soil_s
        const double contact_s = timed_soil->TakeSeconds();
        timings->vehicle_sync_s -= contact_s;
        timings->soil_s += contact_s;
      }
      world.Step(dt);
      if (timings != nullptr) lap(&timings->physics_step_s);
      vehicle.UpdateState();
      if (timings != nullptr) lap(&timings->vehicle_update_s);
      ++k;
      const double t = static_cast<double>(k) * dt;
      result.sim_time_s = t;
      const vehicles::VehicleState& s = vehicle.state();

      // Numerical trouble ends the trial as data, never as a crash.
      std::string trouble = world.StateIsFinite() ? CheckState(s) : "non-finite physics state";
      if (!trouble.empty()) {
        result.status = TrialStatus::kSimError;
        result.message = trouble + " at t = " + Fmt(t) + " s";
        decided = true;
        break;
      }

      // Metrics over every step.
      const double roll_deg = s.rpy.roll_rad * kRadToDeg;
      const double pitch_deg = s.rpy.pitch_rad * kRadToDeg;
      roll.Add(roll_deg);
      pitch.Add(pitch_deg);
      abs_roll.Add(std::abs(roll_deg));
      abs_pitch.Add(std::abs(pitch_deg));
      throttle.Add(inputs.throttle);
      steering.Add(inputs.steering);
      abs_steering.Add(std::abs(inputs.steering));
      const Vec2 xy = s.pose_W.position.head<2>();
      result.path_length_m += (xy - last_xy).norm();
      last_xy = xy;
      window.Push(xy);

      // Contact events with rocks and trees.
      for (const engine::ObstacleContact& c : world.ObstacleContacts()) {
        if (c.body != vehicle.body()) continue;
        const size_t index = c.obstacle_tag >= terrain::kTreeTagOffset
                                 ? task.rocks.size() + (c.obstacle_tag - terrain::kTreeTagOffset)
                                 : static_cast<size_t>(c.obstacle_tag);
        if (index >= last_touch_step.size()) continue;
        if (k - last_touch_step[index] > contact_gap_steps) ++result.obstacle_contacts;
        last_touch_step[index] = k;
      }

      if (k % every == 0) result.trajectory.push_back(MakeSample(t, s, inputs));

      // Success, then the early ends of certain failures, then the time limit.
      result.final_goal_distance_m = (pair.goal_m - xy).norm();
      if (result.final_goal_distance_m <= goal_radius_m) {
        result.status = TrialStatus::kSuccess;
        result.traversal_time_s = t;
        result.message = "reached the goal";
        decided = true;
        break;
      }
      if (rules.end_early) {
        if (std::abs(s.rpy.roll_rad) > kTippedOverRoll_rad) break;
        if (window.Full() && window.Displacement() <= stuck_distance_m) break;
      }
      if (k >= max_steps) break;
    }
  } catch (const std::exception& e) {
    result.status = TrialStatus::kSimError;
    result.message = std::string("exception during stepping at t = ") +
                     Fmt(static_cast<double>(k) * dt) + " s: " + e.what();
    decided = true;
  }

  if (timings != nullptr) lap(&timings->bookkeeping_s);
  if (timings != nullptr && soil) {
    const soil::ScmStats& st = soil->stats();
    timings->soil_contact_nodes = st.contact_nodes;
    timings->soil_tiles = st.tiles;
    timings->soil_memory_bytes = st.memory_bytes;
  }
  const vehicles::VehicleState& final_state = vehicle.state();
  // The last state always closes the trajectory (unless it is the invalid one of a sim_error).
  if (result.status != TrialStatus::kSimError &&
      result.trajectory.back().time_s != result.sim_time_s) {
    result.trajectory.push_back(MakeSample(result.sim_time_s, final_state, inputs));
  }

  // Failure type from the final state (architecture §4).
  if (!decided) {
    const double final_roll = std::abs(final_state.rpy.roll_rad);
    if (final_roll > rules.rollover_roll_rad) {
      result.status = TrialStatus::kRollover;
      result.message = "rolled over (|roll| = " + Fmt(final_roll * kRadToDeg) +
                       " deg at the end)";
    } else if (window.Full() && window.Displacement() <= stuck_distance_m) {
      result.status = TrialStatus::kStuck;
      result.message = "stuck (moved " + Fmt(window.Displacement()) + " m in the last " +
                       Fmt(rules.stuck_window_s) + " s)";
    } else {
      result.status = TrialStatus::kTimeout;
      result.message = "time limit of " + Fmt(rules.time_limit_s) + " s reached";
    }
  }

  result.roll_deg = roll.Get();
  result.pitch_deg = pitch.Get();
  result.abs_roll_deg = abs_roll.Get();
  result.abs_pitch_deg = abs_pitch.Get();
  result.throttle = throttle.Get();
  result.steering = steering.Get();
  result.abs_steering = abs_steering.Get();
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.real_time_factor = result.wall_time_s > 0.0 ? result.sim_time_s / result.wall_time_s : 0.0;
  return result;
}

}  // namespace vb::runner
