#include "view/teleop_session.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "io/result_io.h"
#include "vb/engine/error.h"

namespace vb::view {

namespace {

constexpr double kRadToDeg = 180.0 / kPi;

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  std::string w;
  while (in >> w) words.push_back(w);
  return words;
}

// A plain decimal number in [lo, hi]; false (with *error) otherwise.
bool ParseBounded(const std::string& name, const std::string& text, double lo, double hi,
                  double* value, std::string* error) {
  // strtod also reads hexadecimal ("0x1") and "inf"/"nan": only digits, sign, '.', exponent.
  const bool plain = text.find_first_not_of("0123456789+-.eE") == std::string::npos;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || !plain || end != text.c_str() + text.size() || !std::isfinite(v)) {
    *error = name + " '" + text + "' is not a number";
    return false;
  }
  if (v < lo || v > hi) {
    *error = name + " " + text + " is outside [" + io::JsonNumber(lo) + ", " + io::JsonNumber(hi) +
             "]";
    return false;
  }
  *value = v;
  return true;
}

}  // namespace

TeleopSession::TeleopSession(const terrain::TaskSpec& task,
                             const vehicles::VehicleParams& vehicle, const soil::SoilConfig* soil,
                             const TeleopOptions& options)
    : options_(options) {
  if (options.pair < 0 || static_cast<size_t>(options.pair) >= task.pairs.size()) {
    throw InputError(task.source_file, 0, "--pair",
                     "pair " + std::to_string(options.pair) + " is not in the task (" +
                         std::to_string(task.pairs.size()) + " pairs)");
  }
  runner::EpisodeRules rules;
  rules.control_period_s = options.control_period_s;
  rules.trajectory_every_n_steps = 1;
  episode_ = std::make_unique<runner::Episode>(task, vehicle, rules, soil);
}

TeleopSession::~TeleopSession() = default;

std::string TeleopSession::HandleMessage(const std::string& text, double wall_s) {
  const std::vector<std::string> w = Words(text);
  if (w.empty()) return "empty message (expected start, command or stop)";
  if (w[0] == "start") {
    if (w.size() != 1) return "start takes no arguments";
    if (driving_) return "a drive is running: stop it first (it is then recorded)";
    if (finished_) return "the last drive is not recorded yet";
    runner::TrialSpec spec;
    spec.pair_index = options_.pair;
    spec.seed = options_.seed;
    spec.system = "teleop";
    spec.vehicle = options_.vehicle;
    episode_->Reset(spec);
    command_ = controllers::Command();
    driving_ = true;
    finished_ = false;
    stopped_ = false;
    ++drives_;
    start_wall_s_ = wall_s;
    slipped_s_ = 0.0;
    return "";
  }
  if (w[0] == "command") {
    if (w.size() != 4) return "command needs THROTTLE STEERING BRAKING, got '" + text + "'";
    controllers::Command c;
    std::string error;
    if (!ParseBounded("throttle", w[1], 0.0, 1.0, &c.throttle, &error) ||
        !ParseBounded("steering", w[2], -1.0, 1.0, &c.steering, &error) ||
        !ParseBounded("braking", w[3], 0.0, 1.0, &c.braking, &error)) {
      return error;
    }
    command_ = c;
    return "";
  }
  if (w[0] == "stop") {
    if (w.size() != 1) return "stop takes no arguments";
    if (!driving_) return "no drive to stop (send start first)";
    AdvanceTo(wall_s);
    if (driving_) {
      stopped_ = true;
      EndDrive();
    }
    return "";
  }
  return "unknown message '" + w[0] + "' (expected start, command or stop)";
}

void TeleopSession::AdvanceTo(double wall_s) {
  if (!driving_) return;
  const double period = options_.control_period_s;
  double target = wall_s - start_wall_s_ - slipped_s_;
  if (target - episode_->time_s() > options_.max_lag_s) {
    slipped_s_ += target - episode_->time_s() - options_.max_lag_s;
    target = episode_->time_s() + options_.max_lag_s;
  }
  // Half a period of slack: the episode's time is a step count times dt, never drifting.
  while (!episode_->Done() && episode_->time_s() + 0.5 * period <= target) {
    episode_->Step(command_);
  }
  if (episode_->Done()) EndDrive();
}

void TeleopSession::EndDrive() {
  end_status_ = std::string(runner::TrialStatusName(episode_->Result().status));
  driving_ = false;
  finished_ = true;
}

runner::TrialResult TeleopSession::TakeFinishedDrive() {
  VB_DEMAND(finished_);
  finished_ = false;
  runner::TrialResult r = episode_->TakeResult();
  // A drive the operator stopped is not decided by the episode's rules: its status is the
  // outcome as it stood (usually timeout); the message says what happened.
  if (stopped_) {
    char t[32];
    std::snprintf(t, sizeof(t), "%.3f", r.sim_time_s);
    // Not "time limit reached": the time limit was not reached. Other outcomes say why.
    const std::string outcome = r.status == runner::TrialStatus::kTimeout
                                    ? "timeout, still driving"
                                    : std::string(runner::TrialStatusName(r.status)) + ": " +
                                          r.message;
    r.message = std::string("stopped by the operator at t = ") + t +
                " s (outcome as it stood: " + outcome + ")";
  }
  return r;
}

std::string TeleopSession::StateJson() {
  std::string j = "{\"type\": \"state\", \"drive\": " + std::to_string(drives_) +
                  ", \"driving\": " + (driving_ ? "true" : "false");
  if (drives_ == 0) return j + "}";
  const vehicles::VehicleState& s = episode_->vehicle_state();
  const controllers::Observation& obs = episode_->Observe();
  j += ", \"t_s\": " + io::JsonNumber(episode_->time_s());
  j += ", \"x_m\": " + io::JsonNumber(s.pose_W.position.x());
  j += ", \"y_m\": " + io::JsonNumber(s.pose_W.position.y());
  j += ", \"z_m\": " + io::JsonNumber(s.pose_W.position.z());
  j += ", \"roll_deg\": " + io::JsonNumber(s.rpy.roll_rad * kRadToDeg);
  j += ", \"pitch_deg\": " + io::JsonNumber(s.rpy.pitch_rad * kRadToDeg);
  j += ", \"yaw_deg\": " + io::JsonNumber(s.rpy.yaw_rad * kRadToDeg);
  j += ", \"speed_mps\": " + io::JsonNumber(s.velocity_W.norm());
  j += ", \"forward_speed_mps\": " + io::JsonNumber(s.forward_speed_mps);
  j += ", \"gear\": " + std::to_string(s.gear);
  j += ", \"throttle\": " + io::JsonNumber(command_.throttle);
  j += ", \"steering\": " + io::JsonNumber(command_.steering);
  j += ", \"braking\": " + io::JsonNumber(command_.braking);
  j += ", \"goal_distance_m\": " + io::JsonNumber(obs.goal_distance_m);
  j += ", \"status\": " +
       io::JsonString(driving_ ? "driving" : end_status_);
  return j + "}";
}

}  // namespace vb::view
