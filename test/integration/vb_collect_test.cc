// vb_collect end to end (docs/datasets.md): a tiny exploration dataset collected in full, again
// (byte-identical: determinism), killed with SIGKILL after its first episode and resumed (the
// same bytes), as two shards; failure windows of a small vb_batch run that end exactly at each
// trial's end with its failure label; expert demonstrations that keep only successes; teleoperated
// drives (the committed vb_view recordings in test/data/teleop) replayed bit for bit; bad input.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

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

// The committed recordings (test/data/teleop/README.md): drive_001 reaches the goal, drive_002
// is stopped by its operator after 2 s.
const fs::path kTeleopData = fs::path(VB_TEST_DATA_DIR) / "teleop";
const std::string kTeleopStem = "teleop_demo_p0_s0_hmmwv_teleop";

// The rows of a trajectory CSV as numbers (header skipped).
std::vector<std::vector<double>> CsvRows(const fs::path& csv) {
  std::istringstream in(Bytes(csv));
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ',')) v.push_back(std::strtod(f.c_str(), nullptr));
    rows.push_back(v);
  }
  return rows;
}

// Replaces the first occurrence of `from` in a file by `to`.
void Edit(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = Bytes(file);
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << file;
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary) << text;
}

TEST_F(VbCollectTest, TeleopRecordingsBecomeDemonstrations) {
  const std::string cmd = kCollect + " teleop " + kTeleopData.string() +
                          " --crop-size 8 --crop-res 0.5 --quiet ";
  const Outcome t = Sh(cmd + "--out " + (root_ / "teleop").string());
  ASSERT_EQ(t.exit_code, 0) << t.output;
  ASSERT_EQ(CountEpisodes(root_ / "teleop"), 2u);
  const vb::dataset::EpisodeRecord kept =
      vb::io::ReadEpisodeFile((root_ / "teleop" / "episodes" / "ep0000000.h5").string());
  EXPECT_EQ(kept.FindAttribute("status")->text, "success");
  EXPECT_EQ(kept.FindAttribute("mode")->text, "teleop");
  EXPECT_EQ(kept.FindAttribute("source")->text, "teleop");
  EXPECT_EQ(kept.FindAttribute("system")->text, "teleop");
  EXPECT_EQ(kept.FindAttribute("operator")->text, "scripted");
  EXPECT_EQ(kept.FindAttribute("failure_type")->text, "");
  EXPECT_EQ(kept.FindAttribute("action_space_kind")->text, "direct");
  EXPECT_NE(kept.FindAttribute("recording")->text.find("drive_001/" + kTeleopStem + ".json"),
            std::string::npos);
  EXPECT_EQ(kept.FindAttribute("task")->text, "teleop_demo");
  EXPECT_EQ(kept.FindAttribute("task_file")->text, "teleop/teleop_demo.yaml");
  EXPECT_EQ(kept.Find("terminations")->i8.back(), 1);
  EXPECT_LE(kept.Find("infos/goal_distance_m")->f64.back(), 10.0);

  // The episode is the recorded drive: every sample's position and command are the recording's
  // values at that step, to the bit (a sample every 20 physics steps and at the end).
  const std::vector<std::vector<double>> rec =
      CsvRows(kTeleopData / "drive_001" / (kTeleopStem + "_traj.csv"));
  const vb::dataset::Column& pos = *kept.Find("infos/position_m");
  const vb::dataset::Column& cmd_col = *kept.Find("infos/command");
  const size_t samples = pos.Rows();
  ASSERT_EQ(samples, (rec.size() - 1 + 19) / 20 + 1);
  for (size_t i = 0; i < samples; ++i) {
    const size_t k = std::min(i * 20, rec.size() - 1);
    SCOPED_TRACE(k);
    EXPECT_EQ(pos.f64[3 * i + 0], rec[k][1]);
    EXPECT_EQ(pos.f64[3 * i + 1], rec[k][2]);
    EXPECT_EQ(pos.f64[3 * i + 2], rec[k][3]);
    if (k > 0) {
      EXPECT_EQ(cmd_col.f64[3 * i + 0], rec[k][11]);   // throttle applied in step k
    }
  }
  // The driver held W from the start: a real drive forward, not a standstill.
  EXPECT_GT(pos.f64[3 * (samples - 1)] - pos.f64[0], 2.0);

  // The stopped drive is not a success: filtered out, an empty episode that says why.
  const vb::dataset::EpisodeRecord filtered =
      vb::io::ReadEpisodeFile((root_ / "teleop" / "episodes" / "ep0000001.h5").string());
  EXPECT_EQ(filtered.steps, 0);
  EXPECT_EQ(filtered.FindAttribute("status")->text, "timeout");
  EXPECT_NE(filtered.FindAttribute("message")->text.find("filtered out"), std::string::npos);
  EXPECT_NE(filtered.FindAttribute("message")->text.find("stopped by the operator"),
            std::string::npos);
  const auto meta = Bytes(root_ / "teleop" / "data" / "metadata.json");
  EXPECT_NE(meta.find("\"total_episodes\": 1"), std::string::npos) << meta;

  // --keep-failures keeps it, labelled; the same command twice gives the same bytes.
  const Outcome k1 = Sh(cmd + "--keep-failures --out " + (root_ / "teleop_all").string());
  ASSERT_EQ(k1.exit_code, 0) << k1.output;
  const Outcome k2 = Sh(cmd + "--keep-failures --out " + (root_ / "teleop_all2").string());
  ASSERT_EQ(k2.exit_code, 0) << k2.output;
  ExpectSameDataset(root_ / "teleop_all", root_ / "teleop_all2");
  const vb::dataset::EpisodeRecord stopped =
      vb::io::ReadEpisodeFile((root_ / "teleop_all" / "episodes" / "ep0000001.h5").string());
  EXPECT_EQ(stopped.FindAttribute("failure_type")->text, "timeout");
  EXPECT_EQ(vb::io::ReadEpisodeAttributes(
                (root_ / "teleop_all" / "episodes" / "ep0000001.h5").string())
                .at("stopped_by_operator"),
            "1");
  const std::vector<std::vector<double>> rec2 =
      CsvRows(kTeleopData / "drive_002" / (kTeleopStem + "_traj.csv"));
  EXPECT_EQ(stopped.steps, static_cast<long>((rec2.size() - 1 + 19) / 20));   // about 2 s
  EXPECT_EQ(stopped.Find("infos/time_s")->f64.back(), rec2.back()[0]);
  EXPECT_NEAR(rec2.back()[0], 2.0, 0.1);
  EXPECT_EQ(stopped.Find("truncations")->i8.back(), 1);
  EXPECT_EQ(stopped.Find("terminations")->i8.back(), 0);
  const auto meta_all = Bytes(root_ / "teleop_all" / "data" / "metadata.json");
  EXPECT_NE(meta_all.find("\"total_episodes\": 2"), std::string::npos) << meta_all;
}

TEST_F(VbCollectTest, BadTeleopRecordingsAreRefusedNamingTheFile) {
  // A copy of the recordings to spoil (the task is found beside them, as in test/data).
  const fs::path src = root_ / "teleop_bad" / "teleop";
  fs::create_directories(src.parent_path());
  fs::copy(kTeleopData, src, fs::copy_options::recursive);
  const fs::path json = src / "drive_001" / (kTeleopStem + ".json");
  const fs::path csv = src / "drive_001" / (kTeleopStem + "_traj.csv");
  const std::string collect = kCollect + " teleop " + json.string() +
                              " --crop-size 8 --crop-res 0.5 --quiet --out ";
  int n = 0;
  auto run = [&] { return Sh(collect + (root_ / "teleop_bad" / std::to_string(++n)).string()); };

  // Another command in one step: the drive is no longer the recording's.
  const std::vector<std::vector<double>> rows = CsvRows(csv);
  std::string text = Bytes(csv);
  {
    std::istringstream in(text);
    std::string line, out;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (number == 52) {   // row 50, the command of step 50 (t = 0.25 s): full throttle
        std::vector<std::string> f;
        std::istringstream fields(line);
        std::string x;
        while (std::getline(fields, x, ',')) f.push_back(x);
        f[11] = "1";
        line.clear();
        for (size_t i = 0; i < f.size(); ++i) line += (i ? "," : "") + f[i];
      }
      out += line + "\n";
    }
    ASSERT_NE(rows[50][11], 1.0);
    std::ofstream(csv, std::ios::binary) << out;
  }
  Outcome o = run();
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(json.string()), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("re-simulation differs from the recording"), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("_traj.csv line "), std::string::npos) << o.output;
  std::ofstream(csv, std::ios::binary) << text;   // restored

  // A field that is not a number: the CSV file, its line and the column.
  {
    std::string bad = text;
    const size_t line3 = bad.find('\n', bad.find('\n') + 1) + 1;
    bad.replace(line3, bad.find(',', line3) - line3, "zero");
    std::ofstream(csv, std::ios::binary) << bad;
  }
  o = run();
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(csv.string() + ":3: key 't_s'"), std::string::npos) << o.output;
  std::ofstream(csv, std::ios::binary) << text;

  // A trajectory cut short: fewer rows than the record's trajectory_samples.
  std::ofstream(csv, std::ios::binary) << text.substr(0, text.size() / 2);
  o = run();
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("trajectory_samples"), std::string::npos) << o.output;
  std::ofstream(csv, std::ios::binary) << text;

  // A record without its seed; a record of another system.
  const std::string record = Bytes(json);
  Edit(json, "\"seed\": 0,", "");
  o = run();
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(json.string() + ": key 'seed'"), std::string::npos) << o.output;
  std::ofstream(json, std::ios::binary) << record;
  Edit(json, "\"system\": \"teleop\"", "\"system\": \"pid\"");
  o = run();
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("not a teleoperated drive"), std::string::npos) << o.output;
  std::ofstream(json, std::ios::binary) << record;

  // An edited world: the task's FNV-1a is not the recording's.
  Edit(src / "teleop_demo.yaml", "scale: 0.8", "scale: 0.9");
  o = run();
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("provenance.task_file"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("does not match the drive"), std::string::npos) << o.output;

  // No recordings at all; a missing one.
  o = Sh(kCollect + " teleop --out " + (root_ / "teleop_bad" / "none").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("RECORDING"), std::string::npos) << o.output;
  o = Sh(kCollect + " teleop /nonexistent/drive.json --out " +
         (root_ / "teleop_bad" / "none").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("/nonexistent/drive.json"), std::string::npos) << o.output;
}

}  // namespace
