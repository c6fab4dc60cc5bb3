// Cost of the privileged expert (runner/oracle.h): whole trials of pair 0 with PID and with the
// oracle (budget given as a system name, default "oracle"), HMMWV, on the given tasks. Prints per
// trial the outcome, the process CPU time per simulated second of each system, and the oracle's
// work: replans, early accepts, rollouts and simulated rollout seconds per driven second. CPU
// time (getrusage) rather than wall time, so a loaded machine does not inflate it much.
//   usage: vb_bench_oracle [--system NAME] [TASK ...]
//          (default tasks/env000 env002 env017 env042 env061 env095)
#include <sys/resource.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/oracle.h"
#include "vb/engine/runner/systems.h"

namespace {

double CpuSeconds() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace vb;
  std::string system = "oracle";
  std::vector<std::string> tasks;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--system" && i + 1 < argc) {
      system = argv[++i];
    } else {
      tasks.push_back(a);
    }
  }
  if (tasks.empty()) {
    for (const char* n : {"env000", "env002", "env017", "env042", "env061", "env095"}) {
      tasks.push_back(std::string(VB_SOURCE_DIR "/tasks/") + n + ".yaml");
    }
  }
  const runner::OracleParams params = runner::ParseOracleName(system);
  const vehicles::VehicleParams hmmwv = io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  std::printf("vb_bench_oracle: pair 0, HMMWV, PID vs %s; CPU ms per simulated s\n",
              system.c_str());
  std::printf("%-8s %-9s %7s %8s | %-9s %7s %9s %7s %6s %8s %10s\n", "task", "pid", "sim s",
              "ms/sim s", system.c_str(), "sim s", "ms/sim s", "replans", "early", "rollouts",
              "rollout/s");
  double pid_cpu = 0, pid_sim = 0, or_cpu = 0, or_sim = 0;
  for (const std::string& path : tasks) {
    const terrain::TaskSpec task = io::LoadTask(path);
    const std::optional<soil::SoilConfig> soil =
        io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml");
    runner::EpisodeRules rules;
    rules.trajectory_every_n_steps = 10;
    runner::TrialSpec spec;
    spec.system = "pid";
    double c0 = CpuSeconds();
    const runner::TrialResult p = runner::RunTrial(task, hmmwv, spec, rules, soil ? &*soil : nullptr);
    const double p_cpu = CpuSeconds() - c0;

    runner::Episode episode(task, hmmwv, rules, soil ? &*soil : nullptr);
    runner::OracleController oracle(&episode, params, system);
    c0 = CpuSeconds();
    episode.SetObservationConfig(oracle.observation_config());
    spec.system = system;
    episode.Reset(spec);
    oracle.Reset(episode.context());
    while (!episode.Done()) episode.Step(oracle.Update(episode.Observe()));
    const double o_cpu = CpuSeconds() - c0;
    const runner::TrialResult o = episode.TakeResult();
    const runner::OracleStats& st = oracle.stats();
    const double rollout_s = static_cast<double>(st.rollout_steps) * rules.step_s;
    std::printf("%-8s %-9s %7.2f %8.1f | %-9s %7.2f %9.1f %7ld %6ld %8ld %10.1f\n",
                task.name.c_str(), std::string(runner::TrialStatusName(p.status)).c_str(),
                p.sim_time_s, 1e3 * p_cpu / p.sim_time_s,
                std::string(runner::TrialStatusName(o.status)).c_str(), o.sim_time_s,
                1e3 * o_cpu / o.sim_time_s, st.replans, st.early_accepts, st.rollouts,
                rollout_s / o.sim_time_s);
    std::fflush(stdout);
    pid_cpu += p_cpu;
    pid_sim += p.sim_time_s;
    or_cpu += o_cpu;
    or_sim += o.sim_time_s;
  }
  std::printf("all: pid %.1f CPU ms per simulated s (%.0fx real time); %s %.1f ms (%.1fx real "
              "time), %.1fx the PID's\n",
              1e3 * pid_cpu / pid_sim, pid_sim / pid_cpu, system.c_str(), 1e3 * or_cpu / or_sim,
              or_sim / or_cpu, (or_cpu / or_sim) / (pid_cpu / pid_sim));
  return 0;
}
