// One trial in a forked worker process, and how its end is described when it left no record.
#pragma once

#include <string>

#include "options.h"
#include "vb/batch/matrix.h"

namespace vb_batch {

// Runs trial `key` of task `t` in this (forked) process and writes its record and trajectory at
// `stem_path` + ".json" / "_traj.csv": the runner's result, or an `error` record when the trial
// cannot be set up. Exits 0 when a record was written, 1 otherwise (the parent then records the
// trial as `crashed`). Never returns.
[[noreturn]] void RunWorker(const Options& o, const vb::batch::MatrixTask& t,
                            const vb::batch::TrialKey& key, const std::string& stem_path);

// "worker killed by signal 11 (Segmentation fault)" etc., from a waitpid status.
std::string DescribeWaitStatus(int status);

}  // namespace vb_batch
