#include "vb/vehicles/steering_linkage.h"

#include <algorithm>
#include <cmath>

namespace vb::vehicles {

double MaxInnerSteerAngle(const SteeringParams& s, double steering_arm_m) {
  switch (s.model) {
    case SteeringModel::kAckermann:
      return s.max_angle_rad;
    case SteeringModel::kPitmanArm:
    case SteeringModel::kRotaryArm:
      return s.max_angle_rad * s.wheel_per_arm;
    case SteeringModel::kRackPinion:
      return std::asin(std::min(1.0, s.max_pinion_angle_rad * s.pinion_radius_m / steering_arm_m));
  }
  return 0.0;
}

void LinkageSteerAngles(const SteeringParams& s, const TurnGeometry& g, double input,
                        double axle_x_m, double track_m, double steering_arm_m, double* left,
                        double* right) {
  input = std::clamp(input, -1.0, 1.0);
  if (s.model == SteeringModel::kRackPinion) {
    const double rack = input * s.max_pinion_angle_rad * s.pinion_radius_m;
    *left = *right = std::asin(std::clamp(rack / steering_arm_m, -1.0, 1.0));
    return;
  }
  const double inner = input * MaxInnerSteerAngle(s, steering_arm_m);
  const double wheelbase = g.first_steered_x_m - g.centre_x_m;   // of the first steered axle
  const double distance = axle_x_m - g.centre_x_m;                // of this axle
  if (std::abs(inner) < 1e-9 || wheelbase <= 0.0) {
    *left = *right = inner;
    return;
  }
  const double radius = wheelbase / std::tan(std::abs(inner));   // turning centre to inner wheel
  const double a_inner = std::atan(distance / radius);
  const double a_outer = std::atan(distance / (radius + track_m));
  if (inner > 0) {  // left turn: left wheel inside
    *left = a_inner;
    *right = a_outer;
  } else {
    *right = -a_inner;
    *left = -a_outer;
  }
}

}  // namespace vb::vehicles
