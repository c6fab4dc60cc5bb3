// The in-process reference for the gym throughput benchmark (bench/gym_throughput.py): the same
// work vb_gym does per env step, without the protocol and Python. An Episode stepped with random
// actions in "speed" mode (uniform steering in [-1, 1], uniform target speed in [-4, 4] m/s,
// held for the control period with the speed controller every 5 ms physics step), a 64 x 64
// elevation crop at 0.1 m observed after every control period, every episode from pair 0 (the
// gym benchmark restricts its envs to pair 0 too: the soil under the start decides much of the
// cost on deformable worlds, so both must drive the same ground). Reports env steps per second and simulated seconds per wall second
// (median over runs), by wall clock and by CPU time (the CPU figure is what a shared, loaded
// machine distorts least); setup (episode construction) excluded as vb_gym caches it.
//   usage: vb_bench_gym_inprocess [TASK] [STEPS] [RUNS] [CONTROL_PERIOD_S]
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"
#include "vb/engine/rng.h"
#include "vb/engine/runner/episode.h"

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  using Clock = std::chrono::steady_clock;
  const std::string task_path = argc > 1 ? argv[1] : VB_SOURCE_DIR "/tasks/env000.yaml";
  const long steps = argc > 2 ? std::atol(argv[2]) : 3000;
  const int runs = argc > 3 ? std::atoi(argv[3]) : 3;
  const double period_s = argc > 4 ? std::atof(argv[4]) : 0.1;
  if (steps < 1 || runs < 1 || !(period_s > 0.0)) {
    std::fprintf(stderr, "usage: vb_bench_gym_inprocess [TASK] [STEPS >= 1] [RUNS >= 1] "
                         "[CONTROL_PERIOD_S > 0]\n");
    return 2;
  }
  try {
    const vb::terrain::TaskSpec task = vb::io::LoadTask(task_path);
    const vb::vehicles::VehicleParams params =
        vb::io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
    const std::optional<vb::soil::SoilConfig> soil =
        vb::io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml");
    vb::runner::EpisodeRules rules;
    rules.control_period_s = rules.step_s;   // as vb_gym: it holds the action itself
    rules.trajectory_every_n_steps = 0;      // as the gym's default (no results written)
    vb::runner::Episode episode(task, params, rules, soil ? &*soil : nullptr);
    vb::controllers::ObservationConfig obs_config;
    obs_config.crops.push_back({vb::terrain::MapLayer::kElevation, 64, 0.1});
    episode.SetObservationConfig(obs_config);
    const int per_period = static_cast<int>(std::lround(period_s / rules.step_s));
    std::printf("vb_bench_gym_inprocess %s %ld %d %g: random actions, speed mode, 64x64 crop\n",
                task_path.c_str(), steps, runs, period_s);
    std::vector<double> steps_per_s, rtf, cpu_rtf;
    for (int r = 0; r < runs; ++r) {
      vb::Rng rng(1234 + static_cast<uint64_t>(r));
      vb::runner::TrialSpec spec;
      spec.pair_index = 0;
      episode.Reset(spec);
      double sim_s = 0.0;
      double checksum = 0.0;
      const auto t0 = Clock::now();
      const std::clock_t cpu0 = std::clock();
      for (long k = 0; k < steps; ++k) {
        if (episode.Done()) {
          sim_s += episode.time_s();
          episode.Reset(spec);
        }
        vb::controllers::Command command;
        command.steering = rng.Uniform(-1.0, 1.0);
        const double target_mps = rng.Uniform(-4.0, 4.0);
        for (int i = 0; i < per_period && !episode.Done(); ++i) {
          vb::controllers::SpeedControl(target_mps, episode.vehicle_state().forward_speed_mps,
                                        1.0, &command);
          episode.Step(command);
        }
        checksum += episode.Observe().crops[0].values[0];
      }
      sim_s += episode.time_s();
      const double wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
      steps_per_s.push_back(static_cast<double>(steps) / wall_s);
      rtf.push_back(sim_s / wall_s);
      const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
      cpu_rtf.push_back(sim_s / cpu_s);
      std::printf("run %d: %ld env steps, %.1f s simulated in %.3f s (%.3f s CPU): %.0f steps/s, "
                  "%.1fx real time (%.1fx per CPU s; checksum %.3f)\n",
                  r + 1, steps, sim_s, wall_s, cpu_s, steps_per_s.back(), rtf.back(),
                  cpu_rtf.back(), checksum);
    }
    std::printf("median over %d runs: %.0f env steps/s, %.1fx real time, %.1fx per CPU s\n",
                runs, Median(steps_per_s), Median(rtf), Median(cpu_rtf));
  } catch (const vb::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
