// Prints the regression digest (runner/result_digest.h) of PID + HMMWV trials, seed 0, every
// physics step in the trajectory, as CSV rows "task,pair,status,sim_time_s,digest". Used by
// scripts/make_regression_digests.sh to regenerate test/data/regression/pid_hmmwv_digests.csv
// after an intended change of results; the tests compare against that file.
//
// usage: vb_make_regression_digests TASK_DIR [--shard I/N] [--contacts]
//   --contacts appends the trial's obstacle contact events as a sixth column (for the benchmark
//   tables in docs/validation.md; the committed file has five columns)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/result_digest.h"
#include "vb/engine/text_format.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s TASK_DIR [--shard I/N] [--contacts]\n", argv[0]);
    return 2;
  }
  int shard = 0, shards = 1;
  bool contacts = false;
  if (argc >= 3 && std::string(argv[argc - 1]) == "--contacts") {
    contacts = true;
    --argc;
  }
  if (argc == 4 && std::string(argv[2]) == "--shard" &&
      std::sscanf(argv[3], "%d/%d", &shard, &shards) == 2 && shards > 0 && shard >= 0 &&
      shard < shards) {
  } else if (argc != 2) {
    std::fprintf(stderr, "usage: %s TASK_DIR [--shard I/N] [--contacts]\n", argv[0]);
    return 2;
  }
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(argv[1]))
    if (e.path().extension() == ".yaml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  const std::string data = VB_SOURCE_DIR "/data";
  const vb::vehicles::VehicleParams hmmwv = vb::io::LoadVehicle(data + "/vehicles/hmmwv.yaml");
  vb::runner::EpisodeRules rules;
  long index = 0;
  for (const std::string& f : files) {
    const vb::terrain::TaskSpec task = vb::io::LoadTask(f);
    const std::optional<vb::soil::SoilConfig> soil =
        vb::io::LoadSoilIfNeeded(task, data + "/soils/verti_bench.yaml");
    for (int k = 0; k < static_cast<int>(task.pairs.size()); ++k, ++index) {
      if (index % shards != shard) continue;
      vb::runner::TrialSpec spec;
      spec.pair_index = k;
      const vb::runner::TrialResult r =
          vb::runner::RunTrial(task, hmmwv, spec, rules, soil ? &*soil : nullptr);
      std::printf("%s,%d,%s,%s,%s", task.name.c_str(), k,
                  std::string(vb::runner::TrialStatusName(r.status)).c_str(),
                  vb::FormatExact(r.sim_time_s).c_str(), vb::runner::TrialDigest(r).c_str());
      if (contacts) std::printf(",%d", r.obstacle_contacts);
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  return 0;
}
