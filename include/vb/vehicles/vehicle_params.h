// Vehicle description as plain data (loaded strictly from data/vehicles/<name>.yaml by
// tools/io/vehicle_io.h). Chassis frame: ISO, x forward, y left, z up; origin at the chassis
// reference point (midway between the outer axles, at wheel-centre height), which is also the
// point whose position is reported as the vehicle position. SI units, radians.
#pragma once

#include <string>
#include <vector>

#include "vb/engine/types.h"

namespace vb::vehicles {

struct ChassisParams {
  double mass_kg = 0.0;
  Vec3 inertia_kgm2 = Vec3::Zero();     // principal moments about the COM
  Vec3 com_B = Vec3::Zero();            // COM in the chassis reference frame
  Vec3 collision_box_center_B = Vec3::Zero();
  Vec3 collision_box_size_m = Vec3::Zero();  // full lengths
};

// Vertical strut suspension (first version): the wheel carrier slides along chassis z.
// Travel s is positive in compression (wheel moves up relative to the chassis); s = 0 at the
// design position. Strut force on the wheel (downwards, N) = preload + k*s + c*ds/dt.
struct SuspensionParams {
  double stiffness_npm = 0.0;       // wheel rate (spring rate times motion ratio squared)
  double damping_nspm = 0.0;        // wheel-rate damping
  double preload_n = 0.0;           // spring force at s = 0
  double bump_travel_m = 0.0;       // max compression (bump stop)
  double rebound_travel_m = 0.0;    // max extension (rebound stop)
  double carrier_mass_kg = 0.0;     // upright + spindle
  Vec3 carrier_inertia_kgm2 = Vec3::Ones();
};

struct WheelParams {
  double radius_m = 0.0;
  double width_m = 0.0;
  double mass_kg = 0.0;             // rim + tire
  Vec3 inertia_kgm2 = Vec3::Ones(); // (x, spin y, z)
};

// Rigid tire contact: normal penalty spring-damper, elastic bristle for static friction,
// Coulomb limit mu = min(tire mu, patch mu) (Chrono's NSC composition rule).
struct TireParams {
  double friction = 0.9;                 // tire material mu
  double normal_stiffness_npm = 0.0;
  double normal_damping_nspm = 0.0;
  double bristle_stiffness_npm = 0.0;    // tangential stiffness of the stick state
  double bristle_damping_nspm = 0.0;
};

struct AxleParams {
  double x_m = 0.0;                 // wheel-centre x in chassis frame
  double half_track_m = 0.0;        // wheel-centre |y|
  double z_m = 0.0;                 // wheel-centre z at design position
  bool steered = false;
  bool driven = true;
  double brake_torque_nm = 0.0;     // max braking torque per wheel
  SuspensionParams suspension;
};

struct SteeringParams {
  double max_angle_rad = 0.0;       // road-wheel angle of the inner wheel at full input
  bool ackermann = true;            // inner/outer angles from Ackermann geometry
};

struct EngineMapPoint {
  double speed_radps = 0.0;
  double full_throttle_nm = 0.0;
  double zero_throttle_nm = 0.0;
};

struct EngineParams {
  double max_speed_radps = 0.0;
  std::vector<EngineMapPoint> map;  // ascending speed; linear interpolation
};

struct TransmissionParams {
  std::vector<double> forward_ratios;   // output/input, gear 1 first
  double reverse_ratio = 0.0;           // magnitude (> 0) of the reverse gear ratio
  std::vector<double> upshift_rpm;      // per gear
  std::vector<double> downshift_rpm;    // per gear
};

struct DrivelineParams {
  double conical_ratio = 1.0;          // wheel speed / differential input shaft speed
  bool lock_axle_differentials = false;
  bool lock_central_differential = false;
  double lock_torque_limit_nm = 0.0;   // clutch torque of a "locked" differential
};

struct VehicleParams {
  std::string name;
  ChassisParams chassis;
  std::vector<AxleParams> axles;       // front to rear; each axle has a left and a right wheel
  SteeringParams steering;
  WheelParams wheel;
  TireParams tire;
  EngineParams engine;
  TransmissionParams transmission;
  DrivelineParams driveline;
};

}  // namespace vb::vehicles
