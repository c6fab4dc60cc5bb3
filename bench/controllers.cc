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

namespace {

using Clock = std::chrono::steady_clock;
using vb::bench::Quantile;
using vb::bench::ThreadCpuSeconds;

}  // namespace

int main(int argc, char** argv) {
  using namespace vb;
  std::vector<std::string> tasks;
  for (int i = 1; i < argc; ++i) tasks.push_back(argv[i]);
  if (tasks.empty()) {
    for (const char* t : {"env008", "env017", "env026"}) {
      tasks.push_back(std::string(VB_SOURCE_DIR) + "/tasks/" + t + ".yaml");
    }
  }
  const vehicles::VehicleParams hmmwv =
      io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  std::printf("command: vb_bench_controllers");
  for (const std::string& t : tasks) std::printf(" %s", t.c_str());
  std::printf("\n\n");

  // 1 + 2: per-decision cost on the first task, from the observations of a real PID trial.
  {
    const terrain::TaskSpec task = io::LoadTask(tasks[0]);
    const std::optional<soil::SoilConfig> soil =
        io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml");
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
        const auto t0 = Clock::now();
        const double c0 = ThreadCpuSeconds();
        mppi.Update(obs[i]);
        cpu_us.push_back(1e6 * (ThreadCpuSeconds() - c0));
        us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
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
        const auto t0 = Clock::now();
        const double c0 = ThreadCpuSeconds();
        for (const controllers::Observation& o : obs) eh->Update(o);
        cpu_us.push_back(1e6 * (ThreadCpuSeconds() - c0) / obs.size());
        us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() /
                     obs.size());
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
    const std::optional<soil::SoilConfig> soil =
        io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml");
    for (const char* system : {"pid", "eh", "mppi"}) {
      std::vector<double> rtf;
      double controller_s = 0.0, wall_s = 0.0;
      std::string outcomes;
      for (int pair = 0; pair < 3; ++pair) {
        runner::StepTimings timings;
        runner::EpisodeRules rules;
        rules.timings = &timings;
        runner::TrialSpec spec;
        spec.pair_index = pair;
        spec.system = system;
        const runner::TrialResult r =
            runner::RunTrial(task, hmmwv, spec, rules, soil ? &*soil : nullptr);
        rtf.push_back(r.real_time_factor);
        controller_s += timings.controller_s;
        wall_s += r.wall_time_s;
        outcomes += std::string(outcomes.empty() ? "" : " ") +
                    std::string(runner::TrialStatusName(r.status));
      }
      std::printf("| %s | %s | 3 | %.1fx | %.0f %% | %s |\n", task.name.c_str(), system,
                  Quantile(rtf, 0.5), 100.0 * controller_s / wall_s, outcomes.c_str());
    }
  }
  return 0;
}
