// Static validation of the HMMWV at rest on flat rigid ground (mu 0.9), after 4 s of settling.
// References are closed-form statics of the model data (data/vehicles/hmmwv.yaml, from Chrono's
// HMMWV_Reduced, spec reference_vehicle_soil.md §1):
//  - the wheel loads carry the weight: sum = m g (tolerance 0.5 %);
//  - the front/rear split follows the centre of mass: front axle load = m g (x_com - x_r) / L
//    (tolerance 0.5 % of the weight: the 1.1 deg nose-down pitch of the sprung mass moves the COM
//    forward by ~4 mm = 0.1 % of the wheelbase);
//  - static sag = load / rate: the travel at which the spring along the shock, through the
//    motion ratio the hard points give, carries the corner's sprung load (tolerance 2 mm, about
//    the deflection of 300 N at the wheel rate).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/vehicle_sim.h"
#include "vb/vehicles/suspension_kinematics.h"

namespace vb {
namespace {

using test::kStep_s;

// Travel s at which the shock spring balances the sprung corner load F (N): spring force along
// the shock times the motion ratio -dL/ds equals F. Bisection on the linkage solution.
double StaticTravel(const vehicles::SuspensionParams& su, double load_n) {
  auto wheel_force = [&](double s) {
    constexpr double h = 1e-5;
    const double l = vehicles::SolveDoubleWishbone(su.hardpoints, s, 0.0).shock_length_m;
    const double l2 = vehicles::SolveDoubleWishbone(su.hardpoints, s + h, 0.0).shock_length_m;
    const double motion_ratio = -(l2 - l) / h;
    return -su.spring_stiffness_npm * (l - su.spring_free_length_m) * motion_ratio;
  };
  double lo = -su.rebound_travel_m, hi = su.bump_travel_m;  // force increases with s
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (wheel_force(mid) < load_n ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(VehicleStatic, LoadsSplitAndSag) {
  const vehicles::VehicleParams p = test::Hmmwv();
  test::VehicleSim sim(test::PlaneTask(), p, test::PoseOnPlane(0, 0, 0, 0, 0, 0.467, 0.05));
  sim.Run(4.0, {});
  const auto& s = sim.state();
  const double m = test::TotalMass(p);
  const double weight = m * kGravity;

  // 1. loads sum to the weight
  double sum = 0.0;
  for (const auto& w : s.wheels) sum += w.normal_force_n;
  std::printf("sum of wheel loads %.1f N, weight %.1f N (mass %.2f kg, Chrono 2493.56 kg)\n", sum,
              weight, m);
  EXPECT_NEAR(sum, weight, 0.005 * weight);

  // 2. front/rear split from the COM (design pose)
  double mx = p.chassis.mass_kg * p.chassis.com_B.x() +
              p.steering.link_mass_kg * p.steering.link_position_B.x();
  for (const auto& a : p.axles) mx += 2.0 * test::UnsprungMass(p, a) * a.x_m;
  const double x_com = mx / m;
  const double xf = p.axles[0].x_m, xr = p.axles[1].x_m;
  const double front_expected = weight * (x_com - xr) / (xf - xr);
  const double front = s.wheels[0].normal_force_n + s.wheels[1].normal_force_n;
  std::printf("front axle load %.1f N (%.2f %%), expected %.1f N (%.2f %%), x_com %.4f m\n", front,
              100 * front / sum, front_expected, 100 * front_expected / weight, x_com);
  EXPECT_NEAR(front, front_expected, 0.005 * weight);
  EXPECT_NEAR(s.wheels[0].normal_force_n, s.wheels[1].normal_force_n, 0.002 * weight);  // L = R

  // 3. static sag = load / rate, per corner
  for (size_t i = 0; i < s.wheels.size(); ++i) {
    const vehicles::AxleParams& a = p.axles[i / 2];
    const double sprung_load = s.wheels[i].normal_force_n - test::UnsprungMass(p, a) * kGravity;
    const double expected = StaticTravel(a.suspension, sprung_load);
    std::printf("corner %zu: sprung load %.1f N, sag (bump travel from design) sim %.4f m, "
                "load/rate %.4f m\n",
                i, sprung_load, s.wheels[i].suspension_travel_m, expected);
    EXPECT_NEAR(s.wheels[i].suspension_travel_m, expected, 0.002);
  }
  // at rest
  EXPECT_LT(std::abs(s.velocity_W.z()), 1e-3);
}

// The original's own flat rigid run puts the front spindles at 0.470 m and the rear at 0.467 m
// over ground (reference_chrono_runs.md; tire radius 0.467 m, given to the millimetre). Its rigid
// tire is a cylinder: a cambered one rests on its tread edge, centre r cos(camber) + w/2
// |sin(camber)| high. The camber is the linkage's at the static travel: the published hard points
// tilt the front upright as the front sags ~7 cm into bump, the rear (at design) not. vb's
// vehicle keeps its wheels upright (docs/validation.md "Not modelled"), so this checks vb's
// linkage and sag against the reference's reading, and tells what the reference's sinkage measure
// (r minus the spindle height, docs/validation.md "Flat soil") reads on ground that does not
// sink: about -3 mm at the front, 0 at the rear. Tolerance 1.5 mm (the reference's rounding and the
// 2 mm sag tolerance above).
TEST(VehicleStatic, TheReferencesSpindleHeightsAreItsFrontCamber) {
  const vehicles::VehicleParams p = test::Hmmwv();
  test::VehicleSim sim(test::PlaneTask(), p, test::PoseOnPlane(0, 0, 0, 0, 0, 0.467, 0.05));
  sim.Run(4.0, {});
  const auto& s = sim.state();
  const double r = p.wheel.radius_m, w = p.wheel.width_m;
  const double reference[2] = {0.470, 0.467};   // front, rear spindle height (m)
  for (size_t axle = 0; axle < 2; ++axle) {
    const double travel = s.wheels[2 * axle].suspension_travel_m;
    const vehicles::UprightSolution u =
        vehicles::SolveDoubleWishbone(p.axles[axle].suspension.hardpoints, travel, 0.0);
    ASSERT_TRUE(u.ok);
    const double height = r * std::cos(u.camber_rad) + 0.5 * w * std::abs(std::sin(u.camber_rad));
    std::printf("axle %zu: static travel %.4f m, camber %.2f deg, cylinder on its edge: centre "
                "%.4f m (reference %.3f m)\n",
                axle, travel, u.camber_rad / kPi * 180.0, height, reference[axle]);
    EXPECT_NEAR(height, reference[axle], 0.0015) << "axle " << axle;
  }
}

}  // namespace
}  // namespace vb
