// vb_import and vb_gen end to end through their command lines: an imported original rigid world
// runs in vb_run; bad inputs exit with code 2 and name the culprit; vb_gen --env reproduces the
// committed files and its scale variant runs.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "support/cli.h"

namespace {

namespace fs = std::filesystem;

const std::string kBin = VB_BIN_DIR;
const std::string kSamples = VB_SHARED_DIR "/verti_bench_samples";

using Outcome = vb::testing::CommandOutcome;
using vb::testing::RunCommand;


std::string ReadAll(const fs::path& path) { return vb::testing::ReadFileBytes(path); }

class ToolsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vb_import_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ToolsTest, ImportedOriginalRigidWorldRunsInVbRun) {
  if (!fs::exists(kSamples + "/config42_low.yaml")) {
    GTEST_SKIP() << "original Verti-Bench samples not found in " << kSamples;
  }
  const Outcome imp = RunCommand(kBin + "/vb_import --config " + kSamples +
                                 "/config42_low.yaml --world " + kSamples +
                                 "/world42.bmp --labels " + kSamples + "/labels42_low.npy --out " +
                                 (dir_ / "tasks").string());
  ASSERT_EQ(imp.exit_code, 0) << imp.output;
  EXPECT_NE(imp.output.find("labels checked"), std::string::npos) << imp.output;
  const fs::path task = dir_ / "tasks" / "config42_low.yaml";
  ASSERT_TRUE(fs::exists(task));
  const Outcome run = RunCommand(kBin + "/vb_run " + task.string() +
                          " --vehicle hmmwv --pair 1 --time-limit 3 --quiet --out " +
                          (dir_ / "results").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("1 trials"), std::string::npos) << run.output;
}

TEST_F(ToolsTest, ImportBadInputsExitWithCodeTwo) {
  EXPECT_EQ(RunCommand(kBin + "/vb_import").exit_code, 2);
  EXPECT_EQ(
      RunCommand(kBin + "/vb_import --config nope.yaml --world nope.bmp --out " + dir_.string())
          .exit_code,
      2);
  if (!fs::exists(kSamples + "/config42_low.yaml")) return;
  // the obstacle map is not a world image
  const Outcome o = RunCommand(kBin + "/vb_import --config " + kSamples +
                               "/config42_low.yaml --world " + kSamples +
                               "/obs42_low.bmp --out " + dir_.string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("obs42_low.bmp: contains pixel value 255"), std::string::npos)
      << o.output;
}

TEST_F(ToolsTest, GenEnvReproducesCommittedFilesAndScaleVariantRuns) {
  const Outcome gen =
      RunCommand(kBin + "/vb_gen --env 42 --out " + (dir_ / "tasks").string() + " --image-dir " +
          (dir_ / "data" / "worlds").string());
  ASSERT_EQ(gen.exit_code, 0) << gen.output;
  EXPECT_EQ(ReadAll(dir_ / "tasks" / "env042.yaml"),
            ReadAll(fs::path(VB_SOURCE_DIR) / "tasks" / "env042.yaml"));
  EXPECT_EQ(ReadAll(dir_ / "data" / "worlds" / "env042.png"),
            ReadAll(fs::path(VB_SOURCE_DIR) / "data" / "worlds" / "env042.png"));

  const Outcome small = RunCommand(kBin + "/vb_gen --env 42 --scale 1/6 --name env042_s6 --out " +
                            (dir_ / "tasks").string());
  ASSERT_EQ(small.exit_code, 0) << small.output;
  const std::string text = ReadAll(dir_ / "tasks" / "env042_s6.yaml");
  EXPECT_NE(text.find("size_m: [21.333333333333332, 21.333333333333332]"), std::string::npos);
  EXPECT_NE(text.find("scale: 0.16666666666666666"), std::string::npos);
  const Outcome run = RunCommand(kBin + "/vb_run " + (dir_ / "tasks" / "env042_s6.yaml").string() +
                          " --vehicle hmmwv --pair 0 --time-limit 1 --quiet --out " +
                          (dir_ / "results").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;

  EXPECT_EQ(RunCommand(kBin + "/vb_gen --env 100 --out " + dir_.string()).exit_code, 2);
  EXPECT_EQ(RunCommand(kBin + "/vb_gen --env 1 --scale 0 --out " + dir_.string()).exit_code, 2);
  EXPECT_EQ(RunCommand(kBin + "/vb_gen --env 1 --seed 3 --out " + dir_.string()).exit_code, 2);
}

}  // namespace
