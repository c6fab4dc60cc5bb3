// vb_report: turns a vb_batch output directory into the paper's tables and plots, and merges
// shard directories. docs/reports.md has the outputs and the aggregation rules.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "io/batch_io.h"
#include "io/task_io.h"
#include "io/yaml_strict.h"
#include "vb/batch/aggregate.h"
#include "vb/batch/index.h"
#include "vb/engine/error.h"

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage = R"(usage: vb_report DIR [--out REPORT_DIR] [--topdown all|STEM[,STEM...]]
       vb_report merge OUT_DIR SHARD_DIR...

report: reads DIR/index.csv (written by vb_batch or vb_report merge) and writes to REPORT_DIR
  (default DIR/report): table1.csv, fig6.csv, report.md and PNG plots
  (table1.png, fig6_<factor>_<metric>.png). Same results -> byte-identical report.
  --topdown      also draw a top-down picture per trial (all, or the listed trial file stems)
                 into REPORT_DIR/topdown/<stem>.png; needs the task files at their recorded paths

merge: combines shard directories of one matrix (same matrix fingerprint and settings) into
  OUT_DIR: copies the trial files, writes one index.csv in matrix order and batch.json. A trial
  present in several shards with identical results is kept once (reported); with different
  results, or shards from different matrices, settings or builds, merge stops with exit 2.
  Missing trials (an unfinished shard) are reported.

exit codes: 0 ok; 1 internal error; 2 bad input or conflicting shards.
)";

std::string ReadText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw vb::InputError(p.string(), 0, "", "cannot read");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<vb::batch::TrialRow> ReadIndex(const fs::path& dir) {
  const fs::path p = dir / "index.csv";
  return vb::batch::ParseIndexCsv(ReadText(p), p.string());
}

std::string Stem(const vb::batch::TrialRow& r) {
  return r.task + "_p" + std::to_string(r.pair) + "_s" + std::to_string(r.seed) + "_" +
         r.vehicle + "_" + r.system;
}

int Report(const std::vector<std::string>& args) {
  std::string dir, out, topdown;
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
  const std::vector<vb::batch::TrialRow> rows = ReadIndex(dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw vb::InputError(out, 0, "--out", "cannot create directory: " + ec.message());

  const vb::batch::Report report = vb::batch::BuildReport(rows);
  vb::io::WriteFileAtomic(out + "/table1.csv", vb::batch::Table1Csv(report));
  vb::io::WriteFileAtomic(out + "/fig6.csv", vb::batch::FactorsCsv(report));
  std::string md = vb::batch::ReportMarkdown(report);
  const std::vector<std::string> plots = vb::io::WriteReportPlots(report, out);
  if (!plots.empty()) {
    md += "\n## Plots\n\n";
    for (const std::string& p : plots) md += "![" + p + "](" + p + ")\n";
  }
  vb::io::WriteFileAtomic(out + "/report.md", md);

  size_t pictures = 0;
  if (!topdown.empty()) {
    fs::create_directories(out + "/topdown", ec);
    std::vector<std::string> wanted;
    if (topdown != "all") {
      std::stringstream ss(topdown);
      std::string s;
      while (std::getline(ss, s, ',')) wanted.push_back(s);
    }
    std::map<std::string, vb::terrain::TaskSpec> tasks;   // loaded once per task file
    for (const vb::batch::TrialRow& r : rows) {
      const std::string stem = Stem(r);
      if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), stem) == wanted.end()) {
        continue;
      }
      if (r.task_file.empty()) continue;
      auto it = tasks.find(r.task_file);
      if (it == tasks.end()) {
        try {
          it = tasks.emplace(r.task_file, vb::io::LoadTask(r.task_file)).first;
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
      vb::io::WriteTopDownPng(it->second, r.pair,
                              (fs::path(dir) / "trials" / (stem + "_traj.csv")).string(),
                              caption, out + "/topdown/" + stem + ".png");
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

int Merge(const std::vector<std::string>& args) {
  if (args.size() < 2) {
    throw vb::InputError("", 0, "merge", "usage: vb_report merge OUT_DIR SHARD_DIR...");
  }
  const fs::path out = args[0];
  std::vector<fs::path> shards(args.begin() + 1, args.end());
  vb::io::BatchInfo first;
  std::map<size_t, vb::batch::TrialRow> merged;
  std::map<size_t, std::string> origin;
  size_t duplicates = 0;
  std::vector<std::string> conflicts;
  for (size_t s = 0; s < shards.size(); ++s) {
    const fs::path& dir = shards[s];
    const vb::io::BatchInfo info = vb::io::ReadBatchJson((dir / "batch.json").string());
    if (s == 0) {
      first = info;
    } else {
      auto differ = [&](const std::string& what, const std::string& a, const std::string& b) {
        if (a != b) {
          throw vb::InputError(dir.string(), 0, what,
                               "'" + b + "' differs from '" + a + "' of " + shards[0].string() +
                                   ": not shards of one batch");
        }
      };
      differ("matrix_fingerprint", first.matrix_fingerprint, info.matrix_fingerprint);
      differ("settings", first.settings, info.settings);
      differ("git_commit", first.git_commit, info.git_commit);
      differ("vb_version", first.vb_version, info.vb_version);
    }
    for (vb::batch::TrialRow& r : ReadIndex(dir)) {
      if (r.git_commit != info.git_commit || r.vb_version != info.vb_version) {
        conflicts.push_back(Stem(r) + " in " + dir.string() + " was made by build " +
                            r.git_commit + " (shard is " + info.git_commit + ")");
      }
      const std::string stem = Stem(r);
      for (const char* ext : {".json", "_traj.csv"}) {
        const fs::path src = dir / "trials" / (stem + ext);
        if (std::string(ext) == ".json" && !fs::exists(src)) {
          throw vb::InputError(src.string(), 0, "", "listed in the index but missing");
        }
      }
      auto it = merged.find(r.matrix_index);
      if (it != merged.end()) {
        if (vb::batch::StableFields(it->second) == vb::batch::StableFields(r)) {
          ++duplicates;
        } else {
          conflicts.push_back(stem + ": " + origin[r.matrix_index] + " and " + dir.string() +
                              " hold different results");
        }
        continue;
      }
      origin[r.matrix_index] = dir.string();
      merged.emplace(r.matrix_index, std::move(r));
    }
  }
  if (!conflicts.empty()) {
    std::string msg = std::to_string(conflicts.size()) + " conflict(s):\n";
    for (size_t i = 0; i < conflicts.size() && i < 10; ++i) msg += "  " + conflicts[i] + "\n";
    throw vb::InputError(out.string(), 0, "merge", msg + "nothing written");
  }

  std::error_code ec;
  fs::create_directories(out / "trials", ec);
  if (ec) throw vb::InputError(out.string(), 0, "OUT_DIR", "cannot create: " + ec.message());
  std::vector<vb::batch::TrialRow> rows;
  for (auto& [index, r] : merged) {
    const std::string stem = Stem(r);
    // Trajectory first, record last, each atomically: a killed merge leaves no half files.
    for (const char* ext : {"_traj.csv", ".json"}) {
      const fs::path src = fs::path(origin[index]) / "trials" / (stem + ext);
      if (!fs::exists(src)) continue;
      const fs::path dst = out / "trials" / (stem + ext);
      if (fs::exists(dst) && fs::equivalent(src, dst)) continue;
      vb::io::WriteFileAtomic(dst.string(), ReadText(src));
    }
    rows.push_back(r);
  }
  vb::io::WriteFileAtomic((out / "index.csv").string(), vb::batch::IndexCsv(rows));
  vb::io::WriteFileAtomic((out / "settings.txt").string(), first.settings + "\n");
  vb::io::BatchInfo info = first;
  info.shard = "merged";
  info.shard_trials = info.matrix_trials;
  vb::io::WriteBatchJson(info, (out / "batch.json").string());
  std::printf("vb_report merge: %zu shard dirs -> %zu of %zu trials in %s", shards.size(),
              rows.size(), first.matrix_trials, out.c_str());
  if (duplicates) std::printf("; %zu duplicate(s) with identical results kept once", duplicates);
  std::printf("\n");
  if (rows.size() < first.matrix_trials) {
    std::printf("vb_report merge: warning: %zu trial(s) of the matrix missing (unfinished or "
                "absent shards)\n", first.matrix_trials - rows.size());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> args(argv + 1, argv + argc);
    for (const std::string& a : args) {
      if (a == "--help" || a == "-h") {
        std::fputs(kUsage, stdout);
        return 0;
      }
    }
    if (!args.empty() && args[0] == "merge") {
      return Merge(std::vector<std::string>(args.begin() + 1, args.end()));
    }
    return Report(args);
  } catch (const vb::InputError& e) {
    std::fprintf(stderr, "vb_report: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_report: internal error: %s\n", e.what());
    return 1;
  }
}
