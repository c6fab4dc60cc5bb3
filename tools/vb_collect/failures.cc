// failures mode: the last seconds of every rollover and stuck trial of a vb_batch results
// directory, re-simulated and labelled (docs/datasets.md "Failure cases").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "io/batch_io.h"
#include "io/cli_args.h"
#include "io/model_store.h"
#include "io/result_io.h"
#include "io/data_dir.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "io/yaml_strict.h"
#include "mode.h"
#include "vb/batch/index.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/systems.h"

namespace vb_collect {

namespace {

namespace fs = std::filesystem;

// time_limit_s=<x> from the batch's settings.txt; `fallback` when the directory has none (a
// committed report keeps only index.csv).
double BatchTimeLimit(const std::string& batch_dir, double fallback) {
  const fs::path settings = fs::path(batch_dir) / "settings.txt";
  std::FILE* f = std::fopen(settings.c_str(), "rb");
  if (f == nullptr) return fallback;
  char buf[4096] = {0};
  const size_t n = std::fread(buf, 1, sizeof(buf) - 1, f);
  std::fclose(f);
  const std::string text(buf, n);
  const size_t at = text.find("time_limit_s=");
  if (at == std::string::npos) {
    throw vb::InputError(settings.string(), 1, "time_limit_s", "missing");
  }
  return vb::io::ParseNonNegative("time_limit_s",
                                  text.substr(at + 13, text.find_first_of(" \n", at) - at - 13));
}

// The trials of a results directory: its trials/*.json records, or its index.csv.
std::vector<vb::batch::TrialRow> ReadTrials(const std::string& dir) {
  const fs::path trials = fs::path(dir) / "trials";
  std::vector<vb::batch::TrialRow> rows;
  if (fs::is_directory(trials)) {
    std::vector<std::string> files;
    for (const fs::directory_entry& d : fs::directory_iterator(trials)) {
      const std::string name = d.path().filename().string();
      if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0 &&
          name.find(".tmp.") == std::string::npos) {
        files.push_back(d.path().string());
      }
    }
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) rows.push_back(vb::io::ReadTrialJson(f));
    return rows;
  }
  const fs::path index = fs::path(dir) / "index.csv";
  std::FILE* f = std::fopen(index.c_str(), "rb");
  if (f == nullptr) {
    throw vb::InputError(dir, 0, "--from",
                         "not a vb_batch results directory (no trials/ folder, no index.csv)");
  }
  std::string text;
  char buf[65536];
  size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) text.append(buf, n);
  std::fclose(f);
  return vb::batch::ParseIndexCsv(text, index.string());
}

class FailuresMode : public Mode {
 public:
  explicit FailuresMode(const Options& o) : o_(o), config_(MakeSampleConfig(o)) {
    time_limit_s_ = BatchTimeLimit(o.from_dir, o.time_limit_s);
    for (vb::batch::TrialRow& row : ReadTrials(o.from_dir)) {
      if (row.status != "rollover" && row.status != "stuck") continue;
      if (row.perception != "none") {
        std::fprintf(stderr, "vb_collect: skipping %s: perception '%s' (only ground truth)\n",
                     vb::batch::RowStem(row).c_str(), row.perception.c_str());
        continue;
      }
      // The task as recorded, or by name in --tasks (a report made in another checkout).
      if (!fs::exists(row.task_file)) {
        row.task_file = (fs::path(o.tasks_dir) / (row.task + ".yaml")).string();
      }
      WorkItem item;
      item.episodes.push_back(static_cast<long>(rows_.size()));
      items_.push_back(item);
      stems_.push_back(vb::batch::RowStem(row));
      rows_.push_back(std::move(row));
    }
    if (rows_.empty()) {
      throw vb::InputError(o.from_dir, 0, "--from", "holds no rollover or stuck trials");
    }
    for (const vb::batch::TrialRow& r : rows_) {
      if (r.vehicle != rows_.front().vehicle) {
        throw vb::InputError(o.from_dir, 0, "--from",
                             "trials of several vehicles (" + r.vehicle + ", " +
                                 rows_.front().vehicle + "): one dataset has one wheel count");
      }
    }
    vehicle_file_ = vb::io::ListedDataFile(DataDir(), "vehicles", rows_.front().vehicle, "vehicle",
                                           o.from_dir);
    vehicle_ = vb::io::LoadVehicle(vehicle_file_);
  }

  const std::vector<WorkItem>& items() const override { return items_; }
  std::string Settings() const override {
    // The failing trials by name (their records' content is checked by re-simulation).
    std::string trials;
    for (const std::string& s : stems_) trials += s + ";";
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx",
                  static_cast<unsigned long long>(vb::io::Fnv1a64(trials)));
    return "mode=failures trials=" + std::to_string(rows_.size()) + ":" + hex +
           " time_limit_s=" + vb::io::FormatDouble(time_limit_s_) +
           " window_s=" + vb::io::FormatDouble(o_.window_s) + " vehicle=" + rows_.front().vehicle +
           ":" + vb::io::FileFnv1a64Hex(vehicle_file_) + " soil=" + o_.soil + ":" +
           vb::io::FileFnv1a64Hex(DataDir() + "/soils/" + o_.soil + ".yaml") +
           " sample_period_s=" + vb::io::FormatDouble(o_.sample_period_s) + " crops=" + o_.crops +
           " crop_size=" + std::to_string(o_.crop_size) +
           " crop_res=" + vb::io::FormatDouble(o_.crop_resolution_m);
  }
  std::string AlgorithmName() const override { return "failure windows of vb_batch trials"; }
  vb::dataset::ActionKind action_kind() const override { return vb::dataset::ActionKind::kDirect; }
  size_t wheels() const override { return vehicle_.axles.size() * 2; }

  void Run(const WorkItem& item, const std::vector<long>& todo, const EpisodeSink& sink) override {
    for (long e : todo) {
      const vb::batch::TrialRow& row = rows_[static_cast<size_t>(e)];
      const vb::terrain::TaskSpec task = vb::io::LoadTask(row.task_file);
      const std::string soil_file = DataDir() + "/soils/" + o_.soil + ".yaml";
      const std::optional<vb::soil::SoilConfig> soil = vb::io::LoadSoilIfNeeded(task, soil_file);
      vb::runner::EpisodeRules rules;
      rules.time_limit_s = time_limit_s_;
      rules.trajectory_every_n_steps = 0;
      vb::runner::Episode episode(task, vehicle_, rules, soil ? &*soil : nullptr);
      vb::runner::TrialSpec spec;
      spec.pair_index = row.pair;
      spec.seed = row.seed;
      spec.system = row.system;
      spec.vehicle = row.vehicle;
      try {
        vb::runner::ValidateSystemName(row.system);
      } catch (const vb::InputError&) {
        throw vb::InputError(stems_[static_cast<size_t>(e)], 0, "system",
                             "unknown system '" + row.system + "'");
      }
      std::unique_ptr<vb::controllers::Controller> controller =
          vb::runner::MakeSystem(row.system, episode, &models_);
      episode.Reset(spec);
      vb::dataset::ControllerPolicy policy(std::move(controller));
      policy.Start(episode);
      const long k_end = std::lround(row.sim_time_s / rules.step_s);
      const long window_steps = std::lround(o_.window_s / rules.step_s);
      const long every = config_.sample_every_steps;
      vb::dataset::RecordWindow window;
      window.first_step = k_end - every * (std::min(k_end, window_steps) / every);
      vb::dataset::EpisodeRecord r = vb::dataset::RecordEpisode(episode, policy, config_, window);
      const std::string status = r.FindAttribute("status")->text;
      if (status != row.status || episode.physics_steps() != k_end) {
        // Another build or task version: no window can be cut from this trial. An empty episode
        // says so (left out of the assembled dataset, not retried on resume).
        const std::string why = "the batch recorded " + row.status + " at " +
                                vb::io::FormatDouble(row.sim_time_s) + " s, the re-simulation " +
                                status + " at " + vb::io::FormatDouble(episode.time_s()) + " s";
        std::fprintf(stderr, "vb_collect: trial %s did not reproduce: %s\n",
                     stems_[static_cast<size_t>(e)].c_str(), why.c_str());
        r = vb::dataset::EpisodeRecord();
        r.SetText("status", "not_reproduced");
        r.SetText("message", why);
        r.SetReal("sim_time_s", episode.time_s());
      }
      AddCommonAttributes(o_, e, row.seed, &r);
      r.SetText("mode", "failures");
      r.SetText("failure_type", row.status);
      r.SetText("trial", stems_[static_cast<size_t>(e)]);
      r.SetText("task", row.task);
      r.SetText("task_file", row.task_file);
      r.SetText("task_fnv1a64", vb::io::TaskFnv1a64(task));
      r.SetInt("pair", row.pair);
      r.SetText("vehicle", row.vehicle);
      r.SetText("vehicle_fnv1a64", vb::io::FileFnv1a64Hex(vehicle_file_));
      r.SetText("soil", soil ? o_.soil : "");
      r.SetText("system", row.system);
      r.SetReal("trial_end_s", row.sim_time_s);
      r.SetReal("window_s", o_.window_s);
      r.SetText("trial_git_commit", row.git_commit);
      sink(e, r);
    }
  }

 private:
  Options o_;
  vb::dataset::SampleConfig config_;
  double time_limit_s_ = 60.0;
  std::vector<vb::batch::TrialRow> rows_;
  std::vector<std::string> stems_;
  std::string vehicle_file_;
  vb::vehicles::VehicleParams vehicle_;
  vb::io::DataDirModelStore models_{DataDir()};   // weights of learned systems, read on first use
  std::vector<WorkItem> items_;
};

}  // namespace

std::unique_ptr<Mode> MakeFailuresMode(const Options& o) {
  return std::make_unique<FailuresMode>(o);
}

}  // namespace vb_collect
