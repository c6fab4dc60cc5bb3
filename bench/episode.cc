// Whole-trial speed of the HMMWV with the PID system over a world (default tasks/env008.yaml:
// high elevation, dense obstacles, rigid; deformable worlds get data/soils/verti_bench.yaml),
// all start/goal pairs, repeated RUNS times. Reports per run the real-time factor (simulated s /
// wall s over all pairs, setup included) and the median over runs, plus the median step-time
// breakdown from the runner's optional timing hook (controller, vehicle synchronise = suspension +
// powertrain + tire contact, soil, Bullet step, vehicle state read-out, runner bookkeeping,
// setup). One trial at a time on one core.
// Besides the wall-clock RTF it reports the CPU-time RTF (simulated s / process CPU s): on the
// shared 2-core machine other jobs stretch wall time, not CPU time.
//   usage: vb_bench_episode [TASK] [RUNS] [VEHICLE] [STEP_S] [SOIL_FILE]
// SOIL_FILE: the soil parameters of deformable worlds (default data/soils/verti_bench.yaml).
#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string task_path = argc > 1 ? argv[1] : VB_SOURCE_DIR "/tasks/env008.yaml";
  const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  const std::string vehicle = argc > 3 ? argv[3] : "hmmwv";
  const double step_s = argc > 4 ? std::atof(argv[4]) : 0.005;
  const std::string soil_path =
      argc > 5 ? argv[5] : VB_SOURCE_DIR "/data/soils/verti_bench.yaml";
  if (runs < 1 || !(step_s > 0.0)) {
    std::fprintf(stderr,
                 "usage: vb_bench_episode [TASK] [RUNS >= 1] [VEHICLE] [STEP_S > 0] [SOIL_FILE]\n");
    return 2;
  }
  try {
    const vb::terrain::TaskSpec task = vb::io::LoadTask(task_path);
    const vb::vehicles::VehicleParams params =
        vb::io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/" + vehicle + ".yaml");
    const std::optional<vb::soil::SoilConfig> soil =
        vb::io::LoadSoilIfNeeded(task, soil_path);
    std::printf("vb_bench_episode %s %d %s %g: %zu pairs x %d runs, PID, step %g s\n",
                task_path.c_str(), runs, vehicle.c_str(), step_s, task.pairs.size(), runs, step_s);

    std::vector<double> rtf, cpu_rtf, ctrl, sync, soil_us, step, update, book, setup;
    for (int r = 0; r < runs; ++r) {
      vb::runner::StepTimings t;
      vb::runner::EpisodeRules rules;
      rules.step_s = step_s;
      rules.timings = &t;
      double sim_s = 0.0, wall_s = 0.0;
      int successes = 0;
      const std::clock_t cpu0 = std::clock();
      for (int pair = 0; pair < static_cast<int>(task.pairs.size()); ++pair) {
        vb::runner::TrialSpec spec;
        spec.pair_index = pair;
        spec.vehicle = vehicle;
        const vb::runner::TrialResult res = vb::runner::RunTrial(task, params, spec, rules, soil ? &*soil : nullptr);
        sim_s += res.sim_time_s;
        wall_s += res.wall_time_s;
        successes += res.status == vb::runner::TrialStatus::kSuccess;
      }
      const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
      const double us = 1e6 / static_cast<double>(t.steps);
      rtf.push_back(sim_s / wall_s);
      cpu_rtf.push_back(sim_s / cpu_s);
      ctrl.push_back(t.controller_s * us);
      sync.push_back(t.vehicle_sync_s * us);
      soil_us.push_back(t.soil_s * us);
      step.push_back(t.physics_step_s * us);
      update.push_back(t.vehicle_update_s * us);
      book.push_back(t.bookkeeping_s * us);
      setup.push_back(t.setup_s / static_cast<double>(task.pairs.size()) * 1e3);
      std::printf("run %d: %d/%zu success, %.1f s simulated in %.3f s wall (%.3f s CPU), RTF %.1f "
                  "wall / %.1f CPU, %ld steps\n",
                  r + 1, successes, task.pairs.size(), sim_s, wall_s, cpu_s, rtf.back(),
                  cpu_rtf.back(), t.steps);
    }
    const double total = Median(ctrl) + Median(sync) + Median(soil_us) + Median(step) +
                         Median(update) + Median(book);
    std::printf("median RTF over %d runs: %.1f wall (min %.1f, max %.1f), %.1f CPU\n", runs,
                Median(rtf), *std::min_element(rtf.begin(), rtf.end()),
                *std::max_element(rtf.begin(), rtf.end()), Median(cpu_rtf));
    std::printf("median step time %.2f us (per 5 ms step -> %.0fx real time without setup):\n",
                total, step_s * 1e6 / total);
    auto row = [total](const char* name, double v) {
      std::printf("  %-44s %7.2f us  %5.1f %%\n", name, v, 100.0 * v / total);
    };
    row("controller (PID + path)", Median(ctrl));
    row("vehicle synchronise (susp., powertrain, tires)", Median(sync));
    if (soil) row("soil (wheel contact, material flow)", Median(soil_us));
    row("Bullet step (multibody, collisions)", Median(step));
    row("vehicle state read-out", Median(update));
    row("runner bookkeeping (checks, metrics, traj.)", Median(book));
    std::printf("  setup per trial (terrain mesh, world, vehicle): %.1f ms\n", Median(setup));
  } catch (const vb::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
