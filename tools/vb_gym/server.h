// The vb_gym server: one environment (a set of tasks, one vehicle, one running episode) behind
// the request/reply protocol of docs/gym_protocol.md. Every request frame gets exactly one reply
// frame; a bad request gets an error frame and leaves the server usable. It is a thin loop over
// runner::Episode and its one observation builder: nothing here decides episode outcomes.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "frame.h"
#include "vb/controllers/controller.h"
#include "vb/engine/runner/episode.h"
#include "vb/soil/soil_params.h"
#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::gym {

constexpr int kProtocolVersion = 1;

// How a step request's action becomes the episode's command.
enum class ActionMode {
  kDirect,  // throttle [0, 1], steering [-1, 1], braking [0, 1], held for the control period
  kSpeed,   // steering [-1, 1] + target speed (m/s): throttle/brake from the path followers'
            // proportional speed controller (controllers::SpeedControl), every physics step
};

// What "configure" sets (docs/gym_protocol.md lists keys, units and defaults).
struct GymConfig {
  std::vector<std::string> task_files;
  std::string vehicle = "hmmwv";
  std::string soil = "verti_bench";
  std::string perception = "none";       // preset of data/perception or a .yaml file
  double control_period_s = 0.1;
  double time_limit_s = 60.0;
  runner::RuleSet rules = runner::RuleSet::kVb;   // success and stuck rules (outcome_rules.h)
  controllers::ObservationConfig observation;
  std::vector<std::string> crop_names;   // one per observation.crops entry
  ActionMode action = ActionMode::kDirect;
  double speed_kp = 1.0;
  int trajectory_every_n_steps = 1;      // 0: keep no trajectory (faster; write_result refused)
  int episode_cache = 4;                 // built episodes (static worlds) kept, least recent out
};

class Server {
 public:
  // data_dir: where vehicles/ and soils/ live.
  explicit Server(std::string data_dir);
  ~Server();

  // Handles one request frame; fills the reply. Returns false when the client asked to close
  // (the reply is still to be sent).
  bool Handle(const Frame& request, std::string* reply_header, std::vector<uint8_t>* reply_payload);

 private:
  struct CachedEpisode {
    int task = -1;
    std::unique_ptr<runner::Episode> episode;
    uint64_t last_used = 0;
  };

  void Configure(const nlohmann::json& request, std::string* reply);
  void Reset(const nlohmann::json& request, std::string* reply, std::vector<uint8_t>* payload);
  void Step(const nlohmann::json& request, std::string* reply, std::vector<uint8_t>* payload);
  void ResultReply(const nlohmann::json& request, std::string* reply);
  void WriteResult(const nlohmann::json& request, std::string* reply);
  // Rebuilds DIR/index.csv (vb_batch's format, docs/batch.md) from every record in DIR/trials,
  // so that vb_report shows gym-evaluated systems beside vb_batch's baselines.
  void WriteIndex(const nlohmann::json& request, std::string* reply);
  runner::Episode& EpisodeFor(int task);
  void ObservationReply(std::string* reply, std::vector<uint8_t>* payload);
  void RequireEpisode(const char* op) const;

  std::string data_dir_;
  bool configured_ = false;
  GymConfig config_;
  std::vector<terrain::TaskSpec> tasks_;
  vehicles::VehicleParams vehicle_;
  std::string vehicle_file_;
  std::optional<soil::SoilConfig> soil_;
  std::string soil_file_;
  runner::PerceptionParams perception_;
  std::string perception_file_;          // "" for ground truth
  std::string arrays_json_;   // the obs frame's "arrays" list (fixed by the configuration)
  std::vector<CachedEpisode> cache_;
  uint64_t use_counter_ = 0;
  runner::Episode* episode_ = nullptr;   // the running episode (points into cache_)
  int task_index_ = -1;
  runner::TrialSpec spec_;
  controllers::Command applied_;         // command of the last physics step (clamped)
  std::vector<double> scratch_;          // reused buffers of the obs frame
  std::vector<uint8_t> last_payload_;    // arrays of the last good observation
};

}  // namespace vb::gym
