// The HMMWV's chassis envelope (data/vehicles/hmmwv.yaml, docs/architecture.md "Contact") against
// closed-form geometry: a symmetric crest high-centres the belly only beyond the breakover angle,
// and a tree on the vehicle's centre line cannot pass between the wheels.
#include <gtest/gtest.h>

#include <cmath>

#include "support/vehicle_sim.h"

namespace vb {
namespace {

// A ridge along y at x = 0: z = -tan(half_angle) |x| (1 m grid, the ridge on a vertex column).
terrain::TaskSpec Crest(double half_angle_rad) {
  terrain::TaskSpec t = test::PlaneTask(64.0);
  const int n = t.heights.rows;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      t.heights.heights_m[static_cast<size_t>(r) * n + c] = -std::tan(half_angle_rad) * std::abs(-32.0 + c);
    }
  }
  t.min_height_m = -32.0 * std::tan(half_angle_rad);
  t.max_height_m = 0.0;
  return t;
}

struct CrestRun {
  int steps_with_belly_contact = 0;
  double final_x_m = 0.0;
};

// Crawls over the crest from x = -10 at 1.5 m/s (P speed control) for 20 s.
CrestRun CrossCrest(double half_angle_rad) {
  const vehicles::VehicleParams p = test::Hmmwv();
  const double slope = std::tan(half_angle_rad);
  test::VehicleSim sim(Crest(half_angle_rad), p,
                       test::PoseOnPlane(-10.0, 0.0, slope, 0.0, 0.0, p.wheel.radius_m, 0.02));
  CrestRun run;
  for (int k = 0; k < 4000; ++k) {
    sim.Step(test::SpeedControl(1.5, sim.state().forward_speed_mps));
    if (sim.state().body_ground_contacts > 0) ++run.steps_with_belly_contact;
  }
  run.final_x_m = sim.state().pose_W.position.x();
  return run;
}

// Geometric breakover of the envelope: straddling the crest level, the wheel centres (x = +-a,
// a = 1.651 m) stand r / cos(alpha) above the ramps and the belly's bottom is at wheel-centre
// height, so it touches the ridge when a tan(alpha) = r / cos(alpha): sin(alpha) = r / a,
// alpha = 16.4 deg, a breakover (ridge) angle of 2 alpha = 32.9 deg. The static sag of the
// suspension (front ~6 cm) lowers the belly: the limit in the simulation is a little lower.
TEST(VehicleEnvelope, CrestHighCentresOnlyBeyondTheBreakoverAngle) {
  const double alpha_limit = std::asin(0.467 / 1.651);
  EXPECT_NEAR(2.0 * alpha_limit / test::kDeg, 32.9, 0.05);
  // (a sweep in 1 deg ridge steps: no touch up to 30 deg, a touch at 31, stuck from 32)
  const CrestRun gentle = CrossCrest(alpha_limit - 2.0 * test::kDeg);   // 28.9 deg ridge
  EXPECT_EQ(gentle.steps_with_belly_contact, 0);
  EXPECT_GT(gentle.final_x_m, 10.0) << "crossed the crest";
  const CrestRun sharp = CrossCrest(alpha_limit + 1.0 * test::kDeg);    // 34.9 deg ridge
  EXPECT_GT(sharp.steps_with_belly_contact, 1000) << "the belly rests on the ridge";
  EXPECT_LT(std::abs(sharp.final_x_m), 1.0) << "high-centred on the ridge";
}

TEST(VehicleEnvelope, TreeOnTheCentreLineCannotPassBetweenTheWheels) {
  terrain::TaskSpec task = test::PlaneTask(64.0);
  task.trees.push_back({0.0, 0.0});  // 1 x 1 m trunk straight ahead
  const vehicles::VehicleParams p = test::Hmmwv();
  test::VehicleSim sim(task, p, test::PoseOnPlane(-8.0, 0.0, 0.0, 0.0, 0.0, p.wheel.radius_m, 0.02));
  int steps_on_tree = 0;
  for (int k = 0; k < 2000; ++k) {
    sim.Step(test::SpeedControl(3.0, sim.state().forward_speed_mps));
    if (sim.state().body_obstacle_contacts > 0) ++steps_on_tree;
  }
  EXPECT_GT(steps_on_tree, 100);
  // stopped at the trunk: the front of the belly (x 2.285 m ahead of the reference point) at the
  // tree's west face (x -0.5)
  EXPECT_NEAR(sim.state().pose_W.position.x(), -0.5 - 2.285, 0.15);
  EXPECT_LT(std::abs(sim.state().forward_speed_mps), 0.1);
}

}  // namespace
}  // namespace vb
