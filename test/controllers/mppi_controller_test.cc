// MPPI baseline controller in closed loop with a kinematic vehicle on hand-made worlds: it
// steers around a single rock on a plane towards a goal behind it, runs at 20 Hz, is
// deterministic with a seed, and a clone continues bit for bit.
#include "vb/controllers/mppi_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/worlds.h"
#include "vb/terrain/gt_maps.h"

namespace vb::controllers {
namespace {

// A plane with one rock (scale 1: a 5 x 5 cell footprint) at the origin.
terrain::TaskSpec RockTask() {
  terrain::TaskSpec t = test::PlaneTask(128.0);
  terrain::RockSpec rock;
  rock.x_m = 0.0;
  rock.y_m = 0.0;
  rock.scale = 1.0;
  t.rocks.push_back(rock);
  return t;
}

struct KinematicRun {
  std::vector<Vec2> path;
  std::vector<double> steering;
  long updates = 0;
};

// Drives a kinematic bicycle (HMMWV wheelbase 3.378 m, 0.6 rad wheel angle at full steering,
// 4 m/s) with the controller's steering for `seconds`, local goal fixed at `goal`.
KinematicRun Drive(Controller* c, const Vec2& start, double yaw, const Vec2& goal, double seconds,
                   std::vector<double>* first_steps = nullptr) {
  KinematicRun run;
  Vec2 p = start;
  const double dt = 0.005;
  for (int i = 0; i < static_cast<int>(seconds / dt); ++i) {
    Observation o;
    o.time_s = i * dt;
    o.position_W = Vec3(p.x(), p.y(), 0.0);
    o.rpy.yaw_rad = yaw;
    o.forward_speed_mps = 4.0;
    o.local_goal_m = goal;
    o.goal_m = goal;
    const Vec2 d = goal - p;
    o.heading_error_rad = WrapAngle(std::atan2(d.y(), d.x()) - yaw);
    const Command cmd = c->Update(o);
    run.steering.push_back(cmd.steering);
    yaw += 4.0 * dt / 3.378 * std::tan(0.6 * cmd.steering);
    p += 4.0 * dt * Vec2(std::cos(yaw), std::sin(yaw));
    run.path.push_back(p);
    if ((p - goal).norm() < 2.0) break;
  }
  if (first_steps != nullptr) *first_steps = run.steering;
  return run;
}

EpisodeContext ContextOf(const terrain::TaskSpec& task, const terrain::GroundTruthMaps& maps) {
  EpisodeContext c;
  c.task = &task;
  c.maps = &maps;
  c.control_period_s = 0.005;
  c.seed = 0;
  return c;
}

TEST(MppiControllerTest, SteersAroundARockOnAPlane) {
  const terrain::TaskSpec task = RockTask();
  const terrain::GroundTruthMaps maps(task);   // bare footprints: |x|, |y| <= 2.5 m
  ASSERT_EQ(maps.Sample(terrain::MapLayer::kOccupancy, Vec2(0, 0)), 1.0);
  ASSERT_EQ(maps.Sample(terrain::MapLayer::kOccupancy, Vec2(2.2, 2.2)), 1.0);
  MppiController mppi;
  mppi.Reset(ContextOf(task, maps));
  const Vec2 goal(20.0, 0.0);
  const KinematicRun run = Drive(&mppi, Vec2(-20.0, 0.0), 0.0, goal, 20.0);
  // The cost sees the vehicle as its reference point on the 1 m footprint cells, checked at the
  // rollout steps (~0.4 m apart): the path may graze a footprint corner between two steps but
  // never enters the rock's 4.4 m box.
  double closest_lateral = 1e9;
  for (const Vec2& p : run.path) {
    EXPECT_FALSE(std::abs(p.x()) < 2.2 && std::abs(p.y()) < 2.2) << p.transpose();
    if (std::abs(p.x()) < 2.2) closest_lateral = std::min(closest_lateral, std::abs(p.y()));
  }
  EXPECT_GT(closest_lateral, 2.2);                         // passed beside the rock
  EXPECT_LT((run.path.back() - goal).norm(), 2.0);         // and reached the goal
  // 20 Hz: one update per 10 steps of 5 ms
  EXPECT_EQ(mppi.updates(), (static_cast<long>(run.path.size()) + 9) / 10);
}

TEST(MppiControllerTest, OnAnOpenPlaneItHeadsStraightForTheGoal) {
  const terrain::TaskSpec task = test::PlaneTask(128.0);
  const terrain::GroundTruthMaps maps(task);
  MppiController mppi;
  mppi.Reset(ContextOf(task, maps));
  // goal 30 deg to the left: the first decisions steer left, and it gets there
  const Vec2 goal(-20.0 + 30.0 * std::cos(0.5236), 30.0 * std::sin(0.5236));
  const KinematicRun run = Drive(&mppi, Vec2(-20.0, 0.0), 0.0, goal, 20.0);
  EXPECT_GT(run.steering.front(), 0.2);
  EXPECT_LT((run.path.back() - goal).norm(), 2.0);
}

TEST(MppiControllerTest, DeterministicWithASeedAndClonesContinueIdentically) {
  const terrain::TaskSpec task = RockTask();
  const terrain::GroundTruthMaps maps(task);
  MppiController a, b;
  a.Reset(ContextOf(task, maps));
  b.Reset(ContextOf(task, maps));
  const KinematicRun ra = Drive(&a, Vec2(-20.0, 1.0), 0.0, Vec2(20.0, 0.0), 3.0);
  const KinematicRun rb = Drive(&b, Vec2(-20.0, 1.0), 0.0, Vec2(20.0, 0.0), 3.0);
  EXPECT_EQ(ra.steering, rb.steering);
  // another seed draws other samples
  MppiController c;
  EpisodeContext other = ContextOf(task, maps);
  other.seed = 1;
  c.Reset(other);
  EXPECT_NE(Drive(&c, Vec2(-20.0, 1.0), 0.0, Vec2(20.0, 0.0), 3.0).steering, ra.steering);
  // a clone made mid-run continues as the original
  std::unique_ptr<Controller> clone = a.Clone();
  Observation o;
  o.time_s = 3.0;
  o.position_W = Vec3(-8.0, 0.5, 0.0);
  o.local_goal_m = Vec2(20.0, 0.0);
  for (int i = 0; i < 30; ++i) {
    o.time_s += 0.005;
    EXPECT_EQ(a.Update(o).steering, clone->Update(o).steering) << i;
  }
}

}  // namespace
}  // namespace vb::controllers
