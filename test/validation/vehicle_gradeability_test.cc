// Gradeability: steepest rigid slope the HMMWV climbs from rest at full throttle (>= 5 m uphill
// progress within 8 s), found by bisection (0.15 deg resolution), for mu 0.9 and 0.5.
// References (closed form, h = 0.61 m COM height, b = 1.70 m COM to rear axle, L = 3.302 m):
//  - upper bound: all four wheels at the friction limit, tan(theta) = mu (42.0 / 26.6 deg);
//  - Chrono's driveline is open differentials whose "locks" are 100 N m clutches (spec §1.8),
//    so the lightly loaded front axle limits: 2 mu N_front + C / r = W sin(theta) with
//    N_front = W (b cos - h sin) / L and C = 100 N m / 0.2 = 500 N m the central clutch at the
//    wheels -> 36.6 deg (mu 0.9) and 25.5 deg (mu 0.5);
//  - published capability of the real HMMWV: 60 % grade = 31.0 deg (spec §5.2).
// Asserted: |sim - estimate| <= 2 deg (the estimate takes the COM height from the tilt-table
// run and ignores the transient wheel spin of the clutch coupling within the 8 s window; with
// the driveline's shaft inertia on the wheels, 13.4 kg m^2 each, the spinning front wheels
// speed up more slowly and the sim climbs 1.7 deg above it at mu 0.9), sim <= atan(mu), and
// sim >= 31 deg for mu 0.9 (the 60 % grade is within the model's capability).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "support/slope_climb.h"
#include "support/vehicle_sim.h"

namespace vb {
namespace {

using test::kDeg;

// From rest at x = -40 m, settled for 1 s (test::ClimbsFromRest); 0.15 deg resolution.
double SteepestClimbed(const vehicles::VehicleParams& p, double mu) {
  return test::SteepestClimbed(p, mu, 10.0, 48.0, 8, test::ClimbRun{1.0, 0.0});
}

// Front-axle-limited estimate (see the header comment), by bisection on theta.
double OpenDiffEstimate(const vehicles::VehicleParams& p, double mu, double h_m) {
  const double m = test::TotalMass(p), w = m * kGravity;
  double mx = p.chassis.mass_kg * p.chassis.com_B.x() +
              p.steering.link_mass_kg * p.steering.link_position_B.x();
  for (const auto& a : p.axles) mx += 2.0 * test::UnsprungMass(p, a) * a.x_m;
  const double xr = p.axles[1].x_m, l = p.axles[0].x_m - xr;
  const double b = mx / m - xr;
  const double clutch_force =
      p.driveline.lock_torque_limit_nm / p.driveline.conical_ratio / p.wheel.radius_m;
  double lo = 0.0, hi = 60.0 * kDeg;
  for (int i = 0; i < 60; ++i) {
    const double th = 0.5 * (lo + hi);
    const double n_front = w * (b * std::cos(th) - h_m * std::sin(th)) / l;
    (2.0 * mu * n_front + clutch_force > w * std::sin(th) ? lo : hi) = th;
  }
  return lo / kDeg;
}

TEST(VehicleGradeability, SteepestSlopeFromRest) {
  const vehicles::VehicleParams p = test::Hmmwv();
  constexpr double kComHeight_m = 0.612;  // measured in VehicleTiltTable
  for (double mu : {0.9, 0.5}) {
    const double sim = SteepestClimbed(p, mu);
    const double bound = std::atan(mu) / kDeg;
    const double estimate = OpenDiffEstimate(p, mu, kComHeight_m);
    std::printf("mu %.1f: climbs %.2f deg (%.0f %% grade); open-diff estimate %.2f deg, "
                "4WD friction bound %.2f deg, published 31.0 deg (60 %%)\n",
                mu, sim, 100.0 * std::tan(sim * kDeg), estimate, bound);
    EXPECT_LE(sim, bound);
    EXPECT_NEAR(sim, estimate, 2.0);
    if (mu > 0.8) {
      EXPECT_GE(sim, 31.0);
    }
  }
}

// The original's own slope runs (reference_chrono_runs.md, "Slopes"): start at rest on the
// incline, brakes held 2 s, then full throttle; "climbed" = 30 m up the slope (time limit 20 s,
// the reference's slowest success took 9.4 s). Chrono: mu 0.9 limit about 31 deg (30 climbed,
// 32 fails after 13 m); mu 0.5 between 20 and 25 deg (20 climbed with 41 m at most, 25 fails at
// once). Asserted: mu 0.5 within 3 deg of the reference's interval [20, 25] (measured 25.6);
// mu 0.9 not below 30 - 3 deg. NOT MET: at mu 0.9 vb climbs 37.3 deg, 5 deg above the original's
// ~31 (the front-axle-limited open-differential estimate is 36.6 deg, see SteepestSlopeFromRest).
// The cause is the original's unreacted propeller-shaft torque, a Chrono artefact vb does not copy
// by default: with it vb climbs 32.1 deg (TheOriginalsUnreactedShaftTorqueExplainsItsSlopeLimit,
// docs/validation.md).
// Time to climb 30 m up the slope from rest by that protocol; -1 if not within 20 s. `max_up_m`
// (optional): the furthest point reached up the slope.
double SecondsToClimb30m(const vehicles::VehicleParams& p, double angle_rad, double mu,
                         double* max_up_m = nullptr) {
  const double sx = std::tan(angle_rad);
  test::VehicleSim sim(test::PlaneTask(128.0, sx, 0.0, mu), p,
                       test::PoseOnPlane(-50.0, 0, sx, 0, 0, p.wheel.radius_m, 0.0));
  vehicles::DriverInputs in;
  in.braking = 1.0;
  sim.Run(2.0, in);
  const Vec3 p0 = sim.state().pose_W.position;
  in.braking = 0.0;
  in.throttle = 1.0;
  double up_max = 0.0;
  for (int k = 1; k <= 4000; ++k) {
    sim.Step(in);
    const double up = (sim.state().pose_W.position.x() - p0.x()) / std::cos(angle_rad);
    up_max = std::max(up_max, up);
    if (max_up_m) *max_up_m = up_max;
    if (up > 30.0) return k * test::kStep_s;
  }
  return -1.0;
}

bool ClimbsLikeTheReference(const vehicles::VehicleParams& p, double angle_rad, double mu) {
  return SecondsToClimb30m(p, angle_rad, mu) > 0.0;
}

// Steepest slope climbed by that protocol, bisected between 10 and 45 deg to 0.3 deg.
double SlopeLimit(const vehicles::VehicleParams& p, double mu) {
  double lo = 10.0, hi = 45.0;
  while (hi - lo > 0.3) {
    const double mid = 0.5 * (lo + hi);
    (ClimbsLikeTheReference(p, mid * kDeg, mu) ? lo : hi) = mid;
  }
  return lo;
}

TEST(VehicleGradeability, SlopeLimitMatchesTheOriginalsRuns) {
  const vehicles::VehicleParams p = test::Hmmwv();
  struct Case {
    double mu, ref_lo, ref_hi;
  };
  const Case cases[] = {{0.9, 30.0, 32.0}, {0.5, 20.0, 25.0}};
  for (const Case& c : cases) {
    const double lo = SlopeLimit(p, c.mu);
    std::printf("mu %.1f: climbs 30 m up to %.1f deg; the original %.0f-%.0f deg\n", c.mu, lo,
                c.ref_lo, c.ref_hi);
    EXPECT_GE(lo, c.ref_lo - 3.0) << c.mu;
    if (c.mu < 0.8) {
      EXPECT_LE(lo, c.ref_hi + 3.0) << c.mu;
    }
  }
}

// The original's times to 30 m up the slope (reference_chrono_runs.md, "Slopes"), which say
// more than the pass/fail limit: below 30 deg at mu 0.9 the times follow the original's within
// 11 %, so the climb's traction and engine match. On the steepest slopes both climbs are
// traction-limited with the front wheels spinning (vb at 32 deg: front slip 0.94 falling to 0.2,
// the engine pinned at 232.4 rad/s and 912 N m on the full-load map's falling edge, just under
// the 4th-to-5th upshift at 233.1 rad/s; thrust 15.7 kN against the slope's 13.0 kN). vb is
// faster there (NOT MET): 30 deg mu 0.9 -20 %, 20 deg mu 0.5 -26 %; asserted only that vb is not
// slower. The original's drive torque also rolls its chassis (no engine block in Chrono's
// SIMPLE_MAP powertrain), which yaws the spinning vehicle off the fall line: with that artefact
// vb's mu 0.9 times come within 5 % (TheOriginalsUnreactedShaftTorqueExplainsItsSlopeLimit,
// docs/validation.md).
TEST(VehicleGradeability, ClimbTimesFollowTheOriginalsRuns) {
  const vehicles::VehicleParams p = test::Hmmwv();
  struct Case {
    double mu, deg, ref_s, tolerance;  // tolerance < 0: only "not slower than the original"
  };
  const Case cases[] = {{0.9, 15.0, 3.6, 0.11}, {0.9, 20.0, 4.2, 0.11}, {0.9, 25.0, 4.9, 0.11},
                        {0.9, 28.0, 5.8, 0.11}, {0.9, 30.0, 7.2, -1.0}, {0.5, 15.0, 5.6, 0.11},
                        {0.5, 20.0, 9.4, -1.0}};
  for (const Case& c : cases) {
    const double t = SecondsToClimb30m(p, c.deg * kDeg, c.mu);
    std::printf("mu %.1f %4.1f deg: 30 m in %.2f s, the original %.1f s (%+.0f %%)\n", c.mu,
                c.deg, t, c.ref_s, 100.0 * (t / c.ref_s - 1.0));
    ASSERT_GT(t, 0.0) << c.mu << " " << c.deg;
    if (c.tolerance > 0.0) {
      EXPECT_NEAR(t / c.ref_s, 1.0, c.tolerance) << c.mu << " " << c.deg;
    } else {
      EXPECT_LE(t, c.ref_s) << c.mu << " " << c.deg;
    }
  }
}

// The original's powertrain semantics, which vb does not copy by default: Chrono's SIMPLE_MAP
// engine and AUTOMATIC_SIMPLE_MAP transmission have no engine block, so the propeller shafts'
// torque reacts on the chassis through the conical gears (ChShaftsGearboxAngled's truss term) as a
// net roll torque T_engine / gear ratio (engine_block_reaction: false), and the transmission holds
// no gear after a shift (min_time_in_gear_s 0). The roll torque moves load from one side to the
// other; with "locked" differentials that are 100 N m clutches, the spinning front wheels push
// unequally, the vehicle yaws off the fall line and its uphill progress stops: the original's
// "32 deg: 13 m up, then no progress". With both, vb reproduces the original's mu 0.9 runs: limit
// 32.1 deg (original 30-32), times 3.62 / 4.02 / 4.71 / 5.54 / 7.16 s (original 3.6 / 4.2 / 4.9 /
// 5.8 / 7.2), at 33 deg 9 m up, then none. At mu 0.5 it yaws faster than the original: 15 deg in
// 6.11 s (original 5.6), but 20 deg stops after 12 m (original: 30 m in 9.4 s, 41 m at most),
// limit 16.8 deg (original 20-25): printed, not asserted. docs/validation.md.
TEST(VehicleGradeability, TheOriginalsUnreactedShaftTorqueExplainsItsSlopeLimit) {
  vehicles::VehicleParams p = test::Hmmwv();
  p.driveline.engine_block_reaction = false;
  p.transmission.min_time_in_gear_s = 0.0;
  const double limit = SlopeLimit(p, 0.9);
  std::printf("original's semantics, mu 0.9: climbs 30 m up to %.1f deg; the original 30-32\n",
              limit);
  EXPECT_GE(limit, 30.0 - 3.0);
  EXPECT_LE(limit, 32.0 + 3.0);
  struct Case {
    double deg, ref_s;
  };
  for (const Case& c : {Case{15.0, 3.6}, Case{20.0, 4.2}, Case{25.0, 4.9}, Case{28.0, 5.8},
                        Case{30.0, 7.2}}) {
    const double t = SecondsToClimb30m(p, c.deg * kDeg, 0.9);
    std::printf("original's semantics, mu 0.9 %4.1f deg: 30 m in %.2f s, the original %.1f s "
                "(%+.0f %%)\n", c.deg, t, c.ref_s, 100.0 * (t / c.ref_s - 1.0));
    EXPECT_NEAR(t / c.ref_s, 1.0, 0.11) << c.deg;
  }
  // The failure's signature: some metres up, then no further progress (the original at 32 deg:
  // 13 m), not a failure at the start.
  double up_m = 0.0;
  EXPECT_LT(SecondsToClimb30m(p, 33.0 * kDeg, 0.9, &up_m), 0.0);
  std::printf("original's semantics, mu 0.9 33 deg: %.1f m up at most\n", up_m);
  EXPECT_GT(up_m, 5.0);
  EXPECT_LT(up_m, 25.0);
  // mu 0.5 (printed): 15 deg within 11 % of the original, 20 deg and the limit not met.
  const double t15 = SecondsToClimb30m(p, 15.0 * kDeg, 0.5);
  std::printf("original's semantics, mu 0.5 15.0 deg: 30 m in %.2f s, the original 5.6 s\n", t15);
  EXPECT_NEAR(t15 / 5.6, 1.0, 0.11);
  const double t20 = SecondsToClimb30m(p, 20.0 * kDeg, 0.5, &up_m);
  std::printf("original's semantics, mu 0.5 20.0 deg: %.2f s, %.1f m up at most; the original "
              "9.4 s, 41 m at most; limit %.1f deg, the original 20-25\n",
              t20, up_m, SlopeLimit(p, 0.5));
}

}  // namespace
}  // namespace vb
