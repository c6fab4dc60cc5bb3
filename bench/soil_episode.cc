// Soil benchmark: a vehicle (default the HMMWV) with the PID system across a deformable world
// (default tasks/env061.yaml, mid elevation, mud/snow/sand), each pair one trial of the runner
// (RunTrial, the benchmark's rules) with its step timings on, which time every call into the soil
// solver and report its counters. Prints per pair the
// real-time factor, the soil solver's share and cost per step, and the peak memory (getrusage).
//
// usage: vb_bench_soil_episode [TASK] [--spacing M] [--pairs N] [--soil FILE] [--vehicle NAME]
// (--spacing replaces the soil file's spacing; a vehicle's max_soil_grid_m still caps it.)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/runner/episode.h"

namespace {

using Clock = std::chrono::steady_clock;

double CpuSeconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

struct PairResult {
  std::string outcome;
  double sim_s = 0.0, wall_s = 0.0, cpu_s = 0.0;
  double max_sinkage_m = 0.0;
  vb::runner::StepTimings timings;
};

// One trial through the runner (its rules, start pose and planner), with the step timings on.
PairResult RunPair(const vb::terrain::TaskSpec& task, const vb::vehicles::VehicleParams& params,
                   const vb::soil::SoilConfig& soil_config, int pair_index) {
  PairResult r;
  vb::runner::TrialSpec spec;
  spec.pair_index = pair_index;
  spec.vehicle = params.name;
  vb::runner::EpisodeRules rules;
  rules.timings = &r.timings;
  const auto wall0 = Clock::now();
  const double cpu0 = CpuSeconds();
  const vb::runner::TrialResult t = vb::runner::RunTrial(task, params, spec, rules, &soil_config);
  r.wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  r.cpu_s = CpuSeconds() - cpu0;
  r.sim_s = t.sim_time_s;
  r.outcome = std::string(vb::runner::TrialStatusName(t.status));
  for (const vb::runner::TrajectorySample& sample : t.trajectory) {
    for (double z : sample.wheel_sinkage_m) r.max_sinkage_m = std::max(r.max_sinkage_m, z);
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string task_path = VB_SOURCE_DIR "/tasks/env061.yaml";
  std::string soil_path = VB_SOURCE_DIR "/data/soils/verti_bench.yaml";
  double spacing = 0.0;
  int pairs = -1;
  std::string vehicle = "hmmwv";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--spacing" && i + 1 < argc) {
      spacing = std::atof(argv[++i]);
    } else if (a == "--pairs" && i + 1 < argc) {
      pairs = std::atoi(argv[++i]);
    } else if (a == "--soil" && i + 1 < argc) {
      soil_path = argv[++i];
    } else if (a == "--vehicle" && i + 1 < argc) {
      vehicle = argv[++i];
    } else {
      task_path = a;
    }
  }
  try {
    const vb::terrain::TaskSpec task = vb::io::LoadTask(task_path);
    const vb::vehicles::VehicleParams params =
        vb::io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/" + vehicle + ".yaml");
    vb::soil::SoilConfig soil = vb::io::LoadSoil(soil_path);
    if (spacing > 0.0) soil.grid_spacing_m = spacing;
    const int n = pairs > 0 ? std::min<int>(pairs, static_cast<int>(task.pairs.size()))
                            : static_cast<int>(task.pairs.size());
    const double grid_m = params.max_soil_grid_m > 0.0
                              ? std::min(soil.grid_spacing_m, params.max_soil_grid_m)
                              : soil.grid_spacing_m;
    std::printf("task %s, soil %s, grid %.4f m, %s + PID\n", task_path.c_str(),
                soil_path.c_str(), grid_m, vehicle.c_str());
    std::printf("(RTF = sim / wall; RTF_cpu = sim / process CPU time, insensitive to a loaded "
                "machine; soil_%% and soil_us are wall-clock)\n");
    std::printf("pair outcome     sim_s  wall_s    RTF  RTF_cpu  soil_%%  soil_us/step  nodes/step  "
                "max_sink_m  tiles  soil_MB\n");
    double sim = 0, wall = 0, cpu = 0, soil_s = 0;
    long steps = 0;
    for (int k = 0; k < n; ++k) {
      const PairResult r = RunPair(task, params, soil, k);
      const vb::runner::StepTimings& t = r.timings;
      const double n_steps = std::max<double>(1.0, static_cast<double>(t.steps));
      std::printf("%4d %-9s %6.2f %7.3f %6.1f %8.1f %6.1f %13.1f %11.1f %11.3f %6ld %8.1f\n", k,
                  r.outcome.c_str(), r.sim_s, r.wall_s, r.sim_s / r.wall_s, r.sim_s / r.cpu_s,
                  100.0 * t.soil_s / r.wall_s, 1e6 * t.soil_s / n_steps,
                  static_cast<double>(t.soil_contact_nodes) / n_steps, r.max_sinkage_m,
                  t.soil_tiles, t.soil_memory_bytes / 1048576.0);
      std::fflush(stdout);
      sim += r.sim_s;
      wall += r.wall_s;
      cpu += r.cpu_s;
      soil_s += t.soil_s;
      steps += t.steps;
    }
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    std::printf("all: sim %.1f s, wall %.2f s, RTF %.1f, RTF_cpu %.1f, soil %.1f %% of wall, "
                "%.1f us/step; peak RSS %.1f MB\n",
                sim, wall, sim / wall, sim / cpu, 100.0 * soil_s / wall, 1e6 * soil_s / steps,
                ru.ru_maxrss / 1024.0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_bench_soil_episode: %s\n", e.what());
    return 2;
  }
  return 0;
}
