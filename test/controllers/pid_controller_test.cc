// PID baseline: steering sign and limits, the speed controller's branches, replanning cadence.
#include "vb/controllers/pid_controller.h"

#include <gtest/gtest.h>

#include "vb/controllers/controller.h"
#include "vb/terrain/grid_planner.h"

namespace vb::controllers {
namespace {

// A free 129 x 129 grid of 1 m cells over a 128 m world, as the benchmark's planning grid.
terrain::OccupancyGrid FreeGrid() {
  terrain::OccupancyGrid g;
  g.rows = 129;
  g.cols = 129;
  g.cell_m = 1.0;
  g.size_x_m = 128.0;
  g.size_y_m = 128.0;
  g.occupied.assign(static_cast<size_t>(g.rows) * g.cols, 0);
  return g;
}

EpisodeContext Context(const terrain::OccupancyGrid* grid, const Vec2& goal) {
  EpisodeContext c;
  c.inflated_obstacles = grid;
  c.goal_m = goal;
  c.scale = 1.0;
  c.step_s = 0.005;
  return c;
}

Observation ObsAt(double t, const Vec2& xy, double yaw, double speed) {
  Observation o;
  o.time_s = t;
  o.position_W = Vec3(xy.x(), xy.y(), 0.0);
  o.rpy.yaw_rad = yaw;
  o.forward_speed_mps = speed;
  return o;
}

TEST(PidControllerTest, RegistryKnowsPid) {
  EXPECT_EQ(ControllerNames(), std::vector<std::string>{"pid"});
  ASSERT_NE(MakeController("pid"), nullptr);
  EXPECT_EQ(MakeController("pid")->name(), "pid");
  EXPECT_EQ(MakeController("mppi"), nullptr);
}

TEST(PidControllerTest, GoalToTheLeftSteersLeftAndRightSteersRight) {
  const terrain::OccupancyGrid grid = FreeGrid();
  PidController left, right;
  left.Reset(Context(&grid, Vec2(0.0, 30.0)));
  right.Reset(Context(&grid, Vec2(0.0, -30.0)));
  // Heading east, goal due north: heading error +90 deg, first step limited to +0.05.
  EXPECT_DOUBLE_EQ(left.Update(ObsAt(0.0, Vec2::Zero(), 0.0, 0.0)).steering, 0.05);
  EXPECT_DOUBLE_EQ(right.Update(ObsAt(0.0, Vec2::Zero(), 0.0, 0.0)).steering, -0.05);
}

TEST(PidControllerTest, SteeringRateLimitedThenClamped) {
  PidController pid;
  pid.Reset(Context(nullptr, Vec2(0.0, 30.0)));  // no grid: straight at the goal
  double prev = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double s = pid.Update(ObsAt(k * 0.005, Vec2::Zero(), 0.0, 4.0)).steering;
    EXPECT_LE(std::abs(s - prev), 0.05 + 1e-15) << "step " << k;
    EXPECT_LE(std::abs(s), 1.0);
    prev = s;
  }
  // kp * error = pi/2 > 1: saturates at exactly 1 after 20 steps of 0.05.
  EXPECT_DOUBLE_EQ(prev, 1.0);
}

TEST(PidControllerTest, SmallHeadingErrorIsTrackedProportionally) {
  PidController pid;
  pid.Reset(Context(nullptr, Vec2(100.0, 0.0)));
  const double yaw = -0.02;  // goal 0.02 rad to the left
  double s = 0.0;
  for (int k = 0; k < 5; ++k) s = pid.Update(ObsAt(k * 0.005, Vec2::Zero(), yaw, 4.0)).steering;
  EXPECT_NEAR(s, 0.02, 1e-12);
}

TEST(PidControllerTest, SpeedControllerBranches) {
  PidController pid;
  pid.Reset(Context(nullptr, Vec2(100.0, 0.0)));
  struct Case {
    double speed, throttle, braking;
  };
  // Target 4 m/s, kp 1: full throttle below 3, proportional in (3, 4), braking above 4.
  for (const Case& c : {Case{0.0, 1.0, 0.0}, Case{3.5, 0.5, 0.0}, Case{4.0, 0.0, 0.0},
                        Case{4.25, 0.0, 0.25}, Case{9.0, 0.0, 1.0}, Case{-2.0, 1.0, 0.0}}) {
    const Command cmd = pid.Update(ObsAt(0.0, Vec2::Zero(), 0.0, c.speed));
    EXPECT_DOUBLE_EQ(cmd.throttle, c.throttle) << "speed " << c.speed;
    EXPECT_DOUBLE_EQ(cmd.braking, c.braking) << "speed " << c.speed;
  }
}

TEST(PidControllerTest, ReplansEveryTwentyStepsOfFiveMilliseconds) {
  const terrain::OccupancyGrid grid = FreeGrid();
  PidController pid;
  pid.Reset(Context(&grid, Vec2(40.0, 0.0)));
  std::vector<int> replan_steps;
  int count = 0;
  for (int k = 0; k <= 200; ++k) {
    pid.Update(ObsAt(k * 0.005, Vec2(-20.0 + 0.02 * k, 0.0), 0.0, 4.0));
    if (pid.replan_count() != count) {
      count = pid.replan_count();
      replan_steps.push_back(k);
    }
  }
  std::vector<int> expected;
  for (int k = 0; k <= 200; k += 20) expected.push_back(k);
  EXPECT_EQ(replan_steps, expected);
  ASSERT_FALSE(pid.path().empty());
  EXPECT_NEAR(pid.path().back().x(), 40.0, 0.5);
}

TEST(PidControllerTest, ResetStartsAFreshEpisode) {
  const terrain::OccupancyGrid grid = FreeGrid();
  PidController pid;
  pid.Reset(Context(&grid, Vec2(0.0, 30.0)));
  for (int k = 0; k < 30; ++k) pid.Update(ObsAt(k * 0.005, Vec2::Zero(), 0.0, 0.0));
  pid.Reset(Context(&grid, Vec2(0.0, 30.0)));
  EXPECT_EQ(pid.replan_count(), 0);
  EXPECT_DOUBLE_EQ(pid.Update(ObsAt(0.0, Vec2::Zero(), 0.0, 0.0)).steering, 0.05);
}

}  // namespace
}  // namespace vb::controllers
