// The index of a batch output directory (DIR/index.csv): one row per trial with its matrix
// position, environment labels, outcome, the metrics the report needs and provenance. The
// per-trial JSON files are the source of truth; the index is rebuilt from them on every run.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vb::batch {

// Statuses of a trial in a batch: the runner's six (success, rollover, stuck, timeout,
// sim_error, out_of_bounds) plus two for trials that did not produce a runner result:
//   error   - the trial could not be set up (bad or unsupported input, e.g. deformable terrain
//             before the soil solver exists); deterministic, not retried on resume
//   crashed - the trial's worker process died (signal, internal error, wall-clock limit); retried
//             when the same batch is run again
bool IsRunnerStatus(const std::string& status);
bool IsKnownStatus(const std::string& status);

struct TrialRow {
  size_t matrix_index = 0;
  std::string task;
  int pair = 0;
  uint64_t seed = 0;
  std::string vehicle;
  std::string system;
  std::string perception = "none";   // perception preset (docs/perception.md)
  double scale = 1.0;
  std::string elevation;
  std::string terrain;
  std::string density;
  std::string status;
  double traversal_time_s = 0.0;     // NaN unless success
  double sim_time_s = 0.0;           // NaN for error/crashed
  double final_goal_distance_m = 0.0;
  double mean_abs_roll_deg = 0.0;    // per-trial mean of |roll| over all steps
  double mean_abs_pitch_deg = 0.0;
  std::string task_fnv1a64;
  std::string vb_version;
  std::string git_commit;
  std::string host;
  double wall_time_s = 0.0;
  std::string task_file;
  std::string message;
  // The rule set that decided the outcome (runner::RuleSet: "vb" or "verti_bench"); the index
  // has this column only when some row is not "vb".
  std::string rules = "vb";
  // Not an index column: the record's trajectory length (-1 unknown, e.g. error/crashed), read
  // from the JSON so resume, merge and --topdown can check the trajectory file against it.
  long trajectory_samples = -1;
};

// File stem of a row's trial files: <task>_p<K>_s<seed>_<vehicle>_<system>[_perc-<preset>]
// (as TrialStem; the suffix only for a perception other than none).
std::string RowStem(const TrialRow& row);
// "" for ground truth ("none"), "_perc-<preset>" otherwise.
std::string PerceptionStemSuffix(const std::string& perception);

// CSV text of the index (header + rows in the given order). Numbers print with "%.17g", NaN as
// an empty field.
std::string IndexCsv(const std::vector<TrialRow>& rows);
// Parses IndexCsv output (also indexes without the perception column: "none", or without the
// rules column: "vb"); throws InputError
// naming `source` and the line on malformed input: a missing or unexpected column (named), a
// number that is not finite or is negative, an unknown status, a name that is not a file-name
// component, or the same trial listed twice.
std::vector<TrialRow> ParseIndexCsv(const std::string& text, const std::string& source);

// The fields that must agree between two records of the same trial (everything except host and
// wall time): used by merge to tell a harmless duplicate from a conflict.
std::string StableFields(const TrialRow& row);

}  // namespace vb::batch
