// One trial in a forked worker process, and how its end is described when it left no record.
#pragma once

#include <sys/types.h>

#include <memory>
#include <string>

#include "options.h"
#include "setup.h"
#include "vb/batch/matrix.h"
#include "vb/engine/runner/episode.h"

namespace vb_batch {

// Exit code of a worker whose files could not be written (disk full, read-only directory): the
// trial gets no record at all, so the next run retries it, and the batch exits 1.
constexpr int kWorkerIoFailureExit = 3;

// Runs trial `key` of task `t` in this (forked) process and writes its record and trajectory at
// `stem_path` + ".json" / "_traj.csv": the runner's result, or an `error` record when the trial
// cannot be set up (bad input only: an I/O failure is never an `error`). Exits 0 when a record was
// written, kWorkerIoFailureExit when writing failed, 1 otherwise (the parent then records the
// trial as `crashed`). Inputs the parent parsed (`parsed`) are used as they are; the rest is
// loaded here. `world`, if not null, is the parent's episode of the trial's world (BuildWorld),
// inherited copy-on-write: the trial runs on it instead of building the static world again.
// Never returns.
// When the trial is computed, before its files are written, the worker sends its parent
// kComputedSignal with `seq` (sigqueue), and the parent starts the next trial in its slot.
[[noreturn]] void RunWorker(const Options& o, const vb::batch::MatrixTask& t,
                            const ParsedInputs& parsed, vb::runner::Episode* world,
                            const vb::batch::TrialKey& key, const std::string& stem_path,
                            int seq);

// The worker's "trial computed, writing" signal (queued, real-time: one per worker, none lost).
extern const int kComputedSignal;

// The static world of trial `key` (terrain, maps, planning grid, obstacle field: a
// vb::runner::Episode before Reset; it depends on the task, vehicle and perception, everything
// else is the batch's) from what the parent parsed. The parent builds it once per world and its
// trials' workers inherit it, instead of each building it again (~27 M instructions, ~10 ms, and
// the page faults of its memory; docs/benchmarks.md "The batch's own cost"). Null when an input
// was not parsed or the episode cannot be built: the worker then builds it itself and reports
// any error as before.
std::unique_ptr<vb::runner::Episode> BuildWorld(const Options& o, const ParsedInputs& parsed,
                                                const vb::batch::TrialKey& key);

// "worker killed by signal 11 (Segmentation fault)" etc., from a waitpid status.
std::string DescribeWaitStatus(int status);

// In a freshly forked worker: die with the parent (SIGKILL when it exits, even by kill -9), so no
// worker outlives the batch that owns the directory's lock and enforces --trial-timeout.
void DieWithParent(pid_t parent);

}  // namespace vb_batch
