// vb_report merge OUT SHARD...: shard directories of one matrix into one directory with the
// layout of an unsharded run (docs/batch.md "Shards and merge").
#include <cstdio>
#include <filesystem>

#include "common.h"
#include "io/batch_io.h"
#include "io/yaml_strict.h"
#include "vb/batch/merge.h"
#include "vb/engine/error.h"

namespace vb_report {

namespace fs = std::filesystem;

int Merge(const std::vector<std::string>& args) {
  if (args.size() < 2) {
    throw vb::InputError("", 0, "merge", "usage: vb_report merge OUT_DIR SHARD_DIR...");
  }
  const fs::path out = args[0];
  const std::vector<fs::path> shards(args.begin() + 1, args.end());
  vb::io::BatchInfo first;
  std::vector<vb::batch::MergeInput> inputs;
  for (size_t s = 0; s < shards.size(); ++s) {
    const fs::path& dir = shards[s];
    const vb::io::BatchInfo info = vb::io::ReadBatchJson((dir / "batch.json").string());
    if (s == 0) first = info;
    auto same = [&](const std::string& what, const std::string& a, const std::string& b) {
      if (a != b) {
        throw vb::InputError(dir.string(), 0, what,
                             "'" + b + "' differs from '" + a + "' of " + shards[0].string() +
                                 ": not shards of one batch");
      }
    };
    same("matrix_fingerprint", first.matrix_fingerprint, info.matrix_fingerprint);
    same("settings", first.settings, info.settings);
    same("git_commit", first.git_commit, info.git_commit);
    same("vb_version", first.vb_version, info.vb_version);
    vb::batch::MergeInput in{dir.string(), info.git_commit, info.vb_version, ReadIndex(dir)};
    // The per-trial records are the truth (docs/batch.md): each must read, agree with its index
    // row, come from the shard's build and have its complete trajectory. A shard whose files were
    // damaged after it finished is refused, never copied (DEF-10 of the probe).
    for (const vb::batch::TrialRow& r : in.rows) {
      const fs::path record = dir / "trials" / (Stem(r) + ".json");
      if (!fs::exists(record)) {
        throw vb::InputError(record.string(), 0, "", "listed in the index but missing");
      }
      vb::batch::TrialRow from_record = vb::io::ReadTrialJson(record.string());
      from_record.matrix_index = r.matrix_index;
      from_record.scale = r.scale;
      from_record.elevation = r.elevation;
      from_record.terrain = r.terrain;
      from_record.density = r.density;
      if (from_record.git_commit != info.git_commit || from_record.vb_version != info.vb_version) {
        throw vb::InputError(record.string(), 0, "provenance",
                             "made by vb " + from_record.vb_version + " (" +
                                 from_record.git_commit + "), the shard by vb " +
                                 info.vb_version + " (" + info.git_commit + ")");
      }
      if (vb::batch::StableFields(from_record) != vb::batch::StableFields(r)) {
        throw vb::InputError(record.string(), 0, "",
                             "disagrees with its row in " + (dir / "index.csv").string() +
                                 " (an edited record or index; re-run the shard)");
      }
      const std::string traj_problem = vb::io::TrajectoryProblem(
          (dir / "trials" / (Stem(r) + "_traj.csv")).string(), from_record);
      if (!traj_problem.empty()) throw vb::InputError(record.string(), 0, "", traj_problem);
    }
    inputs.push_back(std::move(in));
  }
  const vb::batch::MergeResult merged = vb::batch::MergeIndexes(inputs);
  if (!merged.conflicts.empty()) {
    std::string msg = std::to_string(merged.conflicts.size()) + " conflict(s):\n";
    for (size_t i = 0; i < merged.conflicts.size() && i < 10; ++i) {
      msg += "  " + merged.conflicts[i] + "\n";
    }
    throw vb::InputError(out.string(), 0, "merge", msg + "nothing written");
  }

  // A fresh directory only: files already there (another merge, a stray trial) would mix with
  // the merged ones.
  std::error_code ec;
  if (fs::exists(out, ec) && !(fs::is_directory(out, ec) && fs::is_empty(out, ec))) {
    throw vb::InputError(out.string(), 0, "OUT_DIR",
                         "exists and is not an empty directory; merge into a new one");
  }
  fs::create_directories(out / "trials", ec);
  if (ec) throw vb::InputError(out.string(), 0, "OUT_DIR", "cannot create: " + ec.message());
  std::vector<vb::batch::TrialRow> rows;
  for (const vb::batch::MergedRow& m : merged.rows) {
    const std::string stem = Stem(m.row);
    // Trajectory first, record last, each atomically: a killed merge leaves no half files.
    for (const char* ext : {"_traj.csv", ".json"}) {
      const fs::path src = fs::path(m.origin) / "trials" / (stem + ext);
      if (!fs::exists(src)) continue;
      const fs::path dst = out / "trials" / (stem + ext);
      if (fs::exists(dst) && fs::equivalent(src, dst)) continue;
      vb::io::WriteFileAtomic(dst.string(), ReadText(src));
    }
    rows.push_back(m.row);
  }
  vb::io::WriteFileAtomic((out / "index.csv").string(), vb::batch::IndexCsv(rows));
  vb::io::WriteFileAtomic((out / "settings.txt").string(), first.settings + "\n");
  vb::io::BatchInfo info = first;
  info.shard = "merged";
  info.shard_trials = info.matrix_trials;
  vb::io::WriteBatchJson(info, (out / "batch.json").string());
  std::printf("vb_report merge: %zu shard dirs -> %zu of %zu trials in %s", shards.size(),
              rows.size(), first.matrix_trials, out.c_str());
  if (merged.duplicates) {
    std::printf("; %zu duplicate(s) with identical results kept once", merged.duplicates);
  }
  std::printf("\n");
  if (rows.size() < first.matrix_trials) {
    std::printf("vb_report merge: warning: %zu trial(s) of the matrix missing (unfinished or "
                "absent shards)\n", first.matrix_trials - rows.size());
  }
  return 0;
}

}  // namespace vb_report
