// Re-runs trials of the committed benchmark and compares them with the regression digests in
// test/data/regression/pid_hmmwv_digests.csv (scripts/make_regression_digests.sh).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/result_digest.h"
#include "vb/engine/text_format.h"

namespace vb::test {

struct DigestRow {
  std::string status;
  std::string sim_time_s;
  std::string digest;
};

// (task, pair) -> committed row.
inline std::map<std::pair<std::string, int>, DigestRow> LoadDigests() {
  std::map<std::pair<std::string, int>, DigestRow> rows;
  std::ifstream in(VB_TEST_DATA_DIR "/regression/pid_hmmwv_digests.csv");
  EXPECT_TRUE(in.good()) << "missing regression digests";
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string task, pair, status, t, digest;
    std::getline(ss, task, ',');
    std::getline(ss, pair, ',');
    std::getline(ss, status, ',');
    std::getline(ss, t, ',');
    std::getline(ss, digest, ',');
    rows[{task, std::stoi(pair)}] = {status, t, digest};
  }
  return rows;
}

// Runs `pairs` of tasks/<task>.yaml (PID, HMMWV, seed 0, every step) and expects each trial to
// match its committed digest.
inline void ExpectMatchesDigests(const std::string& task_name, const std::vector<int>& pairs,
                                 const std::map<std::pair<std::string, int>, DigestRow>& rows) {
  const std::string data = VB_SOURCE_DIR "/data";
  static const vehicles::VehicleParams hmmwv = io::LoadVehicle(data + "/vehicles/hmmwv.yaml");
  const terrain::TaskSpec task = io::LoadTask(VB_SOURCE_DIR "/tasks/" + task_name + ".yaml");
  const std::optional<soil::SoilConfig> soil =
      io::LoadSoilIfNeeded(task, data + "/soils/verti_bench.yaml");
  for (int k : pairs) {
    const auto it = rows.find({task_name, k});
    ASSERT_NE(it, rows.end()) << task_name << " pair " << k << " has no committed digest";
    runner::TrialSpec spec;
    spec.pair_index = k;
    const runner::TrialResult r =
        runner::RunTrial(task, hmmwv, spec, runner::EpisodeRules(), soil ? &*soil : nullptr);
    EXPECT_EQ(std::string(runner::TrialStatusName(r.status)), it->second.status)
        << task_name << " pair " << k;
    EXPECT_EQ(FormatExact(r.sim_time_s), it->second.sim_time_s) << task_name << " pair " << k;
    EXPECT_EQ(runner::TrialDigest(r), it->second.digest)
        << task_name << " pair " << k << ": results moved (a refactor must not change a bit; an "
        << "intended physics change regenerates the digests: scripts/make_regression_digests.sh)";
  }
}

}  // namespace vb::test
