// What the per-decision benchmarks (vb_bench_controllers, vb_bench_learned, vb_bench_hybrid)
// share: thread CPU time, quantiles, and the observations of a real PID trial to replay through a
// controller's Update. Header only: every bench/*.cc is its own program (bench/CMakeLists.txt).
#pragma once

#include <time.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "vb/controllers/controller.h"
#include "vb/engine/runner/episode.h"

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
