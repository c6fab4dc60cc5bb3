// teleop mode: teleoperated demonstrations (docs/datasets.md "Teleoperated demonstrations").
// Each recording of vb_view teleop (a trial record <stem>.json + <stem>_traj.csv with the command
// of every 5 ms physics step) is re-simulated with its recorded commands on its task, pair,
// seed, vehicle and soil; the re-simulation must reproduce the recorded drive bit for bit (every
// trajectory value, the step count and the status), or the run stops with an error naming the
// recording. The drive is recorded as the demonstrations' episodes are (direct action space),
// and, as the paper filters its human demonstrations, only successes are kept unless
// --keep-failures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "io/batch_io.h"
#include "io/build_info.h"
#include "io/cli_args.h"
#include "io/result_io.h"
#include "io/data_dir.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/task_ref.h"
#include "io/vehicle_io.h"
#include "io/yaml_strict.h"
#include "mode.h"
#include "vb/batch/index.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"

namespace vb_collect {

namespace {

namespace fs = std::filesystem;

constexpr double kRadToDeg = 180.0 / vb::kPi;
// The trajectory columns before the per-wheel ones (io::WriteTrajectoryCsv).
const char* const kColumns[] = {"t_s",       "x_m",       "y_m",      "z_m",      "vx_mps",
                                "vy_mps",    "vz_mps",    "speed_mps", "roll_deg", "pitch_deg",
                                "yaw_deg",   "throttle",  "steering", "braking",  "gear"};
constexpr size_t kFixedColumns = sizeof(kColumns) / sizeof(kColumns[0]);
constexpr size_t kThrottle = 11, kSteering = 12, kBraking = 13;

// One teleoperated drive as recorded by vb_view.
struct Recording {
  std::string json_path, csv_path;
  vb::batch::TrialRow row;
  std::string soil, soil_fnv1a64, vehicle_fnv1a64, operator_name;
  std::string fnv1a64;   // of the record and the trajectory, for the settings
};

std::string ReadWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw vb::InputError(path, 0, "", "cannot read the recording's trajectory");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The trial record, plus what ReadTrialJson does not keep (soil, parameter hashes, operator).
Recording ReadRecording(const std::string& path) {
  Recording r;
  r.json_path = path;
  r.row = vb::io::ReadTrialJson(path);   // InputError naming the file and key
  if (r.row.system != "teleop") {
    throw vb::InputError(path, 0, "system",
                         "'" + r.row.system + "' is not a teleoperated drive (vb_view teleop "
                         "records system 'teleop'; failure windows of other trials: vb_collect "
                         "failures)");
  }
  if (r.row.perception != "none") {
    throw vb::InputError(path, 0, "perception", "only ground-truth drives can be collected");
  }
  if (r.row.trajectory_samples < 0) {
    throw vb::InputError(path, 0, "trajectory_samples",
                         "missing: not a vb_view recording with a trajectory");
  }
  const YAML::Node prov = YAML::LoadFile(path)["provenance"];
  auto text = [&](const char* key) {
    const YAML::Node n = prov[key];
    if (!n.IsDefined() || n.IsNull()) return std::string();
    try {
      return n.as<std::string>();
    } catch (const YAML::Exception&) {
      throw vb::InputError(path, n.Mark().line + 1, std::string("provenance.") + key,
                           "wrong type in trial record");
    }
  };
  r.soil = text("soil");
  r.soil_fnv1a64 = text("soil_fnv1a64");
  r.vehicle_fnv1a64 = text("vehicle_fnv1a64");
  r.operator_name = text("operator");   // recordings made before --operator have none
  r.csv_path = path.substr(0, path.size() - 5) + "_traj.csv";
  const std::string problem = vb::io::TrajectoryProblem(r.csv_path, r.row);
  if (!problem.empty()) throw vb::InputError(path, 0, "trajectory_samples", problem);
  const std::string bytes = ReadWhole(path) + ReadWhole(r.csv_path);
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx",
                static_cast<unsigned long long>(vb::io::Fnv1a64(bytes)));
  r.fnv1a64 = hex;
  return r;
}

// RECORDINGS...: trial records, or directories searched (recursively) for *.json records.
std::vector<std::string> RecordingFiles(const std::vector<std::string>& args) {
  std::vector<std::string> files;
  for (const std::string& a : args) {
    std::error_code ec;
    if (fs::is_directory(a, ec)) {
      std::vector<std::string> found;
      for (const fs::directory_entry& d : fs::recursive_directory_iterator(a, ec)) {
        const std::string name = d.path().filename().string();
        if (d.is_regular_file() && name.size() > 5 &&
            name.compare(name.size() - 5, 5, ".json") == 0 &&
            name.find(".tmp.") == std::string::npos) {
          found.push_back(d.path().string());
        }
      }
      if (found.empty()) {
        throw vb::InputError(a, 0, "RECORDINGS", "directory holds no trial records (*.json)");
      }
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(a, ec)) {
      if (a.size() <= 5 || a.compare(a.size() - 5, 5, ".json") != 0) {
        throw vb::InputError(a, 0, "RECORDINGS",
                             "not a trial record (vb_view teleop writes <stem>.json beside "
                             "<stem>_traj.csv)");
      }
      files.push_back(a);
    } else {
      throw vb::InputError(a, 0, "RECORDINGS", "no such file or directory");
    }
  }
  for (size_t i = 1; i < files.size(); ++i) {
    if (std::find(files.begin(), files.begin() + static_cast<long>(i), files[i]) !=
        files.begin() + static_cast<long>(i)) {
      throw vb::InputError(files[i], 0, "RECORDINGS", "given twice");
    }
  }
  return files;
}

// The recording's task: its recorded path beside the recording (or in its parents), in
// --tasks DIR, or by name there; the task name and FNV-1a must be the recording's.
vb::terrain::TaskSpec FindTask(const Recording& rec, const std::string& tasks_dir) {
  std::vector<std::string> candidates =
      vb::io::TaskFileCandidates(rec.row.task_file, rec.json_path, tasks_dir);
  const std::string by_name = (fs::path(tasks_dir) / (rec.row.task + ".yaml")).string();
  if (std::find(candidates.begin(), candidates.end(), by_name) == candidates.end()) {
    candidates.push_back(by_name);
  }
  std::string mismatch, tried;
  for (const std::string& path : candidates) {
    tried += (tried.empty() ? "" : ", ") + path;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) continue;
    vb::terrain::TaskSpec task = vb::io::LoadTask(path);
    const std::string hash =
        vb::io::TaskFnv1a64(task);
    if (task.name == rec.row.task && hash == rec.row.task_fnv1a64) return task;
    if (mismatch.empty()) {
      mismatch = task.name != rec.row.task
                     ? "task '" + task.name + "' at " + path + " is not the drive's '" +
                           rec.row.task + "'"
                     : "task file " + path + " does not match the drive: its FNV-1a is " + hash +
                           ", the drive ran on " + rec.row.task_fnv1a64 +
                           " (the world was edited or regenerated)";
    }
  }
  if (!mismatch.empty()) {
    throw vb::InputError(rec.json_path, 0, "provenance.task_file", mismatch);
  }
  throw vb::InputError(rec.json_path, 0, "provenance.task_file",
                       "the drive's task file was not found (tried: " + tried +
                           "); give its task set with --tasks DIR");
}

// The trajectory CSV: every row's values (gear and wheel surfaces as numbers too). Checks the
// header, that every field is a number, and that there is a sample at every physics step.
std::vector<std::vector<double>> ReadTrajectory(const Recording& rec, double step_s) {
  std::istringstream in(ReadWhole(rec.csv_path));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header = vb::io::SplitList(line, ',');
  const size_t wheels = header.size() >= kFixedColumns ? (header.size() - kFixedColumns) / 2 : 0;
  std::string expected;
  for (const char* c : kColumns) expected += std::string(expected.empty() ? "" : ",") + c;
  for (size_t i = 0; i < wheels; ++i) expected += ",surface_w" + std::to_string(i);
  for (size_t i = 0; i < wheels; ++i) expected += ",sinkage_w" + std::to_string(i) + "_m";
  if (line != expected || wheels == 0) {
    throw vb::InputError(rec.csv_path, 1, "", "not a vb trajectory header (expected '" +
                                                  expected + "')");
  }
  std::vector<std::vector<double>> rows;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    std::vector<double> v;
    v.reserve(header.size());
    size_t at = 0;
    for (size_t c = 0; c < header.size(); ++c) {
      const size_t comma = line.find(',', at);
      if ((comma == std::string::npos) != (c + 1 == header.size())) {
        throw vb::InputError(rec.csv_path, number, "",
                             "expected " + std::to_string(header.size()) + " fields");
      }
      const std::string field = line.substr(at, comma == std::string::npos ? std::string::npos
                                                                              : comma - at);
      char* end = nullptr;
      const double x = std::strtod(field.c_str(), &end);
      if (field.empty() || end != field.c_str() + field.size() || !std::isfinite(x)) {
        throw vb::InputError(rec.csv_path, number, header[c], "'" + field + "' is not a number");
      }
      v.push_back(x);
      at = comma + 1;
    }
    const double expected_t = static_cast<double>(rows.size()) * step_s;
    if (std::abs(v[0] - expected_t) > 1e-9) {
      throw vb::InputError(rec.csv_path, number, "t_s",
                           "sample at t = " + vb::io::FormatDouble(v[0]) + " s, expected " +
                               vb::io::FormatDouble(expected_t) +
                               " s: a recording needs the command of every 5 ms physics step "
                               "(vb_view teleop records them; vb_run --traj-every > 1 does not)");
    }
    if (v[kThrottle] < 0 || v[kThrottle] > 1 || v[kSteering] < -1 || v[kSteering] > 1 ||
        v[kBraking] < 0 || v[kBraking] > 1) {
      throw vb::InputError(rec.csv_path, number, "throttle",
                           "command outside its range ([0, 1], [-1, 1], [0, 1])");
    }
    rows.push_back(std::move(v));
  }
  // A drive stopped right after its start has only the start sample: an empty episode.
  if (rows.empty()) throw vb::InputError(rec.csv_path, 0, "", "no samples");
  return rows;
}

// The trajectory row of a re-simulated sample, as io::WriteTrajectoryCsv writes it.
std::vector<double> RowOf(const vb::runner::TrajectorySample& s, size_t wheels) {
  std::vector<double> v = {s.time_s,         s.position_W.x(), s.position_W.y(),
                           s.position_W.z(), s.velocity_W.x(), s.velocity_W.y(),
                           s.velocity_W.z(), s.speed_mps,      s.rpy.roll_rad * kRadToDeg,
                           s.rpy.pitch_rad * kRadToDeg,        s.rpy.yaw_rad * kRadToDeg,
                           s.throttle,       s.steering,       s.braking,
                           static_cast<double>(s.gear)};
  for (size_t i = 0; i < wheels; ++i) {
    v.push_back(i < s.wheel_surface.size() ? s.wheel_surface[i] : -1);
  }
  for (size_t i = 0; i < wheels; ++i) {
    v.push_back(i < s.wheel_sinkage_m.size() ? s.wheel_sinkage_m[i] : 0.0);
  }
  return v;
}

// Replays the recorded commands: physics step k applies the command of sample k + 1 (sample 0 is
// the start state; sample k carries the command applied during step k).
class ReplayPolicy : public vb::dataset::SamplePolicy {
 public:
  explicit ReplayPolicy(const std::vector<std::vector<double>>& rows) : rows_(rows) {}
  vb::controllers::Command Step(vb::runner::Episode& episode) override {
    const size_t k = std::min(static_cast<size_t>(episode.physics_steps()) + 1, rows_.size() - 1);
    const std::vector<double>& r = rows_[k];
    vb::controllers::Command c;
    c.throttle = r[kThrottle];
    c.steering = r[kSteering];
    c.braking = r[kBraking];
    return c;
  }
  vb::dataset::ActionKind action_kind() const override {
    return vb::dataset::ActionKind::kDirect;
  }

 private:
  const std::vector<std::vector<double>>& rows_;
};

class TeleopMode : public Mode {
 public:
  explicit TeleopMode(const Options& o) : o_(o), config_(MakeSampleConfig(o)) {
    for (const std::string& f : RecordingFiles(o.recordings)) {
      WorkItem item;
      item.episodes.push_back(static_cast<long>(recs_.size()));
      items_.push_back(item);
      recs_.push_back(ReadRecording(f));
    }
    const Recording& first = recs_.front();
    for (const Recording& r : recs_) {
      if (r.row.vehicle != first.row.vehicle) {
        throw vb::InputError(r.json_path, 0, "vehicle",
                             "'" + r.row.vehicle + "', but " + first.json_path + " drove '" +
                                 first.row.vehicle + "': one dataset has one wheel count");
      }
    }
    vehicle_file_ = vb::io::ListedDataFile(DataDir(), "vehicles", first.row.vehicle, "vehicle",
                                           first.json_path);
    vehicle_ = vb::io::LoadVehicle(vehicle_file_);
    const std::string vehicle_hash = vb::io::FileFnv1a64Hex(vehicle_file_);
    for (const Recording& r : recs_) {
      if (!r.vehicle_fnv1a64.empty() && r.vehicle_fnv1a64 != vehicle_hash) {
        throw vb::InputError(r.json_path, 0, "provenance.vehicle_fnv1a64",
                             "the drive used another version of " + vehicle_file_ + " (FNV-1a " +
                                 r.vehicle_fnv1a64 + ", the file's is " + vehicle_hash + ")");
      }
    }
  }

  const std::vector<WorkItem>& items() const override { return items_; }
  std::string Settings() const override {
    std::string recordings;
    for (const Recording& r : recs_) recordings += r.json_path + ":" + r.fnv1a64 + ";";
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx",
                  static_cast<unsigned long long>(vb::io::Fnv1a64(recordings)));
    return "mode=teleop recordings=" + std::to_string(recs_.size()) + ":" + hex +
           " keep_failures=" + (o_.keep_failures ? "1" : "0") +
           " time_limit_s=" + vb::io::FormatDouble(o_.time_limit_s) + " vehicle=" +
           recs_.front().row.vehicle + ":" + vb::io::FileFnv1a64Hex(vehicle_file_) +
           " sample_period_s=" + vb::io::FormatDouble(o_.sample_period_s) + " crops=" + o_.crops +
           " crop_size=" + std::to_string(o_.crop_size) +
           " crop_res=" + vb::io::FormatDouble(o_.crop_resolution_m);
  }
  std::string AlgorithmName() const override {
    return std::string("vb teleoperated demonstrations (vb_view teleop") +
           (o_.keep_failures ? ", failures kept)" : ", successes only)");
  }
  vb::dataset::ActionKind action_kind() const override { return vb::dataset::ActionKind::kDirect; }
  size_t wheels() const override { return vehicle_.axles.size() * 2; }

  void Run(const WorkItem&, const std::vector<long>& todo, const EpisodeSink& sink) override {
    for (long e : todo) {
      const Recording& rec = recs_[static_cast<size_t>(e)];
      const vb::terrain::TaskSpec task = FindTask(rec, o_.tasks_dir);
      const std::string soil_file = vb::io::ListedDataFile(
          DataDir(), "soils", rec.soil.empty() ? o_.soil : rec.soil, "provenance.soil",
          rec.json_path);
      const std::optional<vb::soil::SoilConfig> soil = vb::io::LoadSoilIfNeeded(task, soil_file);
      if (soil && !rec.soil_fnv1a64.empty() &&
          vb::io::FileFnv1a64Hex(soil_file) != rec.soil_fnv1a64) {
        throw vb::InputError(rec.json_path, 0, "provenance.soil_fnv1a64",
                             "the drive used another version of " + soil_file);
      }
      vb::runner::EpisodeRules rules;
      rules.time_limit_s = o_.time_limit_s;
      rules.trajectory_every_n_steps = 1;   // compared with the recording, step by step
      const std::vector<std::vector<double>> rows = ReadTrajectory(rec, rules.step_s);
      const long recorded_steps = static_cast<long>(rows.size()) - 1;
      if (std::abs(rec.row.sim_time_s - static_cast<double>(recorded_steps) * rules.step_s) >
          1e-9) {
        throw vb::InputError(rec.json_path, 0, "sim_time_s",
                             vb::io::FormatDouble(rec.row.sim_time_s) +
                                 " s, but the trajectory ends at " +
                                 vb::io::FormatDouble(rows.back()[0]) + " s");
      }
      vb::runner::Episode episode(task, vehicle_, rules, soil ? &*soil : nullptr);
      vb::runner::TrialSpec spec;
      spec.pair_index = rec.row.pair;
      spec.seed = rec.row.seed;
      spec.system = "teleop";
      spec.vehicle = rec.row.vehicle;
      episode.Reset(spec);
      ReplayPolicy policy(rows);
      vb::dataset::RecordWindow window;
      window.end_step = recorded_steps;
      vb::dataset::EpisodeRecord r = vb::dataset::RecordEpisode(episode, policy, config_, window);
      const bool stopped = !episode.Done();
      const vb::runner::TrialResult again = episode.TakeResult();
      CheckReproduced(rec, rows, again, wheels());
      std::string status = r.FindAttribute("status")->text;
      if (stopped) {   // the recorded "stopped by the operator at ...", not the rules' message
        for (vb::dataset::Attribute& a : r.attributes) {
          if (a.name == "message") a.text = rec.row.message;
        }
      }
      const bool success = status == "success";
      if (!success && !o_.keep_failures) {
        const std::string message = r.FindAttribute("message")->text;
        r = vb::dataset::EpisodeRecord();
        r.SetText("status", status);
        r.SetText("message", "filtered out (not a success): " + message);
        r.SetReal("sim_time_s", episode.time_s());
      }
      AddCommonAttributes(o_, e, spec.seed, &r);
      r.SetText("mode", "teleop");
      r.SetText("task", task.name);
      r.SetText("task_file", rec.row.task_file);
      r.SetText("task_fnv1a64", rec.row.task_fnv1a64);
      r.SetInt("pair", spec.pair_index);
      r.SetText("vehicle", spec.vehicle);
      r.SetText("vehicle_fnv1a64", vb::io::FileFnv1a64Hex(vehicle_file_));
      r.SetText("soil", soil ? (rec.soil.empty() ? o_.soil : rec.soil) : "");
      r.SetText("system", "teleop");
      r.SetText("source", "teleop");
      r.SetText("operator", rec.operator_name);
      r.SetText("recording", rec.json_path);
      r.SetText("recording_fnv1a64", rec.fnv1a64);
      r.SetText("recording_git_commit", rec.row.git_commit);
      r.SetText("failure_type", success ? "" : status);
      r.SetInt("stopped_by_operator", stopped ? 1 : 0);
      r.SetReal("time_limit_s", o_.time_limit_s);
      sink(e, r);
    }
  }

 private:
  // The re-simulation must be the recorded drive: every trajectory value to the bit (the CSV
  // holds each double exactly, "%.17g"), the same number of steps and status.
  static void CheckReproduced(const Recording& rec, const std::vector<std::vector<double>>& rows,
                              const vb::runner::TrialResult& again, size_t wheels) {
    const std::string build = " (recorded by commit " + rec.row.git_commit + ", re-simulated by " +
                              vb::io::BuildGitCommit() +
                              "; a replay is bit-exact only on a build with the same physics)";
    // the first differing value first: it is where the drives part, the status is a consequence
    const size_t common = std::min(rows.size(), again.trajectory.size());
    for (size_t i = 0; i < common; ++i) {
      const std::vector<double> v = RowOf(again.trajectory[i], wheels);
      for (size_t c = 0; c < v.size(); ++c) {
        if (v[c] == rows[i][c]) continue;
        const std::string column =
            c < kFixedColumns ? kColumns[c]
            : c < kFixedColumns + wheels
                ? "surface_w" + std::to_string(c - kFixedColumns)
                : "sinkage_w" + std::to_string(c - kFixedColumns - wheels) + "_m";
        throw vb::InputError(rec.json_path, 0, column,
                             "the re-simulation differs from the recording at t = " +
                                 vb::io::FormatDouble(rows[i][0]) + " s (" + rec.csv_path +
                                 " line " + std::to_string(i + 2) + "): recorded " +
                                 vb::io::FormatDouble(rows[i][c]) + ", re-simulated " +
                                 vb::io::FormatDouble(v[c]) + build);
      }
    }
    const std::string status(vb::runner::TrialStatusName(again.status));
    if (again.trajectory.size() != rows.size() || status != rec.row.status) {
      throw vb::InputError(
          rec.json_path, 0, "status",
          "the re-simulation does not reproduce the drive: recorded " + rec.row.status + " at " +
              vb::io::FormatDouble(rec.row.sim_time_s) + " s, re-simulated " + status + " at " +
              vb::io::FormatDouble(again.sim_time_s) + " s" + build);
    }
  }

  Options o_;
  vb::dataset::SampleConfig config_;
  std::vector<Recording> recs_;
  std::vector<WorkItem> items_;
  std::string vehicle_file_;
  vb::vehicles::VehicleParams vehicle_;
};

}  // namespace

std::unique_ptr<Mode> MakeTeleopMode(const Options& o) { return std::make_unique<TeleopMode>(o); }

}  // namespace vb_collect
