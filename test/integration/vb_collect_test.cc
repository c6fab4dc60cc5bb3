// vb_collect end to end (docs/datasets.md): a tiny exploration dataset collected in full, again
// (byte-identical: determinism), killed with SIGKILL after its first episode and resumed (the
// same bytes), as two shards; failure windows of a small vb_batch run that end exactly at each
// trial's end with its failure label; expert demonstrations that keep only successes; bad input.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "io/batch_io.h"
#include "io/hdf5_dataset.h"
#include "support/cli.h"

namespace {

namespace fs = std::filesystem;
using Outcome = vb::testing::CommandOutcome;

const std::string kCollect = VB_BIN_DIR "/vb_collect";
const std::string kBatch = VB_BIN_DIR "/vb_batch";
// 6 episodes on 2 generated worlds, 6 s each at most, small crops.
const std::string kExplore = kCollect + " explore --episodes 6 --episodes-per-world 3 "
                             "--max-episode-s 6 --crop-size 8 --crop-res 0.5 --quiet";

Outcome Sh(const std::string& cmd) { return vb::testing::RunCommand(cmd); }
std::string Bytes(const fs::path& p) { return vb::testing::ReadFileBytes(p); }

size_t CountEpisodes(const fs::path& dir) {
  size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "episodes", ec)) {
    n += e.path().extension() == ".h5";
  }
  return n;
}

void ExpectSameDataset(const fs::path& a, const fs::path& b) {
  ASSERT_TRUE(fs::exists(a / "data" / "main_data.hdf5"));
  ASSERT_TRUE(fs::exists(b / "data" / "main_data.hdf5"));
  EXPECT_TRUE(Bytes(a / "data" / "main_data.hdf5") == Bytes(b / "data" / "main_data.hdf5"))
      << a << " vs " << b;
  EXPECT_EQ(Bytes(a / "data" / "metadata.json"), Bytes(b / "data" / "metadata.json"));
}

class VbCollectTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("vb_collect_test_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    full_ = Sh(kExplore + " --out " + (root_ / "full").string());
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static Outcome full_;
};
fs::path VbCollectTest::root_;
Outcome VbCollectTest::full_;

TEST_F(VbCollectTest, ExplorationIsDeterministic) {
  ASSERT_EQ(full_.exit_code, 0) << full_.output;
  EXPECT_NE(full_.output.find("6 episodes"), std::string::npos) << full_.output;
  const Outcome again = Sh(kExplore + " --out " + (root_ / "again").string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  ExpectSameDataset(root_ / "full", root_ / "again");
  for (int e = 0; e < 6; ++e) {
    const std::string name = "episodes/ep000000" + std::to_string(e) + ".h5";
    EXPECT_TRUE(Bytes(root_ / "full" / name) == Bytes(root_ / "again" / name)) << name;
  }
  // Both worlds are outside the benchmark's seeds, and every episode names its world.
  EXPECT_TRUE(fs::exists(root_ / "full" / "worlds" / "gen_low_rigid_sparse_s1000.yaml"));
  EXPECT_TRUE(fs::exists(root_ / "full" / "worlds" / "gen_mid_rigid_sparse_s1001.yaml"));
  const auto a =
      vb::io::ReadEpisodeAttributes((root_ / "full" / "episodes" / "ep0000004.h5").string());
  EXPECT_EQ(a.at("world_seed"), "1001");
  EXPECT_EQ(a.at("pair"), "1");
  EXPECT_EQ(a.at("seed"), "100101");
  EXPECT_EQ(a.at("id"), "4");
  // Run again on the finished directory: nothing to record, the same dataset.
  const Outcome rerun = Sh(kExplore + " --out " + (root_ / "full").string());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find("0 to record"), std::string::npos) << rerun.output;
  ExpectSameDataset(root_ / "full", root_ / "again");
}

TEST_F(VbCollectTest, KilledAndResumedGivesTheSameBytes) {
  const fs::path dir = root_ / "killed";
  const std::string cmd = kExplore + " --out " + dir.string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    ::execl("/bin/sh", "sh", "-c", ("exec " + cmd + " > /dev/null 2>&1").c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (CountEpisodes(dir) < 1 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::kill(-pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "collection finished before it could be killed";
  const size_t done = CountEpisodes(dir);
  ASSERT_GE(done, 1u);
  ASSERT_LT(done, 6u);
  EXPECT_FALSE(fs::exists(dir / "data" / "main_data.hdf5"));
  const Outcome resumed = Sh(cmd);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(std::to_string(6 - done) + " to record"), std::string::npos)
      << resumed.output;
  ExpectSameDataset(root_ / "full", dir);
}

TEST_F(VbCollectTest, ShardsAssembleToTheSameDataset) {
  const fs::path dir = root_ / "shards";
  const Outcome s0 = Sh(kExplore + " --shard 0/2 --out " + dir.string());
  ASSERT_EQ(s0.exit_code, 0) << s0.output;
  EXPECT_NE(s0.output.find("missing"), std::string::npos) << s0.output;
  EXPECT_FALSE(fs::exists(dir / "data"));
  const Outcome s1 = Sh(kExplore + " --shard 1/2 --out " + dir.string());
  ASSERT_EQ(s1.exit_code, 0) << s1.output;
  ExpectSameDataset(root_ / "full", dir);
}

TEST_F(VbCollectTest, BadInputIsRefusedWithExitCode2) {
  const Outcome mode = Sh(kCollect + " wander --out " + (root_ / "bad").string());
  EXPECT_EQ(mode.exit_code, 2) << mode.output;
  EXPECT_NE(mode.output.find("explore | failures | demos"), std::string::npos) << mode.output;
  const Outcome crops = Sh(kExplore + " --crops height --out " + (root_ / "bad").string());
  EXPECT_EQ(crops.exit_code, 2) << crops.output;
  EXPECT_NE(crops.output.find("--crops"), std::string::npos) << crops.output;
  const Outcome period = Sh(kExplore + " --sample-period 0.0123 --out " + (root_ / "bad").string());
  EXPECT_EQ(period.exit_code, 2) << period.output;
  const Outcome from = Sh(kCollect + " failures --out " + (root_ / "bad").string());
  EXPECT_EQ(from.exit_code, 2) << from.output;
  EXPECT_NE(from.output.find("--from"), std::string::npos) << from.output;
  const Outcome system = Sh(kCollect + " demos --system nope --out " + (root_ / "bad").string());
  EXPECT_EQ(system.exit_code, 2) << system.output;
  EXPECT_NE(system.output.find("--system"), std::string::npos) << system.output;
  const Outcome budget =
      Sh(kCollect + " demos --system oracle-h0 --out " + (root_ / "bad").string());
  EXPECT_EQ(budget.exit_code, 2) << budget.output;
  EXPECT_NE(budget.output.find("horizon"), std::string::npos) << budget.output;
  // Other settings into an existing collection: refused, nothing mixed.
  const Outcome other = Sh(kExplore + " --crop-size 4 --out " + (root_ / "full").string());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("settings"), std::string::npos) << other.output;
}

// env010/env042 pairs 0-1 in 32 s: two successes and two stuck trials (as vb_batch_test).
TEST_F(VbCollectTest, FailureWindowsEndAtTheTrialsEndWithTheirLabel) {
  const fs::path batch = root_ / "batch";
  const Outcome b = Sh(kBatch + " " VB_SOURCE_DIR "/tasks/env010.yaml " VB_SOURCE_DIR
                       "/tasks/env042.yaml --pairs 0,1 --time-limit 32 --traj-every 20 --quiet "
                       "--jobs 2 --out " + batch.string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const fs::path out = root_ / "failures";
  const Outcome f = Sh(kCollect + " failures --from " + batch.string() +
                       " --window-s 4 --crop-size 8 --crop-res 0.5 --quiet --out " + out.string());
  ASSERT_EQ(f.exit_code, 0) << f.output;
  std::map<std::string, vb::batch::TrialRow> failed;
  for (const auto& e : fs::directory_iterator(batch / "trials")) {
    if (e.path().extension() != ".json") continue;
    const vb::batch::TrialRow row = vb::io::ReadTrialJson(e.path().string());
    if (row.status == "rollover" || row.status == "stuck") failed[e.path().stem().string()] = row;
  }
  ASSERT_GE(failed.size(), 1u);
  ASSERT_EQ(CountEpisodes(out), failed.size());
  for (size_t i = 0; i < failed.size(); ++i) {
    const vb::dataset::EpisodeRecord r = vb::io::ReadEpisodeFile(
        (out / "episodes" / ("ep000000" + std::to_string(i) + ".h5")).string());
    const std::string trial = r.FindAttribute("trial")->text;
    ASSERT_TRUE(failed.count(trial)) << trial;
    const vb::batch::TrialRow& row = failed.at(trial);
    EXPECT_EQ(r.FindAttribute("failure_type")->text, row.status) << trial;
    EXPECT_EQ(r.FindAttribute("status")->text, row.status) << trial;
    const vb::dataset::Column& t = *r.Find("infos/time_s");
    ASSERT_EQ(t.Rows(), 41u) << trial;   // 4 s at 0.1 s, both ends included
    EXPECT_DOUBLE_EQ(t.f64.back(), row.sim_time_s) << trial;
    EXPECT_NEAR(t.f64.front(), row.sim_time_s - 4.0, 1e-9) << trial;
    EXPECT_EQ(r.steps, 40);
    const vb::dataset::Column& trunc = *r.Find("truncations");
    const vb::dataset::Column& term = *r.Find("terminations");
    EXPECT_EQ(trunc.i8.back(), row.status == "stuck" ? 1 : 0);
    EXPECT_EQ(term.i8.back(), row.status == "rollover" ? 1 : 0);
  }
  const auto meta = Bytes(out / "data" / "metadata.json");
  EXPECT_NE(meta.find("\"total_episodes\": " + std::to_string(failed.size())), std::string::npos)
      << meta;
}

// Demonstrations keep only successes: the PID on generated worlds 1000-1002 (low, mid, high) with
// a 30 s limit reaches some goals in time and not others; the oracle runs through the same path.
TEST_F(VbCollectTest, DemonstrationsContainOnlySuccesses) {
  const fs::path out = root_ / "demos";
  const Outcome d = Sh(kCollect + " demos --episodes 6 --episodes-per-world 2 --system pid "
                       "--time-limit 30 --crop-size 8 --crop-res 0.5 --quiet --out " +
                       out.string());
  ASSERT_EQ(d.exit_code, 0) << d.output;
  ASSERT_EQ(CountEpisodes(out), 6u);
  long kept = 0, filtered = 0, steps = 0;
  for (int e = 0; e < 6; ++e) {
    const vb::dataset::EpisodeRecord r = vb::io::ReadEpisodeFile(
        (out / "episodes" / ("ep000000" + std::to_string(e) + ".h5")).string());
    EXPECT_EQ(r.FindAttribute("mode")->text, "demos");
    EXPECT_EQ(r.FindAttribute("system")->text, "pid");
    if (r.FindAttribute("status")->text == "success") {
      ++kept;
      steps += r.steps;
      ASSERT_GT(r.steps, 0);
      EXPECT_EQ(r.Find("terminations")->i8.back(), 1);
      EXPECT_LE(r.Find("infos/goal_distance_m")->f64.back(), 10.0);
    } else {
      ++filtered;
      EXPECT_EQ(r.steps, 0) << "a failed demonstration must be empty";
      EXPECT_NE(r.FindAttribute("message")->text.find("filtered out"), std::string::npos);
    }
  }
  EXPECT_GE(kept, 1);
  EXPECT_GE(filtered, 1);
  const auto meta = Bytes(out / "data" / "metadata.json");
  EXPECT_NE(meta.find("\"total_episodes\": " + std::to_string(kept)), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"total_steps\": " + std::to_string(steps)), std::string::npos) << meta;

  // The oracle as the expert (a small budget, 4 s: a timeout, so filtered out) twice: same bytes.
  const std::string oracle = kCollect + " demos --episodes 1 --system oracle-h1-r0.5-n3 "
                             "--time-limit 4 --crop-size 8 --crop-res 0.5 --quiet --out ";
  const Outcome o1 = Sh(oracle + (root_ / "oracle1").string());
  ASSERT_EQ(o1.exit_code, 0) << o1.output;
  const Outcome o2 = Sh(oracle + (root_ / "oracle2").string());
  ASSERT_EQ(o2.exit_code, 0) << o2.output;
  const fs::path ep = fs::path("episodes") / "ep0000000.h5";
  EXPECT_TRUE(Bytes(root_ / "oracle1" / ep) == Bytes(root_ / "oracle2" / ep));
  const vb::dataset::EpisodeRecord r = vb::io::ReadEpisodeFile((root_ / "oracle1" / ep).string());
  EXPECT_EQ(r.FindAttribute("system")->text, "oracle-h1-r0.5-n3");
  EXPECT_EQ(r.FindAttribute("status")->text, "timeout");
  EXPECT_EQ(r.steps, 0);
}

}  // namespace
