#include "worker.h"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "io/batch_io.h"
#include "io/perception_io.h"
#include "io/result_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "setup.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"

namespace vb_batch {

namespace {

// The rules of trial `key` under the batch's options.
vb::runner::EpisodeRules RulesFor(const Options& o, const vb::batch::TrialKey& key) {
  vb::runner::EpisodeRules rules;
  rules.time_limit_s = o.time_limit_s;
  rules.target_speed_mps = o.target_speed_mps;
  rules.rule_set = o.rules;
  rules.trajectory_every_n_steps = o.traj_every;
  rules.perception = vb::io::ResolvePerception(key.perception, DataDir());
  return rules;
}

}  // namespace

std::unique_ptr<vb::runner::Episode> BuildWorld(const Options& o, const ParsedInputs& parsed,
                                                const vb::batch::TrialKey& key) {
  if (key.task_index >= parsed.tasks.size() || !parsed.tasks[key.task_index]) return nullptr;
  const vb::terrain::TaskSpec& task = *parsed.tasks[key.task_index];
  const auto vehicle = parsed.vehicles.find(key.vehicle);
  if (vehicle == parsed.vehicles.end()) return nullptr;
  const bool needs_soil = vb::io::NeedsSoil(task);
  if (needs_soil && !parsed.soil) return nullptr;
  try {
    return std::make_unique<vb::runner::Episode>(task, vehicle->second, RulesFor(o, key),
                                                 needs_soil ? &*parsed.soil : nullptr);
  } catch (const std::exception&) {
    return nullptr;   // the worker builds it and reports the error as before
  }
}

const int kComputedSignal = SIGRTMIN;

namespace {
pid_t g_parent = 0;   // the batch that forked this worker (DieWithParent)
}  // namespace

[[noreturn]] void RunWorker(const Options& o, const vb::batch::MatrixTask& t,
                            const ParsedInputs& parsed, vb::runner::Episode* world,
                            const vb::batch::TrialKey& key, const std::string& stem_path,
                            int seq) {
  int code = 0;
  try {
    if (!t.load_error.empty()) {
      vb::io::WriteUnrunTrialJson(stem_path + ".json", t.name, key.pair,
                                  ProvenanceFor(t, key, o.rules), "error", t.load_error);
      std::_Exit(0);
    }
    try {
      const std::shared_ptr<const vb::terrain::TaskSpec> parsed_task =
          key.task_index < parsed.tasks.size() ? parsed.tasks[key.task_index] : nullptr;
      const std::shared_ptr<const vb::terrain::TaskSpec> task_ptr =
          parsed_task ? parsed_task
                      : std::make_shared<const vb::terrain::TaskSpec>(vb::io::LoadTask(t.path));
      const vb::terrain::TaskSpec& task = *task_ptr;
      const std::string vehicle_file = DataDir() + "/vehicles/" + key.vehicle + ".yaml";
      const std::string soil_file = DataDir() + "/soils/" + o.soil + ".yaml";
      vb::runner::TrialSpec spec;
      spec.pair_index = key.pair;
      spec.seed = key.seed;
      spec.system = key.system;
      spec.vehicle = key.vehicle;
      bool with_soil = false;
      vb::runner::TrialResult r;
      if (world != nullptr) {
        // The parent's episode of this world (BuildWorld: the parsed task, vehicle and soil).
        with_soil = world->soil_config() != nullptr;
        r = vb::runner::RunTrial(world, spec, &Models());
      } else {
        const auto parsed_vehicle = parsed.vehicles.find(key.vehicle);
        const vb::vehicles::VehicleParams params = parsed_vehicle != parsed.vehicles.end()
                                                       ? parsed_vehicle->second
                                                       : vb::io::LoadVehicle(vehicle_file);
        const vb::runner::EpisodeRules rules = RulesFor(o, key);
        const std::optional<vb::soil::SoilConfig> soil =
            parsed.soil && vb::io::NeedsSoil(task) ? parsed.soil
                                                   : vb::io::LoadSoilIfNeeded(task, soil_file);
        with_soil = soil.has_value();
        r = vb::runner::RunTrial(task, params, spec, rules, soil ? &*soil : nullptr, &Models());
      }
      // Computed: the parent may start the next trial while this one writes its files.
      // Only to the batch itself: an orphaned worker's new parent (a subreaper) must not get it.
      if (g_parent > 0 && ::getppid() == g_parent) {
        union sigval value;
        value.sival_int = seq;
        ::sigqueue(g_parent, kComputedSignal, value);
      }
      // The task's hash: the parent's, taken from the same files it parsed this task from.
      vb::io::Provenance provenance =
          vb::io::MakeProvenance(task, spec, parsed_task ? t.task_fnv1a64 : std::string());
      vb::io::RecordParameterFiles(vehicle_file, o.soil, with_soil ? soil_file : "", &provenance);
      vb::io::RecordPerception(key.perception,
                               key.perception == "none"
                                   ? std::string()
                                   : vb::io::PerceptionFile(key.perception, DataDir()),
                               &provenance);
      vb::io::WriteTrialFiles(r, stem_path, provenance);   // trajectory first
    } catch (const vb::InputError& e) {
      vb::io::WriteUnrunTrialJson(stem_path + ".json", t.name, key.pair,
                                  ProvenanceFor(t, key, o.rules), "error", e.what());
    }
  } catch (const vb::IoError& e) {
    // Disk full or similar: not the trial's fault, and not deterministic. No record, so the
    // trial runs again on resume; the parent reports it and exits 1.
    std::fprintf(stderr, "vb_batch worker: %s: I/O error: %s\n", stem_path.c_str(), e.what());
    code = kWorkerIoFailureExit;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_batch worker: %s: %s\n", stem_path.c_str(), e.what());
    code = 1;   // the parent records the trial as crashed
  }
  std::fflush(stderr);
  std::_Exit(code);
}

void DieWithParent(pid_t parent) {
  g_parent = parent;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // The parent may have died between fork and prctl: then nobody would send the signal.
  if (::getppid() != parent) std::_Exit(1);
}

std::string DescribeWaitStatus(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return "worker killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  }
  if (WIFEXITED(status)) {
    return "worker exited with code " + std::to_string(WEXITSTATUS(status)) +
           " without a result (internal error, see the batch's stderr)";
  }
  return "worker ended abnormally";
}

}  // namespace vb_batch
