// Regression tests of the adversarial probe of vb at 745d427
// (../shared/reports/reliability_probe_745d427.md): one test per root cause DEF-1 ... DEF-17,
// each reproducing the probe's case through the tools' command lines. Every command runs under
// `timeout`, so a regression to a hang fails the test instead of stalling CI; docs/reliability.md
// lists the causes and fixes.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "support/probe.h"

namespace {

namespace fs = std::filesystem;
using Outcome = vb::testing::CommandOutcome;

const std::string kRun = VB_BIN_DIR "/vb_run";
const std::string kBatch = VB_BIN_DIR "/vb_batch";
const std::string kReport = VB_BIN_DIR "/vb_report";
const std::string kGen = VB_BIN_DIR "/vb_gen";
const std::string kImport = VB_BIN_DIR "/vb_import";
const std::string kSamples = VB_SHARED_DIR "/verti_bench_samples";

using vb::testing::Has;
using vb::testing::ReadFile;
using vb::testing::Replace;
using vb::testing::Sh;
using vb::testing::WriteFile;

class ReliabilityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vb_reliability_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // The probe's base.yaml: env042 with its height image path made absolute.
    base_ = Replace(ReadFile(VB_SOURCE_DIR "/tasks/env042.yaml"), "../data/worlds/env042.png",
                    VB_SOURCE_DIR "/data/worlds/env042.png");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes a variant of the base task and returns its path.
  std::string Task(const std::string& name, const std::string& from, const std::string& to) {
    const fs::path p = dir_ / (name + ".yaml");
    WriteFile(p, Replace(base_, from, to));
    return p.string();
  }
  // vb_run on `task` (60 s timeout: a hang is exit 124).
  Outcome Run(const std::string& task, const std::string& flags) {
    return Sh("timeout 60 " + kRun + " " + task + " --vehicle hmmwv " + flags);
  }
  std::string Out(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
  std::string base_;
};

constexpr const char* kRockScale = "scale: 0.7001880648016574}";

TEST_F(ReliabilityTest, Def01HugeScalesAreBadInputNotACrashOrHang) {
  for (const char* scale : {"1e308", "1e10", "1e9", "1e7"}) {
    const Outcome o = Run(Task("ws", "  scale: 1.0\n", std::string("  scale: ") + scale + "\n"),
                          "--pair 0 --out " + Out("o"));
    EXPECT_EQ(o.exit_code, 2) << scale << ": " << o.output;
    EXPECT_TRUE(Has(o, "ws.yaml:8: key 'world.scale': must be in [0.001, 1000.0]")) << o.output;
  }
  const Outcome rock =
      Run(Task("rs", kRockScale, "scale: 1e308}"), "--pair 0 --out " + Out("o"));
  EXPECT_EQ(rock.exit_code, 2) << rock.output;
  EXPECT_TRUE(Has(rock, "key 'obstacles.rocks[0].scale'")) << rock.output;
  // A rock scale below the bound whose box is still wider than the 128 m world.
  const Outcome wide = Run(Task("rw", kRockScale, "scale: 30.0}"), "--pair 0 --out " + Out("o"));
  EXPECT_EQ(wide.exit_code, 2) << wide.output;
  EXPECT_TRUE(Has(wide, "must fit in the world")) << wide.output;

  // vb_import refuses such a rock at the config's line instead of writing a task that crashes.
  const std::string config = Replace(ReadFile(kSamples + "/config42_low.yaml"),
                                     "scale: 0.8016853177123608", "scale: 1e308");
  WriteFile(dir_ / "c42.yaml", config);
  const Outcome imp = Sh(kImport + " --config " + Out("c42.yaml") + " --world " + kSamples +
                         "/world42.bmp --out " + Out("imp"));
  EXPECT_EQ(imp.exit_code, 2) << imp.output;
  EXPECT_TRUE(Has(imp, "c42.yaml:")) << imp.output;
  EXPECT_TRUE(Has(imp, "rock scale 1e+308 out of range")) << imp.output;
  EXPECT_FALSE(fs::exists(dir_ / "imp/c42.yaml"));
}

TEST_F(ReliabilityTest, Def02WriteFailureIsRetriedNeverAPermanentError) {
  // A file-size limit makes every write of more than 16 kB fail (EFBIG), as a full disk does:
  // the trajectories (about 40 kB) cannot be written, the small files can. SIGXFSZ is ignored so
  // the write returns the error instead of killing the process.
  const std::string limit = "trap '' XFSZ; ulimit -f 16; ";
  const std::string cmd = kBatch + " " VB_SOURCE_DIR "/tasks/env042.yaml --pairs 0-1 "
                          "--time-limit 1 --quiet --out " + Out("b");
  const Outcome full = Sh("(" + limit + "timeout 120 " + cmd + ")");
  EXPECT_EQ(full.exit_code, 1) << full.output;
  EXPECT_TRUE(Has(full, "could not be recorded (I/O error")) << full.output;
  EXPECT_FALSE(fs::exists(dir_ / "b/trials/env042_p0_s0_hmmwv_pid.json"));
  EXPECT_FALSE(fs::exists(dir_ / "b/trials/env042_p1_s0_hmmwv_pid.json"));
  // Space again: the same command runs the two trials (none is an `error` record).
  const Outcome resumed = Sh("timeout 120 " + cmd);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(Has(resumed, "0 already done, 2 to run")) << resumed.output;
  EXPECT_TRUE(fs::exists(dir_ / "b/trials/env042_p1_s0_hmmwv_pid_traj.csv"));
  EXPECT_EQ(ReadFile(dir_ / "b/index.csv").find(",error,"), std::string::npos);

  // vb_run: exit 1 (not 2, "bad input"), and no record without its trajectory.
  const Outcome run = Sh("(" + limit + "timeout 60 " + kRun + " " VB_SOURCE_DIR
                         "/tasks/env042.yaml --vehicle hmmwv --pair 0 --time-limit 1 --out " +
                         Out("r") + ")");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(Has(run, "vb_run: I/O error:")) << run.output;
  EXPECT_FALSE(fs::exists(dir_ / "r/env042_p0_s0_hmmwv_pid.json"));
}

TEST_F(ReliabilityTest, Def03TaskNameCannotLeaveTheOutputDirectory) {
  fs::create_directories(dir_ / "deep/er");
  const Outcome o = Run(Task("nt", "name: env042\n", "name: ../../pwn\n"),
                        "--pair 0 --time-limit 1 --out " + Out("deep/er/x"));
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_TRUE(Has(o, "nt.yaml:4: key 'name': name may contain only letters")) << o.output;
  for (const auto& e : fs::recursive_directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().find("pwn"), std::string::npos) << e.path();
  }
  const Outcome slash = Run(Task("ab", "name: env042\n", "name: a/b\n"), "--out " + Out("o"));
  EXPECT_EQ(slash.exit_code, 2) << slash.output;
  const Outcome longname =
      Run(Task("ln", "name: env042\n", "name: " + std::string(300, 'a') + "\n"), "--out " + Out("o"));
  EXPECT_EQ(longname.exit_code, 2) << longname.output;
  EXPECT_TRUE(Has(longname, "at most 128")) << longname.output;
  // vb_batch: the task is an `error` trial named by its file, written inside --out.
  const Outcome batch = Sh("timeout 60 " + kBatch + " " + Out("nt.yaml") + " --pairs 0 --quiet "
                           "--out " + Out("deep/er/b"));
  EXPECT_EQ(batch.exit_code, 0) << batch.output;
  EXPECT_TRUE(fs::exists(dir_ / "deep/er/b/trials/nt_p0_s0_hmmwv_pid.json"));
  for (const auto& e : fs::recursive_directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().find("pwn"), std::string::npos) << e.path();
  }
}

TEST_F(ReliabilityTest, Def04TimeLimitIsBoundedWithALocatedError) {
  for (const char* limit : {"1e308", "1e6", "3600.5"}) {
    const Outcome run = Run(VB_SOURCE_DIR "/tasks/env042.yaml",
                            std::string("--pair 0 --time-limit ") + limit + " --out " + Out("o"));
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_TRUE(Has(run, "key '--time-limit': must be in (0, 3600]")) << run.output;
    const Outcome batch = Sh(kBatch + " " VB_SOURCE_DIR "/tasks/env042.yaml --pairs 0 "
                             "--time-limit " + std::string(limit) + " --out " + Out("b"));
    EXPECT_EQ(batch.exit_code, 2) << batch.output;
    EXPECT_TRUE(Has(batch, "key '--time-limit'")) << batch.output;
  }
}

TEST_F(ReliabilityTest, Def05PairDoesNotWrapAt2To32) {
  const Outcome o =
      Run(VB_SOURCE_DIR "/tasks/env042.yaml", "--pair 4294967297 --time-limit 1 --out " + Out("o"));
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_TRUE(Has(o, "key '--pair': pair 4294967297 out of range")) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "o/env042_p1_s0_hmmwv_pid.json"));
}

TEST_F(ReliabilityTest, Def06SeedRangeEndingAtTheLargestSeedTerminates) {
  const Outcome o = Sh("timeout 120 " + kBatch + " " VB_SOURCE_DIR "/tasks/env042.yaml --pairs 0 "
                       "--seeds 18446744073709551614-18446744073709551615 --time-limit 0.5 "
                       "--quiet --out " + Out("b"));
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_TRUE(Has(o, "2/2 trials recorded")) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "b/trials/env042_p0_s18446744073709551615_hmmwv_pid.json"));
}

TEST_F(ReliabilityTest, Def07NonUtf8NameIsRefused) {
  const Outcome o = Run(Task("u", "name: env042\n", "name: env\xff" "42\n"), "--out " + Out("o"));
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_TRUE(Has(o, "key 'name'")) << o.output;
}

TEST_F(ReliabilityTest, Def12UnboundedInputsAreRefusedQuickly) {
  const Outcome zero = Sh("timeout 20 " + kRun + " /dev/zero --vehicle hmmwv --out " + Out("o"));
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_TRUE(Has(zero, "/dev/zero: is a device or special file")) << zero.output;
  ASSERT_EQ(Sh("mkfifo " + Out("fifo.yaml")).exit_code, 0);
  const Outcome fifo = Sh("timeout 20 " + kRun + " " + Out("fifo.yaml") + " --vehicle hmmwv "
                          "--out " + Out("o"));
  EXPECT_EQ(fifo.exit_code, 2) << fifo.output;
  EXPECT_TRUE(Has(fifo, "is a FIFO")) << fifo.output;
  // A PNG whose header claims 100000 x 100000 pixels (16-bit): refused before decoding.
  std::string png("\x89PNG\r\n\x1a\n", 8);
  png += std::string("\0\0\0\x0dIHDR", 8) + std::string("\x00\x01\x86\xa0\x00\x01\x86\xa0", 8) +
         std::string("\x10\0\0\0\0", 5) + std::string(4, '\0');
  WriteFile(dir_ / "hdr.png", png);
  const Outcome big = Run(Task("hdr", VB_SOURCE_DIR "/data/worlds/env042.png", Out("hdr.png")),
                          "--pair 0 --out " + Out("o"));
  EXPECT_EQ(big.exit_code, 2) << big.output;
  EXPECT_TRUE(Has(big, "is 100000x100000 pixels; at most 8192")) << big.output;
  // 10001 trees: over the obstacle limit, refused at once instead of hours of setup.
  std::string trees = "  trees:\n";
  for (int i = 0; i < 10001; ++i) trees += "    - {x: 1.0, y: 2.0}\n";
  const fs::path many = dir_ / "many.yaml";
  const size_t at = base_.find("  trees:");
  ASSERT_NE(at, std::string::npos);
  const size_t end = base_.find("pairs:", at);
  WriteFile(many, base_.substr(0, at) + trees + base_.substr(end));
  const Outcome m = Run(many.string(), "--pair 0 --out " + Out("o"));
  EXPECT_EQ(m.exit_code, 2) << m.output;
  EXPECT_TRUE(Has(m, "at most 10000 obstacles")) << m.output;
}

TEST_F(ReliabilityTest, Def13MessagesNameTheRealProblem) {
  const Outcome dir_image = Run(Task("d", VB_SOURCE_DIR "/data/worlds/env042.png", dir_.string()),
                                "--pair 0 --out " + Out("o"));
  EXPECT_EQ(dir_image.exit_code, 2) << dir_image.output;
  EXPECT_TRUE(Has(dir_image, "is a directory")) << dir_image.output;
  const Outcome dir_task = Run(dir_.string(), "--out " + Out("o"));
  EXPECT_EQ(dir_task.exit_code, 2) << dir_task.output;
  EXPECT_TRUE(Has(dir_task, "is a directory, not a file")) << dir_task.output;
  const Outcome scale = Sh(kBatch + " " VB_SOURCE_DIR "/tasks/env042.yaml --scale 0.5 --out " +
                           Out("b"));
  EXPECT_EQ(scale.exit_code, 2) << scale.output;
  EXPECT_TRUE(Has(scale, "key '--scale': no task has world scale 0.5")) << scale.output;
  // 100000 levels of flow nesting: yaml-cpp's depth guard, said as such.
  WriteFile(dir_ / "deep.yaml", "foo: " + std::string(100000, '[') + std::string(100000, ']') +
                                    "\n" + base_);
  const Outcome deep = Run(Out("deep.yaml"), "--out " + Out("o"));
  EXPECT_EQ(deep.exit_code, 2) << deep.output;
  EXPECT_TRUE(Has(deep, "nesting too deep")) << deep.output;
}

TEST_F(ReliabilityTest, Def14FlagsAndNamesAreStrict) {
  const std::string task = VB_SOURCE_DIR "/tasks/env042.yaml";   // rigid: needs no soil
  const Outcome nosuch = Run(task, "--pair 0 --soil nosuch --out " + Out("o"));
  EXPECT_EQ(nosuch.exit_code, 2) << nosuch.output;
  EXPECT_TRUE(Has(nosuch, "unknown soil 'nosuch'")) << nosuch.output;
  const Outcome up = Run(VB_SOURCE_DIR "/tasks/env061.yaml",
                         "--pair 0 --soil ../soils/verti_bench --out " + Out("o"));
  EXPECT_EQ(up.exit_code, 2) << up.output;
  const Outcome out = Run(task, "--pair 0 --out ''");
  EXPECT_EQ(out.exit_code, 2) << out.output;
  EXPECT_TRUE(Has(out, "key '--out': empty value")) << out.output;
  const Outcome pairs = Sh(kBatch + " " + task + " --pairs '' --out " + Out("b"));
  EXPECT_EQ(pairs.exit_code, 2) << pairs.output;
  EXPECT_TRUE(Has(pairs, "key '--pairs': empty value")) << pairs.output;
  const Outcome nul = Run(Task("nul", "height_image: " VB_SOURCE_DIR "/data/worlds/env042.png",
                               "height_image: \"" VB_SOURCE_DIR "/data/worlds/env042.png\\0junk\""),
                          "--pair 0 --out " + Out("o"));
  EXPECT_EQ(nul.exit_code, 2) << nul.output;
  EXPECT_TRUE(Has(nul, "key 'world.height_image': string contains a NUL")) << nul.output;
}

TEST_F(ReliabilityTest, Def15HighWorldIsNotADivergence) {
  const std::string range = base_.substr(base_.find("height_range_m:"));
  const std::string line = range.substr(0, range.find('\n'));
  const Outcome o = Run(Task("a40", line, "height_range_m: [1000000.0, 1000100.0]"),
                        "--pair 0 --time-limit 1 --out " + Out("o"));
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_FALSE(Has(o, "diverged")) << o.output;
  EXPECT_TRUE(Has(o, "sim_error 0 (0%)")) << o.output;
}

// DEF-10, DEF-16 and DEF-9 on one small batch (4 trials of 0.5 s, 2 shards).
TEST_F(ReliabilityTest, Def09Def10Def16RecordsAreVerifiedNotTrusted) {
  const std::string matrix = kBatch + " " VB_SOURCE_DIR "/tasks/env042.yaml --pairs 0-3 "
                             "--time-limit 0.5 --traj-every 10 --quiet";
  const fs::path b = dir_ / "b";
  ASSERT_EQ(Sh(matrix + " --out " + b.string()).exit_code, 0);

  // DEF-16: a record copied under another trial's name, a deleted and a cut trajectory: resume
  // re-runs those three trials and the index lists every trial once.
  fs::copy_file(b / "trials/env042_p0_s0_hmmwv_pid.json", b / "trials/env042_p1_s0_hmmwv_pid.json",
                fs::copy_options::overwrite_existing);
  fs::remove(b / "trials/env042_p2_s0_hmmwv_pid_traj.csv");
  const fs::path traj3 = b / "trials/env042_p3_s0_hmmwv_pid_traj.csv";
  fs::resize_file(traj3, fs::file_size(traj3) / 2);
  const Outcome resume = Sh(matrix + " --out " + b.string());
  EXPECT_EQ(resume.exit_code, 0) << resume.output;
  EXPECT_TRUE(Has(resume, "1 already done, 3 to run")) << resume.output;
  const std::string index = ReadFile(b / "index.csv");
  for (int k = 0; k < 4; ++k) {
    EXPECT_NE(index.find(",env042," + std::to_string(k) + ",0,"), std::string::npos) << index;
  }
  // --topdown of a trial whose trajectory is cut: an error, not a picture without it.
  fs::resize_file(traj3, fs::file_size(traj3) / 2);
  const Outcome pic = Sh(kReport + " " + b.string() + " --topdown env042_p3_s0_hmmwv_pid");
  EXPECT_EQ(pic.exit_code, 2) << pic.output;
  EXPECT_TRUE(Has(pic, "its record says")) << pic.output;

  // DEF-9: a duplicated index row, a nan and a negative number are refused with their line.
  const std::string good = ReadFile(b / "index.csv");
  const std::string last = good.substr(good.rfind('\n', good.size() - 2) + 1);
  WriteFile(b / "index.csv", good + last);
  const Outcome dup = Sh(kReport + " " + b.string());
  EXPECT_EQ(dup.exit_code, 2) << dup.output;
  EXPECT_TRUE(Has(dup, "index.csv:6:")) << dup.output;
  EXPECT_TRUE(Has(dup, "is listed twice (first at line 5)")) << dup.output;
  WriteFile(b / "index.csv", Replace(good, ",0.5,", ",nan,"));
  const Outcome nan = Sh(kReport + " " + b.string());
  EXPECT_EQ(nan.exit_code, 2) << nan.output;
  EXPECT_TRUE(Has(nan, "key 'sim_time_s': 'nan' is not a finite number")) << nan.output;
  WriteFile(b / "index.csv", Replace(good, ",0.5,", ",-0.5,"));
  const Outcome neg = Sh(kReport + " " + b.string());
  EXPECT_EQ(neg.exit_code, 2) << neg.output;
  EXPECT_TRUE(Has(neg, "'-0.5' is negative")) << neg.output;
  WriteFile(b / "index.csv", good);

  // DEF-10: a record truncated in a shard whose index is intact is refused, nothing is written;
  // so is a merge into a directory that is not empty.
  for (int s = 0; s < 2; ++s) {
    ASSERT_EQ(Sh(matrix + " --shard " + std::to_string(s) + "/2 --out " +
                 Out("s" + std::to_string(s))).exit_code, 0);
  }
  const fs::path cut = dir_ / "s1/trials/env042_p1_s0_hmmwv_pid.json";
  const std::string record = ReadFile(cut);
  fs::resize_file(cut, 300);
  const Outcome m = Sh(kReport + " merge " + Out("m") + " " + Out("s0") + " " + Out("s1"));
  EXPECT_EQ(m.exit_code, 2) << m.output;
  EXPECT_TRUE(Has(m, "env042_p1_s0_hmmwv_pid.json")) << m.output;
  EXPECT_FALSE(fs::exists(dir_ / "m/index.csv"));
  // A record of another build (same results) inside the shard.
  WriteFile(cut, Replace(record, "\"vb_version\": \"", "\"vb_version\": \"9."));
  const Outcome other = Sh(kReport + " merge " + Out("m2") + " " + Out("s0") + " " + Out("s1"));
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_TRUE(Has(other, "the shard by vb")) << other.output;
  WriteFile(cut, record);
  fs::create_directories(dir_ / "m3");
  WriteFile(dir_ / "m3/stray.txt", "x");
  const Outcome stray = Sh(kReport + " merge " + Out("m3") + " " + Out("s0") + " " + Out("s1"));
  EXPECT_EQ(stray.exit_code, 2) << stray.output;
  EXPECT_TRUE(Has(stray, "not an empty directory")) << stray.output;
  const Outcome ok = Sh(kReport + " merge " + Out("m4") + " " + Out("s0") + " " + Out("s1"));
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_TRUE(Has(ok, "4 of 4 trials")) << ok.output;
}

TEST_F(ReliabilityTest, Def11WritersNeverEmitTasksTheLoaderRefuses) {
  for (const char* scale : {"1e308", "1e-300"}) {
    const Outcome o = Sh(kGen + " --env 42 --scale " + std::string(scale) + " --name big --out " +
                         Out("g"));
    EXPECT_EQ(o.exit_code, 2) << scale << ": " << o.output;
    EXPECT_TRUE(Has(o, "key '--scale'")) << o.output;
    EXPECT_FALSE(fs::exists(dir_ / "g/big.yaml"));
  }
  // A rock and a start outside the imported world: refused at the config's line.
  const std::string config = ReadFile(kSamples + "/config42_low.yaml");
  WriteFile(dir_ / "c_out.yaml", Replace(config, "x: -41.3250779826441", "x: 500.0"));
  const Outcome imp = Sh(kImport + " --config " + Out("c_out.yaml") + " --world " + kSamples +
                         "/world42.bmp --out " + Out("imp"));
  EXPECT_EQ(imp.exit_code, 2) << imp.output;
  EXPECT_TRUE(Has(imp, "is outside the world [-64.0, 64.0]")) << imp.output;
  EXPECT_FALSE(fs::exists(dir_ / "imp/c_out.yaml"));
}

TEST_F(ReliabilityTest, Def17WorkersDieWithTheirParent) {
  // Six long trials (deformable terrain, the pairs that drive 34-44 s to the goal: ~1 s of wall
  // time each, ~3 s for the batch on 2 jobs; pairs 0-1 stop stuck within 0.1-0.3 s, too short for
  // the 0.1 s polling below); kill -9 the parent only. Workers are forks, so they share the
  // parent's command line with the out path; the pattern's "[/]" keeps pgrep's own shell from
  // matching it.
  const std::string out = Out("orphans");
  const std::string pattern = "[/]" + out.substr(1);
  const Outcome started = Sh(kBatch + " " VB_SOURCE_DIR "/tasks/env061.yaml --pairs 2,3,5,6,7,9 "
                             "--jobs 2 --quiet --out " + out + " > /dev/null 2>&1 & echo $!");
  const std::string pid = started.output.substr(0, started.output.find('\n'));
  ASSERT_FALSE(pid.empty());
  // Wait until both workers run (the parent and its forks share the command line).
  int processes = 0;
  for (int i = 0; i < 100 && processes < 3; ++i) {
    ::usleep(100000);
    processes = std::stoi("0" + Sh("pgrep -fc -- '" + pattern + "'").output);
  }
  ASSERT_GE(processes, 2) << "workers did not start";
  Sh("kill -9 " + pid);
  int left = 1;
  for (int i = 0; i < 50 && left > 0; ++i) {
    ::usleep(100000);
    left = std::stoi("0" + Sh("pgrep -fc -- '" + pattern + "'").output);
  }
  EXPECT_EQ(left, 0) << "workers outlived the killed vb_batch";
}

}  // namespace
