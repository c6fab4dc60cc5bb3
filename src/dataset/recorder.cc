// The dataset recorder: drive, sample, and keep the transitions (recorder.h).
#include "vb/dataset/recorder.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>

#include "vb/engine/error.h"

namespace vb::dataset {

namespace {

// vb_gym.RewardWeights defaults (python/vb_gym/reward.py): kept in step by the Python test that
// recomputes a dataset's rewards with step_reward.
constexpr double kProgressPerM = 50.0;
constexpr double kStall = -10.0;
constexpr double kStallSpeedMps = 2.0;
constexpr double kTilt = -20.0;
constexpr double kTiltThresholdDeg = 30.0;
constexpr double kSuccess = 3000.0;
constexpr double kTimeout = -100.0;
constexpr double kTimeoutPerM = -10.0;
constexpr double kStuck = -300.0;
constexpr double kOutOfBounds = -600.0;
constexpr double kRollover = -600.0;
constexpr double kSimError = 0.0;
constexpr double kReferenceStep_s = 0.005;

controllers::Command Clamped(const controllers::Command& c) {
  controllers::Command a;
  a.throttle = std::clamp(c.throttle, 0.0, 1.0);
  a.steering = std::clamp(c.steering, -1.0, 1.0);
  a.braking = std::clamp(c.braking, 0.0, 1.0);
  return a;
}

bool IsTerminated(const std::string& status) {
  return status == "success" || status == "rollover" || status == "out_of_bounds" ||
         status == "sim_error";
}

// The columns of one episode, filled sample by sample.
class Columns {
 public:
  Columns(EpisodeRecord* r, const SampleConfig& config, size_t wheels, ActionKind kind)
      : r_(r), config_(config), wheels_(wheels) {
    Add("observations/state", ColumnType::kFloat32, {static_cast<size_t>(kGymStateSize)});
    Add("observations/wheels", ColumnType::kFloat32, {wheels, 6});
    for (const CropSpec& c : config.crops) {
      const size_t n = static_cast<size_t>(c.size_cells);
      Add("observations/" + c.name, ColumnType::kFloat32, {n, n}, true);
    }
    Add("actions", ColumnType::kFloat32, {static_cast<size_t>(ActionSize(kind))});
    Add("rewards", ColumnType::kFloat64);
    Add("terminations", ColumnType::kBool);
    Add("truncations", ColumnType::kBool);
    Add("infos/time_s", ColumnType::kFloat64);
    Add("infos/position_m", ColumnType::kFloat64, {3});
    Add("infos/rpy_rad", ColumnType::kFloat64, {3});
    Add("infos/velocity_mps", ColumnType::kFloat64, {3});
    Add("infos/angular_velocity_radps", ColumnType::kFloat64, {3});
    Add("infos/forward_speed_mps", ColumnType::kFloat64);
    Add("infos/gear", ColumnType::kInt32);
    Add("infos/engine_speed_radps", ColumnType::kFloat64);
    Add("infos/command", ColumnType::kFloat64, {3});
    Add("infos/wheel_in_contact", ColumnType::kInt8, {wheels});
    Add("infos/wheel_surface", ColumnType::kInt8, {wheels});
    Add("infos/wheel_sinkage_m", ColumnType::kFloat64, {wheels});
    Add("infos/wheel_normal_force_n", ColumnType::kFloat64, {wheels});
    Add("infos/wheel_spin_radps", ColumnType::kFloat64, {wheels});
    Add("infos/wheel_slip", ColumnType::kFloat64, {wheels});
    Add("infos/goal_m", ColumnType::kFloat64, {2});
    Add("infos/local_goal_m", ColumnType::kFloat64, {2});
    Add("infos/goal_distance_m", ColumnType::kFloat64);
    Add("infos/heading_error_rad", ColumnType::kFloat64);
  }

  Column& operator[](const char* path) { return *r_->Find(path); }

  void Sample(const runner::Episode& episode, const controllers::Observation& obs,
              const controllers::Command& applied) {
    Column& state = (*this)["observations/state"];
    state.f32.resize(state.f32.size() + kGymStateSize);
    GymState(obs, applied, state.f32.data() + state.f32.size() - kGymStateSize);
    Column& wheels = (*this)["observations/wheels"];
    for (size_t i = 0; i < wheels_; ++i) {
      const controllers::WheelObservation& w = obs.wheels[i];
      for (double v : {w.in_contact ? 1.0 : 0.0, static_cast<double>(w.surface), w.normal_force_n,
                       w.sinkage_m, w.spin_radps, w.slip}) {
        wheels.f32.push_back(static_cast<float>(v));
      }
    }
    const terrain::GroundTruthMaps* maps = episode.context().maps;
    VB_DEMAND(maps != nullptr);
    for (const CropSpec& c : config_.crops) {
      maps->CropInto(c.layer, obs.position_W.head<2>(), obs.rpy.yaw_rad, c.size_cells,
                     c.resolution_m * episode.context().scale, &scratch_);
      const double offset = c.layer == terrain::MapLayer::kElevation ? obs.position_W.z() : 0.0;
      Column& col = *r_->Find("observations/" + c.name);
      for (double v : scratch_.values) col.f32.push_back(static_cast<float>(v - offset));
    }
    Push("infos/time_s", {obs.time_s});
    Push("infos/position_m", {obs.position_W.x(), obs.position_W.y(), obs.position_W.z()});
    Push("infos/rpy_rad", {obs.rpy.roll_rad, obs.rpy.pitch_rad, obs.rpy.yaw_rad});
    Push("infos/velocity_mps", {obs.velocity_W.x(), obs.velocity_W.y(), obs.velocity_W.z()});
    Push("infos/angular_velocity_radps",
         {obs.angular_velocity_B.x(), obs.angular_velocity_B.y(), obs.angular_velocity_B.z()});
    Push("infos/forward_speed_mps", {obs.forward_speed_mps});
    (*this)["infos/gear"].i32.push_back(obs.gear);
    Push("infos/engine_speed_radps", {obs.engine_speed_radps});
    Push("infos/command", {applied.throttle, applied.steering, applied.braking});
    for (size_t i = 0; i < wheels_; ++i) {
      const controllers::WheelObservation& w = obs.wheels[i];
      (*this)["infos/wheel_in_contact"].i8.push_back(w.in_contact ? 1 : 0);
      (*this)["infos/wheel_surface"].i8.push_back(static_cast<int8_t>(w.surface));
      (*this)["infos/wheel_sinkage_m"].f64.push_back(w.sinkage_m);
      (*this)["infos/wheel_normal_force_n"].f64.push_back(w.normal_force_n);
      (*this)["infos/wheel_spin_radps"].f64.push_back(w.spin_radps);
      (*this)["infos/wheel_slip"].f64.push_back(w.slip);
    }
    Push("infos/goal_m", {obs.goal_m.x(), obs.goal_m.y()});
    Push("infos/local_goal_m", {obs.local_goal_m.x(), obs.local_goal_m.y()});
    Push("infos/goal_distance_m", {obs.goal_distance_m});
    Push("infos/heading_error_rad", {obs.heading_error_rad});
  }

  void Transition(const std::vector<double>& action, double reward, bool terminated,
                  bool truncated) {
    for (double a : action) (*this)["actions"].f32.push_back(static_cast<float>(a));
    (*this)["rewards"].f64.push_back(reward);
    (*this)["terminations"].i8.push_back(terminated ? 1 : 0);
    (*this)["truncations"].i8.push_back(truncated ? 1 : 0);
  }

 private:
  void Add(const std::string& path, ColumnType type, std::vector<size_t> shape = {},
           bool compress = false) {
    r_->Add(path, type, std::move(shape), compress);
  }
  void Push(const char* path, std::initializer_list<double> values) {
    std::vector<double>& v = (*this)[path].f64;
    v.insert(v.end(), values.begin(), values.end());
  }

  EpisodeRecord* r_;
  const SampleConfig& config_;
  size_t wheels_;
  terrain::GridMap scratch_;
};

}  // namespace

int ActionSize(ActionKind kind) { return kind == ActionKind::kSpeed ? 2 : 3; }
const char* ActionKindName(ActionKind kind) {
  return kind == ActionKind::kSpeed ? "speed" : "direct";
}

ControllerPolicy::ControllerPolicy(std::unique_ptr<controllers::Controller> controller)
    : controller_(std::move(controller)) {
  VB_DEMAND(controller_ != nullptr);
}

void ControllerPolicy::Start(runner::Episode& episode) {
  episode.SetObservationConfig(controller_->observation_config());
  controller_->Reset(episode.context());
}

controllers::Command ControllerPolicy::Step(runner::Episode& episode) {
  return controller_->Update(episode.Observe());
}

void GymState(const controllers::Observation& obs, const controllers::Command& applied,
              float* out) {
  const double c = std::cos(obs.rpy.yaw_rad);
  const double s = std::sin(obs.rpy.yaw_rad);
  auto ego = [&](const Vec2& p, double* forward, double* left) {
    const double dx = p.x() - obs.position_W.x();
    const double dy = p.y() - obs.position_W.y();
    *forward = c * dx + s * dy;
    *left = -s * dx + c * dy;
  };
  double lf = 0, ll = 0, gf = 0, gl = 0;
  ego(obs.local_goal_m, &lf, &ll);
  ego(obs.goal_m, &gf, &gl);
  const double v[kGymStateSize] = {
      lf, ll, gf, gl, obs.goal_distance_m, obs.heading_error_rad, obs.forward_speed_mps,
      obs.rpy.roll_rad, obs.rpy.pitch_rad, obs.angular_velocity_B.x(), obs.angular_velocity_B.y(),
      obs.angular_velocity_B.z(), obs.velocity_W.z(), static_cast<double>(obs.gear),
      obs.engine_speed_radps, applied.throttle, applied.steering, applied.braking, obs.time_s};
  for (int i = 0; i < kGymStateSize; ++i) out[i] = static_cast<float>(v[i]);
}

double GymReward(double dt_s, const Vec2& prev_xy, const Vec2& xy, const Vec2& local_goal_xy,
                 double roll_rad, double pitch_rad, const std::string& status,
                 double goal_distance_m) {
  const double d_prev = (local_goal_xy - prev_xy).norm();
  const double d = (local_goal_xy - xy).norm();
  const double scale = dt_s / kReferenceStep_s;
  double reward = kProgressPerM * (d_prev - d);
  if (std::abs(d_prev - d) < kStallSpeedMps * dt_s) reward += kStall * scale;
  const double th = kTiltThresholdDeg * kPi / 180.0;
  for (double angle : {std::abs(roll_rad), std::abs(pitch_rad)}) {
    if (angle > th) reward += kTilt * (angle / th) * (angle - th) * scale;
  }
  if (status == "success") reward += kSuccess;
  else if (status == "timeout") reward += kTimeout + kTimeoutPerM * goal_distance_m;
  else if (status == "stuck") reward += kStuck;
  else if (status == "out_of_bounds") reward += kOutOfBounds;
  else if (status == "rollover") reward += kRollover;
  else if (status == "sim_error") reward += kSimError;
  return reward;
}

EpisodeRecord RecordEpisode(runner::Episode& episode, SamplePolicy& policy,
                            const SampleConfig& config, const RecordWindow& window) {
  VB_DEMAND(config.sample_every_steps >= 1);
  VB_DEMAND(episode.steps_per_control_period() == 1);
  EpisodeRecord record;
  const size_t wheels = episode.vehicle_state().wheels.size();
  const ActionKind kind = policy.action_kind();
  Columns cols(&record, config, wheels, kind);
  const double dt = episode.rules().step_s;

  controllers::Command applied;       // during the last physics step
  controllers::Command sum;           // over the current interval
  std::vector<double> held;           // kSpeed: the interval's action
  long interval_start = -1;           // step of the last sample, -1 before the first
  long interval_steps = 0;
  Vec2 prev_xy = Vec2::Zero();

  auto close_interval = [&](const controllers::Observation& obs, long k,
                            const std::string& status) {
    std::vector<double> action;
    if (kind == ActionKind::kSpeed) {
      action = held;
    } else {
      const double n = static_cast<double>(std::max(1L, interval_steps));
      action = {2.0 * sum.throttle / n - 1.0, sum.steering / n, 2.0 * sum.braking / n - 1.0};
    }
    const double reward = GymReward(static_cast<double>(k - interval_start) * dt, prev_xy,
                                    obs.position_W.head<2>(), obs.local_goal_m, obs.rpy.roll_rad,
                                    obs.rpy.pitch_rad, status, obs.goal_distance_m);
    const bool end = status != "running";
    cols.Transition(action, reward, end && IsTerminated(status), end && !IsTerminated(status));
    ++record.steps;
  };
  auto take_sample = [&](long k, const std::string& status) {
    const controllers::Observation& obs = episode.Observe();
    if (interval_start >= 0) close_interval(obs, k, status);
    cols.Sample(episode, obs, applied);
    prev_xy = obs.position_W.head<2>();
    interval_start = k;
    interval_steps = 0;
    sum = controllers::Command();
  };

  while (!episode.Done() && (window.end_step < 0 || episode.physics_steps() < window.end_step)) {
    const long k = episode.physics_steps();
    if (k >= window.first_step && (k - window.first_step) % config.sample_every_steps == 0) {
      take_sample(k, "running");
    }
    controllers::Command command;
    try {
      command = policy.Step(episode);
    } catch (const std::exception& e) {
      episode.EndWithSimError(std::string("exception in the policy at t = ") +
                              std::to_string(episode.time_s()) + " s: " + e.what());
      break;
    }
    if (std::isfinite(command.throttle) && std::isfinite(command.steering) &&
        std::isfinite(command.braking)) {
      applied = Clamped(command);
    }
    if (interval_start >= 0) {
      if (interval_steps == 0 && kind == ActionKind::kSpeed) held = policy.HeldAction();
      sum.throttle += applied.throttle;
      sum.steering += applied.steering;
      sum.braking += applied.braking;
      ++interval_steps;
    }
    episode.Step(command);
  }
  const runner::TrialResult result = episode.Result();
  const std::string status(runner::TrialStatusName(result.status));
  const long k_end = episode.physics_steps();
  // The end state closes the last interval (unless the trial never reached the window, or the
  // last sample is already the end, which happens only when the episode ended before stepping).
  if (interval_start >= 0 && interval_start < k_end &&
      result.status != runner::TrialStatus::kSimError) {
    take_sample(k_end, status);
  }
  // sim_error: the end state may be non-finite; no transition goes into it, and the status marks
  // the episode (docs/datasets.md: such episodes are left out of the assembled dataset).
  record.SetText("status", status);
  record.SetText("message", result.message);
  record.SetReal("sim_time_s", result.sim_time_s);
  record.SetInt("end_step", k_end);
  record.SetInt("first_step", window.first_step);
  record.SetReal("sample_period_s", config.sample_every_steps * dt);
  record.SetText("action_space_kind", ActionKindName(kind));
  return record;
}

}  // namespace vb::dataset
