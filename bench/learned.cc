// Cost of the learned baselines (RL, MCL, ACL; docs/learning.md) per decision and per trial.
//  1. One decision: the 76 features from an observation + the policy's forward pass (Eigen,
//     float32), on the observations of a real PID trial (pair 0 of the first task, built with the
//     learned systems' observation config); median and p90 of the thread's CPU time per call.
//  2. The observation itself (builder with the 16 x 16 elevation crop) is measured by
//     vb_bench_observation; whole trials (pairs 0-2 of each TASK) of PID, RL, MCL and ACL:
//     median real-time factor and the controller's share of the wall time.
//   usage: vb_bench_learned [TASK...]   (default: tasks/env042)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "io/model_store.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/controllers/learned_controller.h"
#include "vb/engine/runner/episode.h"

#include "pid_observations.h"

namespace {

using vb::bench::Quantile;
using vb::bench::ThreadCpuSeconds;

}  // namespace

int main(int argc, char** argv) {
  using namespace vb;
  const std::vector<std::string> tasks = bench::BenchTasks(
      "vb_bench_learned", std::vector<std::string>(argv + 1, argv + argc), {"env042"});
  const vehicles::VehicleParams hmmwv = io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  const io::DataDirModelStore store(VB_SOURCE_DIR "/data");

  {
    const terrain::TaskSpec task = io::LoadTask(tasks[0]);
    const controllers::ObservationConfig learned_config = controllers::LearnedObservationConfig();
    const bench::PidObservations pid_run =
        bench::RecordPidTrial(task, hmmwv, nullptr, &learned_config);
    const std::vector<controllers::Observation>& obs = pid_run.observations;
    std::printf("per decision (features + forward), %zu observations of a PID trial:\n",
                obs.size());
    for (const char* system : {"rl", "mcl", "acl"}) {
      const controllers::LearnedController c(system,
                                             store.Load(std::string("policies/") + system +
                                                        ".safetensors"));
      std::array<float, controllers::kLearnedFeatures> f{};
      std::vector<double> cpu, wall;
      float sink = 0.0f;
      for (int rep = 0; rep < 5; ++rep) {
        for (const controllers::Observation& o : obs) {
          const double c0 = ThreadCpuSeconds();
          const auto w0 = std::chrono::steady_clock::now();
          controllers::LearnedFeatures(o, 0.0, f.data());
          const std::array<float, 2> a = c.Act(f.data());
          wall.push_back(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
          cpu.push_back(ThreadCpuSeconds() - c0);
          sink += a[0];
        }
      }
      std::printf("  %-4s median CPU %.2f us, p90 %.2f us; wall median %.2f us (checksum %.3f)\n",
                  system, 1e6 * Quantile(cpu, 0.5), 1e6 * Quantile(cpu, 0.9),
                  1e6 * Quantile(wall, 0.5), sink);
    }
  }

  std::printf("\nwhole trials, pairs 0-2 (median RTF; controller share of the wall time):\n");
  for (const std::string& path : tasks) {
    const terrain::TaskSpec task = io::LoadTask(path);
    const std::optional<soil::SoilConfig> soil = bench::BenchSoil(task);
    std::printf("  %s:", task.name.c_str());
    for (const char* system : {"pid", "rl", "mcl", "acl"}) {
      const bench::PairTrials t =
          bench::RunPairs(task, hmmwv, system, soil ? &*soil : nullptr, &store, 3);
      std::printf("  %s %.1fx (%.1f %%)", system, t.median_rtf, 100.0 * t.controller_share);
    }
    std::printf("\n");
  }
  return 0;
}
