// Aggregation of batch results into the paper's tables (docs/reports.md has the rules):
//   * Denominator: trials that ran (the runner's five statuses). `error` and `crashed` trials did
//     not run the system under test; they are counted and shown separately, never as failures.
//   * success / rollover / stuck / timeout / sim_error / out_of_bounds %: count / trials that
//     ran (out_of_bounds: the vehicle left the world, a failure).
//   * traversal time: mean and population variance over successful trials only.
//   * roll and pitch: each trial contributes its mean |roll| (|pitch|) over all its steps; the
//     group's mean and population variance are taken over those per-trial means of successful
//     trials only (as Verti-Bench's multiple_experiments; not pooled per step).
// Groups are (system, vehicle) for Table I, and additionally a label value (elevation level,
// terrain type, obstacle density) for the Fig. 6 breakdowns.
#pragma once

#include <string>
#include <vector>

#include "vb/batch/index.h"

namespace vb::batch {

struct GroupStats {
  int trials = 0;          // all rows of the group
  int ran = 0;             // rows with a runner status (the denominator)
  int success = 0, rollover = 0, stuck = 0, timeout = 0, sim_error = 0, out_of_bounds = 0;
  int error = 0, crashed = 0;
  double success_pct = 0.0, rollover_pct = 0.0, stuck_pct = 0.0, timeout_pct = 0.0,
         sim_error_pct = 0.0, out_of_bounds_pct = 0.0;   // NaN when ran == 0
  double traversal_mean_s = 0.0, traversal_var_s2 = 0.0;   // NaN when no success
  double roll_mean_deg = 0.0, roll_var_deg2 = 0.0;         // NaN when no success
  double pitch_mean_deg = 0.0, pitch_var_deg2 = 0.0;
};

GroupStats Aggregate(const std::vector<const TrialRow*>& rows);

// "system/vehicle", with "/perception:<preset>" appended when the perception is not ground truth
// and "/rules:<set>" when the outcome rules are not vb's (so Table I and Fig. 6 never pool
// results of different perception or rules).
std::string SystemLabel(const TrialRow& row);

struct Table1Row {
  std::string system;      // "system/vehicle"
  GroupStats stats;
};
struct FactorRow {
  std::string factor;      // "elevation", "terrain", "density"
  std::string level;       // e.g. "low"
  std::string system;      // "system/vehicle"
  GroupStats stats;
};

// Robustness (docs/perception.md): one system/vehicle under one perception preset.
struct RobustnessRow {
  std::string system;      // "system/vehicle"
  std::string perception;  // preset
  GroupStats stats;
};

struct Report {
  std::vector<std::string> systems;   // sorted
  std::vector<Table1Row> table1;      // one per system, in `systems` order
  std::vector<FactorRow> factors;     // factor, then level (canonical order), then system
  // Only when some trial had a perception other than none: presets in order (none, mild,
  // moderate, severe, then others sorted) and rows system-major in that order.
  std::vector<std::string> perceptions;
  std::vector<std::string> robustness_systems;   // "system/vehicle", sorted
  std::vector<RobustnessRow> robustness;
};

// The canonical levels of each factor (low/mid/high, rigid/deformable/mixed,
// sparse/medium/dense); label values outside these follow in sorted order.
const std::vector<std::string>& FactorNames();
Report BuildReport(const std::vector<TrialRow>& rows);

// Text outputs (deterministic: same rows -> same bytes; no wall times or host names).
std::string Table1Csv(const Report& report);
std::string FactorsCsv(const Report& report);
// system,perception,<stats> (header only when the report has no robustness rows).
std::string RobustnessCsv(const Report& report);
std::string ReportMarkdown(const Report& report);

}  // namespace vb::batch
