// Trial records written by the runner's writer and by the batch (error/crashed) read back into
// index rows; batch.json round trip.
#include "io/batch_io.h"
#include "io/build_info.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "vb/engine/error.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

class BatchIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vb_batch_io_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(BatchIoTest, RunnerRecordReadsBack) {
  runner::TrialResult r;
  r.task_name = "env042";
  r.spec.pair_index = 4;
  r.spec.seed = 9;
  r.spec.vehicle = "hmmwv";
  r.spec.system = "pid";
  r.status = runner::TrialStatus::kSuccess;
  r.traversal_time_s = 31.25;
  r.sim_time_s = 31.25;
  r.final_goal_distance_m = 9.5;
  r.abs_roll_deg.mean = 2.5;
  r.abs_pitch_deg.mean = 3.75;
  r.wall_time_s = 1.5;
  Provenance p;
  p.vb_version = "0.1.0";
  p.git_commit = "abc";
  p.task_file = "tasks/env042.yaml";
  p.task_fnv1a64 = "0011223344556677";
  p.host = "h";
  const std::string path = (dir_ / "t.json").string();
  WriteTrialJson(r, path, p);
  const batch::TrialRow row = ReadTrialJson(path);
  EXPECT_EQ(row.task, "env042");
  EXPECT_EQ(row.pair, 4);
  EXPECT_EQ(row.seed, 9u);
  EXPECT_EQ(row.status, "success");
  EXPECT_EQ(row.traversal_time_s, 31.25);
  EXPECT_EQ(row.mean_abs_roll_deg, 2.5);
  EXPECT_EQ(row.mean_abs_pitch_deg, 3.75);
  EXPECT_EQ(row.git_commit, "abc");
  EXPECT_EQ(row.task_fnv1a64, "0011223344556677");
  r.status = runner::TrialStatus::kStuck;
  WriteTrialJson(r, path, p);
  EXPECT_TRUE(std::isnan(ReadTrialJson(path).traversal_time_s));
}

TEST_F(BatchIoTest, UnrunRecordReadsBackWithNullMetrics) {
  Provenance p;
  p.vehicle = "hmmwv";
  p.system = "pid";
  p.seed = 3;
  p.git_commit = "abc";
  const std::string path = (dir_ / "e.json").string();
  WriteUnrunTrialJson(path, "env061", 2, p, "error", "deformable \"terrain\"\nneeds soil");
  const batch::TrialRow row = ReadTrialJson(path);
  EXPECT_EQ(row.status, "error");
  EXPECT_EQ(row.pair, 2);
  EXPECT_EQ(row.seed, 3u);
  EXPECT_EQ(row.message, "deformable \"terrain\"\nneeds soil");
  EXPECT_TRUE(std::isnan(row.sim_time_s));
  EXPECT_TRUE(std::isnan(row.mean_abs_roll_deg));
}

// A record says "rules" only when not vb's (default records keep their format); read back, and
// an unrun (error/crashed) trial of a verti_bench batch says it too.
TEST_F(BatchIoTest, TheRuleSetIsRecordedOnlyWhenNotVb) {
  runner::TrialResult r;
  r.task_name = "env042";
  r.spec.vehicle = "hmmwv";
  r.spec.system = "pid";
  r.status = runner::TrialStatus::kStuck;
  Provenance p;
  const std::string path = (dir_ / "r.json").string();
  WriteTrialJson(r, path, p);
  std::ifstream in(path);
  const std::string vb_text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(vb_text.find("rules"), std::string::npos) << vb_text;
  EXPECT_EQ(ReadTrialJson(path).rules, "vb");
  r.rule_set = runner::RuleSet::kVertiBench;
  WriteTrialJson(r, path, p);
  EXPECT_EQ(ReadTrialJson(path).rules, "verti_bench");
  p.rules = "verti_bench";
  WriteUnrunTrialJson(path, "env042", 0, p, "crashed", "killed");
  EXPECT_EQ(ReadTrialJson(path).rules, "verti_bench");
  std::ofstream(path, std::ios::trunc)
      << "{\"task\": \"x\", \"pair\": 0, \"seed\": 0, \"vehicle\": \"v\", \"system\": \"s\", "
         "\"rules\": \"paper\"}\n";
  try {
    ReadTrialJson(path);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "rules");
    EXPECT_NE(std::string(e.what()).find("vb, verti_bench"), std::string::npos) << e.what();
  }
}

TEST_F(BatchIoTest, TruncatedOrForeignRecordIsInputErrorNamingFile) {
  const std::string path = (dir_ / "bad.json").string();
  std::ofstream(path) << "{\n  \"task\": \"env042\",\n  \"pair\": ";
  try {
    ReadTrialJson(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
  }
  std::ofstream(path, std::ios::trunc) << "{\"task\": \"x\"}\n";
  try {
    ReadTrialJson(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "pair");
  }
  EXPECT_THROW(ReadTrialJson((dir_ / "missing.json").string()), InputError);
}

TEST_F(BatchIoTest, BatchJsonRoundTrip) {
  BatchInfo b;
  b.matrix_fingerprint = "0123456789abcdef";
  b.matrix_trials = 1000;
  b.shard = "3/8";
  b.shard_trials = 125;
  b.settings = "time_limit_s=60.0 traj_every=1";
  b.vb_version = "0.1.0";
  b.git_commit = "abc";
  const std::string path = (dir_ / "batch.json").string();
  WriteBatchJson(b, path);
  const BatchInfo c = ReadBatchJson(path);
  EXPECT_EQ(c.matrix_fingerprint, b.matrix_fingerprint);
  EXPECT_EQ(c.matrix_trials, 1000u);
  EXPECT_EQ(c.shard, "3/8");
  EXPECT_EQ(c.shard_trials, 125u);
  EXPECT_EQ(c.settings, b.settings);
  EXPECT_EQ(c.git_commit, "abc");
}

}  // namespace
}  // namespace vb::io

namespace vb::io {
namespace {

// The commit comes from the build (cmake/vb_build_info.cmake): 12 hex digits, optionally
// "-dirty", or "unknown" outside a git checkout — and it is what provenance records.
TEST(BuildInfoTest, GitCommitIsAShortHashOrUnknownAndGoesIntoProvenance) {
  const std::string c = BuildGitCommit();
  if (c != "unknown") {
    ASSERT_GE(c.size(), 12u) << c;
    for (size_t i = 0; i < 12; ++i) {
      EXPECT_NE(std::string("0123456789abcdef").find(c[i]), std::string::npos) << c;
    }
    EXPECT_TRUE(c.size() == 12 || c.substr(12) == "-dirty") << c;
  }
  terrain::TaskSpec task;
  task.source_file = VB_SOURCE_DIR "/tasks/env042.yaml";
  EXPECT_EQ(MakeProvenance(task, runner::TrialSpec()).git_commit, c);
}

}  // namespace
}  // namespace vb::io
