// Cost of the classical baselines' decisions and their whole-trial speed.
//  1. One MPPI update (800 samples x 20 steps, bicycle model, goal + obstacle cost) on a benchmark
//     world, from the states of a real trial with the local goal of its observation; median and
//     90th percentile over all updates, for the intent and the original variants.
//  2. One EH decision (six 6.4 m regions of 16 x 16 height samples + the steering law): median.
//  3. Whole trials of EH and MPPI (pairs 0-2) on each TASK: real-time factor (median) and the
//     controller's share of the wall time.
//   usage: vb_bench_controllers [TASK...]   (default: tasks/env008, env017, env026)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/controllers/eh_controller.h"
#include "vb/controllers/mppi_controller.h"
#include "vb/engine/runner/episode.h"

#include "pid_observations.h"

int main(int argc, char** argv) {
  using namespace vb;
  using bench::Quantile;
  using bench::TimeCall;
  const std::vector<std::string> tasks = bench::BenchTasks(
      "vb_bench_controllers", std::vector<std::string>(argv + 1, argv + argc),
      {"env008", "env017", "env026"});
  const vehicles::VehicleParams hmmwv =
      io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");

  // 1 + 2: per-decision cost on the first task, from the observations of a real PID trial.
  {
    const terrain::TaskSpec task = io::LoadTask(tasks[0]);
    const std::optional<soil::SoilConfig> soil = bench::BenchSoil(task);
    const bench::PidObservations pid_run =
        bench::RecordPidTrial(task, hmmwv, soil ? &*soil : nullptr, nullptr);
    const std::vector<controllers::Observation>& obs = pid_run.observations;
    const controllers::EpisodeContext& context = pid_run.context();

    for (const char* variant : {"mppi", "mppi_original"}) {
      controllers::MppiController mppi(std::string(variant) == "mppi"
                                           ? controllers::MppiIntentParams()
                                           : controllers::MppiOriginalParams(),
                                       variant);
      mppi.Reset(context);
      std::vector<double> us, cpu_us;
      for (size_t i = 0; i < obs.size(); i += 10) {   // each one a 20 Hz update
        TimeCall([&] { mppi.Update(obs[i]); }, &us, &cpu_us);
      }
      std::printf("%-14s update (K 800 x T 20) on %s: median %.0f us wall (p90 %.0f), "
                  "%.0f us CPU (p90 %.0f) over %zu updates\n",
                  variant, task.name.c_str(), Quantile(us, 0.5), Quantile(us, 0.9),
                  Quantile(cpu_us, 0.5), Quantile(cpu_us, 0.9), us.size());
    }
    for (const char* variant : {"eh", "eh_original"}) {
      std::unique_ptr<controllers::Controller> eh = controllers::MakeController(variant);
      eh->Reset(context);
      std::vector<double> us, cpu_us;
      for (int rep = 0; rep < 5; ++rep) {
        TimeCall([&] { for (const controllers::Observation& o : obs) eh->Update(o); }, &us,
                 &cpu_us, static_cast<double>(obs.size()));
      }
      std::printf("%-14s decision on %s: median %.1f us wall, %.1f us CPU (5 runs over %zu "
                  "observations)\n", variant, task.name.c_str(), Quantile(us, 0.5),
                  Quantile(cpu_us, 0.5), obs.size());
    }
  }

  // 3: whole trials.
  std::printf("\n| task | system | trials | median RTF | controller share | outcomes |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const std::string& path : tasks) {
    const terrain::TaskSpec task = io::LoadTask(path);
    const std::optional<soil::SoilConfig> soil = bench::BenchSoil(task);
    for (const char* system : {"pid", "eh", "mppi"}) {
      const bench::PairTrials t =
          bench::RunPairs(task, hmmwv, system, soil ? &*soil : nullptr, nullptr, 3);
      std::printf("| %s | %s | 3 | %.1fx | %.0f %% | %s |\n", task.name.c_str(), system,
                  t.median_rtf, 100.0 * t.controller_share, t.outcomes.c_str());
    }
  }
  return 0;
}
