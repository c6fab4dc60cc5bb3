// The observation builder on synthetic worlds with known answers: crop axes and values on a ramp
// and around a single rock, the friction layer, the robot state in the vehicle frame, and the
// navigation (replanning cadence, local goal, heading error) that the path followers use.
#include "vb/engine/runner/observation_builder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/worlds.h"
#include "vb/engine/runner/episode.h"

namespace vb::runner {
namespace {

terrain::OccupancyGrid PlanningGrid(const terrain::TaskSpec& task) {
  return terrain::Inflate(terrain::RasterizeObstacles(task), terrain::PlannerInflationCells(task));
}

vehicles::VehicleState StateAt(const Vec2& xy, double yaw) {
  vehicles::VehicleState s;
  s.pose_W.position = Vec3(xy.x(), xy.y(), 0.0);
  s.pose_W.rotation = FromYaw(yaw);
  s.rpy.yaw_rad = yaw;
  return s;
}

TEST(ObservationBuilderTest, RampCropsFollowTheHeadingAtTheConfiguredResolution) {
  const terrain::TaskSpec task = test::PlaneTask(64.0, 0.2, 0.0);  // h = 0.2 x
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid grid = PlanningGrid(task);
  ObservationBuilder b(maps, grid, 1.0);
  controllers::ObservationConfig config;
  config.crops = {{terrain::MapLayer::kElevation, 8, 0.5},
                  {terrain::MapLayer::kFriction, 4, 1.0}};
  b.SetConfig(config);
  b.Reset(Vec2(20.0, 0.0));
  controllers::Observation obs;
  for (double yaw : {0.0, 0.5 * kPi, -2.0}) {
    b.Build(0.0, StateAt(Vec2(3.0, -4.0), yaw), &obs);
    ASSERT_EQ(obs.crops.size(), 2u);
    const terrain::GridMap& e = obs.crops[0];
    ASSERT_EQ(e.rows, 8);
    EXPECT_EQ(e.resolution_m, 0.5);
    for (int i = 0; i < 8; ++i) {
      for (int j = 0; j < 8; ++j) {
        const double forward = (3.5 - i) * 0.5, left = (3.5 - j) * 0.5;
        const double x = 3.0 + std::cos(yaw) * forward - std::sin(yaw) * left;
        EXPECT_NEAR(e.At(i, j), 0.2 * x, 1e-12) << "yaw " << yaw << " cell " << i << "," << j;
      }
    }
    for (double mu : obs.crops[1].values) EXPECT_EQ(mu, 0.9);  // PlaneTask's concrete
  }
}

TEST(ObservationBuilderTest, CropsScaleWithTheEnvironment) {
  terrain::TaskSpec task = test::PlaneTask(64.0, 0.2, 0.0);
  task.scale = 0.5;
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid grid = PlanningGrid(task);
  ObservationBuilder b(maps, grid, task.scale);
  controllers::ObservationConfig config;
  config.crops = {{terrain::MapLayer::kElevation, 4, 0.2}};
  b.SetConfig(config);
  b.Reset(Vec2(20.0, 0.0));
  controllers::Observation obs;
  b.Build(0.0, StateAt(Vec2(0.0, 0.0), 0.0), &obs);
  EXPECT_DOUBLE_EQ(obs.crops[0].resolution_m, 0.1);
  EXPECT_NEAR(obs.crops[0].At(0, 0) - obs.crops[0].At(3, 0), 0.2 * 3 * 0.1, 1e-12);
}

TEST(ObservationBuilderTest, SingleRockOccupancyAndTheLocalGoalAroundIt) {
  terrain::TaskSpec task = test::PlaneTask(64.0);
  task.rocks.push_back({10.0, 0.0, 0.7});  // footprint x 9..11, y -1..1 (3 cells)
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid grid = PlanningGrid(task);
  ObservationBuilder b(maps, grid, 1.0);
  controllers::ObservationConfig config;
  config.crops = {{terrain::MapLayer::kOccupancy, 32, 1.0}};
  b.SetConfig(config);
  b.Reset(Vec2(25.0, 0.0));
  controllers::Observation obs;
  b.Build(0.0, StateAt(Vec2(0.0, 0.0), 0.0), &obs);
  // rock 10 m ahead (rows 5-6 = x 10.5/9.5), on the centre line (columns 15-16)
  EXPECT_EQ(obs.crops[0].At(5, 15), 1.0);
  EXPECT_EQ(obs.crops[0].At(6, 16), 1.0);
  EXPECT_EQ(obs.crops[0].At(5, 5), 0.0);
  // the path bends around the inflated rock (4 cells around its 3): the look-ahead point 10 m
  // ahead is off the centre line, and the heading error points at it
  ASSERT_NE(obs.global_path_m, nullptr);
  EXPECT_NEAR(obs.global_path_m->back().x(), 25.0, 0.51);
  EXPECT_GE(std::abs(obs.local_goal_m.y()), 1.0);
  EXPECT_NEAR(obs.heading_error_rad, std::atan2(obs.local_goal_m.y(), obs.local_goal_m.x()),
              1e-12);
  EXPECT_NEAR((obs.local_goal_m - Vec2::Zero()).norm(), 10.0, 1.5);
  EXPECT_DOUBLE_EQ(obs.goal_distance_m, 25.0);
}

TEST(ObservationBuilderTest, ReplansEveryTwentyStepsOfFiveMilliseconds) {
  const terrain::TaskSpec task = test::PlaneTask(128.0);
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid grid = PlanningGrid(task);
  ObservationBuilder b(maps, grid, 1.0);
  b.Reset(Vec2(40.0, 0.0));
  controllers::Observation obs;
  std::vector<int> replan_steps;
  int count = 0;
  for (int k = 0; k <= 200; ++k) {
    b.Build(k * 0.005, StateAt(Vec2(-20.0 + 0.02 * k, 0.0), 0.0), &obs);
    if (b.navigation().replan_count != count) {
      count = b.navigation().replan_count;
      replan_steps.push_back(k);
    }
  }
  std::vector<int> expected;
  for (int k = 0; k <= 200; k += 20) expected.push_back(k);
  EXPECT_EQ(replan_steps, expected);
  EXPECT_NEAR(b.navigation().path_m.back().x(), 40.0, 0.5);
  // a new episode starts from scratch
  b.Reset(Vec2(40.0, 0.0));
  EXPECT_EQ(b.navigation().replan_count, 0);
  EXPECT_TRUE(b.navigation().path_m.empty());
}

TEST(ObservationBuilderTest, CropsAreRebuiltEveryCropPeriodAndAtOnceForAFreshObservation) {
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.2, 0.0);  // h = 0.2 x
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid grid = PlanningGrid(task);
  ObservationBuilder b(maps, grid, 1.0);
  controllers::ObservationConfig config;
  config.crops = {{terrain::MapLayer::kElevation, 4, 1.0}};
  config.crop_period_s = 0.1;
  b.SetConfig(config);
  b.Reset(Vec2(40.0, 0.0));
  controllers::Observation obs;
  // The vehicle moves 0.02 m per 5 ms step along x: the crop's centre height (0.2 x) says at
  // which step it was made.
  std::vector<int> rebuilt;
  double last = std::nan("");
  for (int k = 0; k <= 100; ++k) {
    const double x = -20.0 + 0.02 * k;
    b.Build(k * 0.005, StateAt(Vec2(x, 0.0), 0.0), &obs);
    ASSERT_EQ(obs.crops.size(), 1u);
    const double centre = 0.25 * (obs.crops[0].At(1, 1) + obs.crops[0].At(1, 2) +
                                  obs.crops[0].At(2, 1) + obs.crops[0].At(2, 2));
    if (!(centre == last)) rebuilt.push_back(k);
    last = centre;
    const int made_at = rebuilt.back();
    EXPECT_NEAR(centre, 0.2 * (-20.0 + 0.02 * made_at), 1e-9) << "step " << k;
  }
  EXPECT_EQ(rebuilt, (std::vector<int>{0, 20, 40, 60, 80, 100}));
  // Another Observation object has no crops yet: it gets them now, of the current pose.
  controllers::Observation fresh;
  b.Build(101 * 0.005, StateAt(Vec2(-20.0 + 0.02 * 101, 0.0), 0.0), &fresh);
  ASSERT_EQ(fresh.crops.size(), 1u);
  EXPECT_NEAR(fresh.crops[0].At(1, 1), 0.2 * (-20.0 + 0.02 * 101 + 0.5), 1e-9);
  // The default period (0) rebuilds with every observation.
  config.crop_period_s = 0.0;
  b.SetConfig(config);
  b.Build(102 * 0.005, StateAt(Vec2(-20.0 + 0.02 * 102, 0.0), 0.0), &obs);
  EXPECT_NEAR(obs.crops[0].At(1, 1), 0.2 * (-20.0 + 0.02 * 102 + 0.5), 1e-9);
}

TEST(ObservationBuilderTest, WithoutAPlanningGridTheGoalIsTheLocalGoal) {
  const terrain::TaskSpec task = test::PlaneTask(64.0);
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid none;  // rows 0: no planner
  ObservationBuilder b(maps, none, 1.0);
  b.Reset(Vec2(0.0, 30.0));
  controllers::Observation obs;
  b.Build(0.0, StateAt(Vec2(0.0, 0.0), 0.0), &obs);
  EXPECT_EQ(obs.local_goal_m, Vec2(0.0, 30.0));
  EXPECT_DOUBLE_EQ(obs.heading_error_rad, 0.5 * kPi);  // due north while heading east: left
}

TEST(ObservationBuilderTest, AngularVelocityIsInTheVehicleFrame) {
  const terrain::TaskSpec task = test::PlaneTask(64.0);
  const terrain::GroundTruthMaps maps(task, 0);
  const terrain::OccupancyGrid grid = PlanningGrid(task);
  ObservationBuilder b(maps, grid, 1.0);
  b.Reset(Vec2(20.0, 0.0));
  vehicles::VehicleState s = StateAt(Vec2(0.0, 0.0), 0.5 * kPi);  // facing north
  // about world +x (east), which is the vehicle's right (-y_B) when it faces north
  s.angular_velocity_W = Vec3(1.0, 0.0, 0.3);
  controllers::Observation obs;
  b.Build(0.0, s, &obs);
  EXPECT_NEAR(obs.angular_velocity_B.x(), 0.0, 1e-12);
  EXPECT_NEAR(obs.angular_velocity_B.y(), -1.0, 1e-12);
  EXPECT_NEAR(obs.angular_velocity_B.z(), 0.3, 1e-12);
}

TEST(ObservationBuilderTest, EpisodeObservationsCarryTheWheelsAndAreCachedPerStep) {
  const terrain::TaskSpec task = test::PlaneTask(128.0);
  const vehicles::VehicleParams hmmwv = test::Hmmwv();
  Episode episode(task, hmmwv);
  controllers::ObservationConfig config;
  config.crops = {{terrain::MapLayer::kElevation, 16, 0.25}};
  episode.SetObservationConfig(config);
  episode.Reset(TrialSpec());
  for (int k = 0; k < 400; ++k) episode.Step({1.0, 0.0, 0.0});  // 2 s full throttle
  const controllers::Observation& a = episode.Observe();
  EXPECT_DOUBLE_EQ(a.time_s, 2.0);
  ASSERT_EQ(a.wheels.size(), 4u);
  double slip_sum = 0.0;
  for (const controllers::WheelObservation& w : a.wheels) {
    EXPECT_TRUE(w.in_contact);
    EXPECT_EQ(w.surface, static_cast<int>(terrain::SurfaceClass::kConcrete));
    EXPECT_GT(w.normal_force_n, 3000.0);
    EXPECT_GT(w.spin_radps, 5.0);
    EXPECT_LT(std::abs(w.slip), 0.15);  // concrete: a few per cent even at full throttle
    slip_sum += w.slip;
  }
  EXPECT_GT(slip_sum, 0.0);  // accelerating: the wheels drive (the locked axles may share unevenly)
  EXPECT_GT(a.forward_speed_mps, 4.0);
  EXPECT_GE(a.gear, 1);
  ASSERT_EQ(a.crops.size(), 1u);
  EXPECT_EQ(a.crops[0].rows, 16);
  ASSERT_NE(a.global_path_m, nullptr);
  EXPECT_FALSE(a.global_path_m->empty());
  // the same object until the next step
  EXPECT_EQ(&episode.Observe(), &a);
  EXPECT_DOUBLE_EQ(episode.Observe().time_s, 2.0);
}

}  // namespace
}  // namespace vb::runner
