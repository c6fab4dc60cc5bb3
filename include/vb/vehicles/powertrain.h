// Powertrain of a wheeled vehicle: engine torque map, automatic transmission (kinematic, no
// torque converter, as Chrono's SIMPLE_MAP pair used by the original), and a driveline that splits
// torque equally through open differentials whose "lock" is a clutch of limited torque.
// Pure functions and a small state; the vehicle applies the resulting wheel torques.
#pragma once

#include <vector>

#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

// Engine torque (N·m) at speed (rad/s) and throttle [0, 1]:
// T = T0(w)·(1 - throttle) + TF(w)·throttle, tables linearly interpolated, w clamped to the map.
double EngineTorque(const EngineParams& engine, double speed_radps, double throttle);

struct PowertrainState {
  int gear = 1;                      // 1-based forward gear
  double engine_speed_radps = 0.0;
  double engine_torque_nm = 0.0;
};

// Shift logic of the automatic transmission: upshift above upshift_rpm[gear-1], downshift below
// downshift_rpm[gear-1]; one gear per call.
void UpdateGear(const TransmissionParams& transmission, PowertrainState* state);

// Drive torque on each driven wheel (N·m, + = forward) for the given throttle and wheel spin
// speeds (rad/s, same order as `driven`): engine speed from the mean driven-wheel speed, engine
// torque through gear and conical ratios, equal split, plus the clutch torques of locked
// differentials that oppose left-right (and front-rear) speed differences.
void ComputeWheelTorques(const VehicleParams& params, double throttle,
                         const std::vector<double>& wheel_speeds_radps,
                         const std::vector<bool>& driven, PowertrainState* state,
                         std::vector<double>* wheel_torques_nm);

}  // namespace vb::vehicles
