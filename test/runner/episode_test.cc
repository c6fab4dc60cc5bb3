// RunTrial end to end on small synthetic worlds with the real HMMWV: success on flat ground,
// bit-identical reruns, failure classification, and the set-up errors.
#include "vb/engine/runner/episode.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/error.h"
#include "support/worlds.h"
#include "vb/engine/runner/result_digest.h"

namespace vb::runner {
namespace {

// 128 m x 128 m flat dirt (mu 0.8), no obstacles, one pair 40 m apart along x.
terrain::TaskSpec FlatTask() {
  terrain::TaskSpec t;
  t.name = "flat";
  t.source_file = "synthetic_flat.yaml";
  t.size_x_m = 128.0;
  t.size_y_m = 128.0;
  t.heights.rows = 129;
  t.heights.cols = 129;
  t.heights.heights_m.assign(129 * 129, 0.0);
  t.patches.rows = 16;
  t.patches.cols = 16;
  t.patches.classes.assign(16 * 16, terrain::SurfaceClass::kDirt);
  t.patches.friction.assign(16 * 16, 0.8);
  terrain::StartGoalPair pair;
  pair.start_m = Vec2(-20.0, 0.0);
  pair.goal_m = Vec2(20.0, 0.0);
  pair.path_m = {pair.start_m, pair.goal_m};
  t.pairs.push_back(pair);
  return t;
}

std::string TrialDigestOf(const TrialResult& r) { return TrialDigest(r); }

const vehicles::VehicleParams& Hmmwv() {
  static const vehicles::VehicleParams params =
      io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  return params;
}

TEST(EpisodeTest, DrivesToTheGoalOnFlatGround) {
  const TrialResult r = RunTrial(FlatTask(), Hmmwv(), TrialSpec());
  EXPECT_EQ(r.status, TrialStatus::kSuccess) << r.message;
  // 30 m to the goal circle from rest at <= 4 m/s.
  EXPECT_GT(r.traversal_time_s, 6.0);
  EXPECT_LT(r.traversal_time_s, 20.0);
  EXPECT_EQ(r.traversal_time_s, r.sim_time_s);
  EXPECT_LE(r.final_goal_distance_m, 10.0);
  EXPECT_NEAR(r.path_length_m, 30.0, 3.0);
  EXPECT_EQ(r.obstacle_contacts, 0);
  EXPECT_LT(r.abs_roll_deg.max, 5.0);
  EXPECT_LT(r.abs_pitch_deg.max, 8.0);  // squat under full throttle
  // Full throttle from rest, then the speed controller holds the target speed.
  EXPECT_EQ(r.throttle.max, 1.0);
  EXPECT_NEAR(r.trajectory.back().speed_mps, 4.0, 0.3);
  EXPECT_LT(r.abs_steering.max, 0.2);
  // One sample per step, the initial state included.
  EXPECT_EQ(r.trajectory.size(),
            static_cast<size_t>(std::lround(r.sim_time_s / EpisodeRules().step_s)) + 1);
  EXPECT_EQ(r.trajectory.front().time_s, 0.0);
  EXPECT_EQ(r.trajectory.back().time_s, r.sim_time_s);
  ASSERT_EQ(r.trajectory.back().wheel_surface.size(), Hmmwv().axles.size() * 2);
  EXPECT_GT(r.real_time_factor, 0.0);
}

TEST(EpisodeTest, RerunsAreBitIdentical) {
  EpisodeRules rules;
  rules.time_limit_s = 4.0;
  const TrialResult a = RunTrial(FlatTask(), Hmmwv(), TrialSpec(), rules);
  const TrialResult b = RunTrial(FlatTask(), Hmmwv(), TrialSpec(), rules);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (size_t i = 0; i < a.trajectory.size(); ++i) {
    const TrajectorySample& p = a.trajectory[i];
    const TrajectorySample& q = b.trajectory[i];
    ASSERT_TRUE(p.position_W == q.position_W && p.velocity_W == q.velocity_W &&
                p.rpy.roll_rad == q.rpy.roll_rad && p.rpy.pitch_rad == q.rpy.pitch_rad &&
                p.rpy.yaw_rad == q.rpy.yaw_rad && p.throttle == q.throttle &&
                p.steering == q.steering && p.braking == q.braking && p.gear == q.gear &&
                p.wheel_surface == q.wheel_surface)
        << "first difference at sample " << i;
  }
  EXPECT_EQ(a.path_length_m, b.path_length_m);
  EXPECT_EQ(a.abs_roll_deg.var, b.abs_roll_deg.var);
}

TEST(EpisodeTest, ShortTimeLimitIsATimeout) {
  EpisodeRules rules;
  rules.time_limit_s = 3.0;
  rules.trajectory_every_n_steps = 7;
  const TrialResult r = RunTrial(FlatTask(), Hmmwv(), TrialSpec(), rules);
  EXPECT_EQ(r.status, TrialStatus::kTimeout) << r.message;
  EXPECT_NEAR(r.sim_time_s, 3.0, 1e-9);
  EXPECT_EQ(r.traversal_time_s, -1.0);
  // Samples at steps 0, 7, ..., 595, then the final step 600.
  EXPECT_EQ(r.trajectory.size(), 600u / 7 + 2);
  EXPECT_EQ(r.trajectory.back().time_s, r.sim_time_s);
}

TEST(EpisodeTest, WallOfRocksGetsStuckAndCountsContacts) {
  terrain::TaskSpec task = FlatTask();
  for (double y = -62.0; y <= 62.0; y += 4.0) task.rocks.push_back({0.0, y, 1.0});
  EpisodeRules rules;
  rules.time_limit_s = 25.0;
  const TrialResult r = RunTrial(task, Hmmwv(), TrialSpec(), rules);
  EXPECT_TRUE(r.status == TrialStatus::kStuck || r.status == TrialStatus::kTimeout)
      << TrialStatusName(r.status) << ": " << r.message;
  EXPECT_GE(r.obstacle_contacts, 1);
  EXPECT_LT(r.trajectory.back().position_W.x(), 0.0);
  EXPECT_GT(r.final_goal_distance_m, 10.0);
}

TEST(EpisodeTest, SetUpErrorsAreInputErrors) {
  const terrain::TaskSpec task = FlatTask();
  TrialSpec spec;
  spec.pair_index = 1;
  EXPECT_THROW(RunTrial(task, Hmmwv(), spec), InputError);
  spec.pair_index = -1;
  EXPECT_THROW(RunTrial(task, Hmmwv(), spec), InputError);
  spec.pair_index = 0;
  spec.system = "teleport";
  try {
    RunTrial(task, Hmmwv(), spec);
    FAIL() << "unknown system accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "system");
    EXPECT_NE(std::string(e.what()).find("valid: pid"), std::string::npos) << e.what();
  }
}

TEST(EpisodeTest, DeformableTerrainWithoutSoilParametersIsRefused) {
  terrain::TaskSpec task = FlatTask();
  task.patches.classes[17] = terrain::SurfaceClass::kMud;
  task.patches.friction[17] = 0.0;
  try {
    RunTrial(task, Hmmwv(), TrialSpec());
    FAIL() << "deformable task accepted without soil parameters";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "synthetic_flat.yaml");
    EXPECT_EQ(e.key(), "semantics.classes");
    EXPECT_NE(std::string(e.what()).find("soil parameters"), std::string::npos) << e.what();
  }
}

// A mixed world (a mud band across the path of a flat dirt world) runs with the soil solver:
// the wheels report sinkage on the mud and none on the dirt, and the HMMWV still gets through.
TEST(EpisodeTest, MixedWorldRunsWithTheSoilSolver) {
  terrain::TaskSpec task = FlatTask();
  for (int r = 0; r < 16; ++r) {
    for (int c = 6; c <= 8; ++c) {  // x in [-16, 8] m
      task.patches.classes[static_cast<size_t>(r * 16 + c)] = terrain::SurfaceClass::kMud;
      task.patches.friction[static_cast<size_t>(r * 16 + c)] = 0.0;
    }
  }
  const soil::SoilConfig soil = io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
  const TrialResult r = RunTrial(task, Hmmwv(), TrialSpec(), EpisodeRules(), &soil);
  EXPECT_EQ(r.status, TrialStatus::kSuccess) << r.message;
  double max_sinkage_mud = 0.0, max_sinkage_dirt = 0.0;
  for (const TrajectorySample& s : r.trajectory) {
    for (size_t w = 0; w < s.wheel_surface.size(); ++w) {
      if (s.wheel_surface[w] == static_cast<int>(terrain::SurfaceClass::kMud)) {
        max_sinkage_mud = std::max(max_sinkage_mud, s.wheel_sinkage_m[w]);
      } else {
        max_sinkage_dirt = std::max(max_sinkage_dirt, s.wheel_sinkage_m[w]);
      }
    }
  }
  EXPECT_GT(max_sinkage_mud, 0.03);
  EXPECT_LT(max_sinkage_mud, 0.25);
  EXPECT_EQ(max_sinkage_dirt, 0.0);
}

// The step timings (benchmarks) never change a result: the same mixed-world trial with and
// without them is bit-identical, and the soil's time and counters are reported.
TEST(EpisodeTest, StepTimingsLeaveResultsUnchangedAndCountTheSoil) {
  terrain::TaskSpec task = FlatTask();
  for (int r = 0; r < 16; ++r) {
    for (int c = 6; c <= 8; ++c) {
      task.patches.classes[static_cast<size_t>(r * 16 + c)] = terrain::SurfaceClass::kMud;
      task.patches.friction[static_cast<size_t>(r * 16 + c)] = 0.0;
    }
  }
  const soil::SoilConfig soil = io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
  EpisodeRules plain;
  plain.time_limit_s = 8.0;
  EpisodeRules timed = plain;
  StepTimings timings;
  timed.timings = &timings;
  const TrialResult a = RunTrial(task, Hmmwv(), TrialSpec(), plain, &soil);
  const TrialResult b = RunTrial(task, Hmmwv(), TrialSpec(), timed, &soil);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (size_t i = 0; i < a.trajectory.size(); ++i) {
    ASSERT_TRUE(a.trajectory[i].position_W == b.trajectory[i].position_W &&
                a.trajectory[i].wheel_sinkage_m == b.trajectory[i].wheel_sinkage_m)
        << "first difference at sample " << i;
  }
  EXPECT_EQ(timings.steps, static_cast<long>(a.trajectory.size()) - 1);
  EXPECT_GT(timings.soil_s, 0.0);
  EXPECT_GE(timings.vehicle_sync_s, 0.0);
  EXPECT_GT(timings.soil_contact_nodes, 0);
  EXPECT_GT(timings.soil_tiles, 0);
  EXPECT_GT(timings.soil_memory_bytes, 0u);
}

// The Episode API directly: control periods, a reused episode, provisional results, the ways a
// trial ends from outside.

// Steps a fresh episode of the flat task with full throttle, straight, for `periods` periods.
TrialResult DriveStraight(Episode* episode, int periods) {
  episode->Reset(TrialSpec());
  for (int i = 0; i < periods && !episode->Done(); ++i) episode->Step({1.0, 0.0, 0.0});
  return episode->Result();
}

TEST(EpisodeApiTest, ControlPeriodOfTenStepsEqualsTenSingleSteps) {
  const terrain::TaskSpec task = FlatTask();
  EpisodeRules fine;
  EpisodeRules coarse;
  coarse.control_period_s = 0.05;
  Episode a(task, Hmmwv(), fine), b(task, Hmmwv(), coarse);
  EXPECT_EQ(b.steps_per_control_period(), 10);
  const TrialResult ra = DriveStraight(&a, 300);
  const TrialResult rb = DriveStraight(&b, 30);
  EXPECT_EQ(a.physics_steps(), 300);
  EXPECT_EQ(b.physics_steps(), 300);
  ASSERT_EQ(ra.trajectory.size(), rb.trajectory.size());
  EXPECT_TRUE(ra.trajectory.back().position_W == rb.trajectory.back().position_W);
  EXPECT_EQ(TrialDigestOf(ra), TrialDigestOf(rb));
}

TEST(EpisodeApiTest, AResetEpisodeRepeatsItsTrialBitForBit) {
  const terrain::TaskSpec task = FlatTask();
  Episode episode(task, Hmmwv());
  const TrialResult first = DriveStraight(&episode, 500);
  const TrialResult second = DriveStraight(&episode, 500);
  EXPECT_EQ(TrialDigestOf(first), TrialDigestOf(second));
  // and RunTrial's loop is the same episode with PID
  const TrialResult via_run_trial = RunTrial(task, Hmmwv(), TrialSpec());
  Episode manual(task, Hmmwv());
  std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
  manual.SetObservationConfig(pid->observation_config());
  manual.Reset(TrialSpec());
  pid->Reset(manual.context());
  while (!manual.Done()) manual.Step(pid->Update(manual.Observe()));
  EXPECT_EQ(TrialDigestOf(manual.TakeResult()), TrialDigestOf(via_run_trial));
}

// RunTrial on an episode built beforehand (vb_batch builds one per world and its trials' workers
// inherit it) gives the trial RunTrial builds itself, bit for bit, also when the episode already
// ran another pair: on a deformable world with obstacles and the soil solver.
TEST(EpisodeApiTest, ATrialOnAPrebuiltEpisodeIsTheTrialOnAFreshOne) {
  const terrain::TaskSpec task = io::LoadTask(VB_SOURCE_DIR "/tasks/env061.yaml");
  const soil::SoilConfig soil =
      io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
  EpisodeRules rules;
  rules.time_limit_s = 4.0;
  rules.trajectory_every_n_steps = 10;
  TrialSpec pair0, pair1;
  pair1.pair_index = 1;
  const TrialResult fresh0 = RunTrial(task, Hmmwv(), pair0, rules, &soil);
  const TrialResult fresh1 = RunTrial(task, Hmmwv(), pair1, rules, &soil);
  Episode world(task, Hmmwv(), rules, &soil);
  const TrialResult shared0 = RunTrial(&world, pair0);
  const TrialResult shared1 = RunTrial(&world, pair1);   // after pair 0 on the same episode
  EXPECT_EQ(TrialDigestOf(shared0), TrialDigestOf(fresh0));
  EXPECT_EQ(TrialDigestOf(shared1), TrialDigestOf(fresh1));
  EXPECT_NE(TrialDigestOf(fresh0), TrialDigestOf(fresh1));
  EXPECT_EQ(shared1.trajectory.size(), fresh1.trajectory.size());
}

TEST(EpisodeApiTest, ResultBeforeTheEndIsProvisionalAndStepAfterTheEndDoesNothing) {
  const terrain::TaskSpec task = FlatTask();
  EpisodeRules rules;
  rules.time_limit_s = 2.0;
  Episode episode(task, Hmmwv(), rules);
  const TrialResult mid = DriveStraight(&episode, 100);
  EXPECT_FALSE(episode.Done());
  EXPECT_DOUBLE_EQ(mid.sim_time_s, 0.5);
  EXPECT_EQ(mid.status, TrialStatus::kTimeout);  // what it would be if it ended now
  for (int i = 0; i < 1000; ++i) episode.Step({1.0, 0.0, 0.0});
  EXPECT_TRUE(episode.Done());
  EXPECT_EQ(episode.physics_steps(), 400);
  EXPECT_EQ(episode.Result().status, TrialStatus::kTimeout);
}

TEST(EpisodeApiTest, NonFiniteCommandAndEndWithSimErrorEndTheTrial) {
  const terrain::TaskSpec task = FlatTask();
  Episode episode(task, Hmmwv());
  episode.Reset(TrialSpec());
  episode.Step({0.5, 0.0, 0.0});
  episode.Step({std::nan(""), 0.0, 0.0});
  EXPECT_TRUE(episode.Done());
  EXPECT_EQ(episode.Result().status, TrialStatus::kSimError);
  EXPECT_NE(episode.Result().message.find("non-finite command"), std::string::npos);
  episode.Reset(TrialSpec());
  EXPECT_FALSE(episode.Done());
  episode.EndWithSimError("planner gave up");
  EXPECT_EQ(episode.Result().status, TrialStatus::kSimError);
  EXPECT_EQ(episode.Result().message, "planner gave up");
}

TEST(EpisodeApiTest, BadRulesAreInputErrors) {
  const terrain::TaskSpec task = FlatTask();
  auto key_of = [&](const EpisodeRules& rules) -> std::string {
    try {
      Episode e(task, Hmmwv(), rules);
    } catch (const InputError& e) {
      return e.key();
    }
    return "";
  };
  EpisodeRules r;
  r.control_period_s = 0.0123;  // not a whole number of 5 ms steps
  EXPECT_EQ(key_of(r), "control_period_s");
  r = EpisodeRules();
  r.time_limit_s = 1e308;
  EXPECT_EQ(key_of(r), "time_limit_s");
  r = EpisodeRules();
  r.time_limit_s = std::nan("");
  EXPECT_EQ(key_of(r), "time_limit_s");
  r = EpisodeRules();
  r.step_s = -1.0;
  EXPECT_EQ(key_of(r), "step_s");
  r = EpisodeRules();
  r.trajectory_every_n_steps = -1;
  EXPECT_EQ(key_of(r), "trajectory_every_n_steps");
  // DEF-4 of the probe: one simulated hour at most, and never more than 10^6 trajectory samples
  // (an hour at every step is 720000; with a 1 ms step it would be 3.6e6).
  r = EpisodeRules();
  r.time_limit_s = 3600.5;
  EXPECT_EQ(key_of(r), "time_limit_s");
  r = EpisodeRules();
  r.time_limit_s = 3600.0;
  EXPECT_EQ(key_of(r), "");
  r.step_s = 0.001;
  r.control_period_s = 0.001;
  EXPECT_EQ(key_of(r), "trajectory_every_n_steps");
  r.trajectory_every_n_steps = 4;
  EXPECT_EQ(key_of(r), "");
  for (double v : {0.0, -1.0, 40.5, std::nan(""), 1e308}) {
    r = EpisodeRules();
    r.target_speed_mps = v;
    EXPECT_EQ(key_of(r), "target_speed_mps") << v;
  }
}

// The target speed is a rule of the episode (the original's CLI `speed`): PID holds the speed
// it is given, and the result says which it was.
TEST(EpisodeApiTest, TheTargetSpeedIsTheEpisodesRule) {
  for (double v : {2.0, 6.0}) {
    EpisodeRules rules;
    rules.target_speed_mps = v;
    const TrialResult r = RunTrial(FlatTask(), Hmmwv(), TrialSpec(), rules);
    EXPECT_EQ(r.status, TrialStatus::kSuccess) << r.message;
    EXPECT_EQ(r.target_speed_mps, v);
    // the P controller (gain 1) holds the target within a few per cent on flat dirt
    EXPECT_NEAR(r.trajectory.back().speed_mps, v, 0.06 * v) << v;
    // 30 m to the goal circle: about 30 / v plus the launch
    EXPECT_GT(r.traversal_time_s, 30.0 / v) << v;
    EXPECT_LT(r.traversal_time_s, 30.0 / v + 4.0) << v;
  }
  EXPECT_EQ(RunTrial(FlatTask(), Hmmwv(), TrialSpec()).target_speed_mps, 4.0);
}

TEST(EpisodeApiTest, NoTrajectoryWhenAskedForNone) {
  const terrain::TaskSpec task = FlatTask();
  EpisodeRules rules;
  rules.trajectory_every_n_steps = 0;
  Episode episode(task, Hmmwv(), rules);
  const TrialResult r = DriveStraight(&episode, 200);
  EXPECT_TRUE(r.trajectory.empty());
  EXPECT_GT(r.path_length_m, 1.0);
}

TEST(EpisodeApiTest, LeavingTheWorldIsOutOfBoundsAtOnce) {
  terrain::TaskSpec task = FlatTask();
  task.pairs[0].start_m = Vec2(50.0, 0.0);
  task.pairs[0].goal_m = Vec2(50.0, 40.0);  // due north; the vehicle is driven east instead
  Episode episode(task, Hmmwv());
  episode.Reset(TrialSpec());
  // face east: drive with full left lock until heading east... simpler: the start faces the goal
  // (north); turn right at full lock, then straight: it reaches the east edge (x 64) in seconds
  for (int i = 0; i < 12000 && !episode.Done(); ++i) {
    const double yaw = episode.vehicle_state().rpy.yaw_rad;
    episode.Step({1.0, std::clamp(-2.0 * yaw, -1.0, 1.0), 0.0});
  }
  const TrialResult r = episode.Result();
  EXPECT_EQ(r.status, TrialStatus::kOutOfBounds) << r.message;
  EXPECT_GT(r.trajectory.back().position_W.x(), 64.0);
  EXPECT_LT(r.trajectory[r.trajectory.size() - 2].position_W.x(), 64.0);  // ended at once
  EXPECT_NE(r.message.find("left the world"), std::string::npos);
  EXPECT_EQ(TrialStatusName(TrialStatus::kOutOfBounds), "out_of_bounds");
}

TEST(EpisodeApiTest, TippingPastFortyFiveDegreesIsRecorded) {
  // a 40 deg side slope rising to the north, the vehicle facing east: it rolls over downhill
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, std::tan(40.0 * kPi / 180.0));
  Episode episode(task, Hmmwv());
  episode.Reset(TrialSpec());
  for (int i = 0; i < 2000 && !episode.Done(); ++i) episode.Step({0.0, 0.0, 1.0});
  const TrialResult r = episode.Result();
  EXPECT_TRUE(r.tipped);
  EXPECT_GT(r.abs_roll_deg.max, 45.0);
  // on flat ground nothing tips
  Episode flat(FlatTask(), Hmmwv());
  flat.Reset(TrialSpec());
  for (int i = 0; i < 400; ++i) flat.Step({1.0, 0.0, 0.0});
  EXPECT_FALSE(flat.Result().tipped);
}

// The start drop scales with the world, as the original's (terrain + 1.0 m x scale factor):
// the wheel bottoms start 0.5 m x scale above the ground (a 1/10 world's vehicle 5 cm).
TEST(EpisodeApiTest, TheStartDropScalesWithTheWorld) {
  const vehicles::VehicleParams vw = io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/vw.yaml");
  for (const double scale : {1.0, 0.1}) {
    const vehicles::VehicleParams& vp = scale == 1.0 ? Hmmwv() : vw;
    terrain::TaskSpec task = FlatTask();
    task.scale = scale;
    Episode episode(task, vp);
    episode.Reset(TrialSpec());
    const double wheel_bottom_m = episode.vehicle_state().pose_W.position.z() + vp.axles[0].z_m -
                                  vp.wheel.radius_m;
    EXPECT_NEAR(wheel_bottom_m, EpisodeRules().start_height_m * scale, 1e-9) << scale;
  }
}

TEST(EpisodeTest, StatusNames) {
  EXPECT_EQ(TrialStatusName(TrialStatus::kSuccess), "success");
  EXPECT_EQ(TrialStatusName(TrialStatus::kRollover), "rollover");
  EXPECT_EQ(TrialStatusName(TrialStatus::kStuck), "stuck");
  EXPECT_EQ(TrialStatusName(TrialStatus::kTimeout), "timeout");
  EXPECT_EQ(TrialStatusName(TrialStatus::kSimError), "sim_error");
}

}  // namespace
}  // namespace vb::runner
