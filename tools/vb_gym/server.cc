// vb_gym request handling (docs/gym_protocol.md). Requests are parsed strictly: an unknown op or
// key, a wrong type or an out-of-range value is answered with an error frame naming it.
#include "server.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

#include "io/batch_io.h"
#include "io/build_info.h"
#include "io/cli_args.h"
#include "io/perception_io.h"
#include "io/result_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/task_ref.h"
#include "io/vehicle_io.h"
#include "io/yaml_strict.h"
#include "vb/batch/index.h"
#include "vb/controllers/pid_controller.h"
#include "io/data_dir.h"
#include "vb/engine/error.h"
#include "vb/engine/file_name.h"

namespace vb::gym {

namespace {

using nlohmann::json;

// A request that cannot be served; answered with an error frame, the server stays usable.
class RequestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The order of the "state" array (docs/gym_protocol.md); the Python package reads the names from
// the configure reply, never from a copy of this list.
const std::vector<std::string> kStateFields = {
    "time_s",         "x_m",           "y_m",           "z_m",
    "roll_rad",       "pitch_rad",     "yaw_rad",       "vx_mps",
    "vy_mps",         "vz_mps",        "roll_rate_radps", "pitch_rate_radps",
    "yaw_rate_radps", "forward_speed_mps", "gear",       "engine_speed_radps",
    "goal_x_m",       "goal_y_m",      "goal_distance_m", "local_goal_x_m",
    "local_goal_y_m", "heading_error_rad", "throttle",  "steering",
    "braking"};
// Room in an observation frame's payload for the crops: the protocol's limit less a megabyte for
// the state and wheel arrays (a few hundred bytes each; a vehicle has at most a few dozen
// wheels).
constexpr uint64_t kMaxCropPayloadBytes = kMaxPayloadBytes - (1u << 20);

const std::vector<std::string> kWheelFields = {"in_contact", "surface",    "normal_force_n",
                                               "sinkage_m",  "spin_radps", "slip"};

// Every reply goes through Dump: bytes that are not UTF-8 (a task path, a vehicle file's message,
// a request's own bytes quoted in an error) become U+FFFD instead of making nlohmann throw
// type_error.316, so a reply can always be encoded (NEW-1 of the probe at 8ff4def).
std::string Dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// A client's value or key quoted in an error message: at most kMaxQuotedBytes of it (a request
// may hold a megabyte), never the whole. Nesting is bounded when the header is parsed, so dump()
// cannot recurse deeply here.
constexpr size_t kMaxQuotedBytes = 80;
std::string Abridged(const std::string& text, size_t max_bytes = kMaxQuotedBytes) {
  if (text.size() <= max_bytes) return text;
  return text.substr(0, max_bytes) + "... (" + std::to_string(text.size()) + " bytes)";
}
std::string Quoted(const json& v) { return Abridged(Dump(v)); }

// The request header as JSON: a UTF-8 JSON object nested at most kMaxHeaderDepth deep. The
// depth is checked while parsing (a parser callback), before anything could recurse over the
// value: 200 000 nested brackets fit in the 1 MiB header limit and overflowed the stack in
// dump() (NEW-2).
json ParseHeader(const std::string& text) {
  const json::parser_callback_t depth_check = [](int depth, json::parse_event_t event, json&) {
    if ((event == json::parse_event_t::object_start ||
         event == json::parse_event_t::array_start) && depth >= kMaxHeaderDepth) {
      throw RequestError("header nests objects and lists deeper than " +
                         std::to_string(kMaxHeaderDepth) + " levels");
    }
    return true;
  };
  try {
    return json::parse(text, depth_check);
  } catch (const json::parse_error& e) {
    throw RequestError(std::string("header is not valid JSON: ") + Abridged(e.what(), 4 * kMaxQuotedBytes));
  }
}

std::string Fmt(double x) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", x);
  return buf;
}

void CheckKeys(const json& j, const std::string& op, const std::vector<std::string>& allowed) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end()) {
      throw RequestError("op '" + op + "': unknown key '" + Abridged(it.key()) +
                         "'; valid: " + io::JoinNames(allowed));
    }
  }
}

double GetNumber(const json& j, const std::string& op, const std::string& key, double fallback,
                 double lo, double hi, bool required = false) {
  if (!j.contains(key)) {
    if (required) throw RequestError("op '" + op + "': missing key '" + key + "'");
    return fallback;
  }
  const json& v = j.at(key);
  if (!v.is_number()) {
    throw RequestError("op '" + op + "': key '" + key + "': expected a number, got " + Quoted(v));
  }
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) {
    throw RequestError("op '" + op + "': key '" + key + "': " + Quoted(v) + " out of range [" +
                       Fmt(lo) + ", " + Fmt(hi) + "]");
  }
  return x;
}

// A whole number in [lo, hi] (uint64 for seeds).
uint64_t GetUnsigned(const json& j, const std::string& op, const std::string& key,
                     uint64_t fallback, uint64_t lo, uint64_t hi, bool required = false) {
  if (!j.contains(key)) {
    if (required) throw RequestError("op '" + op + "': missing key '" + key + "'");
    return fallback;
  }
  const json& v = j.at(key);
  if (!v.is_number_unsigned()) {
    throw RequestError("op '" + op + "': key '" + key +
                       "': expected a whole number >= 0, got " + Quoted(v));
  }
  const uint64_t x = v.get<uint64_t>();
  if (x < lo || x > hi) {
    throw RequestError("op '" + op + "': key '" + key + "': " + Quoted(v) + " out of range [" +
                       std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return x;
}

std::string GetString(const json& j, const std::string& op, const std::string& key,
                      const std::string& fallback, bool required = false) {
  if (!j.contains(key)) {
    if (required) throw RequestError("op '" + op + "': missing key '" + key + "'");
    return fallback;
  }
  const json& v = j.at(key);
  if (!v.is_string()) {
    throw RequestError("op '" + op + "': key '" + key + "': expected a string, got " + Quoted(v));
  }
  return v.get<std::string>();
}

// Names that become parts of file names (the system) or of the reply's array names (crops):
// the tools' one file-name rule (vb/engine/file_name.h).
void CheckName(const std::string& op, const std::string& key, const std::string& name) {
  const std::string problem = FileNameComponentProblem(name, io::kMaxDataNameLength);
  if (!problem.empty()) {
    throw RequestError("op '" + op + "': key '" + key + "': '" + Abridged(name) + "': " + problem);
  }
}

terrain::MapLayer ParseLayer(const std::string& name) {
  if (name == "elevation") return terrain::MapLayer::kElevation;
  if (name == "semantics") return terrain::MapLayer::kSemantics;
  if (name == "occupancy") return terrain::MapLayer::kOccupancy;
  if (name == "friction") return terrain::MapLayer::kFriction;
  throw RequestError("op 'configure': crops: unknown layer '" + Abridged(name) +
                     "'; valid: elevation, semantics, occupancy, friction");
}

json ResultJson(const runner::TrialResult& r) {
  json j;
  j["status"] = std::string(runner::TrialStatusName(r.status));
  j["message"] = r.message;
  j["rules"] = std::string(runner::RuleSetName(r.rule_set));   // which rules decided the status
  j["sim_time_s"] = r.sim_time_s;
  j["traversal_time_s"] = r.traversal_time_s;
  j["final_goal_distance_m"] = r.final_goal_distance_m;
  j["path_length_m"] = r.path_length_m;
  j["obstacle_contacts"] = r.obstacle_contacts;
  j["tipped"] = r.tipped;
  j["abs_roll_deg_mean"] = r.abs_roll_deg.mean;
  j["abs_roll_deg_max"] = r.abs_roll_deg.max;
  j["abs_pitch_deg_mean"] = r.abs_pitch_deg.mean;
  j["abs_pitch_deg_max"] = r.abs_pitch_deg.max;
  j["wall_time_s"] = r.wall_time_s;
  j["real_time_factor"] = r.real_time_factor;
  return j;
}

}  // namespace

Server::Server(std::string data_dir) : data_dir_(std::move(data_dir)) {}
Server::~Server() = default;

namespace {

// An error reply, built without nlohmann (nothing here can throw but bad_alloc): JsonString
// replaces bytes that are not UTF-8, the op is abridged.
std::string ErrorReply(const std::string& op, const char* kind, const std::string& message) {
  return "{\"type\":\"error\",\"op\":" + io::JsonString(Abridged(op)) + ",\"kind\":\"" + kind +
         "\",\"message\":" + io::JsonString(message) + "}";
}

}  // namespace

bool Server::Handle(const Frame& request, std::string* reply_header,
                    std::vector<uint8_t>* reply_payload) {
  reply_payload->clear();
  std::string op = "?";
  // Each failure is one error reply and the server stays usable: a bad request (kind
  // "request"), a bad file (kind "input", naming file, line and key), a file that cannot be
  // written (kind "io": a full disk ends no session, NEW-3), anything else (kind "internal").
  try {
    const json j = ParseHeader(request.header);
    if (!j.is_object()) throw RequestError("header must be a JSON object, got " + Quoted(j));
    op = GetString(j, "?", "op", "", /*required=*/true);
    if (!request.payload.empty()) {
      throw RequestError("op '" + Abridged(op) + "': requests carry no payload (got " +
                         std::to_string(request.payload.size()) + " bytes)");
    }
    if (op == "hello") {
      CheckKeys(j, op, {"op", "protocol"});
      const uint64_t version = GetUnsigned(j, op, "protocol", kProtocolVersion, 0, 1000000);
      if (version != kProtocolVersion) {
        throw RequestError("protocol version " + std::to_string(version) +
                           " not supported; this vb_gym speaks version " +
                           std::to_string(kProtocolVersion));
      }
      json r = {{"type", "hello"}, {"protocol", kProtocolVersion},
                {"vb_version", VB_VERSION}, {"git_commit", io::BuildGitCommit()}};
      *reply_header = Dump(r);
    } else if (op == "configure") {
      Configure(j, reply_header);
    } else if (op == "reset") {
      Reset(j, reply_header, reply_payload);
    } else if (op == "step") {
      Step(j, reply_header, reply_payload);
    } else if (op == "result") {
      ResultReply(j, reply_header);
    } else if (op == "write_result") {
      WriteResult(j, reply_header);
    } else if (op == "write_index") {
      WriteIndex(j, reply_header);
    } else if (op == "close") {
      CheckKeys(j, op, {"op"});
      *reply_header = Dump(json{{"type", "bye"}});
      return false;
    } else {
      throw RequestError("unknown op '" + Abridged(op) +
                         "'; valid: hello, configure, reset, step, result, write_result, "
                         "write_index, close");
    }
  } catch (const RequestError& e) {
    reply_payload->clear();
    *reply_header = ErrorReply(op, "request", e.what());
  } catch (const InputError& e) {
    reply_payload->clear();
    *reply_header = ErrorReply(op, "input", e.what());
  } catch (const IoError& e) {
    reply_payload->clear();
    *reply_header = ErrorReply(op, "io", std::string("I/O error: ") + e.what());
  } catch (const json::exception& e) {
    reply_payload->clear();
    *reply_header = ErrorReply(op, "request", "op '" + Abridged(op) + "': " + e.what());
  } catch (const std::exception& e) {
    reply_payload->clear();
    *reply_header = ErrorReply(op, "internal", "op '" + Abridged(op) + "': internal error: " +
                                                   e.what());
  }
  return true;
}

void Server::Configure(const json& j, std::string* reply) {
  const std::string op = "configure";
  CheckKeys(j, op, {"op", "tasks", "vehicle", "soil", "perception", "control_period_s",
                    "time_limit_s", "rules",
                    "lookahead_m", "replan_period_s", "crops", "action", "speed_kp",
                    "trajectory_every_n_steps", "episode_cache"});
  GymConfig c;
  if (!j.contains("tasks") || !j.at("tasks").is_array() || j.at("tasks").empty()) {
    throw RequestError("op 'configure': key 'tasks': expected a non-empty list of task files");
  }
  for (const json& t : j.at("tasks")) {
    if (!t.is_string()) {
      throw RequestError("op 'configure': key 'tasks': expected file names, got " + Quoted(t));
    }
    c.task_files.push_back(t.get<std::string>());
  }
  c.vehicle = GetString(j, op, "vehicle", c.vehicle);
  c.soil = GetString(j, op, "soil", c.soil);
  c.perception = GetString(j, op, "perception", c.perception);
  const runner::EpisodeRules defaults;
  c.control_period_s = GetNumber(j, op, "control_period_s", c.control_period_s, 1e-9, 60.0);
  const double ratio = c.control_period_s / defaults.step_s;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio || std::round(ratio) < 1.0) {
    throw RequestError("op 'configure': key 'control_period_s': " + Fmt(c.control_period_s) +
                       " s is not a whole number of physics steps of " + Fmt(defaults.step_s) +
                       " s");
  }
  c.time_limit_s = GetNumber(j, op, "time_limit_s", c.time_limit_s, 1e-9,
                            vb::runner::kMaxTimeLimit_s);
  const std::string rules = GetString(j, op, "rules", "vb");
  const std::optional<runner::RuleSet> rule_set = runner::RuleSetFromName(rules);
  if (!rule_set) {
    throw RequestError("op 'configure': key 'rules': " + runner::UnknownRuleSet(rules));
  }
  c.rules = *rule_set;
  c.observation.lookahead_m = GetNumber(j, op, "lookahead_m", c.observation.lookahead_m, 0.0, 1e4);
  c.observation.replan_period_s =
      GetNumber(j, op, "replan_period_s", c.observation.replan_period_s, 0.0, 1e4);
  if (j.contains("crops")) {
    if (!j.at("crops").is_array()) {
      throw RequestError("op 'configure': key 'crops': expected a list of {layer, size_cells, "
                         "resolution_m, name}");
    }
    for (const json& cj : j.at("crops")) {
      if (!cj.is_object()) throw RequestError("op 'configure': crops: expected objects");
      CheckKeys(cj, "configure.crops", {"layer", "size_cells", "resolution_m", "name"});
      controllers::CropSpec spec;
      const std::string layer = GetString(cj, "configure.crops", "layer", "", true);
      spec.layer = ParseLayer(layer);
      spec.size_cells =
          static_cast<int>(GetUnsigned(cj, "configure.crops", "size_cells", 64, 1, 1024));
      spec.resolution_m = GetNumber(cj, "configure.crops", "resolution_m", 0.1, 1e-3, 100.0);
      const std::string name = GetString(cj, "configure.crops", "name", layer);
      CheckName("configure.crops", "name", name);
      if (name == "state" || name == "wheels" ||
          std::find(c.crop_names.begin(), c.crop_names.end(), name) != c.crop_names.end()) {
        throw RequestError("op 'configure': crops: name '" + name +
                           "' used twice (or reserved: state, wheels); give each crop a name");
      }
      c.observation.crops.push_back(spec);
      c.crop_names.push_back(name);
    }
  }
  const std::string action = GetString(j, op, "action", "direct");
  if (action == "direct") {
    c.action = ActionMode::kDirect;
  } else if (action == "speed") {
    c.action = ActionMode::kSpeed;
  } else {
    throw RequestError("op 'configure': key 'action': unknown '" + action +
                       "'; valid: direct, speed");
  }
  c.speed_kp = GetNumber(j, op, "speed_kp", c.speed_kp, 0.0, 1e3);
  c.trajectory_every_n_steps = static_cast<int>(
      GetUnsigned(j, op, "trajectory_every_n_steps", 1, 0, 1000000));
  c.episode_cache = static_cast<int>(GetUnsigned(j, op, "episode_cache", 4, 1, 1000));

  // Every observation frame must stay within the protocol's payload limit (docs/gym_protocol.md),
  // which the client's reader enforces as this server's does: each crop is bounded, so is their
  // sum (NEW-11: 70 crops of 1024 x 1024 made 280 MiB frames).
  uint64_t crop_bytes = 0;
  for (const controllers::CropSpec& crop : c.observation.crops) {
    crop_bytes += static_cast<uint64_t>(crop.size_cells) * crop.size_cells * sizeof(float);
  }
  if (crop_bytes > kMaxCropPayloadBytes) {
    throw RequestError("op 'configure': key 'crops': the crops would make every observation " +
                       std::to_string(crop_bytes) + " bytes, above the limit of " +
                       std::to_string(kMaxCropPayloadBytes) + " (the protocol's payload limit " +
                       "less room for the state arrays)");
  }

  // Load everything before touching the current state: a failed configure changes nothing.
  // The tools' one name rule: names of the data directory's listings, never paths.
  const std::string vehicle_file = io::ListedDataFile(data_dir_, "vehicles", c.vehicle, "vehicle");
  const std::string soil_file = io::ListedDataFile(data_dir_, "soils", c.soil, "soil");
  vehicles::VehicleParams vehicle = io::LoadVehicle(vehicle_file);
  std::vector<terrain::TaskSpec> tasks;
  tasks.reserve(c.task_files.size());
  runner::PerceptionParams perception =
      io::ResolvePerception(c.perception, data_dir_, "perception");
  const std::string perception_file =
      c.perception == "none" ? "" : io::PerceptionFile(c.perception, data_dir_);
  std::optional<soil::SoilConfig> soil;
  for (const std::string& f : c.task_files) {
    tasks.push_back(io::LoadTask(f));
    if (!soil) soil = io::LoadSoilIfNeeded(tasks.back(), soil_file);
  }

  config_ = std::move(c);
  tasks_ = std::move(tasks);
  vehicle_ = std::move(vehicle);
  vehicle_file_ = vehicle_file;
  soil_ = std::move(soil);
  soil_file_ = soil_ ? soil_file : "";
  perception_ = std::move(perception);
  perception_file_ = perception_file;
  cache_.clear();
  episode_ = nullptr;
  task_index_ = -1;
  configured_ = true;

  const size_t num_wheels = vehicle_.axles.size() * 2;
  json arrays = json::array();
  arrays.push_back({{"name", "state"}, {"dtype", "<f8"}, {"shape", {kStateFields.size()}}});
  arrays.push_back(
      {{"name", "wheels"}, {"dtype", "<f8"}, {"shape", {num_wheels, kWheelFields.size()}}});
  for (size_t i = 0; i < config_.observation.crops.size(); ++i) {
    const int n = config_.observation.crops[i].size_cells;
    arrays.push_back({{"name", config_.crop_names[i]}, {"dtype", "<f4"}, {"shape", {n, n}}});
  }
  arrays_json_ = Dump(arrays);

  json r;
  r["type"] = "configured";
  r["state_fields"] = kStateFields;
  r["wheel_fields"] = kWheelFields;
  r["obs_arrays"] = arrays;   // the layout of every observation frame (not arrays of this one)
  r["num_wheels"] = num_wheels;
  r["step_s"] = runner::EpisodeRules().step_s;
  r["control_period_s"] = config_.control_period_s;
  r["time_limit_s"] = config_.time_limit_s;
  r["rules"] = std::string(runner::RuleSetName(config_.rules));
  r["perception"] = perception_.name;
  json tj = json::array();
  for (const terrain::TaskSpec& t : tasks_) {
    tj.push_back({{"name", t.name}, {"file", t.source_file}, {"pairs", t.pairs.size()},
                  {"scale", t.scale}, {"size_x_m", t.size_x_m}, {"size_y_m", t.size_y_m},
                  {"goal_radius_m", config_.rules == runner::RuleSet::kVb
                                        ? runner::EpisodeRules().goal_radius_m * t.scale
                                        : runner::kVertiBenchGoalRadius_m * t.scale}});
  }
  r["tasks"] = tj;
  *reply = Dump(r);
}

runner::Episode& Server::EpisodeFor(int task) {
  ++use_counter_;
  for (CachedEpisode& c : cache_) {
    if (c.task == task) {
      c.last_used = use_counter_;
      return *c.episode;
    }
  }
  if (static_cast<int>(cache_.size()) >= config_.episode_cache) {
    auto oldest = std::min_element(cache_.begin(), cache_.end(),
                                   [](const CachedEpisode& a, const CachedEpisode& b) {
                                     return a.last_used < b.last_used;
                                   });
    if (oldest->episode.get() == episode_) episode_ = nullptr;
    cache_.erase(oldest);
  }
  runner::EpisodeRules rules;
  // The episode advances one physics step per Step call; this server holds the action for the
  // control period (and runs the speed controller every physics step in speed mode).
  rules.control_period_s = rules.step_s;
  rules.time_limit_s = config_.time_limit_s;
  rules.rule_set = config_.rules;
  rules.trajectory_every_n_steps = config_.trajectory_every_n_steps;
  rules.perception = perception_;
  CachedEpisode c;
  c.task = task;
  c.last_used = use_counter_;
  c.episode = std::make_unique<runner::Episode>(tasks_[static_cast<size_t>(task)], vehicle_,
                                                rules, soil_ ? &*soil_ : nullptr);
  c.episode->SetObservationConfig(config_.observation);
  cache_.push_back(std::move(c));
  return *cache_.back().episode;
}

void Server::RequireEpisode(const char* op) const {
  if (!configured_) throw RequestError(std::string("op '") + op + "': send configure first");
  if (episode_ == nullptr) throw RequestError(std::string("op '") + op + "': send reset first");
}

void Server::Reset(const json& j, std::string* reply, std::vector<uint8_t>* payload) {
  const std::string op = "reset";
  if (!configured_) throw RequestError("op 'reset': send configure first");
  CheckKeys(j, op, {"op", "task", "pair", "seed", "system"});
  const int task = static_cast<int>(
      GetUnsigned(j, op, "task", 0, 0, tasks_.size() - 1, /*required=*/true));
  const terrain::TaskSpec& spec_task = tasks_[static_cast<size_t>(task)];
  if (spec_task.pairs.empty()) throw RequestError("op 'reset': task has no start/goal pairs");
  const int pair = static_cast<int>(
      GetUnsigned(j, op, "pair", 0, 0, spec_task.pairs.size() - 1, /*required=*/true));
  runner::TrialSpec spec;
  spec.pair_index = pair;
  spec.seed = GetUnsigned(j, op, "seed", 0, 0, UINT64_MAX);
  spec.system = GetString(j, op, "system", "gym");
  CheckName(op, "system", spec.system);
  spec.vehicle = config_.vehicle;
  episode_ = nullptr;
  runner::Episode& e = EpisodeFor(task);
  e.Reset(spec);
  episode_ = &e;
  task_index_ = task;
  spec_ = spec;
  applied_ = controllers::Command();
  ObservationReply(reply, payload);
}

void Server::Step(const json& j, std::string* reply, std::vector<uint8_t>* payload) {
  const std::string op = "step";
  RequireEpisode("step");
  if (episode_->Done()) {
    throw RequestError("op 'step': the episode is over (" +
                       std::string(runner::TrialStatusName(episode_->Result().status)) +
                       "); send reset");
  }
  controllers::Command command;
  double target_speed_mps = 0.0;
  if (config_.action == ActionMode::kDirect) {
    CheckKeys(j, op, {"op", "throttle", "steering", "braking"});
    command.throttle = GetNumber(j, op, "throttle", 0.0, -1e9, 1e9, true);
    command.steering = GetNumber(j, op, "steering", 0.0, -1e9, 1e9, true);
    command.braking = GetNumber(j, op, "braking", 0.0, -1e9, 1e9, true);
  } else {
    CheckKeys(j, op, {"op", "steering", "speed_mps"});
    command.steering = GetNumber(j, op, "steering", 0.0, -1e9, 1e9, true);
    target_speed_mps = GetNumber(j, op, "speed_mps", 0.0, -1e9, 1e9, true);
  }
  const int steps = static_cast<int>(
      std::lround(config_.control_period_s / episode_->rules().step_s));
  for (int i = 0; i < steps && !episode_->Done(); ++i) {
    if (config_.action == ActionMode::kSpeed) {
      controllers::SpeedControl(target_speed_mps, episode_->vehicle_state().forward_speed_mps,
                                config_.speed_kp, &command);
    }
    // As the episode applies it (Episode::Step clamps to the command ranges).
    applied_.throttle = std::clamp(command.throttle, 0.0, 1.0);
    applied_.steering = std::clamp(command.steering, -1.0, 1.0);
    applied_.braking = std::clamp(command.braking, 0.0, 1.0);
    episode_->Step(command);
  }
  ObservationReply(reply, payload);
}

void Server::ObservationReply(std::string* reply, std::vector<uint8_t>* payload) {
  payload->clear();
  const bool done = episode_->Done();
  std::string result_json;
  runner::TrialStatus status = runner::TrialStatus::kTimeout;
  if (done) {
    runner::TrialResult r = episode_->Result();
    status = r.status;
    r.trajectory.clear();
    result_json = Dump(ResultJson(r));
  }
  // After a sim_error the vehicle state may be non-finite: the observation is not rebuilt from
  // it (the arrays are the last good observation's, or zeros right after reset).
  if (!(done && status == runner::TrialStatus::kSimError)) {
    const controllers::Observation& o = episode_->Observe();
    scratch_.assign({o.time_s,
                     o.position_W.x(), o.position_W.y(), o.position_W.z(),
                     o.rpy.roll_rad, o.rpy.pitch_rad, o.rpy.yaw_rad,
                     o.velocity_W.x(), o.velocity_W.y(), o.velocity_W.z(),
                     o.angular_velocity_B.x(), o.angular_velocity_B.y(),
                     o.angular_velocity_B.z(),
                     o.forward_speed_mps, static_cast<double>(o.gear), o.engine_speed_radps,
                     o.goal_m.x(), o.goal_m.y(), o.goal_distance_m,
                     o.local_goal_m.x(), o.local_goal_m.y(), o.heading_error_rad,
                     applied_.throttle, applied_.steering, applied_.braking});
    AppendFloat64(scratch_, payload);
    scratch_.clear();
    const size_t num_wheels = vehicle_.axles.size() * 2;
    for (size_t i = 0; i < num_wheels; ++i) {
      if (i < o.wheels.size()) {
        const controllers::WheelObservation& w = o.wheels[i];
        scratch_.insert(scratch_.end(), {w.in_contact ? 1.0 : 0.0, static_cast<double>(w.surface),
                                         w.normal_force_n, w.sinkage_m, w.spin_radps, w.slip});
      } else {
        scratch_.insert(scratch_.end(), {0.0, -1.0, 0.0, 0.0, 0.0, 0.0});
      }
    }
    AppendFloat64(scratch_, payload);
    for (const terrain::GridMap& crop : o.crops) AppendFloat32(crop.values, payload);
    last_payload_ = *payload;
  } else {
    *payload = last_payload_;
  }
  *reply = "{\"type\":\"obs\",\"task\":" + std::to_string(task_index_) +
           ",\"pair\":" + std::to_string(spec_.pair_index) +
           ",\"seed\":" + std::to_string(spec_.seed) +
           ",\"time_s\":" + Fmt(episode_->time_s()) +
           ",\"physics_steps\":" + std::to_string(episode_->physics_steps()) +
           ",\"done\":" + (done ? "true" : "false") +
           ",\"status\":\"" + (done ? std::string(runner::TrialStatusName(status)) : "running") +
           "\"" + (done ? ",\"result\":" + result_json : "") +
           ",\"arrays\":" + arrays_json_ + "}";
}

void Server::ResultReply(const json& j, std::string* reply) {
  RequireEpisode("result");
  CheckKeys(j, "result", {"op"});
  runner::TrialResult r = episode_->Result();
  json out = ResultJson(r);
  out["type"] = "result";
  out["done"] = episode_->Done();
  out["task"] = task_index_;
  out["task_name"] = r.task_name;
  out["pair"] = r.spec.pair_index;
  out["seed"] = r.spec.seed;
  *reply = Dump(out);
}

void Server::WriteResult(const json& j, std::string* reply) {
  const std::string op = "write_result";
  RequireEpisode("write_result");
  CheckKeys(j, op, {"op", "dir"});
  const std::string dir = GetString(j, op, "dir", "", /*required=*/true);
  if (!episode_->Done()) {
    throw RequestError("op 'write_result': the episode is still running; results are written "
                       "once it is over");
  }
  if (config_.trajectory_every_n_steps == 0) {
    throw RequestError("op 'write_result': configured with trajectory_every_n_steps = 0 (no "
                       "trajectory); configure with >= 1 to write results");
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw RequestError("op 'write_result': cannot create '" + dir + "': " + ec.message());
  const runner::TrialResult r = episode_->Result();
  const terrain::TaskSpec& task = tasks_[static_cast<size_t>(task_index_)];
  io::Provenance provenance = io::MakeProvenance(task, spec_);
  io::RecordParameterFiles(vehicle_file_, config_.soil, soil_file_, &provenance);
  io::RecordPerception(perception_.name, perception_file_, &provenance);
  const std::string stem = dir + "/" + io::TrialFileStem(r);
  // As vb_run writes them: the trajectory first, so a record's presence implies its trajectory
  // (NEW-3); a write that fails is an error reply of kind "io" (Handle).
  io::WriteTrialFiles(r, stem, provenance);
  *reply = Dump(json{{"type", "written"}, {"json", stem + ".json"},
                     {"trajectory", stem + "_traj.csv"}});
}

void Server::WriteIndex(const json& j, std::string* reply) {
  namespace fs = std::filesystem;
  const std::string op = "write_index";
  CheckKeys(j, op, {"op", "dir"});
  const fs::path dir = GetString(j, op, "dir", "", /*required=*/true);
  const fs::path trials = dir / "trials";
  if (!fs::is_directory(trials)) {
    throw RequestError("op 'write_index': no directory '" + trials.string() + "'");
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(trials)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  // Labels and scale come from the task a record names, identified by its name and FNV-1a:
  // a configured task, else the record's task set path (io::TaskFileCandidates) in the
  // configured tasks' directories, then beside the results.
  std::deque<std::pair<terrain::TaskSpec, std::string>> known;   // task, FNV-1a (stable refs)
  std::vector<std::string> set_dirs;
  for (const terrain::TaskSpec& t : tasks_) {
    known.emplace_back(t, io::TaskFnv1a64(t));
    const std::string d = fs::path(t.source_file).parent_path().string();
    if (std::find(set_dirs.begin(), set_dirs.end(), d) == set_dirs.end()) set_dirs.push_back(d);
  }
  auto matches = [](const batch::TrialRow& r, const terrain::TaskSpec& t, const std::string& h) {
    return t.name == r.task && (r.task_fnv1a64.empty() || h == r.task_fnv1a64);
  };
  auto task_of = [&](const batch::TrialRow& r, const fs::path& record) -> const terrain::TaskSpec& {
    for (const auto& [t, h] : known) {
      if (matches(r, t, h)) return t;
    }
    std::vector<std::string> candidates;
    for (const std::string& d : set_dirs) {
      for (const std::string& c : io::TaskFileCandidates(r.task_file, record.string(), d)) {
        if (std::find(candidates.begin(), candidates.end(), c) == candidates.end()) {
          candidates.push_back(c);
        }
      }
    }
    for (const std::string& c : candidates) {
      std::error_code ec;
      if (!fs::is_regular_file(c, ec)) continue;
      terrain::TaskSpec t = io::LoadTask(c);
      std::string h = io::TaskFnv1a64(t);
      if (!matches(r, t, h)) continue;
      known.emplace_back(std::move(t), std::move(h));
      return known.back().first;
    }
    throw RequestError("op 'write_index': the task of " + record.string() + " (" + r.task_file +
                       ", FNV-1a " + r.task_fnv1a64 + ") is neither configured nor found in "
                       "the configured tasks' directories or beside the results");
  };
  std::vector<batch::TrialRow> rows;
  for (const fs::path& f : files) {
    batch::TrialRow r = io::ReadTrialJson(f.string());
    const terrain::TaskSpec& t = task_of(r, f);
    r.scale = t.scale;
    r.elevation = std::string(terrain::ElevationLevelName(t.labels.elevation));
    r.terrain = std::string(terrain::TerrainTypeName(t.labels.terrain));
    r.density = std::string(terrain::ObstacleDensityName(t.labels.density));
    rows.push_back(std::move(r));
  }
  // vb_batch's matrix order: task, pair, vehicle, system, perception, seed.
  std::sort(rows.begin(), rows.end(), [](const batch::TrialRow& a, const batch::TrialRow& b) {
    return std::tie(a.task, a.pair, a.vehicle, a.system, a.perception, a.seed) <
           std::tie(b.task, b.pair, b.vehicle, b.system, b.perception, b.seed);
  });
  for (size_t i = 0; i < rows.size(); ++i) rows[i].matrix_index = i;
  io::WriteFileAtomic((dir / "index.csv").string(), batch::IndexCsv(rows));
  *reply = Dump(json{{"type", "indexed"}, {"index", (dir / "index.csv").string()},
                {"trials", rows.size()}});
}

}  // namespace vb::gym
