// vb_batch and vb_report end to end: a small matrix (2 rigid tasks x 2 pairs that end in success
// and stuck, plus a deformable task the runner cannot run yet -> error trials) run four ways:
// in full, killed with SIGKILL mid-batch and resumed, as 2 shards merged, and again after a
// stale-record rerun. All must give byte-identical reports (tables and plots).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "support/cli.h"

namespace {

namespace fs = std::filesystem;

const std::string kBatch = VB_BIN_DIR "/vb_batch";
const std::string kReport = VB_BIN_DIR "/vb_report";
const std::string kTasks = std::string(VB_SOURCE_DIR "/tasks/env010.yaml ") +
                           VB_SOURCE_DIR "/tasks/env042.yaml " VB_SOURCE_DIR "/tasks/env061.yaml";
// 32 s is enough for both successes (29-30 s) and both stuck trials (13-15 s) of these pairs.
const std::string kMatrix = kTasks + " --pairs 0,1 --time-limit 32 --traj-every 20 --quiet";

using Outcome = vb::testing::CommandOutcome;

Outcome Sh(const std::string& cmd) { return vb::testing::RunCommand(cmd); }

std::string ReadFile(const fs::path& path) { return vb::testing::ReadFileBytes(path); }

size_t CountJson(const fs::path& trials) {
  size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(trials, ec)) n += e.path().extension() == ".json";
  return n;
}

// Every file of two report directories, byte for byte.
void ExpectSameReport(const fs::path& a, const fs::path& b) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(a)) {
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  }
  ASSERT_GE(names.size(), 10u) << a;
  for (const std::string& n : names) {
    ASSERT_TRUE(fs::exists(b / n)) << b / n;
    EXPECT_TRUE(ReadFile(a / n) == ReadFile(b / n)) << n << " differs between " << a << " and "
                                                    << b;
  }
  size_t count_b = 0;
  for (const auto& e : fs::directory_iterator(b)) count_b += e.is_regular_file();
  EXPECT_EQ(count_b, names.size());
}

class VbBatchTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("vb_batch_test_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    full_ = Sh(kBatch + " " + kMatrix + " --jobs 2 --out " + (root_ / "full").string());
    report_ = Sh(kReport + " " + (root_ / "full").string());
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
  static Outcome full_, report_;
};
fs::path VbBatchTest::root_;
Outcome VbBatchTest::full_;
Outcome VbBatchTest::report_;

TEST_F(VbBatchTest, FullRunRecordsEveryTrialWithItsStatus) {
  ASSERT_EQ(full_.exit_code, 0) << full_.output;
  ASSERT_EQ(report_.exit_code, 0) << report_.output;
  const std::string index = ReadFile(root_ / "full/index.csv");
  EXPECT_EQ(CountJson(root_ / "full/trials"), 6u);
  // env061 is deformable: it runs on the soil solver (a runner status, not an error).
  EXPECT_NE(index.find("env061,0,0,hmmwv,pid,none,1,mid,deformable,dense,"), std::string::npos)
      << index;
  EXPECT_EQ(index.find(",error,"), std::string::npos) << index;
  // Table I agrees with the index: the outcomes themselves are physics, the counting is not.
  const std::vector<std::string> statuses = {"success", "rollover", "stuck", "timeout", "sim_error",
                                             "out_of_bounds"};
  std::vector<int> counts;
  int ran = 0;
  for (const std::string& st : statuses) {
    int n = 0;
    for (size_t at = index.find("," + st + ","); at != std::string::npos;
         at = index.find("," + st + ",", at + 1)) {
      ++n;
    }
    counts.push_back(n);
    ran += n;
  }
  ASSERT_EQ(ran, 6) << index;
  std::string row = "| pid/hmmwv | 6 | 6 |";
  for (int n : counts) {
    char buf[16];
    std::snprintf(buf, sizeof(buf), " %.1f |", 100.0 * n / ran);
    row += buf;
  }
  row += " 0 | 0 |";
  const std::string md = ReadFile(root_ / "full/report/report.md");
  EXPECT_NE(md.find(row), std::string::npos) << row << "\n" << md;
  EXPECT_TRUE(fs::exists(root_ / "full/report/fig6_terrain_success.png"));
  // Every trial that ran is linked to its 3-D replay (docs/viewer.md).
  EXPECT_NE(md.find("[trials.html](trials.html)"), std::string::npos);
  const std::string trials = ReadFile(root_ / "full/report/trials.html");
  EXPECT_NE(trials.find("<a href=\"/viewer/index.html?result=trials/env042_p1_s0_hmmwv_pid.json\">"),
            std::string::npos)
      << trials;
  int links = 0;
  for (size_t at = trials.find("?result=trials/"); at != std::string::npos;
       at = trials.find("?result=trials/", at + 1)) {
    ++links;
  }
  EXPECT_EQ(links, 6) << trials;

  // Top-down pictures on request; an unknown trial name is bad input.
  const std::string dir = (root_ / "full").string();
  const Outcome pic = Sh(kReport + " " + dir + " --out " + dir + "/pics --topdown " +
                         "env042_p1_s0_hmmwv_pid,env061_p0_s0_hmmwv_pid");
  ASSERT_EQ(pic.exit_code, 0) << pic.output;
  EXPECT_GT(fs::file_size(root_ / "full/pics/topdown/env042_p1_s0_hmmwv_pid.png"), 10000u);
  EXPECT_TRUE(fs::exists(root_ / "full/pics/topdown/env061_p0_s0_hmmwv_pid.png"));
  EXPECT_FALSE(fs::exists(root_ / "full/pics/topdown/env010_p0_s0_hmmwv_pid.png"));
  const Outcome bad = Sh(kReport + " " + dir + " --topdown env999_p0_s0_hmmwv_pid");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("env999_p0_s0_hmmwv_pid"), std::string::npos) << bad.output;
}

// The batch's trials run on the static world its parent built once per world (BuildWorld), the
// two pairs of a world in two workers; vb_run builds the world itself. The same trial must come
// out: the trajectory byte for byte, the record up to its wall-clock fields.
TEST_F(VbBatchTest, TrialsOnTheParentsWorldAreVbRunsTrials) {
  ASSERT_EQ(full_.exit_code, 0) << full_.output;
  auto record = [](const fs::path& json) {
    std::istringstream in(ReadFile(json));
    std::string kept, line;
    while (std::getline(in, line)) {
      if (line.find("\"wall_time_s\"") == std::string::npos &&
          line.find("\"real_time_factor\"") == std::string::npos) {
        kept += line + "\n";
      }
    }
    return kept;
  };
  for (const std::string trial : {"env061_p0", "env061_p1", "env042_p1"}) {
    const std::string task = trial.substr(0, 6);
    const std::string pair = trial.substr(8);
    const fs::path out = root_ / ("vb_run_" + trial);
    const Outcome run = Sh(VB_BIN_DIR "/vb_run " VB_SOURCE_DIR "/tasks/" + task +
                           ".yaml --pair " + pair + " --vehicle hmmwv --time-limit 32 " +
                           "--traj-every 20 --quiet --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::string stem = trial + "_s0_hmmwv_pid";
    EXPECT_TRUE(ReadFile(out / (stem + "_traj.csv")) ==
                ReadFile(root_ / "full/trials" / (stem + "_traj.csv")))
        << stem;
    EXPECT_EQ(record(out / (stem + ".json")), record(root_ / "full/trials" / (stem + ".json")));
  }
}

TEST_F(VbBatchTest, RerunSkipsFinishedTrials) {
  const Outcome o = Sh(kBatch + " " + kMatrix + " --out " + (root_ / "full").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("6 already done, 0 to run"), std::string::npos) << o.output;
}

TEST_F(VbBatchTest, KilledMidBatchAndResumedGivesTheSameReport) {
  const fs::path dir = root_ / "killed";
  const std::string cmd = kBatch + " " + kMatrix + " --jobs 1 --out " + dir.string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    ::execl("/bin/sh", "sh", "-c", ("exec " + cmd + " > /dev/null 2>&1").c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  // Wait for the first finished trial, then kill the batch and its workers at once.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (CountJson(dir / "trials") < 1 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(-pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "batch finished before it could be killed";
  const size_t done = CountJson(dir / "trials");
  ASSERT_GE(done, 1u);
  ASSERT_LT(done, 6u);
  EXPECT_FALSE(fs::exists(dir / "index.csv"));

  const Outcome resumed = Sh(cmd);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(std::to_string(done) + " already done"), std::string::npos)
      << resumed.output;
  for (const auto& e : fs::directory_iterator(dir / "trials")) {
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  }
  ASSERT_EQ(Sh(kReport + " " + dir.string()).exit_code, 0);
  ExpectSameReport(root_ / "full/report", dir / "report");
}

TEST_F(VbBatchTest, SigtermStopsCleanlyWritesTheIndexAndResumes) {
  const fs::path dir = root_ / "sigterm";
  const std::string cmd = kBatch + " " + kMatrix + " --jobs 1 --out " + dir.string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", ("exec " + cmd + " > /dev/null 2>&1").c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (CountJson(dir / "trials") < 1 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGTERM);   // the batch only, as Slurm's time limit does first
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  const std::string index = ReadFile(dir / "index.csv");
  const size_t rows = static_cast<size_t>(std::count(index.begin(), index.end(), '\n')) - 1;
  EXPECT_GE(rows, 1u);
  EXPECT_LT(rows, 6u);
  const Outcome resumed = Sh(cmd);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  ASSERT_EQ(Sh(kReport + " " + dir.string()).exit_code, 0);
  ExpectSameReport(root_ / "full/report", dir / "report");
}

TEST_F(VbBatchTest, ShardedAndMergedGivesTheSameReport) {
  for (int i = 0; i < 2; ++i) {
    const Outcome o = Sh(kBatch + " " + kMatrix + " --shard " + std::to_string(i) +
                         "/2 --out " + (root_ / ("shard" + std::to_string(i))).string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("shard " + std::to_string(i) + "/2: 3 trials"), std::string::npos)
        << o.output;
  }
  const Outcome m = Sh(kReport + " merge " + (root_ / "merged").string() + " " +
                       (root_ / "shard0").string() + " " + (root_ / "shard1").string());
  ASSERT_EQ(m.exit_code, 0) << m.output;
  EXPECT_NE(m.output.find("6 of 6 trials"), std::string::npos) << m.output;
  ASSERT_EQ(Sh(kReport + " " + (root_ / "merged").string()).exit_code, 0);
  ExpectSameReport(root_ / "full/report", root_ / "merged/report");

  // The same shard twice: identical duplicates are kept once; altered ones are a conflict.
  const Outcome dup = Sh(kReport + " merge " + (root_ / "dup").string() + " " +
                         (root_ / "shard0").string() + " " + (root_ / "shard0").string());
  EXPECT_EQ(dup.exit_code, 0) << dup.output;
  EXPECT_NE(dup.output.find("3 duplicate(s)"), std::string::npos) << dup.output;
  fs::copy(root_ / "shard0", root_ / "shard0x", fs::copy_options::recursive);
  std::string index = ReadFile(root_ / "shard0x/index.csv");
  // Change one result field (the status of the first trial) in the copy.
  for (const char* s : {",success,", ",stuck,", ",error,"}) {
    const size_t p = index.find(s);
    if (p != std::string::npos) {
      index.replace(p, std::string(s).size(), ",timeout,");
      break;
    }
  }
  std::ofstream(root_ / "shard0x/index.csv", std::ios::trunc) << index;
  const Outcome conflict = Sh(kReport + " merge " + (root_ / "conflict").string() + " " +
                              (root_ / "shard0").string() + " " + (root_ / "shard0x").string());
  // The index no longer matches the record it was built from: refused before anything is
  // compared or copied (DEF-10: the records are the truth).
  EXPECT_EQ(conflict.exit_code, 2) << conflict.output;
  EXPECT_NE(conflict.output.find("disagrees with its row"), std::string::npos)
      << conflict.output;
  EXPECT_FALSE(fs::exists(root_ / "conflict/index.csv"));
  // A shard of another matrix (only the deformable task: error trials, instant).
  ASSERT_EQ(Sh(kBatch + " " VB_SOURCE_DIR "/tasks/env061.yaml --pairs 0,1 --time-limit 32 "
               "--traj-every 20 --out " + (root_ / "othermatrix").string()).exit_code, 0);
  const Outcome other = Sh(kReport + " merge " + (root_ / "other").string() + " " +
                           (root_ / "shard0").string() + " " + (root_ / "othermatrix").string());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("matrix_fingerprint"), std::string::npos) << other.output;
}

TEST_F(VbBatchTest, ChangedTaskIsReportedNotMixed) {
  const fs::path dir = root_ / "stale";
  fs::copy(root_ / "full", dir, fs::copy_options::recursive);
  const fs::path rec = dir / "trials/env010_p0_s0_hmmwv_pid.json";
  std::string json = ReadFile(rec);
  const size_t p = json.find("\"task_fnv1a64\": \"");
  ASSERT_NE(p, std::string::npos);
  json.replace(p + 17, 16, "0000000000000000");
  std::ofstream(rec, std::ios::trunc) << json;
  const std::string cmd = kBatch + " " + kMatrix + " --out " + dir.string();
  const Outcome refused = Sh(cmd);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("env010_p0_s0_hmmwv_pid: task changed"), std::string::npos)
      << refused.output;
  const Outcome rerun = Sh(cmd + " --rerun-stale");
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find("5 already done, 1 to run"), std::string::npos) << rerun.output;
  ASSERT_EQ(Sh(kReport + " " + dir.string()).exit_code, 0);
  ExpectSameReport(root_ / "full/report", dir / "report");
  // Different result-changing settings in the same directory are refused.
  const Outcome other = Sh(kBatch + " " + kTasks + " --pairs 0,1 --time-limit 5 --out " +
                           dir.string());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  // ... and so is another target speed (the default 4 m/s is the same as not giving it).
  const Outcome faster = Sh(cmd + " --speed 5");
  EXPECT_EQ(faster.exit_code, 2) << faster.output;
  EXPECT_NE(faster.output.find("settings"), std::string::npos) << faster.output;
  const Outcome same = Sh(cmd + " --speed 4");
  EXPECT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("6 already done, 0 to run"), std::string::npos) << same.output;
  // ... and so are the original's rules (vb's, the default, are the same as not giving them).
  const Outcome original = Sh(cmd + " --rules verti_bench");
  EXPECT_EQ(original.exit_code, 2) << original.output;
  EXPECT_NE(original.output.find("rules=verti_bench"), std::string::npos) << original.output;
  const Outcome vb_rules = Sh(cmd + " --rules vb");
  EXPECT_EQ(vb_rules.exit_code, 0) << vb_rules.output;
  EXPECT_NE(vb_rules.output.find("6 already done, 0 to run"), std::string::npos)
      << vb_rules.output;
}

// A vehicle or soil file edited after a batch (same names, other content) is a settings change:
// resuming into the old directory is refused rather than mixing parameter sets.
TEST_F(VbBatchTest, EditedParameterFileIsRefused) {
  const fs::path data = root_ / "data";
  fs::copy(VB_SOURCE_DIR "/data", data, fs::copy_options::recursive);
  const fs::path dir = root_ / "edited";
  const std::string cmd = "VB_DATA_DIR=" + data.string() + " " + kBatch + " " VB_SOURCE_DIR
                          "/tasks/env042.yaml --pairs 1 --time-limit 2 --quiet --out " +
                          dir.string();
  ASSERT_EQ(Sh(cmd).exit_code, 0);
  EXPECT_EQ(Sh(cmd).exit_code, 0);  // unchanged: resumes (nothing to do)
  std::ofstream(data / "soils/verti_bench.yaml", std::ios::app) << "# edited\n";
  const Outcome soil = Sh(cmd);
  EXPECT_EQ(soil.exit_code, 2) << soil.output;
  EXPECT_NE(soil.output.find("settings"), std::string::npos) << soil.output;
  const std::string json = ReadFile(dir / "trials/env042_p1_s0_hmmwv_pid.json");
  EXPECT_NE(json.find("\"vehicle_fnv1a64\": \""), std::string::npos) << json;
  EXPECT_NE(json.find("\"soil\": \"\""), std::string::npos) << json;  // rigid world: no soil
}

TEST_F(VbBatchTest, KilledWorkerBecomesCrashedTrialAndIsRetried) {
  const fs::path dir = root_ / "crash";
  const std::string cmd = kBatch + " " VB_SOURCE_DIR "/tasks/env042.yaml --pairs 0 "
                          "--time-limit 32 --traj-every 20 --out " + dir.string();
  const Outcome o = Sh(cmd + " --trial-timeout 0.01");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string json = ReadFile(dir / "trials/env042_p0_s0_hmmwv_pid.json");
  EXPECT_NE(json.find("\"status\": \"crashed\""), std::string::npos) << json;
  EXPECT_NE(json.find("wall-clock limit of 0.01 s exceeded"), std::string::npos) << json;
  const Outcome retry = Sh(cmd);
  ASSERT_EQ(retry.exit_code, 0) << retry.output;
  EXPECT_NE(retry.output.find("0 already done, 1 to run"), std::string::npos) << retry.output;
  // the retried trial ran to its end (env042 pair 0 reaches the goal in 32 s among boulders)
  EXPECT_NE(ReadFile(dir / "trials/env042_p0_s0_hmmwv_pid.json").find("\"status\": \"success\""),
            std::string::npos);
}

TEST(VbBatchCliTest, UnloadableTaskBecomesErrorTrialsNotABatchFailure) {
  const fs::path dir = fs::temp_directory_path() / ("vb_batch_bad_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "tasks");
  std::ofstream(dir / "tasks/broken.yaml") << "format: vb-task\nversion: 99\n";
  const Outcome o = Sh(kBatch + " " + (dir / "tasks").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  const std::string index = ReadFile(dir / "out/index.csv");
  // All pairs of a task that does not load: the benchmark's 10, each an error with the reason.
  size_t errors = 0;
  for (size_t p = index.find(",error,"); p != std::string::npos; p = index.find(",error,", p + 1)) {
    ++errors;
  }
  EXPECT_EQ(errors, 10u) << index;
  EXPECT_NE(index.find("broken.yaml"), std::string::npos) << index;
  EXPECT_NE(index.find("version"), std::string::npos) << index;
  EXPECT_EQ(Sh(kReport + " " + (dir / "out").string()).exit_code, 0);
  fs::remove_all(dir);
}

// --rules verti_bench: the settings, every record, the index and the report's labels say so.
TEST(VbBatchCliTest, VertiBenchRulesAreNamedInEveryOutput) {
  const fs::path dir = fs::temp_directory_path() / ("vb_batch_rules_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Outcome o = Sh(kBatch + " " VB_SOURCE_DIR "/tasks/env042.yaml --pairs 0 --time-limit 5 "
                       "--traj-every 100 --quiet --rules verti_bench --out " + dir.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(ReadFile(dir / "settings.txt").find(" rules=verti_bench"), std::string::npos);
  EXPECT_NE(ReadFile(dir / "trials/env042_p0_s0_hmmwv_pid.json").find("\"rules\": \"verti_bench\""),
            std::string::npos);
  const std::string index = ReadFile(dir / "index.csv");
  EXPECT_NE(index.find(",message,rules\n"), std::string::npos) << index;
  EXPECT_NE(index.find(",verti_bench\n"), std::string::npos) << index;
  ASSERT_EQ(Sh(kReport + " " + dir.string()).exit_code, 0);
  EXPECT_NE(ReadFile(dir / "report/report.md").find("| pid/hmmwv/rules:verti_bench |"),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(VbBatchCliTest, BadInputExitsTwoNamingTheCulprit) {
  const std::string task = VB_SOURCE_DIR "/tasks/env042.yaml";
  struct Case {
    std::string args, expect;
  } cases[] = {
      {task + " --out /tmp/x --vehicles nosuch", "--vehicles"},
      {task + " --out /tmp/x --systems nosuch", "--systems"},
      {task + " --out /tmp/x --systems pid,oracle-r9", "replanning period longer than the horizon"},
      {task + " --out /tmp/x --shard 2/2", "--shard"},
      {task + " --out /tmp/x --seeds 3-1", "--seeds"},
      {task + " --out /tmp/x --jobs 0", "--jobs"},
      {"/nonexistent/task.yaml --out /tmp/x", "/nonexistent/task.yaml"},
      {"'/nonexistent/*.yaml' --out /tmp/x", "glob matches no files"},
      {task, "--out"},
      {task + " --out /tmp/x --scale 0.1", "key '--scale': no task has world scale 0.1"},
      {task + " --out /tmp/x --rules paper", "key '--rules': unknown rule set 'paper'; valid: vb, "
                                             "verti_bench"},
      {task + " --out /tmp/x --rules", "--rules"},
  };
  for (const Case& c : cases) {
    const Outcome o = Sh(kBatch + " " + c.args);
    EXPECT_EQ(o.exit_code, 2) << c.args << "\n" << o.output;
    EXPECT_NE(o.output.find(c.expect), std::string::npos) << c.args << "\n" << o.output;
  }
  const Outcome r = Sh(kReport + " /nonexistent_dir");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/nonexistent_dir/index.csv"), std::string::npos) << r.output;
  EXPECT_EQ(Sh(kBatch + " --help").exit_code, 0);
  EXPECT_EQ(Sh(kReport + " --help").exit_code, 0);
}

}  // namespace

namespace {

// Provenance that travels: a batch names its task by the task set path ("tasks/env042.yaml")
// and its FNV-1a, not by this machine's absolute path; vb_report finds the task again in the
// task set given with --tasks, and never takes another version of it (same name, other bytes).
TEST(VbBatchProvenanceTest, TaskSetPathAndReportTasksFlag) {
  const fs::path root = fs::temp_directory_path() / ("vb_prov_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "set/tasks");
  fs::create_directories(root / "set/data/worlds");
  fs::copy_file(VB_SOURCE_DIR "/data/worlds/env042.png", root / "set/data/worlds/env042.png");
  fs::copy_file(VB_SOURCE_DIR "/tasks/env042.yaml", root / "set/tasks/env042.yaml");
  std::ofstream(root / "set/tasks/env042.yaml", std::ios::app) << "# a private version\n";
  const fs::path out = root / "out";
  const Outcome batch = Sh(kBatch + " " + (root / "set/tasks/env042.yaml").string() +
                           " --pairs 0 --time-limit 2 --quiet --out " + out.string());
  ASSERT_EQ(batch.exit_code, 0) << batch.output;
  const std::string index = ReadFile(out / "index.csv");
  EXPECT_NE(index.find(",tasks/env042.yaml,"), std::string::npos) << index;
  EXPECT_EQ(index.find(root.string()), std::string::npos) << index;
  EXPECT_NE(ReadFile(out / "trials/env042_p0_s0_hmmwv_pid.json")
                .find("\"task_file\": \"tasks/env042.yaml\""),
            std::string::npos);
  fs::rename(root / "set", root / "moved");   // the task set elsewhere now
  const fs::path png = out / "report/topdown/env042_p0_s0_hmmwv_pid.png";
  // Without --tasks: vb's shipped env042 has other bytes, so no picture (and a message).
  const Outcome shipped = Sh(kReport + " " + out.string() + " --topdown all");
  EXPECT_EQ(shipped.exit_code, 0) << shipped.output;
  EXPECT_FALSE(fs::exists(png));
  EXPECT_NE(shipped.output.find("another version of the task"), std::string::npos)
      << shipped.output;
  EXPECT_NE(shipped.output.find("--tasks DIR"), std::string::npos) << shipped.output;
  const Outcome given = Sh(kReport + " " + out.string() + " --topdown all --tasks " +
                           (root / "moved/tasks").string());
  EXPECT_EQ(given.exit_code, 0) << given.output;
  EXPECT_TRUE(fs::exists(png)) << given.output;
  fs::remove_all(root);
}

}  // namespace
