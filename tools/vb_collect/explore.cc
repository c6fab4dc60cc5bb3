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
    const long k = o.episodes_per_world;
    for (long first = 0; first < o.episodes; first += k) {
      WorkItem item;
      for (long e = first; e < std::min(o.episodes, first + k); ++e) item.episodes.push_back(e);
      items_.push_back(item);
    }
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
    const long w = item.episodes.front() / o_.episodes_per_world;
    const GeneratedWorld world = WriteWorld(o_, w);
    const vb::terrain::GeneratorOptions& gen = world.options;
    const vb::terrain::TaskSpec& task = world.task;
    const std::optional<vb::soil::SoilConfig> soil = vb::io::LoadSoilIfNeeded(task, soil_file_);

    vb::runner::EpisodeRules rules;
    rules.time_limit_s = o_.max_episode_s;
    rules.goal_ends_trial = false;
    rules.trajectory_every_n_steps = 0;
    vb::runner::Episode episode(task, vehicle_, rules, soil ? &*soil : nullptr);
    for (long e : todo) {
      const int j = static_cast<int>(e - item.episodes.front());
      vb::runner::TrialSpec spec;
      spec.pair_index = j % static_cast<int>(task.pairs.size());
      spec.seed = gen.seed * 100 + static_cast<uint64_t>(j);
      spec.system = "explorer";
      spec.vehicle = o_.vehicle;
      episode.Reset(spec);
      const vb::dataset::ExplorerParams p = vb::dataset::DrawExplorerParams(spec.seed);
      vb::dataset::ExplorerPolicy policy(p, config_.sample_every_steps);
      vb::dataset::EpisodeRecord r = vb::dataset::RecordEpisode(episode, policy, config_);
      AddCommonAttributes(o_, e, spec.seed, &r);
      vb::io::Provenance prov = vb::io::MakeProvenance(task, spec);
      r.SetText("mode", "explore");
      r.SetText("task", task.name);
      r.SetText("task_file", "worlds/" + gen.name + ".yaml");
      r.SetText("task_fnv1a64", prov.task_fnv1a64);
      r.SetInt("pair", spec.pair_index);
      r.SetText("vehicle", o_.vehicle);
      r.SetText("vehicle_fnv1a64", vb::io::FileFnv1a64Hex(vehicle_file_));
      r.SetText("soil", soil ? o_.soil : "");
      r.SetText("system", "explorer");
      r.SetInt("world_seed", static_cast<int64_t>(gen.seed));
      r.SetText("elevation", std::string(vb::terrain::ElevationLevelName(gen.elevation)));
      r.SetText("terrain", std::string(vb::terrain::TerrainTypeName(gen.terrain)));
      r.SetText("density", std::string(vb::terrain::ObstacleDensityName(gen.density)));
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
