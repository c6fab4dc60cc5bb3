// The fuzz targets' seed corpus replayed through the parsers in the normal (CI) build: every
// seed, and every seed cut at eight points, must be accepted or refused with an InputError,
// never anything else. The libFuzzer runs themselves (fuzz/run_fuzz.sh) are not part of CI; this
// keeps what they found fixed. Each seed of fuzz/corpus/<target>/ that came from a finding is
// named after the defect it reproduces.
#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/cli.h"
#include "targets.h"

namespace {

namespace fs = std::filesystem;

// The committed corpus of a target plus the repository files that seed it.
std::vector<fs::path> Seeds(const vb::fuzz::Target& t) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(VB_SOURCE_DIR) / "fuzz/corpus" / t.name;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file()) files.push_back(it->path());
  }
  for (const std::string& pattern : t.seed_globs) {
    glob_t g;
    if (::glob((std::string(VB_SOURCE_DIR) + "/" + pattern).c_str(), 0, nullptr, &g) == 0) {
      for (size_t i = 0; i < g.gl_pathc; ++i) files.emplace_back(g.gl_pathv[i]);
    }
    ::globfree(&g);
  }
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzReplayTest : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzReplayTest, SeedsAndTheirPrefixesAreAcceptedOrRefusedCleanly) {
  const vb::fuzz::Target* t = vb::fuzz::FindTarget(GetParam());
  ASSERT_NE(t, nullptr);
  const std::vector<fs::path> seeds = Seeds(*t);
  ASSERT_FALSE(seeds.empty()) << "no seeds for " << t->name;
  for (const fs::path& seed : seeds) {
    const std::string bytes = vb::testing::ReadFileBytes(seed);
    EXPECT_EQ(t->run(bytes), "") << seed;
    for (int k = 1; k < 8; ++k) {
      EXPECT_EQ(t->run(bytes.substr(0, bytes.size() * k / 8)), "") << seed << " cut at " << k << "/8";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllTargets, FuzzReplayTest,
                         ::testing::Values("task_yaml", "vehicle_yaml", "soil_yaml",
                                           "original_config", "labels_npy", "trial_json",
                                           "batch_json", "index_csv", "gym_frame", "gym_request",
                                           "http_request", "mesh_file"));

}  // namespace
