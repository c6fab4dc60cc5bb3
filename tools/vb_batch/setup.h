// From flags to a matrix: resolving environment arguments to task files, loading every task
// once (labels, pair count, hash), checking vehicle and system names.
#pragma once

#include <string>
#include <vector>

#include "io/result_io.h"
#include "options.h"
#include "vb/batch/matrix.h"
#include "vb/nn/model_store.h"

namespace vb_batch {

// Task files named by ENV arguments: files as given, globs expanded, directories' *.yaml.
// Absolute, sorted and de-duplicated. A name that matches nothing is an InputError.
std::vector<std::string> ResolveEnvs(const std::vector<std::string>& envs);

// The matrix. A task that fails to load is kept with its error (its trials become `error`).
vb::batch::MatrixSpec BuildSpec(const Options& o, const std::vector<std::string>& files);

// The data directory (io::DataDir(): $VB_DATA_DIR or share/vb/data next to the executable),
// located and checked on the first call.
const std::string& DataDir();
// Trained weights of the learned systems, read from DataDir() on first use and kept.
const vb::nn::ModelStore& Models();
// CPUs this process may run on (respects affinity masks set by Slurm or taskset).
int DefaultJobs();
// Provenance of a trial of task `t` (this build, this host, the task's hash).
vb::io::Provenance ProvenanceFor(const vb::batch::MatrixTask& t, const vb::batch::TrialKey& key);

}  // namespace vb_batch
