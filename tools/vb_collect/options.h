// vb_collect command line (docs/datasets.md): mode, flags, strict parsing (every error names
// the flag, exit 2).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/dataset/recorder.h"

namespace vb_collect {

extern const char* const kUsage;

struct Options {
  std::string mode;                 // explore | failures | demos | teleop
  std::string out_dir;
  std::string dataset_id;           // default vb/<mode>-v0
  // explore, demos
  long episodes = 10;
  uint64_t world_seed = 1000;       // first generator seed (the benchmark uses 0..99)
  int episodes_per_world = 10;      // <= 10: one per start/goal pair
  double max_episode_s = 300.0;
  // failures
  std::string from_dir;             // a vb_batch results directory
  double window_s = 10.0;
  double time_limit_s = 60.0;       // failures: when the results directory has no settings.txt;
                                    // demos: the trials' limit
  std::string tasks_dir;            // task files by name when a recorded path does not exist
  // demos
  std::string system = "oracle";
  // teleop
  std::vector<std::string> recordings;   // vb_view teleop records, or directories of them
  bool keep_failures = false;
  // common
  std::string vehicle = "hmmwv";
  std::string soil = "verti_bench";
  double sample_period_s = 0.1;
  std::string crops = "elevation,semantics";
  int crop_size = 64;
  double crop_resolution_m = 0.1;
  int jobs = 1;
  std::string shard = "0/1";
  bool rerun_stale = false;
  bool quiet = false;
  bool help = false;
};

// Why `id` cannot be a Minari dataset id, or "": 1 to kMaxDatasetIdParts parts separated by
// '/', each a file-name component (vb::FileNameComponentProblem).
constexpr size_t kMaxDatasetIdParts = 4;
std::string DatasetIdProblem(const std::string& id);

// Throws vb::InputError naming the flag.
Options ParseArgs(int argc, char** argv);

// The sample configuration of the options (crops, sample period in physics steps).
vb::dataset::SampleConfig MakeSampleConfig(const Options& o);

}  // namespace vb_collect
