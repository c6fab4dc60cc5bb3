// Cost of the hybrid baselines (WMVCT, MPPI-6, TAL, TNT; docs/baselines.md "Hybrid systems").
//  1. One planner update with its learned model (K x T rollouts through the networks, the cost,
//     TNT's traversability map) on a benchmark world, from the observations of a real PID trial
//     (one every 0.05 s, the planners' rate); median and 90th percentile of wall and CPU time,
//     beside the classical MPPI.
//  2. With --trials: whole trials (pair 0) of each on each TASK: real-time factor and outcome
//     (vb_batch's index.csv has the same per trial: wall_time_s, real_time_factor).
//   usage: vb_bench_hybrid [--trials] [TASK...]   (default: tasks/env008, env017, env026)
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
#include "vb/controllers/controller.h"
#include "vb/engine/runner/episode.h"

#include "pid_observations.h"

namespace {

using Clock = std::chrono::steady_clock;
using vb::bench::Quantile;
using vb::bench::ThreadCpuSeconds;
using vb::bench::TimeCall;

}  // namespace

int main(int argc, char** argv) {
  using namespace vb;
  std::vector<std::string> given;
  bool trials = false;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--trials") {
      trials = true;
    } else {
      given.push_back(argv[i]);
    }
  }
  const std::vector<std::string> tasks =
      bench::BenchTasks("vb_bench_hybrid", given, {"env008", "env017", "env026"});
  const vehicles::VehicleParams hmmwv = io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  const io::DataDirModelStore store(VB_SOURCE_DIR "/data");
  const char* systems[] = {"mppi", "wmvct", "mppi6", "tal", "tnt"};

  {
    const terrain::TaskSpec task = io::LoadTask(tasks[0]);
    const std::optional<soil::SoilConfig> soil = bench::BenchSoil(task);
    const bench::PidObservations pid_run =
        bench::RecordPidTrial(task, hmmwv, soil ? &*soil : nullptr, nullptr);
    const std::vector<controllers::Observation>& obs = pid_run.observations;
    const controllers::EpisodeContext& context = pid_run.context();
    for (const char* system : systems) {
      std::unique_ptr<controllers::Controller> c = controllers::MakeController(system, &store);
      c->Reset(context);
      std::vector<double> us, cpu_us;
      for (size_t i = 0; i < obs.size(); i += 10) {   // 0.05 s apart: each call is an update
        TimeCall([&] { c->Update(obs[i]); }, &us, &cpu_us);
      }
      std::printf("%-6s update on %s: median %.0f us wall (p90 %.0f), %.0f us CPU (p90 %.0f) "
                  "over %zu updates\n", system, task.name.c_str(), Quantile(us, 0.5),
                  Quantile(us, 0.9), Quantile(cpu_us, 0.5), Quantile(cpu_us, 0.9), us.size());
      std::fflush(stdout);
    }
  }

  std::fflush(stdout);
  if (!trials) return 0;
  std::printf("\n| task | system | sim time (s) | RTF (wall) | RTF (CPU) | outcome |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const std::string& path : tasks) {
    const terrain::TaskSpec task = io::LoadTask(path);
    const std::optional<soil::SoilConfig> soil = bench::BenchSoil(task);
    for (const char* system : systems) {
      std::unique_ptr<controllers::Controller> c = controllers::MakeController(system, &store);
      runner::Episode episode(task, hmmwv, runner::EpisodeRules(), soil ? &*soil : nullptr);
      episode.SetObservationConfig(c->observation_config());
      runner::TrialSpec spec;
      spec.system = system;
      episode.Reset(spec);
      c->Reset(episode.context());
      const auto t0 = Clock::now();
      const double c0 = ThreadCpuSeconds();
      while (!episode.Done()) episode.Step(c->Update(episode.Observe()));
      const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
      const double cpu = ThreadCpuSeconds() - c0;
      const double sim = episode.time_s();
      const runner::TrialResult r = episode.Result();
      std::printf("| %s | %s | %.1f | %.1fx | %.1fx | %s |\n", task.name.c_str(), system, sim,
                  sim / wall, sim / cpu, std::string(runner::TrialStatusName(r.status)).c_str());
    }
  }
  return 0;
}
