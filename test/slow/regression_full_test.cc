// Every trial of the committed benchmark (PID, HMMWV, seed 0) reproduces its committed digest.
// ~5 CPU-minutes: label slow. Run: ctest --test-dir build -L slow -R Regression
#include <filesystem>
#include <set>

#include "support/regression.h"

namespace vb {
namespace {

TEST(RegressionFullTest, EveryBenchmarkTrialMatchesItsCommittedDigest) {
  const auto rows = test::LoadDigests();
  ASSERT_EQ(rows.size(), 1000u);
  std::map<std::string, std::vector<int>> by_task;
  for (const auto& [key, row] : rows) by_task[key.first].push_back(key.second);
  for (const auto& [task, pairs] : by_task) test::ExpectMatchesDigests(task, pairs, rows);
}

}  // namespace
}  // namespace vb
