#include "vb/vehicles/engine_models.h"

#include <algorithm>

namespace vb::vehicles {

double DcMotorMapEnd(double no_load_speed_radps) { return 2.0 * no_load_speed_radps; }
double SimpleEngineMapEnd(double max_speed_radps) { return kGovernorOverspeed * max_speed_radps; }

std::vector<EngineMapPoint> DcMotorMap(double stall_torque_nm, double no_load_speed_radps) {
  return {{0.0, stall_torque_nm, 0.0},
          {no_load_speed_radps, 0.0, 0.0},
          {2.0 * no_load_speed_radps, -stall_torque_nm, 0.0}};
}

std::vector<EngineMapPoint> SimpleEngineMap(double max_torque_nm, double max_power_w,
                                            double max_speed_radps, int points) {
  points = std::max(points, 8);
  const double corner = max_power_w / max_torque_nm;  // where the power limit takes over
  const double fade = 0.98 * max_speed_radps;
  std::vector<double> speeds;
  for (int i = 0; i < points; ++i) speeds.push_back(fade * i / (points - 1));
  if (corner > 0.0 && corner < fade) speeds.push_back(corner);
  std::sort(speeds.begin(), speeds.end());
  std::vector<EngineMapPoint> map;
  for (double w : speeds) {
    if (!map.empty() && w <= map.back().speed_radps) continue;
    const double t = w > 0.0 ? std::min(max_torque_nm, max_power_w / w) : max_torque_nm;
    map.push_back({w, t, 0.0});
  }
  map.push_back({max_speed_radps, 0.0, 0.0});
  map.push_back({kGovernorOverspeed * max_speed_radps, -max_torque_nm, 0.0});
  return map;
}

}  // namespace vb::vehicles
