// Cost of an episode snapshot and of a restore (runner/episode.h), PID + HMMWV at t = 10 s of a
// trial (default pair 0), on a rigid and a deformable world: median over 200 snapshots and 200
// restores (into the same episode), with the trajectory of the first 10 s included, and the cost
// of one simulated second for comparison.
//   usage: vb_bench_snapshot [TASK ...]   (default tasks/env008.yaml tasks/env061.yaml)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/runner/episode.h"

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace vb;
  using Clock = std::chrono::steady_clock;
  std::vector<std::string> tasks;
  for (int i = 1; i < argc; ++i) tasks.push_back(argv[i]);
  if (tasks.empty()) {
    tasks = {VB_SOURCE_DIR "/tasks/env008.yaml", VB_SOURCE_DIR "/tasks/env061.yaml"};
  }
  const vehicles::VehicleParams hmmwv =
      io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  std::printf("vb_bench_snapshot: PID + HMMWV, pair 0, snapshot at t = 10 s (median of 200)\n");
  for (const std::string& path : tasks) {
    const terrain::TaskSpec task = io::LoadTask(path);
    const std::optional<soil::SoilConfig> soil =
        io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml");
    runner::Episode episode(task, hmmwv, runner::EpisodeRules(), soil ? &*soil : nullptr);
    std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
    episode.SetObservationConfig(pid->observation_config());
    episode.Reset(runner::TrialSpec());
    pid->Reset(episode.context());
    const auto t0 = Clock::now();
    while (!episode.Done() && episode.time_s() < 10.0 - 1e-9) {
      episode.Step(pid->Update(episode.Observe()));
    }
    const double sim_second_ms =
        1e3 * std::chrono::duration<double>(Clock::now() - t0).count() / episode.time_s();
    if (episode.Done()) {
      std::printf("  %s: trial ended before 10 s, skipped\n", task.name.c_str());
      continue;
    }
    std::vector<double> snap_us, restore_us;
    runner::EpisodeSnapshot s;
    for (int i = 0; i < 200; ++i) {
      const auto a = Clock::now();
      s = episode.Snapshot();
      const auto b = Clock::now();
      episode.Restore(s);
      const auto c = Clock::now();
      snap_us.push_back(1e6 * std::chrono::duration<double>(b - a).count());
      restore_us.push_back(1e6 * std::chrono::duration<double>(c - b).count());
    }
    std::printf("  %-8s snapshot %8.1f us, restore %8.1f us; one simulated second %.2f ms\n",
                task.name.c_str(), Median(snap_us), Median(restore_us), sim_second_ms);
  }
  return 0;
}
