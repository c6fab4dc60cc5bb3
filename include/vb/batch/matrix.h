// The benchmark matrix of a batch: environments x pairs x vehicles x systems x seeds, expanded
// into an ordered list of trials, and deterministic shards of it. Plain data, no I/O: the tool
// resolves files and loads tasks (tools/io), this code only orders and slices.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vb::batch {

// What the matrix needs to know about one environment (from its loaded task file).
struct MatrixTask {
  std::string name;           // e.g. "env042"; must be unique within a matrix
  std::string path;           // task file as given
  int num_pairs = 0;          // pairs in the file
  double scale = 1.0;
  std::string elevation;      // labels (low/mid/high, rigid/deformable/mixed, sparse/medium/dense)
  std::string terrain;
  std::string density;
  std::string task_fnv1a64;   // hash of the task file + height image (provenance)
  std::string load_error;     // non-empty: the task could not be loaded (all its trials: error)
};

struct MatrixSpec {
  std::vector<MatrixTask> tasks;   // in the order the tool resolved them (sorted by path)
  std::vector<int> pairs;          // empty: every pair of each task
  std::vector<std::string> vehicles;
  std::vector<std::string> systems;
  std::vector<std::string> perceptions = {"none"};  // perception presets (docs/perception.md)
  std::vector<uint64_t> seeds;
};

// Benchmark tasks have 10 start/goal pairs; a task that cannot be loaded (so its pair count is
// unknown) gets this many error trials when the matrix asks for all pairs.
constexpr int kDefaultPairsPerTask = 10;

struct TrialKey {
  size_t matrix_index = 0;    // position in the full (unsharded) matrix
  size_t task_index = 0;      // into MatrixSpec::tasks
  int pair = 0;
  std::string vehicle;
  std::string system;
  std::string perception = "none";
  uint64_t seed = 0;
};

// All trials, ordered task, pair, vehicle, system, perception, seed (the first varies slowest).
// Throws InputError if two tasks share a name, a list is empty or has duplicates.
std::vector<TrialKey> ExpandMatrix(const MatrixSpec& spec);

// File stem of a trial's outputs, the same as vb_run's:
// <task>_p<K>_s<seed>_<vehicle>_<system>[_perc-<preset>] (suffix only for perception != none).
std::string TrialStem(const MatrixSpec& spec, const TrialKey& key);

struct Shard {
  int index = 0;   // 0 .. count-1
  int count = 1;
};
// Parses "i/N" (0 <= i < N); throws InputError naming --shard otherwise.
Shard ParseShard(const std::string& text);
// The trials of shard i/N: every N-th trial starting at i (round robin over the matrix order, so
// shards mix easy and hard environments and have sizes that differ by at most one).
std::vector<TrialKey> SelectShard(const std::vector<TrialKey>& trials, const Shard& shard);

// 16 hex digits identifying the matrix (trial stems and task hashes, in order): shards of the same
// matrix have the same fingerprint, which merge checks.
std::string MatrixFingerprint(const MatrixSpec& spec, const std::vector<TrialKey>& trials);

}  // namespace vb::batch
