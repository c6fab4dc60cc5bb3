// Teleoperation session on a scripted clock: real-time pacing, commands held per control period,
// the recording, bad messages, and that a recorded drive replays to the same bits.
#include "view/teleop_session.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <set>

#include "support/worlds.h"

namespace vb::view {
namespace {

// The server's loop: the session is advanced every few milliseconds of wall time.
void AdvanceSmoothly(TeleopSession* s, double from_s, double to_s) {
  for (double t = from_s; t < to_s; t += 0.004) s->AdvanceTo(t);
  s->AdvanceTo(to_s);
}

TeleopOptions Options() {
  TeleopOptions o;
  o.vehicle = "hmmwv";
  return o;
}

TEST(TeleopSessionTest, SimulatedTimeFollowsTheWallClockAndCommandsAreRecorded) {
  const terrain::TaskSpec task = test::PlaneTask();
  TeleopSession s(task, test::Hmmwv(), nullptr, Options());
  EXPECT_FALSE(s.driving());
  ASSERT_EQ(s.HandleMessage("start", 100.0), "");
  EXPECT_TRUE(s.driving());
  AdvanceSmoothly(&s, 100.0, 100.5);
  EXPECT_NEAR(s.episode().time_s(), 0.5, 0.0025);
  ASSERT_EQ(s.HandleMessage("command 1 0 0", 100.5), "");
  AdvanceSmoothly(&s, 100.5, 102.5);
  EXPECT_NEAR(s.episode().time_s(), 2.5, 0.0025);
  ASSERT_EQ(s.HandleMessage("command 0 0.25 1", 102.5), "");
  AdvanceSmoothly(&s, 102.5, 103.0);
  ASSERT_EQ(s.HandleMessage("stop", 103.0), "");
  EXPECT_FALSE(s.driving());
  ASSERT_TRUE(s.has_finished_drive());
  const runner::TrialResult r = s.TakeFinishedDrive();
  EXPECT_FALSE(s.has_finished_drive());
  EXPECT_EQ(r.spec.system, "teleop");
  EXPECT_EQ(r.spec.vehicle, "hmmwv");
  // Stopped, not decided by the rules: the status as it stood, and a message that says so.
  EXPECT_EQ(r.status, runner::TrialStatus::kTimeout);
  EXPECT_EQ(r.message, "stopped by the operator at t = 3.000 s (outcome as it stood: timeout, "
                       "still driving)");
  // 3.0 s at 5 ms: the start sample and one per physics step.
  ASSERT_EQ(r.trajectory.size(), 601u);
  EXPECT_NEAR(r.sim_time_s, 3.0, 1e-9);
  for (const runner::TrajectorySample& p : r.trajectory) {
    const double t = p.time_s;
    SCOPED_TRACE(t);
    if (t <= 0.5 + 1e-9) {
      EXPECT_EQ(p.throttle, 0.0);
    } else if (t <= 2.5 + 1e-9) {
      EXPECT_EQ(p.throttle, 1.0);
      EXPECT_EQ(p.steering, 0.0);
      EXPECT_EQ(p.braking, 0.0);
    } else {
      EXPECT_EQ(p.throttle, 0.0);
      EXPECT_EQ(p.steering, 0.25);
      EXPECT_EQ(p.braking, 1.0);
    }
  }
  // Two seconds of full throttle on flat concrete moved the HMMWV forward (towards the goal,
  // +x) by metres, not centimetres.
  const Vec3 start = r.trajectory.front().position_W;
  const Vec3 at_release = r.trajectory[500].position_W;
  EXPECT_GT(at_release.x() - start.x(), 2.0);
  EXPECT_LT(std::abs(at_release.y() - start.y()), 0.2);
}

TEST(TeleopSessionTest, RecordedDriveReplaysToTheSameBits) {
  const terrain::TaskSpec task = test::PlaneTask();
  TeleopSession s(task, test::Hmmwv(), nullptr, Options());
  ASSERT_EQ(s.HandleMessage("start", 0.0), "");
  const char* script[] = {"command 0.6 0 0", "command 1 0.3 0", "command 0.2 -0.5 0",
                          "command 0 0 0.8"};
  double wall = 0.0;
  for (const char* c : script) {
    // Not on a control-period boundary: the session rounds, not the test.
    AdvanceSmoothly(&s, wall, wall + 0.4013);
    wall += 0.4013;
    ASSERT_EQ(s.HandleMessage(c, wall), "");
  }
  AdvanceSmoothly(&s, wall, wall + 0.5);
  ASSERT_EQ(s.HandleMessage("stop", wall + 0.5), "");
  const runner::TrialResult rec = s.TakeFinishedDrive();
  // All four commands are in the recording (the replay below is not of a constant input).
  std::set<double> steering;
  for (const runner::TrajectorySample& p : rec.trajectory) steering.insert(p.steering);
  EXPECT_EQ(steering, (std::set<double>{0.0, 0.3, -0.5}));

  // Replay: the recorded command of every step, into a fresh episode.
  runner::EpisodeRules rules;
  rules.trajectory_every_n_steps = 1;
  runner::Episode replay(task, test::Hmmwv(), rules);
  runner::TrialSpec spec;
  spec.system = "teleop";
  replay.Reset(spec);
  // Sample 0 is the start state; sample k >= 1 carries the command of physics step k.
  for (size_t k = 1; k < rec.trajectory.size(); ++k) {
    const runner::TrajectorySample& p = rec.trajectory[k];
    replay.Step({p.throttle, p.steering, p.braking});
  }
  const runner::TrialResult again = replay.TakeResult();
  ASSERT_EQ(again.trajectory.size(), rec.trajectory.size());
  for (size_t i = 0; i < rec.trajectory.size(); ++i) {
    ASSERT_EQ(again.trajectory[i].position_W, rec.trajectory[i].position_W) << i;
    ASSERT_EQ(again.trajectory[i].rpy.yaw_rad, rec.trajectory[i].rpy.yaw_rad) << i;
  }
}

TEST(TeleopSessionTest, DropsTheBacklogOfAStalledClock) {
  const terrain::TaskSpec task = test::PlaneTask();
  TeleopSession s(task, test::Hmmwv(), nullptr, Options());
  ASSERT_EQ(s.HandleMessage("start", 10.0), "");
  s.AdvanceTo(70.0);   // a minute without stepping: the vehicle must not race through it
  EXPECT_NEAR(s.episode().time_s(), 0.25, 0.0025);
  EXPECT_NEAR(s.slipped_s(), 59.75, 1e-9);
  AdvanceSmoothly(&s, 70.0, 70.1);
  EXPECT_NEAR(s.episode().time_s(), 0.35, 0.0025);
}

TEST(TeleopSessionTest, BadMessagesAreRejectedAndChangeNothing) {
  const terrain::TaskSpec task = test::PlaneTask();
  TeleopSession s(task, test::Hmmwv(), nullptr, Options());
  EXPECT_NE(s.HandleMessage("stop", 0.0).find("no drive"), std::string::npos);
  ASSERT_EQ(s.HandleMessage("start", 0.0), "");
  ASSERT_EQ(s.HandleMessage("command 0.5 0.1 0", 0.0), "");
  EXPECT_NE(s.HandleMessage("command 1.5 0 0", 0.0).find("throttle 1.5 is outside [0, 1]"),
            std::string::npos);
  EXPECT_NE(s.HandleMessage("command 0 -2 0", 0.0).find("steering"), std::string::npos);
  EXPECT_NE(s.HandleMessage("command 0 0 nan", 0.0).find("braking 'nan' is not a number"),
            std::string::npos);
  EXPECT_NE(s.HandleMessage("command 1e x 0", 0.0).find("not a number"), std::string::npos);
  // W10 of the probe at 8ff4def: strtod read "0x1" as 1.0; the protocol says plain decimal.
  EXPECT_NE(s.HandleMessage("command 0x1 0 0", 0.0).find("throttle '0x1' is not a number"),
            std::string::npos);
  EXPECT_NE(s.HandleMessage("command 1 0", 0.0).find("THROTTLE STEERING BRAKING"),
            std::string::npos);
  EXPECT_NE(s.HandleMessage("", 0.0).find("empty"), std::string::npos);
  EXPECT_NE(s.HandleMessage("jump", 0.0).find("unknown message 'jump'"), std::string::npos);
  EXPECT_NE(s.HandleMessage("start now", 0.0).find("no arguments"), std::string::npos);
  EXPECT_NE(s.HandleMessage("start", 0.0).find("a drive is running"), std::string::npos);
  EXPECT_EQ(s.command().throttle, 0.5);
  EXPECT_EQ(s.command().steering, 0.1);
  EXPECT_TRUE(s.driving());
}

TEST(TeleopSessionTest, PairOutOfRangeIsAnInputError) {
  TeleopOptions o = Options();
  o.pair = 3;
  EXPECT_THROW(TeleopSession(test::PlaneTask(), test::Hmmwv(), nullptr, o), InputError);
}

TEST(TeleopSessionTest, StateMessageDescribesTheVehicle) {
  const terrain::TaskSpec task = test::PlaneTask();
  TeleopSession s(task, test::Hmmwv(), nullptr, Options());
  EXPECT_EQ(s.StateJson(), "{\"type\": \"state\", \"drive\": 0, \"driving\": false}");
  ASSERT_EQ(s.HandleMessage("start", 0.0), "");
  s.AdvanceTo(0.1);
  const std::string j = s.StateJson();
  EXPECT_NE(j.find("\"driving\": true"), std::string::npos) << j;
  EXPECT_NE(j.find("\"status\": \"driving\""), std::string::npos) << j;
  const auto number = [&](const std::string& key) {
    std::smatch m;
    const std::regex re("\"" + key + "\": ([-+0-9.eE]+)");
    EXPECT_TRUE(std::regex_search(j, m, re)) << key << " in " << j;
    return m.empty() ? NAN : std::stod(m[1]);
  };
  EXPECT_NEAR(number("x_m"), -20.0, 0.05);   // dropped at the start (-20, 0), facing +x
  EXPECT_NEAR(number("y_m"), 0.0, 0.05);
  EXPECT_NEAR(number("yaw_deg"), 0.0, 0.5);
  EXPECT_NEAR(number("goal_distance_m"), 40.0, 0.05);
  EXPECT_NEAR(number("t_s"), 0.1, 0.0026);
}

}  // namespace
}  // namespace vb::view
