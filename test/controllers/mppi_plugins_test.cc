// The MPPI baseline's plug-ins: the bicycle model against its closed forms (straight step,
// circle of radius L / tan(angle)), the original's sideways step; the goal + obstacle cost's
// normalisation and its straight and transposed obstacle look-ups.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "vb/controllers/bicycle_model.h"
#include "vb/controllers/mppi_goal_cost.h"

namespace vb::controllers {
namespace {

TEST(BicycleModelTest, StraightStepLengthIsTheOriginals) {
  BicycleModel m;
  PlannerState s;
  s.yaw_rad = 0.3;
  s.z_m = 1.5;
  const MppiControl u{0.6, 0.0};
  PlannerState n;
  m.Step(0, &s, &u, 1, &n);
  // 0.6 / 0.75 normalised speed * 0.583 m = 0.4664 m along the heading
  // (the trigonometry is single precision: 1e-7 relative)
  EXPECT_NEAR(std::hypot(n.x_m, n.y_m), 0.6 / 0.75 * 0.583, 1e-7);
  EXPECT_NEAR(std::atan2(n.y_m, n.x_m), 0.3, 1e-7);
  EXPECT_DOUBLE_EQ(n.yaw_rad, 0.3);
  EXPECT_DOUBLE_EQ(n.z_m, 1.5);   // carried through
}

TEST(BicycleModelTest, ConstantSteeringDrivesACircleOfTheBicycleRadius) {
  BicycleModelParams p;
  BicycleModel m(p);
  const double steer = 0.5;
  const double radius = p.wheelbase_m / std::tan(p.wheel_angle_per_steer_rad * steer);
  PlannerState s;   // at the origin heading east: the circle's centre is (0, radius)
  const MppiControl u{0.5, steer};
  for (int i = 0; i < 200; ++i) {
    PlannerState n;
    m.Step(i, &s, &u, 1, &n);
    s = n;
    // the midpoint step is a chord of the circle, shorter than the arc by ds * dyaw^2 / 24
    EXPECT_NEAR(std::hypot(s.x_m, s.y_m - radius), radius, 2e-3 * radius) << i;
  }
  // yaw grew by ds / R per step (positive steering turns left)
  EXPECT_NEAR(s.yaw_rad, 200 * 0.5 * p.step_length_per_speed_m / radius, 1e-6);
}

TEST(BicycleModelTest, OriginalStepGoesAlongTheUnscaledAngle) {
  BicycleModelParams p;
  p.original_step_direction = true;
  BicycleModel m(p);
  PlannerState s;
  const MppiControl u{0.6, 1.0};
  PlannerState n;
  m.Step(0, &s, &u, 1, &n);
  // normalised angle v'/0.32 tan(0.6) = 0.8 / 0.32 * 0.684 = 1.71 rad: the step goes 98 deg to
  // the left while the heading turns by 0.0649 of it
  const double raw = 0.8 / 0.32 * std::tan(0.6);
  EXPECT_NEAR(std::atan2(n.y_m, n.x_m), raw, 1e-6);
  EXPECT_NEAR(n.yaw_rad, 0.0649 * raw, 1e-7);
}

TEST(BicycleModelTest, LengthsScaleWithTheEnvironment) {
  BicycleModelParams p;
  p.scale = 0.1;
  BicycleModel m(p);
  PlannerState s;
  const MppiControl u{0.6, 0.7};
  PlannerState n, n1;
  m.Step(0, &s, &u, 1, &n);
  BicycleModel(BicycleModelParams()).Step(0, &s, &u, 1, &n1);
  EXPECT_NEAR(n.x_m, 0.1 * n1.x_m, 1e-15);
  EXPECT_NEAR(n.y_m, 0.1 * n1.y_m, 1e-15);
  EXPECT_DOUBLE_EQ(n.yaw_rad, n1.yaw_rad);   // same turning geometry
}

// A 21 x 21 m world of 1 m cells with one occupied cell at world (3, 7).
terrain::GridMap OneObstacle() {
  terrain::GridMap g;
  g.rows = g.cols = 21;
  g.resolution_m = 1.0;
  g.values.assign(21 * 21, 0.0);
  g.values[static_cast<size_t>(10 - 7) * 21 + (10 + 3)] = 1.0;   // r = 10 - y, c = 10 + x
  return g;
}

TEST(GoalObstacleCostTest, ObstacleLookupStraightAndTransposed) {
  const terrain::GridMap g = OneObstacle();
  GoalObstacleCost straight(GoalObstacleCostParams(), &g, 20.0, 20.0);
  EXPECT_EQ(straight.ObstacleAt(3.0, 7.0), 1.0);
  EXPECT_EQ(straight.ObstacleAt(3.4, 6.6), 1.0);    // nearest cell
  EXPECT_EQ(straight.ObstacleAt(-7.0, -3.0), 0.0);
  EXPECT_EQ(straight.ObstacleAt(7.0, 3.0), 0.0);
  EXPECT_EQ(straight.ObstacleAt(10.6, 0.0), 1.0);   // outside the world
  GoalObstacleCostParams p;
  p.original_transposed_lookup = true;
  GoalObstacleCost transposed(p, &g, 20.0, 20.0);
  // [row 10 + x, col 10 - y]: the obstacle at (3, 7) is seen at (-7, -3)
  EXPECT_EQ(transposed.ObstacleAt(-7.0, -3.0), 1.0);
  EXPECT_EQ(transposed.ObstacleAt(3.0, 7.0), 0.0);
}

TEST(GoalObstacleCostTest, GoalTermIsMinMaxNormalisedAcrossSamples) {
  const terrain::GridMap g = OneObstacle();
  GoalObstacleCost cost(GoalObstacleCostParams(), &g, 20.0, 20.0);
  cost.set_goal(Vec2(0.0, 0.0));
  std::vector<PlannerState> s(4);
  s[0].x_m = 1.0;             // d^2 1: the closest -> 0
  s[1].x_m = 3.0;             // d^2 9: the farthest -> 10
  s[2].x_m = 2.0;             // d^2 4 -> 10 * 3/8
  s[3].x_m = 3.0;             // on the obstacle (3, 7): d^2 58 -> farthest
  s[3].y_m = 7.0;
  std::vector<MppiControl> u(4, MppiControl{0.5, 0.0});
  std::vector<double> c(4);
  cost.Evaluate(0, s.data(), u.data(), 3, c.data());
  EXPECT_DOUBLE_EQ(c[0], 0.0);
  EXPECT_DOUBLE_EQ(c[1], 10.0);
  EXPECT_DOUBLE_EQ(c[2], 10.0 * 3.0 / 8.0);
  cost.Evaluate(0, s.data(), u.data(), 4, c.data());
  EXPECT_DOUBLE_EQ(c[3], 10.0 + 50.0);
  EXPECT_DOUBLE_EQ(c[1], 10.0 * 8.0 / 57.0);
}

}  // namespace
}  // namespace vb::controllers
