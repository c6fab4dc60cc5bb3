// Force laws of the shock-based suspensions (kSingleWishbone, kAirWishbone, kSolidAxle): spring
// (linear, progressive, air) and damper (linear or degressive) along the shock, and the resulting
// generalised force on the wheel carrier's slider. Pure functions.
#pragma once

#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

// Spring force along the shock (N, + pushes the mounts apart) at shock length L (m).
//  - kLinear: k (L0 - L), L0 = spring_free_length_m (may be negative: a spring in tension).
//  - kProgressive: with x = L0 - L: k1 x + k2 x^2 for x > 0, 0 for x <= 0 (the coil lifts off
//    its seat), L0 = spring_free_length_m (Chrono's "rest length").
//  - kAir: F0 (h / (h - x))^1.4, x = design length - L, h = 1.4 F0 / k (polytropic gas column of
//    stiffness k at design); x is capped at 0.9 h (the bump stop acts long before).
double SpringForce(const SuspensionParams& su, double length_m);

// Damper force along the shock (N, + pushes apart) at shock speed dL/dt (m/s): -c v / (1 + d |v|)
// with the compression (v < 0) or expansion (v > 0) coefficient and degression.
double DamperForce(const SuspensionParams& su, double length_rate_mps);

// The damper's secant coefficient |F / v| at the given speed (N s/m), for the implicit form.
double DamperSecant(const SuspensionParams& su, double length_rate_mps);

// Shock length at wheel travel s (+ compression).
inline double ShockLength(const SuspensionParams& su, double travel_m) {
  return su.spring_design_length_m - su.motion_ratio * travel_m;
}

}  // namespace vb::vehicles
