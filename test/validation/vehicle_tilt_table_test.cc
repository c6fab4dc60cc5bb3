// Tilt table: the HMMWV, braked, is set on a side slope (left side uphill) and left for 3 s; the
// steepest angle it stays on is found by bisection (0.3 deg resolution).
//  - Rollover on high friction (tire and patch mu 2.0, so it tips before it slides). Reference:
//    static stability factor SSF = t / (2 h) (NHTSA), h = COM height at rest measured in the
//    sim, t = 1.819 m wheel-centre track; rigid-body tip angle atan(SSF) = 56.1 deg. The sim must
//    tip below it, by the compliance: at tip the downhill wheels carry all the weight, so (a) the
//    tire bristles deflect downhill by W sin(52 deg) / 4 / 200 kN/m = 2.4 cm, (b) the body rolls
//    by ~2.2 deg (3.5 cm more bump downhill, 3.5 cm rebound uphill at the wheel rates), moving the
//    COM 0.61 m * 0.038 = 2.4 cm downhill, and (c) with the wheels cambered by that roll the
//    cylinder's line load moves towards the inner tread edge (up to w/2 = 12.7 cm). (a)+(b) and
//    half of (c) give an effective half-track of 0.91 - 0.11 = 0.80 m -> 52.6 deg. Tolerance:
//    atan(SSF) - 5 deg <= angle <= atan(SSF).
//  - Sliding on low friction (patch mu 0.3 < tire 0.9): a braked vehicle slides at atan(mu) =
//    16.70 deg (Coulomb); tolerance 0.5 deg (the bristle holds exactly up to mu*Fn).
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "support/vehicle_sim.h"

namespace vb {
namespace {

using test::kDeg;

enum class Outcome { kHolds, kTipped, kSlid };

Outcome TryAngle(const vehicles::VehicleParams& p, double angle_rad, double mu) {
  const double sy = std::tan(angle_rad);
  test::VehicleSim sim(test::PlaneTask(64.0, 0.0, sy, mu), p,
                       test::PoseOnPlane(0, 0, 0, sy, 0, p.wheel.radius_m, 0.0));
  vehicles::DriverInputs brake;
  brake.braking = 1.0;
  // tipped: rolled 15 deg beyond the table at any time (once over, it tumbles down the slope)
  bool tipped = false;
  auto run = [&](double seconds) {
    for (long i = 0; i < std::lround(seconds / test::kStep_s); ++i) {
      sim.Step(brake);
      tipped = tipped || std::abs(sim.state().rpy.roll_rad) > angle_rad + 15.0 * kDeg;
    }
  };
  run(2.0);  // settling onto the springs
  const Vec3 front0 = sim.state().wheels[1].center_W, rear0 = sim.state().wheels[3].center_W;
  const double roll0 = sim.state().rpy.roll_rad;
  run(3.0);
  const auto& s = sim.state();
  // at the threshold the body rocks on its downhill wheels (or starts tipping slowly): unstable,
  // counts as tipping, not as sliding
  if (tipped || std::abs(s.rpy.roll_rad - roll0) > 2.0 * kDeg) return Outcome::kTipped;
  // slid: the downhill wheels (the pivot when tipping) moved. 0.3 deg beyond atan(mu) a sliding
  // vehicle covers g (sin - mu cos) t^2 / 2 = 0.2 m in 3 s.
  const double moved = std::max((s.wheels[1].center_W - front0).norm(),
                                (s.wheels[3].center_W - rear0).norm());
  if (std::getenv("VB_DEBUG")) std::printf("  %.2f deg: moved %.4f m roll %.2f -> %.2f deg\n", angle_rad / kDeg, moved, roll0 / kDeg, s.rpy.roll_rad / kDeg);
  if (moved > 0.02) return Outcome::kSlid;
  return Outcome::kHolds;
}

// Steepest angle in [lo, hi] (deg) that still holds.
double Bisect(const vehicles::VehicleParams& p, double mu, double lo, double hi,
              Outcome* failure) {
  for (int i = 0; i < 8; ++i) {
    const double mid = 0.5 * (lo + hi);
    const Outcome o = TryAngle(p, mid * kDeg, mu);
    if (o == Outcome::kHolds) {
      lo = mid;
    } else {
      hi = mid;
      *failure = o;
    }
  }
  return lo;
}

TEST(VehicleTiltTable, RolloverVsStaticStabilityFactor) {
  vehicles::VehicleParams p = test::Hmmwv();
  p.tire.friction = 2.0;

  // COM height at rest on flat ground (sprung body from the simulation, unsprung parts at the
  // wheel centres)
  test::VehicleSim flat(test::PlaneTask(64.0, 0, 0, 2.0), p,
                        test::PoseOnPlane(0, 0, 0, 0, 0, p.wheel.radius_m, 0.02));
  flat.Run(3.0, {});
  const double m = test::TotalMass(p);
  double mz = (p.chassis.mass_kg + p.steering.link_mass_kg) *
              flat.world.BasePose(flat.vehicle->body()).position.z();
  for (size_t i = 0; i < flat.state().wheels.size(); ++i)
    mz += test::UnsprungMass(p, p.axles[i / 2]) * flat.state().wheels[i].center_W.z();
  const double h = mz / m;
  const double half_track = p.axles[0].half_track_m;
  const double ssf = half_track / h;
  const double ssf_deg = std::atan(ssf) / kDeg;
  const double edge_deg = std::atan((half_track + 0.5 * p.wheel.width_m) / h) / kDeg;

  Outcome failure = Outcome::kHolds;
  const double angle = Bisect(p, 2.0, 35.0, 70.0, &failure);
  std::printf("COM height %.4f m, SSF %.3f -> %.2f deg; tread-edge bound %.2f deg; "
              "sim tips at %.2f deg (%s)\n",
              h, ssf, ssf_deg, edge_deg, angle, failure == Outcome::kTipped ? "tipped" : "slid");
  EXPECT_EQ(failure, Outcome::kTipped);
  EXPECT_GE(angle, ssf_deg - 5.0);
  EXPECT_LE(angle, ssf_deg);
  EXPECT_LE(angle, edge_deg);
}

TEST(VehicleTiltTable, SlidingAngleOnLowFriction) {
  const vehicles::VehicleParams p = test::Hmmwv();
  constexpr double kMu = 0.3;
  Outcome failure = Outcome::kHolds;
  const double angle = Bisect(p, kMu, 5.0, 30.0, &failure);
  const double expected = std::atan(kMu) / kDeg;
  std::printf("mu %.2f: sim slides at %.2f deg, atan(mu) = %.2f deg\n", kMu, angle, expected);
  EXPECT_EQ(failure, Outcome::kSlid);
  EXPECT_NEAR(angle, expected, 0.5);
}

}  // namespace
}  // namespace vb
