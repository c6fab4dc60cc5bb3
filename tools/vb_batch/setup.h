// From flags to a matrix: resolving environment arguments to task files, loading every task
// once (labels, pair count, hash), checking vehicle and system names.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/result_io.h"
#include "options.h"
#include "vb/batch/matrix.h"
#include "vb/nn/model_store.h"
#include "vb/soil/soil_params.h"
#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb_batch {

// Task files named by ENV arguments: files as given, globs expanded, directories' *.yaml.
// Absolute, sorted and de-duplicated. A name that matches nothing is an InputError.
std::vector<std::string> ResolveEnvs(const std::vector<std::string>& envs);

// Inputs the parent parsed while building the matrix, inherited by every forked worker
// (copy-on-write), so a trial does not parse its task, vehicle and soil files again (~60 ms of
// YAML per trial, a fifth of a 1000-task PID batch's CPU; docs/benchmarks.md). Anything missing
// (a file that failed to load, a task beyond the memory budget) the worker loads itself, which
// reports errors exactly as before.
struct ParsedInputs {
  std::vector<std::shared_ptr<const vb::terrain::TaskSpec>> tasks;   // by MatrixSpec::tasks index
  std::map<std::string, vb::vehicles::VehicleParams> vehicles;      // by vehicle name
  std::optional<vb::soil::SoilConfig> soil;                         // the --soil file
};

// Tasks are kept parsed up to this many bytes of height samples (tasks/: 100 x 0.13 MB; an
// original world at 1025^2 is 8 MB); beyond it workers parse their task file themselves.
constexpr size_t kParsedTaskBudget_bytes = size_t{1} << 30;

// The matrix. A task that fails to load is kept with its error (its trials become `error`).
// When `parsed` is given, it receives what was parsed on the way (see ParsedInputs).
vb::batch::MatrixSpec BuildSpec(const Options& o, const std::vector<std::string>& files,
                                ParsedInputs* parsed = nullptr);

// The data directory (io::DataDir(): $VB_DATA_DIR or share/vb/data next to the executable),
// located and checked on the first call.
const std::string& DataDir();
// Trained weights of the learned systems, read from DataDir() on first use and kept.
const vb::nn::ModelStore& Models();
// CPUs this process may run on (respects affinity masks set by Slurm or taskset).
int DefaultJobs();
// Provenance of a trial of task `t` (this build, this host, the task's hash, the rule set).
vb::io::Provenance ProvenanceFor(const vb::batch::MatrixTask& t, const vb::batch::TrialKey& key,
                                 vb::runner::RuleSet rules);

}  // namespace vb_batch
