#include "view/trial_bundle.h"

#include <algorithm>
#include <filesystem>
#include <cstdio>
#include <vector>

#include "io/batch_io.h"
#include "io/cli_args.h"
#include "io/data_dir.h"
#include "io/result_io.h"
#include "io/task_io.h"
#include "io/task_ref.h"
#include "io/vehicle_io.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "view/scene_json.h"

namespace vb::view {

namespace fs = std::filesystem;

namespace {

// A trajectory of the longest trial (3600 s) at full rate is about 220 MB; larger is not read.
constexpr uint64_t kMaxTrialTextBytes = 256ull << 20;

// Reads a regular file of at most kMaxTrialTextBytes; false with *why otherwise (a sparse 64 GiB
// trajectory was read whole and ended the server with bad_alloc: W06 of the probe at 8ff4def).
bool ReadText(const std::string& path, std::string* text, std::string* why) {
  *why = io::InputFileProblem(path, kMaxTrialTextBytes);
  if (!why->empty()) return false;
  *why = "cannot be read";
  // One read of the whole file (a full-rate trajectory is megabytes; streams copy it twice).
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  text->resize(size > 0 ? static_cast<size_t>(size) : 0);
  const bool ok = size >= 0 && std::fread(text->data(), 1, text->size(), f) == text->size();
  std::fclose(f);
  return ok;
}

}  // namespace

std::string JsonText(const std::string& text) {
  std::string out;
  out.reserve(text.size() + text.size() / 16 + 2);
  out += '"';
  size_t run = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    // Non-ASCII text (rare: trial files are ASCII) goes through JsonString, which also replaces
    // bytes that are not well-formed UTF-8 (docs/reliability.md, DEF-7).
    if (c >= 0x80) return io::JsonString(text);
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out.append(text, run, i - run);
    const std::string escaped = io::JsonString(std::string(1, static_cast<char>(c)));
    out.append(escaped, 1, escaped.size() - 2);
    run = i + 1;
  }
  out.append(text, run, std::string::npos);
  out += '"';
  return out;
}

namespace {

double GoalRadius(const terrain::TaskSpec& task) {
  return runner::EpisodeRules().goal_radius_m * task.scale;
}

std::string Bundle(const std::string& task_json, const std::string& vehicle_json, int pair,
                   const std::string& trial_json) {
  std::string out;
  out.reserve(task_json.size() + vehicle_json.size() + trial_json.size() + 128);
  out += "{\"format\": \"vb-viewer\", \"version\": 1, \"pair\": " + std::to_string(pair);
  out.append(",\n\"task\": ").append(task_json);
  out.append(",\n\"vehicle\": ").append(vehicle_json);
  out.append(",\n\"trial\": ").append(trial_json.empty() ? "null" : trial_json);
  return out += "}\n";
}

// The task a record names, checked against the record's task name and hash.
const SceneCache::Task& FindTask(const std::string& result_path, const batch::TrialRow& row,
                                 const BundleOptions& options, SceneCache* cache) {
  std::vector<std::string> candidates;
  if (!options.task_file.empty()) {
    candidates.push_back(options.task_file);
  } else {
    candidates = io::TaskFileCandidates(row.task_file, result_path, options.tasks_dir);
    if (!options.tasks_dir.empty()) {   // by the task's name, when the file was named otherwise
      const std::string by_name = (fs::path(options.tasks_dir) / (row.task + ".yaml")).string();
      if (std::find(candidates.begin(), candidates.end(), by_name) == candidates.end()) {
        candidates.push_back(by_name);
      }
    }
  }
  std::string mismatch;
  for (const std::string& path : candidates) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) continue;
    const SceneCache::Task& loaded = cache->GetTask(path);
    const terrain::TaskSpec& task = loaded.spec;
    if (task.name != row.task) {
      if (mismatch.empty()) {
        mismatch = "task '" + task.name + "' does not match the trial's task '" + row.task + "'";
      }
      continue;
    }
    const std::string& hash = loaded.fnv1a64;
    if (!row.task_fnv1a64.empty() && hash != row.task_fnv1a64) {
      if (mismatch.empty()) {
        mismatch = "task file " + path + " does not match the trial: its FNV-1a is " + hash +
                   ", the trial ran on " + row.task_fnv1a64 +
                   " (the world was edited or regenerated)";
      }
      continue;
    }
    return loaded;
  }
  if (!mismatch.empty()) throw InputError(result_path, 0, "provenance.task_file", mismatch);
  std::string tried;
  for (const std::string& c : candidates) tried += (tried.empty() ? "" : ", ") + c;
  throw InputError(result_path, 0, "provenance.task_file",
                   "task file of trial not found (tried: " + tried + ")");
}

}  // namespace

std::string TrajectoryPathFor(const std::string& result_path) {
  std::string stem = result_path;
  if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, ".json") == 0) {
    stem.resize(stem.size() - 5);
  }
  return stem + "_traj.csv";
}

const SceneCache::Task& SceneCache::GetTask(const std::string& path) {
  const auto it = tasks_.find(path);
  if (it != tasks_.end() &&
      io::MakeProvenance(it->second.spec, runner::TrialSpec()).task_fnv1a64 == it->second.fnv1a64) {
    return it->second;
  }
  Task t;
  t.spec = io::LoadTask(path);
  t.fnv1a64 = io::MakeProvenance(t.spec, runner::TrialSpec()).task_fnv1a64;
  t.scene_json = TaskSceneJson(t.spec, GoalRadius(t.spec));
  return tasks_[path] = std::move(t);
}

const std::string& SceneCache::GetVehicleJson(const std::string& path) {
  const std::string fnv = io::FileFnv1a64Hex(path);
  auto& entry = vehicles_[path];
  if (entry.first != fnv || entry.second.empty()) {
    entry.second = VehicleSceneJson(io::LoadVehicle(path));
    entry.first = fnv;
  }
  return entry.second;
}

std::string TrialBundleJson(const std::string& result_path, const BundleOptions& options) {
  SceneCache local;
  SceneCache* cache = options.cache != nullptr ? options.cache : &local;
  const batch::TrialRow row = io::ReadTrialJson(result_path);
  std::string result_text;
  std::string why;
  if (!ReadText(result_path, &result_text, &why)) {
    throw InputError(result_path, 0, "", "cannot read trial record: it " + why);
  }
  const SceneCache::Task& loaded = FindTask(result_path, row, options, cache);
  const terrain::TaskSpec& task = loaded.spec;
  if (row.pair < 0 || static_cast<size_t>(row.pair) >= task.pairs.size()) {
    throw InputError(result_path, 0, "pair",
                     "pair " + std::to_string(row.pair) + " is not in task " + task.source_file +
                         " (" + std::to_string(task.pairs.size()) + " pairs)");
  }
  const std::string& vehicle_json = cache->GetVehicleJson(
      io::ListedDataFile(options.data_dir, "vehicles", row.vehicle, "vehicle", result_path));

  const std::string traj_path = TrajectoryPathFor(result_path);
  std::string traj_text;
  std::string traj_problem;
  const bool have_traj = ReadText(traj_path, &traj_text, &traj_problem);
  // The goal circle of the rules that decided the trial (the task's scene holds vb's).
  const runner::RuleSet rules = runner::ParseRuleSet("rules", row.rules, result_path);
  const double goal_radius_m =
      runner::GoalCircleRadius_m(rules, task.scale, runner::EpisodeRules().goal_radius_m);
  std::string trial = "{\"result_file\": " + io::JsonString(result_path) +
                      ", \"goal_radius_m\": " + io::JsonNumber(goal_radius_m) +
                      ", \"result_json\": " + JsonText(result_text) +
                      ", \"trajectory_file\": " + io::JsonString(traj_path) +
                      ", \"trajectory_csv\": ";
  trial.append(have_traj ? JsonText(traj_text) : "null");
  trial.append(", \"trajectory_error\": ")
      .append(have_traj ? "null" : io::JsonString("cannot read " + traj_path + ": it " + traj_problem))
      .append("}");
  return Bundle(loaded.scene_json, vehicle_json, row.pair, trial);
}

std::string SceneBundleJson(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                            int pair) {
  return Bundle(TaskSceneJson(task, GoalRadius(task)), VehicleSceneJson(vehicle), pair, "");
}

}  // namespace vb::view
