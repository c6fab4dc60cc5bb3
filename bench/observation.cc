// Cost of one observation (runner/observation_builder.h) on a benchmark world, per
// configuration: robot state + navigation only (what PID uses), plus the crops of the original's
// systems (EH: 64 x 64 elevation at 0.1 m; MPPI: 28 x 28 elevation and occupancy at 0.1 m; RL:
// 64 x 64 elevation at 0.1 m; a rich one: 64 x 64 elevation, semantics, friction, occupancy).
// The vehicle states are those of a real PID trial (pair 0), so replanning happens at its 10 Hz
// cadence as in an episode. Median over 5 runs of the mean cost per observation.
// Each configuration is measured with ground truth and with the `moderate` perception preset
// (docs/perception.md: pose errors, map errors and holes, confusion, perceived obstacles).
//   usage: vb_bench_observation [TASK]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "io/perception_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/observation_builder.h"

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace vb;
  const std::string task_path = argc > 1 ? argv[1] : VB_SOURCE_DIR "/tasks/env008.yaml";
  const terrain::TaskSpec task = io::LoadTask(task_path);
  const vehicles::VehicleParams hmmwv =
      io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  const std::optional<soil::SoilConfig> soil =
      io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml");

  // The states of a real trial, every physics step.
  runner::Episode episode(task, hmmwv, runner::EpisodeRules(), soil ? &*soil : nullptr);
  std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
  episode.SetObservationConfig(pid->observation_config());
  runner::TrialSpec spec;
  episode.Reset(spec);
  pid->Reset(episode.context());
  std::vector<vehicles::VehicleState> states;
  std::vector<double> times;
  while (!episode.Done()) {
    states.push_back(episode.vehicle_state());
    times.push_back(episode.time_s());
    episode.Step(pid->Update(episode.Observe()));
  }

  struct Config {
    const char* name;
    std::vector<controllers::CropSpec> crops;
  };
  using L = terrain::MapLayer;
  const std::vector<Config> configs = {
      {"state + navigation (PID)", {}},
      {"+ 28x28 elevation + occupancy @0.1 m (MPPI)", {{L::kElevation, 28, 0.1}, {L::kOccupancy, 28, 0.1}}},
      {"+ 64x64 elevation @0.1 m (EH, RL)", {{L::kElevation, 64, 0.1}}},
      {"+ 64x64 elevation, semantics, friction, occupancy", {{L::kElevation, 64, 0.1}, {L::kSemantics, 64, 0.1}, {L::kFriction, 64, 0.1}, {L::kOccupancy, 64, 0.1}}},
  };
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid grid =
      terrain::Inflate(terrain::RasterizeObstacles(task), terrain::PlannerInflationCells(task));
  std::printf("vb_bench_observation %s: %zu states of pair 0 (%.1f s simulated)\n",
              task_path.c_str(), states.size(), times.back());
  const runner::PerceptionParams moderate =
      io::ResolvePerception("moderate", VB_SOURCE_DIR "/data");
  for (const Config& c : configs) {
    controllers::ObservationConfig oc;
    oc.crops = c.crops;
    for (const runner::PerceptionParams& perception : {runner::PerceptionParams(), moderate}) {
      std::vector<double> per_call_us;
      for (int run = 0; run < 5; ++run) {
        runner::ObservationBuilder builder(maps, grid, task.scale);
        builder.SetConfig(oc);
        builder.SetPerception(perception, 0.005);
        builder.Reset(task.pairs[0].goal_m, 0, task);
        controllers::Observation obs;
        const auto t0 = std::chrono::steady_clock::now();
        for (size_t i = 0; i < states.size(); ++i) {
          if (perception.Enabled()) builder.Record(static_cast<long>(i), states[i]);
          builder.Build(static_cast<long>(i), times[i], states[i], &obs);
        }
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        per_call_us.push_back(1e6 * s / static_cast<double>(states.size()));
      }
      std::printf("  %-52s %-8s %8.2f us per observation (median of 5 runs)\n", c.name,
                  perception.name.c_str(), Median(per_call_us));
    }
  }
  return 0;
}
