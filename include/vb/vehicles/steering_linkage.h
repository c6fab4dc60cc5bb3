// Road-wheel angles of the steering mechanisms that have no tie-rod hard points in the reference
// (pitman arm, rotary arm with bellcrank, ideal Ackermann, and a rack on single-wishbone knuckle
// arms). The rack-pinion on a double wishbone uses the linkage solver (suspension_kinematics.h).
#pragma once

#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

// Where a vehicle turns about at low speed: the line through the mean x of its unsteered axles;
// `first_steered_x_m` is the front steered axle's x.
struct TurnGeometry {
  double centre_x_m = 0.0;
  double first_steered_x_m = 0.0;
};

// Left and right road-wheel angles (rad, + = left) of the steered axle at x `axle_x_m` with wheel
// track `track_m`, for a steering input in [-1, 1] (+1 full left):
//  - kAckermann, kPitmanArm, kRotaryArm: the inner wheel of the first steered axle turns by
//    input * max_angle_rad * wheel_per_arm (wheel_per_arm 1 for kAckermann); every wheel of
//    every steered axle points at the same turning centre on the unsteered axles' line.
//  - kRackPinion on a single wishbone: asin(rack / steering_arm_m) on both wheels (parallel).
void LinkageSteerAngles(const SteeringParams& steering, const TurnGeometry& geometry,
                        double input, double axle_x_m, double track_m, double steering_arm_m,
                        double* left, double* right);

// Largest inner road-wheel angle of the first steered axle (rad) at full lock.
double MaxInnerSteerAngle(const SteeringParams& steering, double steering_arm_m);

}  // namespace vb::vehicles
