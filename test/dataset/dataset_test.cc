// The dataset library and its HDF5 files (docs/datasets.md): schema round trip through the file,
// byte-identical rewrites, the explorer's draws, failure windows that end exactly at the trial's
// end, and a re-simulated trial that matches RunTrial.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "io/hdf5_dataset.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "support/cli.h"
#include "vb/controllers/controller.h"
#include "vb/dataset/explorer.h"
#include "vb/dataset/recorder.h"
#include "vb/dataset/spaces.h"
#include "vb/engine/runner/episode.h"

namespace vb {
namespace {

namespace fs = std::filesystem;

class DatasetTest : public ::testing::Test {
 protected:
  DatasetTest()
      : task(io::LoadTask(VB_SOURCE_DIR "/tasks/env000.yaml")),
        vehicle(io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml")) {
    dir = fs::temp_directory_path() / ("vb_dataset_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    config.crops = {{"elevation", terrain::MapLayer::kElevation, 8, 0.5},
                    {"semantics", terrain::MapLayer::kSemantics, 8, 0.5}};
  }
  ~DatasetTest() override { fs::remove_all(dir); }

  dataset::EpisodeRecord Explore(double seconds, uint64_t seed) {
    runner::EpisodeRules rules;
    rules.time_limit_s = seconds;
    rules.goal_ends_trial = false;
    rules.trajectory_every_n_steps = 0;
    runner::Episode episode(task, vehicle, rules);
    runner::TrialSpec spec;
    spec.seed = seed;
    spec.system = "explorer";
    episode.Reset(spec);
    dataset::ExplorerPolicy policy(dataset::DrawExplorerParams(seed), config.sample_every_steps);
    return dataset::RecordEpisode(episode, policy, config);
  }

  terrain::TaskSpec task;
  vehicles::VehicleParams vehicle;
  dataset::SampleConfig config;
  fs::path dir;
};

TEST_F(DatasetTest, ExplorationEpisodeHasTheSchemaShapes) {
  const dataset::EpisodeRecord r = Explore(3.0, 7);
  EXPECT_EQ(r.FindAttribute("status")->text, "timeout");
  EXPECT_EQ(r.steps, 30);   // 3 s at 0.1 s
  const auto rows = [&](const char* path) { return r.Find(path)->Rows(); };
  EXPECT_EQ(rows("actions"), 30u);
  EXPECT_EQ(rows("rewards"), 30u);
  EXPECT_EQ(rows("observations/state"), 31u);
  EXPECT_EQ(rows("observations/wheels"), 31u);
  EXPECT_EQ(rows("observations/elevation"), 31u);
  EXPECT_EQ(r.Find("observations/elevation")->RowSize(), 64u);
  EXPECT_EQ(rows("infos/time_s"), 31u);
  EXPECT_EQ(r.Find("infos/wheel_surface")->RowSize(), 4u);
  const dataset::Column& t = *r.Find("infos/time_s");
  for (size_t i = 0; i < t.f64.size(); ++i) EXPECT_NEAR(t.f64[i], 0.1 * i, 1e-12);
  // Only the last transition ends the episode (timeout: truncated, not terminated).
  const dataset::Column& trunc = *r.Find("truncations");
  const dataset::Column& term = *r.Find("terminations");
  for (size_t i = 0; i + 1 < trunc.i8.size(); ++i) EXPECT_EQ(trunc.i8[i] + term.i8[i], 0);
  EXPECT_EQ(trunc.i8.back(), 1);
  EXPECT_EQ(term.i8.back(), 0);
  // The explorer's actions: steering within the drawn amplitude, speed 2 m/s of 4 m/s.
  const dataset::ExplorerParams p = dataset::DrawExplorerParams(7);
  const dataset::Column& a = *r.Find("actions");
  for (size_t i = 0; i < 30; ++i) {
    EXPECT_LE(std::abs(a.f32[2 * i]), p.amplitude + 1e-6);
    EXPECT_FLOAT_EQ(a.f32[2 * i + 1], 0.5f);
    const double t0 = 0.1 * i;
    EXPECT_NEAR(a.f32[2 * i], p.amplitude * std::sin(2 * kPi * t0 / p.period_s + p.phase_rad),
                1e-6);
  }
  // Elevation relative to the chassis: the ground is below it.
  const dataset::Column& elev = *r.Find("observations/elevation");
  EXPECT_LT(elev.f32[28], 0.0f);   // the centre cell of the first sample
  // The vehicle drives: speed near the 2 m/s target after 3 s.
  EXPECT_NEAR(r.Find("infos/forward_speed_mps")->f64.back(), 2.0, 0.5);
}

TEST_F(DatasetTest, ExplorerDrawsAreDeterministicAndInRange) {
  for (uint64_t s = 0; s < 200; ++s) {
    const dataset::ExplorerParams p = dataset::DrawExplorerParams(s);
    EXPECT_GE(p.amplitude, dataset::kExplorerMinAmplitude);
    EXPECT_LT(p.amplitude, dataset::kExplorerMaxAmplitude);
    EXPECT_GE(p.period_s, dataset::kExplorerMinPeriod_s);
    EXPECT_LT(p.period_s, dataset::kExplorerMaxPeriod_s);
    EXPECT_EQ(p.amplitude, dataset::DrawExplorerParams(s).amplitude);
  }
  EXPECT_NE(dataset::DrawExplorerParams(1).period_s, dataset::DrawExplorerParams(2).period_s);
}

TEST_F(DatasetTest, FileRoundTripIsExactAndByteIdentical) {
  dataset::EpisodeRecord r = Explore(2.0, 3);
  r.SetInt("id", 0);
  r.SetInt("total_steps", r.steps);
  r.SetText("task", "env000");
  const std::string a = (dir / "a.h5").string();
  const std::string b = (dir / "b.h5").string();
  io::WriteEpisodeFile(r, a);
  io::WriteEpisodeFile(Explore(2.0, 3), b);   // same episode, recorded again
  dataset::EpisodeRecord again = Explore(2.0, 3);
  again.SetInt("id", 0);
  again.SetInt("total_steps", again.steps);
  again.SetText("task", "env000");
  io::WriteEpisodeFile(again, b);
  EXPECT_TRUE(testing::ReadFileBytes(a) == testing::ReadFileBytes(b));

  const dataset::EpisodeRecord back = io::ReadEpisodeFile(a);
  EXPECT_EQ(back.steps, r.steps);
  ASSERT_EQ(back.columns.size(), r.columns.size());
  for (const dataset::Column& c : r.columns) {
    const dataset::Column* d = back.Find(c.path);
    ASSERT_NE(d, nullptr) << c.path;
    EXPECT_EQ(d->type, c.type) << c.path;
    EXPECT_EQ(d->row_shape, c.row_shape) << c.path;
    EXPECT_EQ(d->f32, c.f32) << c.path;
    EXPECT_EQ(d->f64, c.f64) << c.path;
    EXPECT_EQ(d->i8, c.i8) << c.path;
    EXPECT_EQ(d->i32, c.i32) << c.path;
  }
  const auto attrs = io::ReadEpisodeAttributes(a);
  EXPECT_EQ(attrs.at("task"), "env000");
  EXPECT_EQ(attrs.at("status"), "timeout");
  EXPECT_EQ(attrs.at("total_steps"), "20");
  EXPECT_EQ(attrs.at("sample_period_s"), "0.1");

  // A truncated file is refused by name, never half read.
  const std::string bytes = testing::ReadFileBytes(a);
  const std::string cut = (dir / "cut.h5").string();
  FILE* f = std::fopen(cut.c_str(), "wb");
  std::fwrite(bytes.data(), 1, bytes.size() / 2, f);
  std::fclose(f);
  EXPECT_THROW(io::ReadEpisodeAttributes(cut), InputError);
}

TEST_F(DatasetTest, FailureWindowEndsAtTheTrialsEndAndMatchesRunTrial) {
  runner::EpisodeRules rules;
  rules.time_limit_s = 7.0;
  rules.trajectory_every_n_steps = 0;
  runner::TrialSpec spec;
  spec.system = "pid";
  const runner::TrialResult trial = runner::RunTrial(task, vehicle, spec, rules);
  ASSERT_EQ(trial.status, runner::TrialStatus::kTimeout);

  runner::Episode episode(task, vehicle, rules);
  episode.Reset(spec);
  dataset::ControllerPolicy policy(controllers::MakeController("pid"));
  policy.Start(episode);
  const long k_end = std::lround(trial.sim_time_s / rules.step_s);
  dataset::RecordWindow window;
  window.first_step = k_end - 20 * (std::min(k_end, 400L) / 20);   // the last 2 s
  const dataset::EpisodeRecord r = dataset::RecordEpisode(episode, policy, config, window);
  EXPECT_EQ(episode.physics_steps(), k_end);
  EXPECT_EQ(r.FindAttribute("status")->text, "timeout");
  EXPECT_EQ(r.FindAttribute("sim_time_s")->real, trial.sim_time_s);
  const dataset::Column& t = *r.Find("infos/time_s");
  ASSERT_EQ(t.Rows(), 21u);
  EXPECT_DOUBLE_EQ(t.f64.back(), trial.sim_time_s);
  EXPECT_NEAR(t.f64.front(), trial.sim_time_s - 2.0, 1e-9);
  // The final position is the trial's (same bits as RunTrial's last trajectory sample).
  runner::EpisodeRules with_traj = rules;
  with_traj.trajectory_every_n_steps = 1;
  const runner::TrialResult traj = runner::RunTrial(task, vehicle, spec, with_traj);
  EXPECT_EQ(r.Find("infos/position_m")->f64[3 * 20], traj.trajectory.back().position_W.x());
  // PID actions are direct-space means of its commands: throttle in [0, 1] -> [-1, 1].
  const dataset::Column& a = *r.Find("actions");
  ASSERT_EQ(a.RowSize(), 3u);
  for (float v : a.f32) {
    EXPECT_GE(v, -1.0f);
    EXPECT_LE(v, 1.0f);
  }
}

TEST(DatasetSpacesTest, SerialisationIsMinariJson) {
  dataset::SampleConfig c;
  c.crops = {{"semantics", terrain::MapLayer::kSemantics, 2, 0.5}};
  const std::string obs = dataset::ObservationSpaceJson(c, 4);
  EXPECT_NE(obs.find("\"type\": \"Dict\""), std::string::npos);
  EXPECT_NE(obs.find("\"semantics\": {\"type\": \"Box\", \"dtype\": \"float32\", "
                     "\"shape\": [2, 2], "
                     "\"low\": [[0.0, 0.0], [0.0, 0.0]], \"high\": [[9.0, 9.0], [9.0, 9.0]]}"),
            std::string::npos)
      << obs;
  EXPECT_EQ(dataset::ActionSpaceJson(dataset::ActionKind::kSpeed),
            "{\"type\": \"Box\", \"dtype\": \"float32\", \"shape\": [2], \"low\": [-1.0, -1.0], "
            "\"high\": [1.0, 1.0]}");
}

}  // namespace
}  // namespace vb
