// Shard merging: order, duplicates, conflicts.
#include "vb/batch/merge.h"

#include <gtest/gtest.h>

namespace vb::batch {
namespace {

TrialRow Row(size_t index, int pair, const std::string& status) {
  TrialRow r;
  r.matrix_index = index;
  r.task = "env042";
  r.pair = pair;
  r.vehicle = "hmmwv";
  r.system = "pid";
  r.status = status;
  r.git_commit = "c1";
  r.vb_version = "0.1.0";
  return r;
}

MergeInput Shard(const std::string& origin, std::vector<TrialRow> rows) {
  return MergeInput{origin, "c1", "0.1.0", std::move(rows)};
}

TEST(MergeTest, InterleavedShardsComeBackInMatrixOrder) {
  const MergeResult m = MergeIndexes({Shard("s1", {Row(1, 1, "stuck"), Row(3, 3, "success")}),
                                      Shard("s0", {Row(0, 0, "success"), Row(2, 2, "timeout")})});
  ASSERT_TRUE(m.conflicts.empty());
  ASSERT_EQ(m.rows.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(m.rows[i].row.matrix_index, i);
  EXPECT_EQ(m.rows[0].origin, "s0");
  EXPECT_EQ(m.rows[1].origin, "s1");
  EXPECT_EQ(m.duplicates, 0u);
}

TEST(MergeTest, IdenticalDuplicateIsKeptOnceEvenFromAnotherHost) {
  TrialRow again = Row(0, 0, "success");
  again.host = "node7";
  again.wall_time_s = 3.0;
  const MergeResult m =
      MergeIndexes({Shard("a", {Row(0, 0, "success")}), Shard("b", {again})});
  EXPECT_TRUE(m.conflicts.empty());
  EXPECT_EQ(m.rows.size(), 1u);
  EXPECT_EQ(m.duplicates, 1u);
  EXPECT_EQ(m.rows[0].origin, "a");
}

TEST(MergeTest, DifferentResultsOrTrialsAtOneIndexOrForeignBuildsConflict) {
  EXPECT_EQ(MergeIndexes({Shard("a", {Row(0, 0, "success")}), Shard("b", {Row(0, 0, "stuck")})})
                .conflicts.size(),
            1u);
  EXPECT_EQ(MergeIndexes({Shard("a", {Row(0, 0, "success")}), Shard("b", {Row(0, 5, "success")})})
                .conflicts.size(),
            1u);
  TrialRow foreign = Row(1, 1, "success");
  foreign.git_commit = "c2";
  const MergeResult m = MergeIndexes({Shard("a", {Row(0, 0, "success"), foreign})});
  ASSERT_EQ(m.conflicts.size(), 1u);
  EXPECT_NE(m.conflicts[0].find("c2"), std::string::npos);
}

}  // namespace
}  // namespace vb::batch
