// Files of a batch output directory (docs/batch.md): reading trial JSON records back, writing the
// record of a trial that produced no runner result (error/crashed), and the report's PNG plots
// and top-down trial pictures. yaml-cpp (JSON is read as YAML) and OpenCV stay in tools/io.
#pragma once

#include <string>

#include "io/result_io.h"
#include "vb/batch/aggregate.h"
#include "vb/batch/index.h"
#include "vb/terrain/task.h"

namespace vb::io {

// Reads a trial JSON (vb_run's or vb_batch's) into the outcome and provenance fields of a
// TrialRow (matrix_index, scale and labels are left for the caller). Throws InputError naming the
// file for an unreadable, truncated or malformed record.
batch::TrialRow ReadTrialJson(const std::string& path);

// Why the trajectory file of a trial does not match its record, or "" if it does: missing, or
// not exactly record.trajectory_samples complete rows (a truncated or foreign file). Trials
// without a runner result (trajectory_samples < 0) need none.
std::string TrajectoryProblem(const std::string& traj_path, const batch::TrialRow& record);
// Why a record does not belong to the trial of the given key, or "" if it does (a record copied
// under another trial's file name).
std::string RecordKeyProblem(const batch::TrialRow& record, const std::string& task, int pair,
                             uint64_t seed, const std::string& vehicle,
                             const std::string& system, const std::string& perception);

// Writes the JSON record of a trial that did not produce a runner result: status "error" (could
// not be set up) or "crashed" (worker died), with the reason in `message`; same layout as
// WriteTrialJson, metrics null. Atomic.
void WriteUnrunTrialJson(const std::string& path, const std::string& task_name, int pair,
                         const Provenance& provenance, const std::string& status,
                         const std::string& message);

// DIR/batch.json: what a batch output directory holds (one shard of a matrix, or a merge).
struct BatchInfo {
  std::string matrix_fingerprint;   // batch::MatrixFingerprint of the full matrix
  size_t matrix_trials = 0;         // trials in the full matrix
  std::string shard;                // "i/N", or "merged"
  size_t shard_trials = 0;          // trials this directory is meant to hold
  std::string settings;             // result-changing settings, e.g. "time_limit_s=60.0 ..."
  std::string vb_version;
  std::string git_commit;
};
void WriteBatchJson(const BatchInfo& info, const std::string& path);
// Throws InputError naming the file and key.
BatchInfo ReadBatchJson(const std::string& path);

// Report plots: for each factor (elevation, terrain, density) one grouped bar chart per metric
// (success %, traversal time, roll, pitch; error bars = one standard deviation), files
// <dir>/fig6_<factor>_<metric>.png, and table1.png (success/rollover/stuck % per system).
// Returns the file names written (relative to dir), in order.
std::vector<std::string> WriteReportPlots(const batch::Report& report, const std::string& dir);

// Top-down picture of one trial: height shading, semantic class tint (deformable classes
// hatched), rocks and trees, the planned path, the driven trajectory (from the trajectory CSV,
// may be missing), start, goal and the goal circle of goal_radius_m (the trial's rules:
// runner::GoalCircleRadius_m), and the end status as a caption.
void WriteTopDownPng(const terrain::TaskSpec& task, int pair, const std::string& traj_csv,
                     const std::string& caption, double goal_radius_m,
                     const std::string& png_path);

}  // namespace vb::io
