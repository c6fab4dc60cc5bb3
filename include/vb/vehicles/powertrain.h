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
  double time_in_gear_s = 0.0;       // since the last shift
  double engine_speed_radps = 0.0;
  double engine_torque_nm = 0.0;
  double driveshaft_torque_nm = 0.0;  // engine torque / gear ratio, + = driving forward
};

// Shift logic of the automatic transmission. Chrono's AUTOMATIC_SIMPLE_MAP shifts on the engine
// speed alone: up above upshift_rpm[gear-1], down below downshift_rpm[gear-1]. vb keeps those
// thresholds, holds a gear for min_time_in_gear_s after a shift, and, if
// upshift_on_ground_speed, judges upshifts on min(engine speed, engine speed implied by the
// vehicle's ground speed), so wheels spinning against an obstacle do not climb the gears (off for
// the HMMWV: on env000 it lowered PID success, see docs/validation.md). One gear per call.
// ground_engine_speed_radps: ground speed / (r * ratio).
void UpdateGear(const TransmissionParams& transmission, double ground_engine_speed_radps,
                double dt, PowertrainState* state);

// Drive torque on each driven wheel (N·m, + = forward) for the given throttle and wheel spin
// speeds (rad/s, same order as `driven`), chassis forward speed (m/s, for the shift logic): engine speed from the mean driven-wheel speed, engine
// torque through gear and conical ratios, equal split, plus the clutch torques of locked
// differentials that oppose left-right (and front-rear) speed differences.
void ComputeWheelTorques(const VehicleParams& params, double throttle,
                         const std::vector<double>& wheel_speeds_radps,
                         const std::vector<bool>& driven, double ground_speed_mps, double dt,
                         PowertrainState* state,
                         std::vector<double>* wheel_torques_nm);

// Driveline inertia lumped onto each driven wheel's spin axis (kg m^2): the shafts reflected
// through the conical gears, shared equally by the driven wheels. Exact when the driven wheels
// turn at one speed (locked differentials, straight line); an approximation in turns.
double DrivelineInertiaPerDrivenWheel(const DrivelineParams& d, int driven_axles);

}  // namespace vb::vehicles
