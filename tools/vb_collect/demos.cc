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
    items_ = WorldWorkItems(o);
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
    vb::runner::EpisodeRules rules;
    rules.time_limit_s = o_.time_limit_s;
    rules.trajectory_every_n_steps = 0;
    WorldEpisodes world(o_, item, vehicle_, rules);
    vb::runner::Episode& episode = world.episode();
    for (long e : todo) {
      const vb::runner::TrialSpec spec = world.Spec(e, o_.system);
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
      world.Describe(e, spec, "demos", &r);
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
