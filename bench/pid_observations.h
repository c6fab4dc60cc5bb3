// What the per-decision benchmarks (vb_bench_controllers, vb_bench_learned, vb_bench_hybrid)
// share: their task list, thread CPU time, timed calls, quantiles, whole trials over a few pairs,
// and the observations of a real PID trial to replay through a controller's Update. Header only:
// every bench/*.cc is its own program (bench/CMakeLists.txt).
#pragma once

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "vb/controllers/controller.h"
#include "vb/engine/runner/episode.h"
#include "vb/nn/model_store.h"

namespace vb::bench {

// CPU time of this thread (s): on a shared, oversubscribed machine the wall clock also counts the
// time the thread waited for a core; the CPU time does not.
inline double ThreadCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

inline double Quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}

// The task files a benchmark program runs: its arguments, or `defaults` (names under tasks/).
// Prints the command first, so that a pasted output says how it was made.
inline std::vector<std::string> BenchTasks(const char* program,
                                           const std::vector<std::string>& given,
                                           std::initializer_list<const char*> defaults) {
  std::vector<std::string> tasks = given;
  if (tasks.empty()) {
    for (const char* t : defaults) tasks.push_back(std::string(VB_SOURCE_DIR) + "/tasks/" + t + ".yaml");
  }
  std::printf("command: %s", program);
  for (const std::string& t : tasks) std::printf(" %s", t.c_str());
  std::printf("\n\n");
  return tasks;
}

// The original's soils for a task's deformable patches (none for a rigid task).
inline std::optional<soil::SoilConfig> BenchSoil(const terrain::TaskSpec& task) {
  return io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml");
}

// Calls f once and appends its wall-clock and thread-CPU time in microseconds, divided by
// `calls_inside` when f makes that many calls of what is measured.
template <class F>
void TimeCall(F&& f, std::vector<double>* wall_us, std::vector<double>* cpu_us,
              double calls_inside = 1.0) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = ThreadCpuSeconds();
  f();
  cpu_us->push_back(1e6 * (ThreadCpuSeconds() - c0) / calls_inside);
  wall_us->push_back(
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
      calls_inside);
}

// Whole trials of one system on pairs 0..pairs-1 (seed 0): the median real-time factor, the
// controller's share of the wall time (StepTimings, summed over the trials) and the outcomes.
struct PairTrials {
  double median_rtf = 0.0;
  double controller_share = 0.0;
  std::string outcomes;   // space-separated statuses, pair order
};

inline PairTrials RunPairs(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                           const char* system, const soil::SoilConfig* soil,
                           const nn::ModelStore* models, int pairs) {
  PairTrials out;
  std::vector<double> rtf;
  double controller_s = 0.0, wall_s = 0.0;
  for (int pair = 0; pair < pairs; ++pair) {
    runner::StepTimings timings;
    runner::EpisodeRules rules;
    rules.timings = &timings;
    runner::TrialSpec spec;
    spec.pair_index = pair;
    spec.system = system;
    const runner::TrialResult r = runner::RunTrial(task, vehicle, spec, rules, soil, models);
    rtf.push_back(r.real_time_factor);
    controller_s += timings.controller_s;
    wall_s += r.wall_time_s;
    out.outcomes += std::string(out.outcomes.empty() ? "" : " ") +
                    std::string(runner::TrialStatusName(r.status));
  }
  out.median_rtf = Quantile(rtf, 0.5);
  out.controller_share = wall_s > 0.0 ? controller_s / wall_s : 0.0;
  return out;
}

// A PID trial (pair 0, seed 0) run to its end, every observation kept (built with `config`, or
// PID's own when nullptr; the global path pointer dropped). The episode stays alive: its context (maps, task) is what a
// controller under test is Reset with.
struct PidObservations {
  std::unique_ptr<runner::Episode> episode;
  std::vector<controllers::Observation> observations;
  const controllers::EpisodeContext& context() const { return episode->context(); }
};

inline PidObservations RecordPidTrial(const terrain::TaskSpec& task,
                                      const vehicles::VehicleParams& vehicle,
                                      const soil::SoilConfig* soil,
                                      const controllers::ObservationConfig* config) {
  PidObservations run;
  run.episode = std::make_unique<runner::Episode>(task, vehicle, runner::EpisodeRules(), soil);
  std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
  run.episode->SetObservationConfig(config != nullptr ? *config : pid->observation_config());
  run.episode->Reset(runner::TrialSpec());
  pid->Reset(run.episode->context());
  while (!run.episode->Done()) {
    const controllers::Observation& o = run.episode->Observe();
    run.observations.push_back(o);
    run.observations.back().global_path_m = nullptr;
    run.episode->Step(pid->Update(o));
  }
  return run;
}

}  // namespace vb::bench
