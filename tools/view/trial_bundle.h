// The data the viewer page loads for one trial (docs/viewer.md "Scene and trial data"): the
// scene (task and vehicle, scene_json.h) plus the trial's own files as text, which the page
// parses and checks itself (a missing or truncated trajectory shows as an error in the page).
//
//   {"format": "vb-viewer", "version": 1, "pair": K, "task": {...}, "vehicle": {...},
//    "trial": {"result_file", "result_json", "trajectory_file", "trajectory_csv",
//              "trajectory_error"} | null}
#pragma once

#include <map>
#include <string>

#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::view {

// Loaded tasks and vehicles with their scene JSON, reused while their files are unchanged:
// every use re-hashes the files' bytes (FNV-1a, well under a millisecond), which is what the
// record's provenance is checked against anyway, instead of parsing YAML and decoding the height
// image again (tens of milliseconds).
class SceneCache {
 public:
  struct Task {
    terrain::TaskSpec spec;
    std::string fnv1a64;      // of task file + height image, as io::MakeProvenance
    std::string scene_json;   // TaskSceneJson
  };
  // Throws InputError as io::LoadTask.
  const Task& GetTask(const std::string& path);
  // VehicleSceneJson of the vehicle file; throws InputError as io::LoadVehicle.
  const std::string& GetVehicleJson(const std::string& path);

 private:
  std::map<std::string, Task> tasks_;
  std::map<std::string, std::pair<std::string, std::string>> vehicles_;   // path -> (fnv, json)
};

struct BundleOptions {
  std::string data_dir;    // vehicles/<name>.yaml are read from here
  std::string tasks_dir;   // the task set the trials ran on (io::TaskFileCandidates); also
                           // <tasks_dir>/<task>.yaml, last
  std::string task_file;   // if set, the trial's task (instead of looking it up)
  SceneCache* cache = nullptr;   // optional: reuse loaded tasks and vehicles between calls
};

// The bundle of the trial whose record is `result_path` (vb_run/vb_batch JSON; the trajectory
// is the sibling <stem>_traj.csv). The task is options.task_file if set, else the first of
// io::TaskFileCandidates (provenance.task_file in tasks_dir, then beside the record and its
// parent directories; never the current directory), else <tasks_dir>/<task>.yaml, that is the
// world the trial ran on: same name and the same FNV-1a of task file + height image as the
// record's provenance. Throws InputError naming the file and what is wrong: unreadable or
// malformed record, no task file found, a task that does not match, an unknown vehicle.
std::string TrialBundleJson(const std::string& result_path, const BundleOptions& options);

// A bundle without a trial (teleoperation: the page shows the world and the live vehicle).
std::string SceneBundleJson(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                            int pair);

// io::JsonString for large text (a full-rate trajectory is megabytes): copies the runs of
// characters that need no escape in one go. Same output.
std::string JsonText(const std::string& text);

// Where a trial's trajectory lives: <result without .json>_traj.csv.
std::string TrajectoryPathFor(const std::string& result_path);

}  // namespace vb::view
