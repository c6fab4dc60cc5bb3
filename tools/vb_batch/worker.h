// One trial in a forked worker process, and how its end is described when it left no record.
#pragma once

#include <sys/types.h>

#include <string>

#include "options.h"
#include "setup.h"
#include "vb/batch/matrix.h"

namespace vb_batch {

// Exit code of a worker whose files could not be written (disk full, read-only directory): the
// trial gets no record at all, so the next run retries it, and the batch exits 1.
constexpr int kWorkerIoFailureExit = 3;

// Runs trial `key` of task `t` in this (forked) process and writes its record and trajectory at
// `stem_path` + ".json" / "_traj.csv": the runner's result, or an `error` record when the trial
// cannot be set up (bad input only: an I/O failure is never an `error`). Exits 0 when a record was
// written, kWorkerIoFailureExit when writing failed, 1 otherwise (the parent then records the
// trial as `crashed`). Inputs the parent parsed (`parsed`) are used as they are; the rest is
// loaded here. Never returns.
[[noreturn]] void RunWorker(const Options& o, const vb::batch::MatrixTask& t,
                            const ParsedInputs& parsed, const vb::batch::TrialKey& key,
                            const std::string& stem_path);

// "worker killed by signal 11 (Segmentation fault)" etc., from a waitpid status.
std::string DescribeWaitStatus(int status);

// In a freshly forked worker: die with the parent (SIGKILL when it exits, even by kill -9), so no
// worker outlives the batch that owns the directory's lock and enforces --trial-timeout.
void DieWithParent(pid_t parent);

}  // namespace vb_batch
