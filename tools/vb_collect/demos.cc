// demos mode: expert demonstrations (docs/datasets.md "Expert demonstrations"). The expert
// (--system, default the privileged oracle) drives from every start of generated worlds (the
// explore mode's worlds: seeds outside the benchmark's) to the pair's goal under the benchmark's
// rules; only its successful episodes are kept, as the paper filters its human demonstrations.
// A failed episode leaves an empty episode file (status and message kept, so a resumed run
// does not retry it) that the assembly leaves out.
#include <algorithm>
#include <optional>
#include <string>

#include "io/model_store.h"
#include "io/result_io.h"
#include "io/yaml_strict.h"
#include "io/soil_io.h"
#include "io/vehicle_io.h"
#include "mode.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/systems.h"
#include "worlds.h"

namespace vb_collect {

namespace {

class DemosMode : public Mode {
 public:
  explicit DemosMode(const Options& o)
      : o_(o),
        config_(MakeSampleConfig(o)),
        vehicle_file_(DataDir() + "/vehicles/" + o.vehicle + ".yaml"),
        soil_file_(DataDir() + "/soils/" + o.soil + ".yaml"),
        vehicle_(vb::io::LoadVehicle(vehicle_file_)) {
    vb::runner::ValidateSystemName(o.system, "--system");
    const long k = o.episodes_per_world;
    for (long first = 0; first < o.episodes; first += k) {
      WorkItem item;
      for (long e = first; e < std::min(o.episodes, first + k); ++e) item.episodes.push_back(e);
      items_.push_back(item);
    }
  }

  const std::vector<WorkItem>& items() const override { return items_; }
  std::string Settings() const override {
    return "mode=demos episodes=" + std::to_string(o_.episodes) +
           " world_seed=" + std::to_string(o_.world_seed) +
           " episodes_per_world=" + std::to_string(o_.episodes_per_world) +
           " system=" + o_.system + " time_limit_s=" + vb::io::FormatDouble(o_.time_limit_s) +
           " vehicle=" + o_.vehicle + ":" + vb::io::FileFnv1a64Hex(vehicle_file_) +
           " soil=" + o_.soil + ":" + vb::io::FileFnv1a64Hex(soil_file_) +
           " sample_period_s=" + vb::io::FormatDouble(o_.sample_period_s) + " crops=" + o_.crops +
           " crop_size=" + std::to_string(o_.crop_size) +
           " crop_res=" + vb::io::FormatDouble(o_.crop_resolution_m);
  }
  std::string AlgorithmName() const override {
    return "vb expert demonstrations (" + o_.system + ", successes only)";
  }
  vb::dataset::ActionKind action_kind() const override { return vb::dataset::ActionKind::kDirect; }
  size_t wheels() const override { return vehicle_.axles.size() * 2; }

  void Run(const WorkItem& item, const std::vector<long>& todo, const EpisodeSink& sink) override {
    const long w = item.episodes.front() / o_.episodes_per_world;
    const GeneratedWorld world = WriteWorld(o_, w);
    const vb::terrain::GeneratorOptions& gen = world.options;
    const vb::terrain::TaskSpec& task = world.task;
    const std::optional<vb::soil::SoilConfig> soil = vb::io::LoadSoilIfNeeded(task, soil_file_);

    vb::runner::EpisodeRules rules;
    rules.time_limit_s = o_.time_limit_s;
    rules.trajectory_every_n_steps = 0;
    vb::runner::Episode episode(task, vehicle_, rules, soil ? &*soil : nullptr);
    for (long e : todo) {
      const int j = static_cast<int>(e - item.episodes.front());
      vb::runner::TrialSpec spec;
      spec.pair_index = j % static_cast<int>(task.pairs.size());
      spec.seed = gen.seed * 100 + static_cast<uint64_t>(j);
      spec.system = o_.system;
      spec.vehicle = o_.vehicle;
      vb::dataset::ControllerPolicy policy(vb::runner::MakeSystem(o_.system, episode, &models_));
      episode.Reset(spec);
      policy.Start(episode);
      vb::dataset::EpisodeRecord r = vb::dataset::RecordEpisode(episode, policy, config_);
      const std::string status = r.FindAttribute("status")->text;
      if (status != "success") {
        // Filtered out (the paper keeps only successful demonstrations): an empty episode that
        // says why, left out of the assembled dataset and not retried on resume.
        const std::string message = r.FindAttribute("message")->text;
        r = vb::dataset::EpisodeRecord();
        r.SetText("status", status);
        r.SetText("message", "filtered out (not a success): " + message);
        r.SetReal("sim_time_s", episode.time_s());
      }
      AddCommonAttributes(o_, e, spec.seed, &r);
      const vb::io::Provenance prov = vb::io::MakeProvenance(task, spec);
      r.SetText("mode", "demos");
      r.SetText("task", task.name);
      r.SetText("task_file", "worlds/" + gen.name + ".yaml");
      r.SetText("task_fnv1a64", prov.task_fnv1a64);
      r.SetInt("pair", spec.pair_index);
      r.SetText("vehicle", o_.vehicle);
      r.SetText("vehicle_fnv1a64", vb::io::FileFnv1a64Hex(vehicle_file_));
      r.SetText("soil", soil ? o_.soil : "");
      r.SetText("system", o_.system);
      r.SetInt("world_seed", static_cast<int64_t>(gen.seed));
      r.SetText("elevation", std::string(vb::terrain::ElevationLevelName(gen.elevation)));
      r.SetText("terrain", std::string(vb::terrain::TerrainTypeName(gen.terrain)));
      r.SetText("density", std::string(vb::terrain::ObstacleDensityName(gen.density)));
      r.SetReal("time_limit_s", o_.time_limit_s);
      sink(e, r);
    }
  }

 private:
  Options o_;
  vb::dataset::SampleConfig config_;
  std::string vehicle_file_, soil_file_;
  vb::vehicles::VehicleParams vehicle_;
  std::vector<WorkItem> items_;
  vb::io::DataDirModelStore models_{DataDir()};   // weights of learned experts, read on first use
};

}  // namespace

std::unique_ptr<Mode> MakeDemosMode(const Options& o) { return std::make_unique<DemosMode>(o); }

}  // namespace vb_collect
