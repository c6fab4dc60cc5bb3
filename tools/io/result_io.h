// Writing trial results: one JSON summary and one trajectory CSV per trial, and a summary CSV
// with one row per trial. Doubles are printed with "%.17g" (round trip), so reruns of the same
// trial give byte-identical files apart from the wall-clock fields and the host name. Every file
// is written atomically (temporary file in the same directory, then rename), so a crashed or
// killed batch never leaves a half-written result behind.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/engine/runner/episode.h"
#include "vb/terrain/task.h"

namespace vb::io {

// Where a result came from. vb_version and git_commit default to the build's own.
struct Provenance {
  std::string vb_version;
  std::string git_commit;
  std::string task_file;   // "<task set>/<file>", e.g. "tasks/env042.yaml" (io/task_ref.h)
  // 64-bit FNV-1a over the task file bytes followed by the height image bytes, 16 hex digits:
  // identifies the exact world even if the file is edited in place.
  std::string task_fnv1a64;
  std::string vehicle;
  // FNV-1a of the vehicle file and of the soil file (empty when the task has no soil), so a
  // result names the exact parameters it was made with, not only their names.
  std::string vehicle_fnv1a64;
  std::string soil;
  std::string soil_fnv1a64;
  std::string system;
  // Perception preset and the FNV-1a of its file (written only when not "none").
  std::string perception = "none";
  std::string perception_fnv1a64;
  // The rule set (runner::RuleSetName) of a trial that did not run (WriteUnrunTrialJson writes it
  // when not "vb"); a trial that ran takes it from its TrialResult.
  std::string rules = "vb";
  uint64_t seed = 0;
  std::string host;
  // Who drove a teleoperated trial (vb_view teleop --operator; written only when not empty).
  std::string operator_name;
};

// 64-bit FNV-1a (16 hex digits) of the task file and its height image (a missing image hashes as
// empty): the task's identity in records. Throws InputError if the task file cannot be read.
std::string TaskFnv1a64(const terrain::TaskSpec& task);

// Fills a Provenance for a trial of `task`, its hash by TaskFnv1a64 unless the caller already has
// it (`task_fnv1a64`: vb_batch's parent hashed the files it parsed the task from).
Provenance MakeProvenance(const terrain::TaskSpec& task, const runner::TrialSpec& spec,
                          const std::string& task_fnv1a64 = std::string());

// 64-bit FNV-1a of `bytes`, continuing from `hash` (start with kFnv1a64Offset).
constexpr uint64_t kFnv1a64Offset = 0xcbf29ce484222325ull;
uint64_t Fnv1a64(const std::string& bytes, uint64_t hash = kFnv1a64Offset);
// Records the parameter files a trial used: the vehicle file, and the soil set's name and file
// when the task needed soil (soil_file empty: none).
void RecordParameterFiles(const std::string& vehicle_file, const std::string& soil_name,
                          const std::string& soil_file, Provenance* p);
// FNV-1a of a file's bytes as 16 hex digits; InputError naming the file if it cannot be read.
std::string FileFnv1a64Hex(const std::string& path);

// Standard file names of a trial's outputs: <task>_p<K>_s<seed>_<vehicle>_<system>, with
// _perc-<preset> appended when the perception is not ground truth.
std::string TrialFileStem(const runner::TrialResult& result);

// Writers. Each throws IoError naming the path if the file cannot be written.
void WriteTrialJson(const runner::TrialResult& result, const std::string& path,
                    const Provenance& provenance);
// Columns: t_s, x_m, y_m, z_m, vx_mps, vy_mps, vz_mps, speed_mps, roll_deg, pitch_deg, yaw_deg,
// throttle, steering, braking, gear, surface_w<i> (class id, -1 airborne), sinkage_w<i>_m.
void WriteTrajectoryCsv(const runner::TrialResult& result, const std::string& path);
// A trial's two files, STEM_traj.csv then STEM.json, each atomically: a record's presence
// implies its complete trajectory (what resume and merge rely on, docs/reliability.md DEF-2).
// Every tool that records a trial (vb_run, vb_gym, vb_view teleop) writes through this.
void WriteTrialFiles(const runner::TrialResult& result, const std::string& stem_path,
                     const Provenance& provenance);
void WriteSummaryCsv(const std::vector<runner::TrialResult>& results, const std::string& path);

// JSON string literal of `s` (quotes included), escaping per RFC 8259; bytes that are not
// well-formed UTF-8 become \ufffd, so the output is always valid JSON.
std::string JsonString(const std::string& s);
// JSON number of `x` with "%.17g"; non-finite values (not representable in JSON) become null.
std::string JsonNumber(double x);

}  // namespace vb::io
