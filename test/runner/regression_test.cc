// A sample of the committed benchmark's trials must reproduce their committed digests bit for
// bit (the whole set: test/slow/regression_full_test.cc). The sample covers every outcome and
// terrain type: success, rollover, stuck, out of bounds on rigid, deformable and mixed worlds (no
// trial of the benchmark times out since the soil damping fix).
#include "support/regression.h"

namespace vb {
namespace {

TEST(RegressionTest, SampleOfTheBenchmarkMatchesTheCommittedDigests) {
  const auto rows = test::LoadDigests();
  ASSERT_EQ(rows.size(), 1000u);
  test::ExpectMatchesDigests("env009", {0}, rows);   // rigid, success
  test::ExpectMatchesDigests("env042", {1}, rows);   // rigid, the README's example
  test::ExpectMatchesDigests("env005", {3}, rows);   // rigid high, rollover
  test::ExpectMatchesDigests("env005", {5}, rows);   // rigid high, out of bounds
  test::ExpectMatchesDigests("env014", {9}, rows);   // rigid, stuck
  test::ExpectMatchesDigests("env060", {4}, rows);   // deformable, success
  test::ExpectMatchesDigests("env061", {0}, rows);   // deformable, stuck
  test::ExpectMatchesDigests("env062", {1}, rows);   // deformable, rollover
  test::ExpectMatchesDigests("env095", {6}, rows);   // mixed, stuck
}

}  // namespace
}  // namespace vb
