#include "vb/batch/aggregate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

namespace vb::batch {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void MeanVar(const std::vector<double>& v, double* mean, double* var) {
  if (v.empty()) {
    *mean = *var = kNaN;
    return;
  }
  double sum = 0.0;
  for (double x : v) sum += x;
  const double m = sum / static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - m) * (x - m);
  *mean = m;
  *var = ss / static_cast<double>(v.size());   // population variance, as np.var
}

double Pct(int count, int total) {
  return total > 0 ? 100.0 * count / static_cast<double>(total) : kNaN;
}

std::string Num(double x) {
  if (!std::isfinite(x)) return "";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", x);
  return buf;
}
// Markdown cell: fixed decimals, "-" when undefined.
std::string Cell(double x, int decimals) {
  if (!std::isfinite(x)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, x);
  return buf;
}

const std::string& LevelOf(const TrialRow& r, const std::string& factor) {
  if (factor == "elevation") return r.elevation;
  if (factor == "terrain") return r.terrain;
  return r.density;
}

std::vector<std::string> CanonicalLevels(const std::string& factor) {
  if (factor == "elevation") return {"low", "mid", "high"};
  if (factor == "terrain") return {"rigid", "deformable", "mixed"};
  return {"sparse", "medium", "dense"};
}

std::string StatsCsvHeader() {
  return "trials,ran,success,rollover,stuck,timeout,sim_error,out_of_bounds,error,crashed,"
         "success_pct,rollover_pct,stuck_pct,timeout_pct,sim_error_pct,out_of_bounds_pct,"
         "traversal_mean_s,traversal_var_s2,roll_mean_deg,roll_var_deg2,pitch_mean_deg,"
         "pitch_var_deg2";
}
std::string StatsCsv(const GroupStats& s) {
  std::string t;
  for (int n : {s.trials, s.ran, s.success, s.rollover, s.stuck, s.timeout, s.sim_error,
                s.out_of_bounds, s.error, s.crashed}) {
    t += std::to_string(n) + ",";
  }
  const double v[] = {s.success_pct,      s.rollover_pct,     s.stuck_pct,     s.timeout_pct,
                      s.sim_error_pct,    s.out_of_bounds_pct, s.traversal_mean_s,
                      s.traversal_var_s2,
                      s.roll_mean_deg,    s.roll_var_deg2,    s.pitch_mean_deg, s.pitch_var_deg2};
  for (size_t i = 0; i < sizeof(v) / sizeof(v[0]); ++i) t += (i ? "," : "") + Num(v[i]);
  return t;
}

// "/rules:NAME" for a row decided by other rules than vb's, else "": labels never pool the two.
std::string RulesSuffix(const TrialRow& row) {
  return row.rules != "vb" ? "/rules:" + row.rules : std::string();
}

}  // namespace

std::string SystemLabel(const TrialRow& row) {
  std::string label = row.system + "/" + row.vehicle;
  if (!row.perception.empty() && row.perception != "none") label += "/perception:" + row.perception;
  return label + RulesSuffix(row);
}

const std::vector<std::string>& FactorNames() {
  static const std::vector<std::string> kNames = {"elevation", "terrain", "density"};
  return kNames;
}

GroupStats Aggregate(const std::vector<const TrialRow*>& rows) {
  GroupStats s;
  std::vector<double> times, rolls, pitches;
  for (const TrialRow* r : rows) {
    ++s.trials;
    const std::string& st = r->status;
    if (st == "error") {
      ++s.error;
      continue;
    }
    if (st == "crashed") {
      ++s.crashed;
      continue;
    }
    ++s.ran;
    if (st == "success") {
      ++s.success;
      times.push_back(r->traversal_time_s);
      rolls.push_back(r->mean_abs_roll_deg);
      pitches.push_back(r->mean_abs_pitch_deg);
    } else if (st == "rollover") {
      ++s.rollover;
    } else if (st == "stuck") {
      ++s.stuck;
    } else if (st == "timeout") {
      ++s.timeout;
    } else if (st == "out_of_bounds") {
      ++s.out_of_bounds;
    } else {
      ++s.sim_error;
    }
  }
  s.success_pct = Pct(s.success, s.ran);
  s.rollover_pct = Pct(s.rollover, s.ran);
  s.stuck_pct = Pct(s.stuck, s.ran);
  s.timeout_pct = Pct(s.timeout, s.ran);
  s.sim_error_pct = Pct(s.sim_error, s.ran);
  s.out_of_bounds_pct = Pct(s.out_of_bounds, s.ran);
  MeanVar(times, &s.traversal_mean_s, &s.traversal_var_s2);
  MeanVar(rolls, &s.roll_mean_deg, &s.roll_var_deg2);
  MeanVar(pitches, &s.pitch_mean_deg, &s.pitch_var_deg2);
  return s;
}

Report BuildReport(const std::vector<TrialRow>& rows) {
  Report rep;
  std::map<std::string, std::vector<const TrialRow*>> by_system;
  for (const TrialRow& r : rows) by_system[SystemLabel(r)].push_back(&r);
  for (const auto& [label, group] : by_system) {
    rep.systems.push_back(label);
    rep.table1.push_back({label, Aggregate(group)});
  }
  for (const std::string& factor : FactorNames()) {
    std::vector<std::string> levels = CanonicalLevels(factor);
    std::set<std::string> extra;
    for (const TrialRow& r : rows) {
      const std::string& l = LevelOf(r, factor);
      if (std::find(levels.begin(), levels.end(), l) == levels.end()) extra.insert(l);
    }
    levels.insert(levels.end(), extra.begin(), extra.end());
    for (const std::string& level : levels) {
      for (const std::string& system : rep.systems) {
        std::vector<const TrialRow*> group;
        for (const TrialRow* r : by_system[system]) {
          if (LevelOf(*r, factor) == level) group.push_back(r);
        }
        rep.factors.push_back({factor, level, system, Aggregate(group)});
      }
    }
  }

  // Robustness: success per system per perception preset.
  const bool any_perception = std::any_of(rows.begin(), rows.end(), [](const TrialRow& r) {
    return !r.perception.empty() && r.perception != "none";
  });
  if (any_perception) {
    std::vector<std::string> presets = {"none", "mild", "moderate", "severe"};
    std::set<std::string> present, extra;
    std::map<std::pair<std::string, std::string>, std::vector<const TrialRow*>> groups;
    std::set<std::string> systems;
    for (const TrialRow& r : rows) {
      const std::string p = r.perception.empty() ? "none" : r.perception;
      present.insert(p);
      if (std::find(presets.begin(), presets.end(), p) == presets.end()) extra.insert(p);
      const std::string system = r.system + "/" + r.vehicle + RulesSuffix(r);
      systems.insert(system);
      groups[{system, p}].push_back(&r);
    }
    presets.insert(presets.end(), extra.begin(), extra.end());
    for (const std::string& p : presets) {
      if (present.count(p) != 0) rep.perceptions.push_back(p);
    }
    rep.robustness_systems.assign(systems.begin(), systems.end());
    for (const std::string& system : rep.robustness_systems) {
      for (const std::string& p : rep.perceptions) {
        rep.robustness.push_back({system, p, Aggregate(groups[{system, p}])});
      }
    }
  }
  return rep;
}

std::string RobustnessCsv(const Report& report) {
  std::string t = "system,perception," + StatsCsvHeader() + "\n";
  for (const RobustnessRow& r : report.robustness) {
    t += r.system + "," + r.perception + "," + StatsCsv(r.stats) + "\n";
  }
  return t;
}

std::string Table1Csv(const Report& report) {
  std::string t = "system," + StatsCsvHeader() + "\n";
  for (const Table1Row& r : report.table1) t += r.system + "," + StatsCsv(r.stats) + "\n";
  return t;
}

std::string FactorsCsv(const Report& report) {
  std::string t = "factor,level,system," + StatsCsvHeader() + "\n";
  for (const FactorRow& r : report.factors) {
    t += r.factor + "," + r.level + "," + r.system + "," + StatsCsv(r.stats) + "\n";
  }
  return t;
}

std::string ReportMarkdown(const Report& report) {
  std::string t = "# vb batch report\n\n";
  t += "Aggregation rules: docs/reports.md. Percentages are over trials that ran (runner "
       "statuses); `error`/`crashed` trials are listed but not counted. Traversal time, roll and "
       "pitch: successful trials only; roll/pitch = mean and population variance of the per-trial "
       "mean |angle|.\n\n";
  t += "## Table I: outcomes per system\n\n";
  t += "| system | trials | ran | success % | rollover % | stuck % | timeout % | sim_error % | "
       "out of bounds % | error | crashed |\n"
       "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Table1Row& r : report.table1) {
    const GroupStats& s = r.stats;
    t += "| " + r.system + " | " + std::to_string(s.trials) + " | " + std::to_string(s.ran) +
         " | " + Cell(s.success_pct, 1) + " | " + Cell(s.rollover_pct, 1) + " | " +
         Cell(s.stuck_pct, 1) + " | " + Cell(s.timeout_pct, 1) + " | " +
         Cell(s.sim_error_pct, 1) + " | " + Cell(s.out_of_bounds_pct, 1) + " | " +
         std::to_string(s.error) + " | " +
         std::to_string(s.crashed) + " |\n";
  }
  if (!report.robustness.empty()) {
    t += "\n## Robustness: success % per perception preset\n\n"
         "Presets: docs/perception.md. Each cell: success % of the trials that ran (trials).\n\n";
    t += "| system |";
    for (const std::string& p : report.perceptions) t += " " + p + " |";
    t += "\n|---|";
    for (size_t i = 0; i < report.perceptions.size(); ++i) t += "---:|";
    t += "\n";
    for (const std::string& system : report.robustness_systems) {
      t += "| " + system + " |";
      for (const RobustnessRow& r : report.robustness) {
        if (r.system != system) continue;
        t += " " + Cell(r.stats.success_pct, 1) + " (" + std::to_string(r.stats.ran) + ") |";
      }
      t += "\n";
    }
  }
  for (const std::string& factor : FactorNames()) {
    t += "\n## Fig. 6: by " + factor + "\n\n";
    t += "| " + factor + " | system | ran | success % | traversal time s (mean ± sd) | "
         "roll deg (mean, var) | pitch deg (mean, var) |\n"
         "|---|---|---:|---:|---:|---:|---:|\n";
    for (const FactorRow& r : report.factors) {
      if (r.factor != factor || r.stats.trials == 0) continue;
      const GroupStats& s = r.stats;
      t += "| " + r.level + " | " + r.system + " | " + std::to_string(s.ran) + " | " +
           Cell(s.success_pct, 1) + " | " + Cell(s.traversal_mean_s, 2) + " ± " +
           Cell(std::sqrt(s.traversal_var_s2), 2) + " | " + Cell(s.roll_mean_deg, 2) + ", " +
           Cell(s.roll_var_deg2, 2) + " | " + Cell(s.pitch_mean_deg, 2) + ", " +
           Cell(s.pitch_var_deg2, 2) + " |\n";
    }
  }
  return t;
}

}  // namespace vb::batch
