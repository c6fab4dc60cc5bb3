// vb_batch command line: flags into an Options struct (strict: every error names the flag).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/engine/runner/episode.h"

namespace vb_batch {

extern const char* const kUsage;

struct Options {
  std::vector<std::string> envs;
  std::string pairs = "all";
  std::string vehicles = "hmmwv";
  std::string systems = "pid";
  std::string perception = "none";   // presets (docs/perception.md), comma-separated
  std::string seeds = "0";
  std::string scales;
  std::string soil = "verti_bench";   // data/soils/<soil>.yaml for deformable patches
  std::string out_dir;
  int jobs = 0;
  std::string shard = "0/1";
  double time_limit_s = vb::runner::EpisodeRules().time_limit_s;
  double target_speed_mps = vb::runner::kDefaultTargetSpeed_mps;
  vb::runner::RuleSet rules = vb::runner::RuleSet::kVb;
  int traj_every = 1;
  double trial_timeout_s = 0.0;
  bool rerun_stale = false;
  bool quiet = false;
  bool help = false;
  bool version = false;
};

// Throws vb::InputError naming the flag.
Options ParseArgs(int argc, char** argv);

std::vector<uint64_t> ParseIntList(const std::string& flag, const std::string& text);  // "0,3,5-9"

}  // namespace vb_batch
