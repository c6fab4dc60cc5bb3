// explore mode: generated worlds (vb_gen's generator, seeds outside the benchmark's), the random
// explorer from every start of each world (docs/datasets.md "Random exploration").
#include <algorithm>
#include <optional>
#include <string>

#include "io/result_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "io/yaml_strict.h"
#include "mode.h"
#include "worlds.h"
#include "vb/dataset/explorer.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "vb/terrain/generator.h"

namespace vb_collect {

namespace {

class ExploreMode : public Mode {
 public:
  explicit ExploreMode(const Options& o)
      : o_(o),
        config_(MakeSampleConfig(o)),
        vehicle_file_(DataDir() + "/vehicles/" + o.vehicle + ".yaml"),
        soil_file_(DataDir() + "/soils/" + o.soil + ".yaml"),
        vehicle_(vb::io::LoadVehicle(vehicle_file_)) {
    items_ = WorldWorkItems(o);
  }

  const std::vector<WorkItem>& items() const override { return items_; }
  std::string Settings() const override {
    return "mode=explore episodes=" + std::to_string(o_.episodes) +
           " world_seed=" + std::to_string(o_.world_seed) +
           " episodes_per_world=" + std::to_string(o_.episodes_per_world) +
           " max_episode_s=" + vb::io::FormatDouble(o_.max_episode_s) + " vehicle=" + o_.vehicle +
           ":" + vb::io::FileFnv1a64Hex(vehicle_file_) + " soil=" + o_.soil + ":" +
           vb::io::FileFnv1a64Hex(soil_file_) + " sample_period_s=" +
           vb::io::FormatDouble(o_.sample_period_s) + " crops=" + o_.crops + " crop_size=" +
           std::to_string(o_.crop_size) + " crop_res=" + vb::io::FormatDouble(o_.crop_resolution_m);
  }
  std::string AlgorithmName() const override {
    return "vb random explorer (sinusoidal steering, 2 m/s)";
  }
  vb::dataset::ActionKind action_kind() const override { return vb::dataset::ActionKind::kSpeed; }
  size_t wheels() const override { return vehicle_.axles.size() * 2; }

  void Run(const WorkItem& item, const std::vector<long>& todo, const EpisodeSink& sink) override {
    vb::runner::EpisodeRules rules;
    rules.time_limit_s = o_.max_episode_s;
    rules.goal_ends_trial = false;
    rules.trajectory_every_n_steps = 0;
    WorldEpisodes world(o_, item, vehicle_, rules);
    vb::runner::Episode& episode = world.episode();
    for (long e : todo) {
      const vb::runner::TrialSpec spec = world.Spec(e, "explorer");
      episode.Reset(spec);
      const vb::dataset::ExplorerParams p = vb::dataset::DrawExplorerParams(spec.seed);
      vb::dataset::ExplorerPolicy policy(p, config_.sample_every_steps);
      vb::dataset::EpisodeRecord r = vb::dataset::RecordEpisode(episode, policy, config_);
      world.Describe(e, spec, "explore", &r);
      r.SetReal("explorer_amplitude", p.amplitude);
      r.SetReal("explorer_period_s", p.period_s);
      r.SetReal("explorer_phase_rad", p.phase_rad);
      r.SetReal("explorer_target_speed_mps", p.target_speed_mps);
      sink(e, r);
    }
  }

 private:
  Options o_;
  vb::dataset::SampleConfig config_;
  std::string vehicle_file_, soil_file_;
  vb::vehicles::VehicleParams vehicle_;
  std::vector<WorkItem> items_;
};

}  // namespace

std::unique_ptr<Mode> MakeExploreMode(const Options& o) { return std::make_unique<ExploreMode>(o); }

}  // namespace vb_collect
