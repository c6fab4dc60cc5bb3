// Matrix expansion order, shard slicing and the index CSV round trip.
#include "vb/batch/matrix.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "vb/batch/index.h"
#include "vb/engine/error.h"

namespace vb::batch {
namespace {

MatrixSpec TwoTaskSpec() {
  MatrixSpec s;
  MatrixTask a;
  a.name = "envA";
  a.num_pairs = 3;
  MatrixTask b;
  b.name = "envB";
  b.num_pairs = 2;
  s.tasks = {a, b};
  s.vehicles = {"hmmwv", "art"};
  s.systems = {"pid"};
  s.seeds = {0, 7};
  return s;
}

TEST(MatrixTest, ExpandsEveryCombinationTaskMajorSeedMinor) {
  const MatrixSpec s = TwoTaskSpec();
  const std::vector<TrialKey> t = ExpandMatrix(s);
  ASSERT_EQ(t.size(), (3u + 2u) * 2u * 1u * 2u);
  EXPECT_EQ(TrialStem(s, t[0]), "envA_p0_s0_hmmwv_pid");
  EXPECT_EQ(TrialStem(s, t[1]), "envA_p0_s7_hmmwv_pid");
  EXPECT_EQ(TrialStem(s, t[2]), "envA_p0_s0_art_pid");
  EXPECT_EQ(TrialStem(s, t[4]), "envA_p1_s0_hmmwv_pid");
  EXPECT_EQ(TrialStem(s, t.back()), "envB_p1_s7_art_pid");
  for (size_t i = 0; i < t.size(); ++i) EXPECT_EQ(t[i].matrix_index, i);
}

TEST(MatrixTest, ExplicitPairsAndUnloadableTasks) {
  MatrixSpec s = TwoTaskSpec();
  s.tasks[1].load_error = "broken";
  s.tasks[1].num_pairs = 0;
  // All pairs: an unloadable task gets the benchmark's 10 pairs (each will be an error trial).
  EXPECT_EQ(ExpandMatrix(s).size(), (3u + static_cast<size_t>(kDefaultPairsPerTask)) * 4u);
  s.pairs = {1};
  EXPECT_EQ(ExpandMatrix(s).size(), 2u * 4u);
}

TEST(MatrixTest, RejectsDuplicateNamesAndEmptyOrDuplicateLists) {
  MatrixSpec s = TwoTaskSpec();
  s.tasks[1].name = "envA";
  EXPECT_THROW(ExpandMatrix(s), InputError);
  s = TwoTaskSpec();
  s.seeds = {1, 1};
  EXPECT_THROW(ExpandMatrix(s), InputError);
  s = TwoTaskSpec();
  s.systems.clear();
  EXPECT_THROW(ExpandMatrix(s), InputError);
  s = TwoTaskSpec();
  s.tasks.clear();
  EXPECT_THROW(ExpandMatrix(s), InputError);
}

TEST(ShardTest, ParsesZeroBasedIOverN) {
  const Shard sh = ParseShard("2/5");
  EXPECT_EQ(sh.index, 2);
  EXPECT_EQ(sh.count, 5);
  for (const char* bad : {"5/5", "-1/3", "1", "a/2", "1/0", "1/", "/2", "+1/2"}) {
    EXPECT_THROW(ParseShard(bad), InputError) << bad;
  }
}

TEST(ShardTest, ShardsPartitionTheMatrixWithBalancedSizes) {
  const MatrixSpec s = TwoTaskSpec();
  const std::vector<TrialKey> all = ExpandMatrix(s);
  for (int n : {1, 2, 3, 7, 25}) {
    std::set<size_t> seen;
    size_t min_size = all.size(), max_size = 0;
    for (int i = 0; i < n; ++i) {
      const std::vector<TrialKey> part = SelectShard(all, Shard{i, n});
      min_size = std::min(min_size, part.size());
      max_size = std::max(max_size, part.size());
      for (const TrialKey& k : part) EXPECT_TRUE(seen.insert(k.matrix_index).second);
    }
    EXPECT_EQ(seen.size(), all.size()) << n << " shards";
    EXPECT_LE(max_size - min_size, 1u);
  }
  // Round robin: shard 1/3 holds trials 1, 4, 7, ...
  const std::vector<TrialKey> part = SelectShard(all, Shard{1, 3});
  EXPECT_EQ(part[0].matrix_index, 1u);
  EXPECT_EQ(part[1].matrix_index, 4u);
}

TEST(MatrixTest, FingerprintChangesWithTaskHashAndTrials) {
  MatrixSpec s = TwoTaskSpec();
  const std::string f0 = MatrixFingerprint(s, ExpandMatrix(s));
  EXPECT_EQ(f0.size(), 16u);
  EXPECT_EQ(f0, MatrixFingerprint(s, ExpandMatrix(s)));
  s.tasks[0].task_fnv1a64 = "0123456789abcdef";
  EXPECT_NE(f0, MatrixFingerprint(s, ExpandMatrix(s)));
  s = TwoTaskSpec();
  s.seeds = {0};
  EXPECT_NE(f0, MatrixFingerprint(s, ExpandMatrix(s)));
}

TEST(IndexTest, CsvRoundTripKeepsEveryFieldIncludingQuotesAndNaN) {
  TrialRow r;
  r.matrix_index = 12;
  r.task = "env042";
  r.pair = 3;
  r.seed = 18446744073709551615ull;
  r.vehicle = "hmmwv";
  r.system = "pid";
  r.scale = 0.1;
  r.elevation = "high";
  r.terrain = "mixed";
  r.density = "dense";
  r.status = "error";
  r.traversal_time_s = std::nan("");
  r.sim_time_s = 1.0 / 3.0;
  r.final_goal_distance_m = 12.5;
  r.mean_abs_roll_deg = 2.25;
  r.mean_abs_pitch_deg = 1e-300;
  r.task_fnv1a64 = "00ff00ff00ff00ff";
  r.vb_version = "0.1.0";
  r.git_commit = "abc-dirty";
  r.host = "node,1";
  r.wall_time_s = 4.5;
  r.task_file = "/x/y.yaml";
  r.message = "bad \"value\", see\nline 2";
  TrialRow s = r;
  s.matrix_index = 13;
  s.pair = 4;   // another trial: an index lists each trial once
  s.status = "success";
  s.traversal_time_s = 30.125;
  const std::vector<TrialRow> back = ParseIndexCsv(IndexCsv({r, s}), "index.csv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(IndexCsv(back), IndexCsv({r, s}));
  EXPECT_EQ(back[0].message, r.message);
  EXPECT_EQ(back[0].host, r.host);
  EXPECT_EQ(back[0].seed, r.seed);
  EXPECT_TRUE(std::isnan(back[0].traversal_time_s));
  EXPECT_EQ(back[0].sim_time_s, r.sim_time_s);
  EXPECT_EQ(back[1].traversal_time_s, 30.125);
}

TrialRow NamedRow() {
  TrialRow r;
  r.task = "env000";
  r.vehicle = "hmmwv";
  r.system = "pid";
  return r;
}

TEST(IndexTest, MalformedIndexNamesFileAndLine) {
  const std::string good = IndexCsv({NamedRow()});
  try {
    ParseIndexCsv("task,pair\n", "dir/index.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "dir/index.csv");
    EXPECT_EQ(e.line(), 1);
  }
  std::string bad_status = good;
  // A row with an unknown status (the default TrialRow has an empty one).
  try {
    ParseIndexCsv(bad_status, "i.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.key(), "status");
  }
  TrialRow ok = NamedRow();
  ok.status = "timeout";
  std::string text = IndexCsv({ok});
  text.replace(text.find("\n") + 1, 1, "x");   // matrix_index "x"
  EXPECT_THROW(ParseIndexCsv(text, "i.csv"), InputError);
}

// DEF-9 and DEF-13 of the probe: an index is checked, not trusted, and says what is wrong.
TEST(IndexTest, CorruptIndexIsRefusedWithItsLineAndColumn) {
  TrialRow a = NamedRow();
  a.status = "success";
  a.traversal_time_s = 30.0;
  TrialRow b = a;
  b.pair = 1;
  const std::string text = IndexCsv({a, b});
  auto error = [](const std::string& csv) -> std::string {
    try {
      ParseIndexCsv(csv, "i.csv");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error(text), "");
  const std::string row = text.substr(text.find('\n') + 1, text.find('\n', text.find('\n') + 1) -
                                                             text.find('\n'));
  EXPECT_NE(error(text + row).find("i.csv:4: trial env000_p0_s0_hmmwv_pid is listed twice (first "
                                   "at line 2)"),
            std::string::npos)
      << error(text + row);
  std::string nan = text;
  nan.replace(nan.find(",30,"), 4, ",nan,");
  EXPECT_NE(error(nan).find("key 'traversal_time_s': 'nan' is not a finite number"),
            std::string::npos);
  std::string negative = text;
  negative.replace(negative.find(",30,"), 4, ",-30,");
  EXPECT_NE(error(negative).find("'-30' is negative"), std::string::npos);
  std::string no_host = text;
  no_host.replace(no_host.find(",host"), 5, "");
  EXPECT_NE(error(no_host).find("i.csv:1: key 'host': missing column"), std::string::npos)
      << error(no_host);
  std::string path = text;
  path.replace(path.find(",env000,"), 8, ",../x,");
  EXPECT_NE(error(path).find("key 'task': '../x': name may contain only"), std::string::npos);
}

TEST(IndexTest, StableFieldsIgnoreHostWallTimeAndTaskPath) {
  TrialRow a;
  a.status = "success";
  TrialRow b = a;
  b.host = "other";
  b.wall_time_s = 99.0;
  b.task_file = "/elsewhere/env.yaml";
  EXPECT_EQ(StableFields(a), StableFields(b));
  b.sim_time_s = 1.0;
  EXPECT_NE(StableFields(a), StableFields(b));
}

}  // namespace
}  // namespace vb::batch
