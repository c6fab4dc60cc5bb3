// Perception presets through the tools: vb_run names its files and records the preset,
// vb_batch runs a matrix of presets, vb_report adds the robustness table and plot; ground-truth
// records keep their exact format.
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "support/cli.h"

namespace {

namespace fs = std::filesystem;

const std::string kRun = VB_BIN_DIR "/vb_run";
const std::string kBatch = VB_BIN_DIR "/vb_batch";
const std::string kReport = VB_BIN_DIR "/vb_report";
const std::string kTask = VB_SOURCE_DIR "/tasks/env042.yaml";

fs::path TempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(PerceptionCliTest, VbRunRecordsThePresetInNamesAndProvenance) {
  const fs::path out = TempDir("vb_perc_run");
  const auto r = vb::testing::RunCommand(kRun + " " + kTask +
                                         " --vehicle hmmwv --pair 0 --time-limit 5 --quiet"
                                         " --perception moderate --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path json = out / "env042_p0_s0_hmmwv_pid_perc-moderate.json";
  ASSERT_TRUE(fs::exists(json)) << r.output;
  ASSERT_TRUE(fs::exists(out / "env042_p0_s0_hmmwv_pid_perc-moderate_traj.csv"));
  const std::string text = vb::testing::ReadFileBytes(json);
  EXPECT_NE(text.find("\"perception\": \"moderate\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"perception_fnv1a64\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"missed_obstacles\""), std::string::npos) << text;

  // Ground truth: no perception keys, the usual file name.
  const auto g = vb::testing::RunCommand(kRun + " " + kTask +
                                         " --vehicle hmmwv --pair 0 --time-limit 5 --quiet --out " +
                                         out.string());
  ASSERT_EQ(g.exit_code, 0) << g.output;
  const std::string truth = vb::testing::ReadFileBytes(out / "env042_p0_s0_hmmwv_pid.json");
  EXPECT_EQ(truth.find("perception"), std::string::npos) << truth;

  // An unknown preset is bad input naming the flag and the valid names.
  const auto bad = vb::testing::RunCommand(kRun + " " + kTask +
                                           " --vehicle hmmwv --perception foggy --out " +
                                           out.string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--perception"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("severe"), std::string::npos) << bad.output;
  fs::remove_all(out);
}

TEST(PerceptionCliTest, BatchOfPresetsGivesARobustnessReport) {
  const fs::path root = TempDir("vb_perc_batch");
  const std::string out = (root / "b").string();
  const auto b = vb::testing::RunCommand(kBatch + " " + kTask +
                                         " --pairs 0,1 --time-limit 5 --traj-every 50 --quiet"
                                         " --perception none,severe --jobs 2 --out " + out);
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_TRUE(fs::exists(root / "b/trials/env042_p1_s0_hmmwv_pid_perc-severe.json"));
  EXPECT_TRUE(fs::exists(root / "b/trials/env042_p1_s0_hmmwv_pid.json"));
  const std::string index = vb::testing::ReadFileBytes(root / "b/index.csv");
  EXPECT_NE(index.find(",pid,severe,"), std::string::npos) << index;
  EXPECT_NE(index.find(",pid,none,"), std::string::npos) << index;

  const auto rep = vb::testing::RunCommand(kReport + " " + out);
  ASSERT_EQ(rep.exit_code, 0) << rep.output;
  const std::string md = vb::testing::ReadFileBytes(root / "b/report/report.md");
  EXPECT_NE(md.find("## Robustness"), std::string::npos) << md;
  EXPECT_NE(md.find("| system | none | severe |"), std::string::npos) << md;
  EXPECT_NE(md.find("pid/hmmwv/perception:severe"), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(root / "b/report/robustness.png"));
  const std::string csv = vb::testing::ReadFileBytes(root / "b/report/robustness.csv");
  EXPECT_NE(csv.find("pid/hmmwv,severe,2,2,"), std::string::npos) << csv;

  // Resume: the same command again runs nothing.
  const auto again = vb::testing::RunCommand(kBatch + " " + kTask +
                                             " --pairs 0,1 --time-limit 5 --traj-every 50"
                                             " --perception none,severe --jobs 2 --out " + out);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("4 already done"), std::string::npos) << again.output;
  fs::remove_all(root);
}

}  // namespace
