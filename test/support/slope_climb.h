// Gradeability from rest, shared by the vehicle validation tests (HMMWV, M113): a vehicle on a
// rigid plane tilted up along +x, held by its brakes, then at full throttle; it "climbs" when it
// gets 5 m up the slope within 8 s. SteepestClimbed bisects the slope angle.
#pragma once

#include <cmath>

#include "support/vehicle_sim.h"

namespace vb::test {

struct ClimbRun {
  double settle_s = 1.0;  // held by the brakes first, to settle on the slope
  double lift_m = 0.0;    // start this far above the plane (PoseOnPlane)
};

inline bool ClimbsFromRest(const vehicles::VehicleParams& p, double angle_rad, double mu,
                           const ClimbRun& run) {
  const double sx = std::tan(angle_rad);
  VehicleSim sim(PlaneTask(128.0, sx, 0.0, mu), p,
                 PoseOnPlane(-40.0, 0, sx, 0, 0, p.wheel.radius_m, run.lift_m));
  vehicles::DriverInputs in;
  in.braking = 1.0;
  sim.Run(run.settle_s, in);
  const Vec3 p0 = sim.state().pose_W.position;
  in.braking = 0.0;
  in.throttle = 1.0;
  sim.Run(8.0, in);
  const Vec3 d = sim.state().pose_W.position - p0;
  return d.x() > 5.0 * std::cos(angle_rad);
}

// The steepest angle (deg) in [lo_deg, hi_deg] climbed, after `halvings` bisection steps.
inline double SteepestClimbed(const vehicles::VehicleParams& p, double mu, double lo_deg,
                              double hi_deg, int halvings, const ClimbRun& run) {
  for (int i = 0; i < halvings; ++i) {
    const double mid = 0.5 * (lo_deg + hi_deg);
    (ClimbsFromRest(p, mid * kDeg, mu, run) ? lo_deg : hi_deg) = mid;
  }
  return lo_deg;
}

}  // namespace vb::test
