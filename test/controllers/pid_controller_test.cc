// PID baseline: steering sign and limits, the speed controller's branches, its navigation
// settings (the replanning itself is the observation builder's: observation_builder_test.cc).
#include "vb/controllers/pid_controller.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/model_store.h"
#include "vb/controllers/controller.h"

namespace vb::controllers {
namespace {

EpisodeContext Context() {
  EpisodeContext c;
  c.scale = 1.0;
  c.step_s = 0.005;
  c.control_period_s = 0.005;
  return c;
}

// An observation at the origin heading `yaw` with the local goal at `local_goal`.
Observation ObsAt(double t, const Vec2& local_goal, double yaw, double speed) {
  Observation o;
  o.time_s = t;
  o.rpy.yaw_rad = yaw;
  o.forward_speed_mps = speed;
  o.local_goal_m = local_goal;
  o.heading_error_rad = WrapAngle(std::atan2(local_goal.y(), local_goal.x()) - yaw);
  return o;
}

TEST(PidControllerTest, RegistryKnowsPid) {
  EXPECT_EQ(ControllerNames(),
            (std::vector<std::string>{"pid", "eh", "mppi", "rl", "mcl", "acl", "wmvct", "mppi6",
                                      "tal", "tnt", "pid_original", "eh_original",
                                      "mppi_original", "straight"}));
  const io::DataDirModelStore models(VB_SOURCE_DIR "/data");   // the learned systems' weights
  for (const std::string& name : ControllerNames()) {
    ASSERT_NE(MakeController(name, &models), nullptr) << name;
    EXPECT_EQ(MakeController(name, &models)->name(), name);
  }
  EXPECT_EQ(MakeController("no_such_system"), nullptr);
}

TEST(PidControllerTest, StraightSteersAtTheGoalNotTheLocalGoal) {
  std::unique_ptr<Controller> straight = MakeController("straight");
  std::unique_ptr<Controller> pid = MakeController("pid");
  straight->Reset(Context());
  pid->Reset(Context());
  Observation o = ObsAt(0.0, Vec2(5.0, 5.0), 0.0, 0.0);   // local goal ahead-left
  o.goal_m = Vec2(50.0, -50.0);                              // goal ahead-right
  EXPECT_NEAR(pid->Update(o).steering, 0.05, 1e-12);        // rate limit 0.05 per 5 ms
  EXPECT_NEAR(straight->Update(o).steering, -0.05, 1e-12);
  EXPECT_EQ(straight->name(), "straight");
}

TEST(PidControllerTest, GoalToTheLeftSteersLeftAndRightSteersRight) {
  PidController left, right;
  left.Reset(Context());
  right.Reset(Context());
  // Heading east, local goal due north: heading error +90 deg, first step limited to +0.05.
  EXPECT_DOUBLE_EQ(left.Update(ObsAt(0.0, Vec2(0.0, 30.0), 0.0, 0.0)).steering, 0.05);
  EXPECT_DOUBLE_EQ(right.Update(ObsAt(0.0, Vec2(0.0, -30.0), 0.0, 0.0)).steering, -0.05);
}

TEST(PidControllerTest, SteeringRateLimitedThenClamped) {
  PidController pid;
  pid.Reset(Context());
  double prev = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double s = pid.Update(ObsAt(k * 0.005, Vec2(0.0, 30.0), 0.0, 4.0)).steering;
    EXPECT_LE(std::abs(s - prev), 0.05 + 1e-15) << "step " << k;
    EXPECT_LE(std::abs(s), 1.0);
    prev = s;
  }
  // kp * error = pi/2 > 1: saturates at exactly 1 after 20 steps of 0.05.
  EXPECT_DOUBLE_EQ(prev, 1.0);
}

TEST(PidControllerTest, RateLimitFollowsTheControlPeriod) {
  PidController pid;
  EpisodeContext c = Context();
  c.control_period_s = 0.1;  // 10 units/s over 0.1 s: up to 1.0 per call
  pid.Reset(c);
  EXPECT_DOUBLE_EQ(pid.Update(ObsAt(0.0, Vec2(10.0, 3.0), 0.0, 4.0)).steering,
                   std::atan2(3.0, 10.0));
}

TEST(PidControllerTest, SmallHeadingErrorIsTrackedProportionally) {
  PidController pid;
  pid.Reset(Context());
  const double yaw = -0.02;  // goal 0.02 rad to the left
  double s = 0.0;
  for (int k = 0; k < 5; ++k) s = pid.Update(ObsAt(k * 0.005, Vec2(100.0, 0.0), yaw, 4.0)).steering;
  EXPECT_NEAR(s, 0.02, 1e-12);
}

TEST(PidControllerTest, SpeedControllerBranches) {
  PidController pid;
  pid.Reset(Context());
  struct Case {
    double speed, throttle, braking;
  };
  // Target 4 m/s, kp 1: full throttle below 3, proportional in (3, 4), braking above 4.
  for (const Case& c : {Case{0.0, 1.0, 0.0}, Case{3.5, 0.5, 0.0}, Case{4.0, 0.0, 0.0},
                        Case{4.25, 0.0, 0.25}, Case{9.0, 0.0, 1.0}, Case{-2.0, 1.0, 0.0}}) {
    const Command cmd = pid.Update(ObsAt(0.0, Vec2(100.0, 0.0), 0.0, c.speed));
    EXPECT_DOUBLE_EQ(cmd.throttle, c.throttle) << "speed " << c.speed;
    EXPECT_DOUBLE_EQ(cmd.braking, c.braking) << "speed " << c.speed;
  }
}

TEST(PidControllerTest, AsksForTheOriginalsNavigation) {
  const ObservationConfig c = PidController().observation_config();
  EXPECT_EQ(c.lookahead_m, 10.0);
  EXPECT_EQ(c.replan_period_s, 0.1);
  EXPECT_TRUE(c.crops.empty());
}

TEST(PidControllerTest, ResetStartsAFreshEpisodeAndCloneKeepsTheState) {
  PidController pid;
  pid.Reset(Context());
  for (int k = 0; k < 30; ++k) pid.Update(ObsAt(k * 0.005, Vec2(0.0, 30.0), 0.0, 0.0));
  // A clone continues from the same steering (1.0 after 20+ steps), the reset one from zero.
  std::unique_ptr<Controller> clone = pid.Clone();
  pid.Reset(Context());
  EXPECT_DOUBLE_EQ(pid.Update(ObsAt(0.0, Vec2(0.0, 30.0), 0.0, 0.0)).steering, 0.05);
  EXPECT_DOUBLE_EQ(clone->Update(ObsAt(0.15, Vec2(0.0, 30.0), 0.0, 0.0)).steering, 1.0);
}

}  // namespace
}  // namespace vb::controllers
