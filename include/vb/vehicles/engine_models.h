// Engine models given by a few numbers, turned into the torque map the powertrain interpolates
// (EngineParams::map). Pure functions; the loader calls them.
#pragma once

#include <vector>

#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

// DC motor (Chrono's ARTcar / Verti-Wheeler "motor map"): full-throttle torque falls linearly from
// the stall torque at rest to 0 at the no-load speed (Kv x voltage) and, as a real motor's, on
// beyond it (back-EMF above the supply brakes), to -stall at twice the no-load speed, where the
// map ends (DcMotorMapEnd: the EngineParams::max_speed_radps to use). Zero throttle gives 0.
// Ending the map at the no-load speed with 0 would let a vehicle that overshoots it (a wheelie
// landing, a downhill) keep its speed with no torque: the Verti-Wheeler ran 32 % above its
// no-load speed that way.
std::vector<EngineMapPoint> DcMotorMap(double stall_torque_nm, double no_load_speed_radps);
double DcMotorMapEnd(double no_load_speed_radps);

// Chrono's ChEngineSimple: full-throttle torque min(max torque, max power / w) up to the maximum
// speed, where it drops to 0 (over the last 2 % of the range, so the map stays a function), and
// a governor beyond it: -max torque at 5 % overspeed, where the map ends (SimpleEngineMapEnd).
// Zero throttle gives 0. Sampled at `points` speeds (>= 8) plus the corner speed.
constexpr double kGovernorOverspeed = 1.05;
std::vector<EngineMapPoint> SimpleEngineMap(double max_torque_nm, double max_power_w,
                                            double max_speed_radps, int points = 24);
double SimpleEngineMapEnd(double max_speed_radps);

}  // namespace vb::vehicles
