// A wheel driven at a boulder's base (docs/validation.md, "Boulders and trunks"): the HMMWV at
// 1 m/s (speed controller) on flat concrete drives its left wheels straight at a boulder of the
// benchmark's family (seeded dome, obstacle_shape.h). A low boulder (scale 0.06: 0.23 m high,
// 0.26 m across, below the 0.25 m curb the HMMWV climbs in wheel_step_test.cc) is climbed: the
// front wheel rides up its rounded flank and the rear axle gets past it. A high one (scale 0.7,
// the benchmark's smallest rock: 2.66 m high, 3.08 m across) stops it: the vehicle stays in
// front of the boulder and touches it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "support/vehicle_sim.h"
#include "vb/terrain/obstacle_shape.h"

namespace vb {
namespace {

struct BoulderRun {
  bool passed = false;
  double max_x_m = -1e9;      // of the front axle
  double max_lift_m = 0.0;    // of the left front wheel centre above its start height
  int obstacle_contacts = 0;
  double t_s = 0.0;
};

BoulderRun DriveAtBoulder(double rock_scale) {
  const vehicles::VehicleParams p = test::Hmmwv();
  terrain::TaskSpec task = test::PlaneTask(48.0, 0.0, 0.0, 0.9);
  task.generator_seed = 3;
  task.rocks.push_back({2.0, p.axles[0].half_track_m, rock_scale});
  task.rock_shape.kind = terrain::ObstacleShapeKind::kBoulder;
  terrain::AssignShapeSeeds(&task);
  test::VehicleSim sim(task, p, test::PoseOnPlane(-6.0, 0, 0, 0, 0, p.wheel.radius_m, 0.0));
  const double rock_half_m = 0.5 * terrain::kRockSideAtScale1_m * rock_scale;
  const double z0 = sim.state().pose_W.position.z();
  BoulderRun run;
  for (int k = 0; k < 4000; ++k) {   // 20 s
    sim.Step(test::SpeedControl(1.0, sim.state().forward_speed_mps));
    const Vec3& c = sim.state().pose_W.position;
    run.max_x_m = std::max(run.max_x_m, c.x() + p.axles[0].x_m);
    run.max_lift_m = std::max(run.max_lift_m, c.z() - z0);
    run.obstacle_contacts += sim.state().body_obstacle_contacts;
    if (c.x() + p.axles[1].x_m > 2.0 + rock_half_m + 0.5) {
      run.passed = true;
      break;
    }
  }
  run.t_s = sim.t;
  return run;
}

TEST(BoulderValidation, HmmwvClimbsALowBoulderAndIsStoppedByAHighOne) {
  const BoulderRun low = DriveAtBoulder(0.06);
  const BoulderRun high = DriveAtBoulder(0.7);
  std::printf("low boulder (0.23 m): %s after %.1f s, chassis lifted up to %.3f m\n",
              low.passed ? "climbed" : "NOT climbed", low.t_s, low.max_lift_m);
  std::printf("high boulder (2.66 m): %s, front axle reached x = %.2f m (boulder base from "
              "x = %.2f m), %d body contact-steps\n",
              high.passed ? "CLIMBED" : "stopped", high.max_x_m, 2.0 - 0.5 * 4.4 * 0.7,
              high.obstacle_contacts);
  EXPECT_TRUE(low.passed);
  // climbing lifted the chassis (a wheel went over it, not around it)
  EXPECT_GT(low.max_lift_m, 0.03);
  EXPECT_FALSE(high.passed);
  // stopped at the boulder: the front axle never got past its centre
  EXPECT_LT(high.max_x_m, 2.0);
}

}  // namespace
}  // namespace vb
