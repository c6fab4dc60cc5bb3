// The builder assembles any axle count from data: 6- and 8-wheel variants (the HMMWV's parts on
// extra axles, strut suspension, Ackermann steering on the front axle(s)) settle with the wheel
// loads carrying the weight, drive straight and stop.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/vehicle_sim.h"

namespace vb {
namespace {

vehicles::VehicleParams MultiAxle(int axles) {
  vehicles::VehicleParams p = test::Hmmwv();
  p.name = "test_" + std::to_string(2 * axles) + "x" + std::to_string(2 * axles);
  p.steering.model = vehicles::SteeringModel::kAckermann;
  p.steering.max_angle_rad = 0.4;
  p.steering.link_mass_kg = 0.0;
  p.chassis.mass_kg = 2086.52 * axles / 2.0;
  p.chassis.com_B = Vec3(0.0, 0.0, 0.2);
  vehicles::AxleParams a = p.axles[1];
  a.suspension = vehicles::SuspensionParams();
  a.suspension.model = vehicles::SuspensionModel::kStrut;
  a.suspension.stiffness_npm = 200000.0;
  a.suspension.damping_nspm = 15000.0;
  a.suspension.preload_n = p.chassis.mass_kg * kGravity / (2.0 * axles);
  a.suspension.bump_travel_m = a.suspension.rebound_travel_m = 0.1;
  a.suspension.stop_deflection_m = {0.0, 0.002, 0.05, 0.06};
  a.suspension.stop_force_n = {0.0, 200.0, 12500.0, 125000.0};
  a.suspension.carrier_mass_kg = 43.092;
  a.suspension.carrier_inertia_kgm2 = Vec3(6, 6, 6);
  p.axles.clear();
  const double spacing = 1.6;
  for (int i = 0; i < axles; ++i) {
    a.x_m = spacing * (0.5 * (axles - 1) - i);
    a.steered = i == 0;  // front axle steers
    p.axles.push_back(a);
  }
  return p;
}

TEST(MultiAxle, SixAndEightWheelsSettleDriveAndStop) {
  for (int axles : {3, 4}) {
    const vehicles::VehicleParams p = MultiAxle(axles);
    test::VehicleSim sim(test::PlaneTask(256.0), p,
                         test::PoseOnPlane(-100.0, 0, 0, 0, 0, p.wheel.radius_m, 0.05));
    sim.Run(3.0, {});
    ASSERT_EQ(sim.state().wheels.size(), static_cast<size_t>(2 * axles));
    double sum = 0.0;
    for (const auto& w : sim.state().wheels) {
      EXPECT_TRUE(w.in_contact);
      sum += w.normal_force_n;
    }
    const double weight = test::TotalMass(p) * kGravity;
    for (int i = 0; i < 1200; ++i) sim.Step(test::SpeedControl(8.0, sim.state().forward_speed_mps));
    const double v = sim.state().forward_speed_mps;
    const double y = sim.state().pose_W.position.y();
    vehicles::DriverInputs brake;
    brake.braking = 1.0;
    sim.Run(4.0, brake);
    std::printf("%d wheels: loads %.1f N / weight %.1f N, speed %.2f m/s, lateral drift %.3f m, "
                "after braking %.3f m/s\n",
                2 * axles, sum, weight, v, y, sim.state().forward_speed_mps);
    EXPECT_NEAR(sum, weight, 0.01 * weight);
    EXPECT_NEAR(v, 8.0, 0.3);
    EXPECT_NEAR(y, 0.0, 0.1);
    EXPECT_LT(std::abs(sim.state().forward_speed_mps), 0.05);
  }
}

}  // namespace
}  // namespace vb
