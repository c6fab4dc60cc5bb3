// vb_report DIR: tables, plots and top-down pictures of a batch directory (docs/reports.md).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "common.h"
#include "io/batch_io.h"
#include "io/data_dir.h"
#include "io/result_io.h"
#include "io/task_io.h"
#include "io/task_ref.h"
#include "io/yaml_strict.h"
#include "vb/batch/aggregate.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/outcome_rules.h"

namespace vb_report {

namespace fs = std::filesystem;

namespace {

// The task a trial ran on: the first of io::TaskFileCandidates with the record's task name and
// FNV-1a (task file + height image). Throws InputError listing where it looked.
vb::terrain::TaskSpec FindRecordedTask(const vb::batch::TrialRow& r, const std::string& record,
                                       const std::string& tasks_dir) {
  std::string tried;
  for (const std::string& path : vb::io::TaskFileCandidates(r.task_file, record, tasks_dir)) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) continue;
    tried += (tried.empty() ? "" : ", ") + path;
    vb::terrain::TaskSpec task = vb::io::LoadTask(path);
    const std::string hash =
        vb::io::MakeProvenance(task, vb::runner::TrialSpec()).task_fnv1a64;
    if (task.name == r.task && (r.task_fnv1a64.empty() || hash == r.task_fnv1a64)) return task;
    tried += " (another version of the task)";
  }
  throw vb::InputError(record, 0, "provenance.task_file",
                       "task " + r.task_file + " (FNV-1a " + r.task_fnv1a64 + ") not found" +
                           (tried.empty() ? std::string() : "; found only: " + tried) +
                           "; give its task set with --tasks DIR");
}

}  // namespace

int Report(const std::vector<std::string>& args) {
  std::string dir, out, topdown, tasks_dir;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw vb::InputError("", 0, a, "missing value");
      return args[++i];
    };
    if (a == "--out") {
      out = value();
    } else if (a == "--topdown") {
      topdown = value();
    } else if (a == "--tasks") {
      tasks_dir = value();
    } else if (!a.empty() && a[0] == '-') {
      throw vb::InputError("", 0, a, "unknown option (see --help)");
    } else if (dir.empty()) {
      dir = a;
    } else {
      throw vb::InputError("", 0, a, "more than one directory given (see --help)");
    }
  }
  if (dir.empty()) throw vb::InputError("", 0, "DIR", "no batch directory given (see --help)");
  if (out.empty()) out = (fs::path(dir) / "report").string();
  if (tasks_dir.empty()) tasks_dir = vb::io::TasksDir();
  const std::vector<vb::batch::TrialRow> rows = ReadIndex(dir);
  std::vector<std::string> wanted;   // --topdown trial stems; empty = all
  if (!topdown.empty() && topdown != "all") {
    std::stringstream ss(topdown);
    std::string s;
    while (std::getline(ss, s, ',')) {
      if (std::none_of(rows.begin(), rows.end(),
                       [&](const vb::batch::TrialRow& r) { return Stem(r) == s; })) {
        throw vb::InputError(dir + "/index.csv", 0, "--topdown", "no trial '" + s + "'");
      }
      wanted.push_back(s);
    }
  }
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw vb::InputError(out, 0, "--out", "cannot create directory: " + ec.message());

  // Rows of several builds are aggregated (a merge of re-run shards can do that on purpose), but
  // never silently: results of different code are not one benchmark run.
  std::map<std::string, int> builds;
  for (const vb::batch::TrialRow& r : rows) ++builds["vb " + r.vb_version + " (" + r.git_commit + ")"];
  if (builds.size() > 1) {
    std::string list;
    for (const auto& [b, n] : builds) list += "\n  " + b + ": " + std::to_string(n) + " trial(s)";
    std::fprintf(stderr, "vb_report: warning: the index mixes results of %zu builds:%s\n",
                 builds.size(), list.c_str());
  }
  const vb::batch::Report report = vb::batch::BuildReport(rows);
  vb::io::WriteFileAtomic(out + "/table1.csv", vb::batch::Table1Csv(report));
  vb::io::WriteFileAtomic(out + "/fig6.csv", vb::batch::FactorsCsv(report));
  if (!report.robustness.empty()) {
    vb::io::WriteFileAtomic(out + "/robustness.csv", vb::batch::RobustnessCsv(report));
  }
  std::string md = vb::batch::ReportMarkdown(report);
  const std::vector<std::string> plots = vb::io::WriteReportPlots(report, out);
  if (!plots.empty()) {
    md += "\n## Plots\n\n";
    for (const std::string& p : plots) md += "![" + p + "](" + p + ")\n";
  }
  md += "\nEvery trial with a link to its 3-D replay: [trials.html](trials.html) (serve the batch "
        "directory with `vb_view serve DIR`).\n";
  vb::io::WriteFileAtomic(out + "/report.md", md);
  vb::io::WriteFileAtomic(out + "/trials.html", TrialsPage(rows));

  size_t pictures = 0;
  if (!topdown.empty()) {
    fs::create_directories(out + "/topdown", ec);
    std::map<std::string, vb::terrain::TaskSpec> tasks;   // loaded once per task file
    for (const vb::batch::TrialRow& r : rows) {
      const std::string stem = Stem(r);
      if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), stem) == wanted.end()) {
        continue;
      }
      if (r.task_file.empty()) continue;
      const std::string record = (fs::path(dir) / "trials" / (stem + ".json")).string();
      const std::string key = r.task_file + "#" + r.task_fnv1a64;
      auto it = tasks.find(key);
      if (it == tasks.end()) {
        try {
          it = tasks.emplace(key, FindRecordedTask(r, record, tasks_dir)).first;
        } catch (const vb::InputError& e) {
          std::fprintf(stderr, "vb_report: no picture for %s: %s\n", stem.c_str(), e.what());
          continue;
        }
      }
      char caption[256];
      if (r.status == "success") {
        std::snprintf(caption, sizeof(caption), "%s  %s in %.1f s", stem.c_str(),
                      r.status.c_str(), r.traversal_time_s);
      } else {
        std::snprintf(caption, sizeof(caption), "%s  %s", stem.c_str(), r.status.c_str());
      }
      // The picture draws the trajectory: it must be the record's, complete (DEF-16).
      const std::string traj = (fs::path(dir) / "trials" / (stem + "_traj.csv")).string();
      const std::string problem = vb::io::TrajectoryProblem(traj, vb::io::ReadTrialJson(record));
      if (!problem.empty()) throw vb::InputError(record, 0, "--topdown", problem);
      // The goal circle of the rules that decided the trial (a verti_bench record names them).
      const vb::runner::RuleSet rules = vb::runner::ParseRuleSet("rules", r.rules, record);
      const double goal_radius_m = vb::runner::GoalCircleRadius_m(
          rules, it->second.scale, vb::runner::EpisodeRules().goal_radius_m);
      vb::io::WriteTopDownPng(it->second, r.pair, traj, caption, goal_radius_m,
                              out + "/topdown/" + stem + ".png");
      ++pictures;
    }
  }

  std::map<std::string, int> counts;
  for (const vb::batch::TrialRow& r : rows) ++counts[r.status];
  std::string summary;
  for (const auto& [s, n] : counts) summary += (summary.empty() ? "" : ", ") + s + " " + std::to_string(n);
  std::printf("vb_report: %zu trials (%s), %zu systems -> %s/report.md, %zu plots%s\n",
              rows.size(), summary.c_str(), report.systems.size(), out.c_str(), plots.size(),
              pictures ? (", " + std::to_string(pictures) + " top-down pictures").c_str() : "");
  return 0;
}

}  // namespace vb_report
