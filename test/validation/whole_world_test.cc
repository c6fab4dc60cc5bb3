// The original's three whole-world runs side by side (reference_chrono_runs.md, "Whole original
// worlds"): pair 0 of sample worlds 42 (rigid, low), 1 (rigid, high) and 62 (sand, mid; the whole
// world as SCM at the original's 0.1 m grid), start (60, 0), goal (-60, 0), no obstacles, a
// proportional heading controller towards the goal with the P speed controller at 4 m/s, 60 s.
// The original (Chrono): world 42 reaches the goal at 28.4 s; world 1 does not, and after 60 s
// stands at (-44.5, -5.1) (~105 m crossed); world 62 reaches the goal at 31.8 s.
// vb runs the same through its Episode (drop from 0.5 m, goal radius 10 m, no early end).
// Asserted: world 42 reaches the goal, its time within 15 % (measured 28.6 s). NOT MET, printed
// and recorded in docs/validation.md: world 1 stops after ~30 m (original ~105 m) at full throttle
// in 5th-6th gear with the wheels spinning at 0 m/s (issue 11's "stuck" signature). World 1 is
// chaotic: a 1 % change of the heading gain moves where it ends by up to 90 m (issue 24 measured
// 13 gains 1.92-2.08 on main and with prescribed steering: crossed 17-110 m, some end at
// 0.55-0.56 rad roll, one reaches the goal, one rolls over), so one run's end state is a draw;
// world 1 runs at nine gains 1.92 ... 2.08 and the original's outcome (upright, no goal) must be
// the typical one: at least 5 of the 9; no run may end in numerical trouble. World 62 and 42
// reach the goal; for them: no numerical trouble and upright. Heading gain: steering =
// clamp(2 x heading error [rad]) (the reference does not print its gain). Skipped without the
// original's sample files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/original_io.h"
#include "io/soil_io.h"
#include "support/worlds.h"
#include "vb/engine/runner/episode.h"
#include "vb/terrain/original_world.h"

namespace vb {
namespace {

const std::string kSamples = VB_SHARED_DIR "/verti_bench_samples";

struct WorldRun {
  bool reached = false;
  bool sim_error = false;
  double final_roll_rad = 0.0;
  double time_s = 0.0;
  Vec2 final_m = Vec2::Zero();
};

WorldRun DriveToGoal(int world, const char* level, double heading_gain = 2.0) {
  const std::string stem = kSamples + "/";
  const io::OriginalWorldFiles files = io::LoadOriginalWorld(
      stem + "config" + std::to_string(world) + "_" + level + ".yaml",
      stem + "world" + std::to_string(world) + ".bmp",
      stem + "labels" + std::to_string(world) + "_" + level + ".npy");
  terrain::TaskSpec task = terrain::TaskFromOriginal(files.config, files.world,
                                                     "orig" + std::to_string(world), "sample");
  task.rocks.clear();
  task.trees.clear();
  soil::SoilConfig soil = io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
  soil.grid_spacing_m = 0.1;  // the original's
  runner::EpisodeRules rules;
  rules.end_early = false;
  rules.trajectory_every_n_steps = 0;
  runner::Episode episode(task, test::Hmmwv(), rules, &soil);
  runner::TrialSpec spec;
  spec.pair_index = 0;
  episode.Reset(spec);
  const Vec2 goal = task.pairs[0].goal_m;
  while (!episode.Done()) {
    const controllers::Observation& obs = episode.Observe();
    const Vec2 to_goal = goal - obs.position_W.head<2>();
    double err = std::atan2(to_goal.y(), to_goal.x()) - obs.rpy.yaw_rad;
    err = std::remainder(err, 2.0 * kPi);
    controllers::Command cmd;
    const double speed = std::clamp(4.0 - obs.forward_speed_mps, -1.0, 1.0);
    cmd.throttle = std::max(0.0, speed);
    cmd.braking = std::max(0.0, -speed);
    cmd.steering = std::clamp(heading_gain * err, -1.0, 1.0);
    episode.Step(cmd);
    if (heading_gain == 2.0 && episode.physics_steps() % 1000 == 0) {  // every 5 s: where it is
      const vehicles::VehicleState& st = episode.vehicle_state();
      double slip = 0.0;
      for (const vehicles::WheelState& w : st.wheels) slip += w.longitudinal_slip / st.wheels.size();
      std::printf("  world %d t %4.0f s: (%6.1f, %5.1f) speed %.2f m/s gear %d throttle %.2f "
                  "slip %.2f pitch %+.1f deg\n",
                  world, episode.time_s(), st.pose_W.position.x(), st.pose_W.position.y(),
                  st.forward_speed_mps, st.gear, cmd.throttle, slip, st.rpy.pitch_rad * 180 / kPi);
    }
  }
  const runner::TrialResult r = episode.Result();
  WorldRun run;
  run.sim_error = r.status == runner::TrialStatus::kSimError;
  run.final_roll_rad = episode.vehicle_state().rpy.roll_rad;
  run.reached = r.status == runner::TrialStatus::kSuccess;
  run.time_s = r.sim_time_s;
  run.final_m = episode.vehicle_state().pose_W.position.head<2>();
  return run;
}

TEST(WholeWorldValidation, TheOriginalsThreeRunsSideBySide) {
  if (!std::filesystem::exists(kSamples + "/config42_low.yaml")) {
    GTEST_SKIP() << "original Verti-Bench samples not found in " << kSamples;
  }
  const WorldRun w42 = DriveToGoal(42, "low");
  std::printf("world 42 (rigid, low): %s at %.1f s, at (%.1f, %.1f); original: goal at 28.4 s\n",
              w42.reached ? "goal" : "no goal", w42.time_s, w42.final_m.x(), w42.final_m.y());
  int typical = 0;  // world 1 runs that end as the original's: upright, no goal
  for (int i = 0; i < 9; ++i) {
    const double gain = 1.92 + 0.02 * i;
    const WorldRun w1 = DriveToGoal(1, "high", gain);
    std::printf("world 1 (rigid, high), heading gain %.2f: %s at %.1f s, at (%.1f, %.1f), crossed "
                "%.1f m, roll %.2f rad%s; original: no goal, at (-44.5, -5.1) after 60 s (~105 m)\n",
                gain, w1.reached ? "goal" : "no goal", w1.time_s, w1.final_m.x(), w1.final_m.y(),
                60.0 - w1.final_m.x(), w1.final_roll_rad, w1.sim_error ? ", SIM ERROR" : "");
    EXPECT_FALSE(w1.sim_error) << gain;
    if (!w1.reached && std::abs(w1.final_roll_rad) < 0.5) ++typical;
  }
  EXPECT_GE(typical, 5);
  const WorldRun w62 = DriveToGoal(62, "mid");
  std::printf("world 62 (sand, mid, SCM 0.1 m): %s at %.1f s, at (%.1f, %.1f); original: goal at "
              "31.8 s\n",
              w62.reached ? "goal" : "no goal", w62.time_s, w62.final_m.x(), w62.final_m.y());
  for (const WorldRun& w : {w42, w62}) {
    EXPECT_FALSE(w.sim_error);
    EXPECT_LT(std::abs(w.final_roll_rad), 0.5);
  }
  EXPECT_TRUE(w42.reached);
  EXPECT_NEAR(w42.time_s, 28.4, 0.15 * 28.4);
}

}  // namespace
}  // namespace vb
