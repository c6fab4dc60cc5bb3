// Articulation: the ramp travel index (RTI) of the HMMWV. The front left wheel drives slowly up a
// 20 deg ramp (the other wheels on flat ground) until another wheel leaves the ground;
// RTI = 1000 x (distance up the ramp) / wheelbase.
// Reference (closed form, linear wheel rates): raising one corner's ground by h twists the
// chassis against the suspension; with a rigid chassis on four springs only the warp mode loads
// the wheels, +F on the raised corner and its diagonal, -F on the other two, and compatibility of
// the spring deflections gives F = h / (2 (1/k_f + 1/k_r)) with the wheel rates k (spring rate
// along the shock x motion ratio^2 at the static travel, the linkage's, in series with the tire).
// The lighter of the two unloaded wheels (static load W) lifts at h = 2 W (1/k_f + 1/k_r).
// Asserted: the height at lift-off within 15 % of it (the rates vary along the travel, the ramp's
// normal is tilted, the locked-differential clutches wind up the driveline), and no stop is
// reached before (the articulation is the springs', as in the reference's reduced model).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/vehicle_sim.h"
#include "vb/vehicles/suspension_kinematics.h"

namespace vb {
namespace {

using test::kDeg;

constexpr double kRampDeg = 20.0;

// (driven at 0.3 m/s; "lifted" = no ground force for 0.2 s)
// Flat ground with a 20 deg ramp rising in +x from x = 0 for y >= 0.7 m (under the left track
// only: the right wheels and the belly stay on the flat). Grid 0.05 m.
terrain::TaskSpec RampTask() {
  terrain::TaskSpec t = test::PlaneTask(16.0, 0.0, 0.0, 0.9);
  const double size = 24.0, dx = 0.05;
  const int n = static_cast<int>(std::lround(size / dx)) + 1;
  t.size_x_m = t.size_y_m = size;
  t.heights.rows = t.heights.cols = n;
  t.heights.heights_m.assign(static_cast<size_t>(n) * n, 0.0);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const double x = -0.5 * size + c * dx, y = 0.5 * size - r * dx;
      if (y >= 0.7 && x > 0.0) {
        t.heights.heights_m[static_cast<size_t>(r) * n + c] =
            std::min(2.0, x * std::tan(kRampDeg * kDeg));
      }
    }
  }
  t.min_height_m = 0.0;
  t.max_height_m = 2.0;
  return t;
}

// Wheel rate at the static travel s: spring rate x motion ratio^2, in series with the tire.
double WheelRate(const vehicles::VehicleParams& p, const vehicles::SuspensionParams& su,
                 double s) {
  constexpr double h = 1e-4;
  const double l1 = vehicles::SolveDoubleWishbone(su.hardpoints, s - h, 0.0).shock_length_m;
  const double l2 = vehicles::SolveDoubleWishbone(su.hardpoints, s + h, 0.0).shock_length_m;
  const double mr = -(l2 - l1) / (2.0 * h);
  const double k_susp = su.spring_stiffness_npm * mr * mr;
  return 1.0 / (1.0 / k_susp + 1.0 / p.tire.normal_stiffness_npm);
}

TEST(VehicleArticulation, RampTravelIndexFromTheWheelRates) {
  const vehicles::VehicleParams p = test::Hmmwv();
  test::VehicleSim sim(RampTask(), p, test::PoseOnPlane(-3.0, 0, 0, 0, 0, p.wheel.radius_m, 0.0));
  sim.Run(2.0, {});
  // wheel order: axle by axle, left then right
  const auto& w0 = sim.state().wheels;
  ASSERT_EQ(w0.size(), 4u);
  ASSERT_GT(w0[0].center_W.y(), 0.0);
  const double k_f = WheelRate(p, p.axles[0].suspension, w0[0].suspension_travel_m);
  const double k_r = WheelRate(p, p.axles[1].suspension, w0[2].suspension_travel_m);
  const double w_lift = std::min(w0[1].normal_force_n, w0[2].normal_force_n);
  const double h_expected = 2.0 * w_lift * (1.0 / k_f + 1.0 / k_r);
  const double wheelbase = p.axles[0].x_m - p.axles[1].x_m;

  double h_lift = -1.0, max_travel_bump = -1e9, min_travel = 1e9;
  int lifted_wheel = -1;
  int off = 0;
  for (int k = 0; k < 6000 && h_lift < 0.0; ++k) {
    sim.Step(test::SpeedControl(0.3, sim.state().forward_speed_mps));
    const auto& w = sim.state().wheels;
    bool lifted = false;
    for (int i = 1; i < 4; ++i) {
      if (w[i].normal_force_n <= 0.0) {
        lifted = true;
        lifted_wheel = i;
      }
    }
    off = lifted ? off + 1 : 0;
    for (size_t i = 0; i < 4; ++i) {
      const auto& su = p.axles[i / 2].suspension;
      max_travel_bump = std::max(max_travel_bump, w[i].suspension_travel_m - su.bump_travel_m);
      min_travel = std::min(min_travel, w[i].suspension_travel_m + su.rebound_travel_m);
    }
    if (off >= 40) h_lift = sim.terrain.Height(w[0].center_W.x(), w[0].center_W.y());
  }
  ASSERT_GT(h_lift, 0.0) << "no wheel lifted";
  const double rti = 1000.0 * h_lift / std::sin(kRampDeg * kDeg) / wheelbase;
  const double rti_expected = 1000.0 * h_expected / std::sin(kRampDeg * kDeg) / wheelbase;
  std::printf("wheel %d lifts first (0 FL, 1 FR, 2 RL, 3 RR)\n", lifted_wheel);
  std::printf("wheel rates front %.0f / rear %.0f N/m, lighter unloaded wheel %.0f N: lift-off at "
              "h %.3f m (closed form %.3f m, %+.1f %%), RTI(20 deg) %.0f (closed form %.0f)\n",
              k_f, k_r, w_lift, h_lift, h_expected, 100.0 * (h_lift / h_expected - 1.0), rti,
              rti_expected);
  EXPECT_NEAR(h_lift, h_expected, 0.15 * h_expected);
  EXPECT_LT(max_travel_bump, 0.0);  // no bump stop reached
  EXPECT_GT(min_travel, 0.0);       // no rebound stop reached
}

}  // namespace
}  // namespace vb
