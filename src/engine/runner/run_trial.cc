// RunTrial: a short loop over Episode with the system named by the trial spec (systems.h), called
// every physics step (the original's 200 Hz loop; controllers keep their own rates inside).
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/systems.h"

namespace vb::runner {

namespace {

std::string Fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", x);
  return buf;
}

}  // namespace

TrialResult RunTrial(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                     const TrialSpec& spec, const EpisodeRules& rules,
                     const soil::SoilConfig* soil, const nn::ModelStore* models) {
  using Clock = std::chrono::steady_clock;
  const auto wall_start = Clock::now();
  ValidateSystemName(spec.system);
  Episode episode(task, vehicle, rules, soil);
  TrialResult result = RunTrial(&episode, spec, models);
  result.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  result.real_time_factor = result.wall_time_s > 0.0 ? result.sim_time_s / result.wall_time_s : 0.0;
  return result;
}

TrialResult RunTrial(Episode* episode_ptr, const TrialSpec& spec, const nn::ModelStore* models) {
  using Clock = std::chrono::steady_clock;
  const auto wall_start = Clock::now();
  ValidateSystemName(spec.system);
  Episode& episode = *episode_ptr;
  std::unique_ptr<controllers::Controller> controller = MakeSystem(spec.system, episode, models);
  episode.SetObservationConfig(controller->observation_config());
  episode.Reset(spec);
  controller->Reset(episode.context());

  StepTimings* const timings = episode.rules().timings;
  while (!episode.Done()) {
    const auto t0 = timings != nullptr ? Clock::now() : Clock::time_point();
    controllers::Command command;
    try {
      command = controller->Update(episode.Observe());
    } catch (const std::exception& e) {
      episode.EndWithSimError(std::string("exception during stepping at t = ") +
                              Fmt(episode.time_s()) + " s: " + e.what());
      break;
    }
    if (timings != nullptr) {
      timings->controller_s += std::chrono::duration<double>(Clock::now() - t0).count();
    }
    episode.Step(command);
  }

  TrialResult result = episode.TakeResult();
  result.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  result.real_time_factor = result.wall_time_s > 0.0 ? result.sim_time_s / result.wall_time_s : 0.0;
  return result;
}

}  // namespace vb::runner
