#include "vb/vehicles/powertrain.h"

#include <algorithm>
#include <cmath>

namespace vb::vehicles {
namespace {

constexpr double kRpmToRadps = 3.14159265358979323846 / 30.0;

double Interpolate(const std::vector<EngineMapPoint>& map, double w, bool full) {
  auto value = [full](const EngineMapPoint& p) {
    return full ? p.full_throttle_nm : p.zero_throttle_nm;
  };
  if (w <= map.front().speed_radps) return value(map.front());
  if (w >= map.back().speed_radps) return value(map.back());
  for (size_t i = 1; i < map.size(); ++i) {
    if (w <= map[i].speed_radps) {
      const double t = (w - map[i - 1].speed_radps) / (map[i].speed_radps - map[i - 1].speed_radps);
      return value(map[i - 1]) + t * (value(map[i]) - value(map[i - 1]));
    }
  }
  return value(map.back());
}

// Clutch of a "locked" differential between two shafts: a stiff viscous coupling saturated at the
// clutch torque limit (Chrono's ChShaftsClutch with a 100 N·m limit behaves the same way). The
// coupling (N m s/rad) is the driveline's lock_coupling_nms_per_rad.
double ClutchTorque(double coupling, double speed_difference_radps, double limit_nm) {
  return std::clamp(coupling * speed_difference_radps, -limit_nm, limit_nm);
}

}  // namespace

double EngineTorque(const EngineParams& engine, double speed_radps, double throttle) {
  const double w = std::clamp(speed_radps, 0.0, engine.max_speed_radps);
  const double t = std::clamp(throttle, 0.0, 1.0);
  // Engine drag opposes rotation: it fades out below 1 rad/s so a stopped vehicle is not pushed
  // backwards by the (negative) zero-throttle torque of the map.
  const double drag_fade = std::min(1.0, w / 1.0);
  return Interpolate(engine.map, w, false) * (1.0 - t) * drag_fade +
         Interpolate(engine.map, w, true) * t;
}

void UpdateGear(const TransmissionParams& tr, double ground_engine_speed_radps, double dt,
                PowertrainState* s) {
  s->time_in_gear_s += dt;
  if (s->time_in_gear_s < tr.min_time_in_gear_s) return;
  const int n = static_cast<int>(tr.forward_ratios.size());
  const double rpm = s->engine_speed_radps / kRpmToRadps;
  const double up_rpm =
      (tr.upshift_on_ground_speed ? std::min(s->engine_speed_radps, ground_engine_speed_radps)
                                  : s->engine_speed_radps) /
      kRpmToRadps;
  if (up_rpm > tr.upshift_rpm[s->gear - 1] && s->gear < n) {
    ++s->gear;
    s->time_in_gear_s = 0.0;
  } else if (rpm < tr.downshift_rpm[s->gear - 1] && s->gear > 1) {
    --s->gear;
    s->time_in_gear_s = 0.0;
  }
}

void ComputeWheelTorques(const VehicleParams& p, double throttle,
                         const std::vector<double>& wheel_speeds_radps,
                         const std::vector<bool>& driven, double ground_speed_mps, double dt,
                         PowertrainState* s,
                         std::vector<double>* torques) {
  const size_t n = wheel_speeds_radps.size();
  torques->assign(n, 0.0);
  int n_driven = 0;
  double mean_speed = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (!driven[i]) continue;
    mean_speed += wheel_speeds_radps[i];
    ++n_driven;
  }
  if (n_driven == 0) return;
  mean_speed /= n_driven;

  // Kinematic transmission: engine speed follows the driveshaft (no torque converter).
  const double ratio = p.transmission.forward_ratios[s->gear - 1] * p.driveline.conical_ratio;
  s->engine_speed_radps = std::max(0.0, mean_speed / ratio);
  UpdateGear(p.transmission, std::max(0.0, ground_speed_mps / p.wheel.radius_m / ratio), dt, s);
  const double ratio_after = p.transmission.forward_ratios[s->gear - 1] * p.driveline.conical_ratio;
  s->engine_speed_radps = std::max(0.0, mean_speed / ratio_after);
  s->engine_torque_nm = EngineTorque(p.engine, s->engine_speed_radps, throttle);

  s->driveshaft_torque_nm = s->engine_torque_nm / p.transmission.forward_ratios[s->gear - 1];
  // Open differentials split torque equally between the driven wheels.
  const double per_wheel = s->engine_torque_nm / ratio_after / n_driven;
  for (size_t i = 0; i < n; ++i)
    if (driven[i]) (*torques)[i] = per_wheel;

  // Locked axle differentials: clutch between the left and right wheel of each axle.
  const double limit = p.driveline.lock_torque_limit_nm;
  if (p.driveline.lock_axle_differentials) {
    for (size_t a = 0; 2 * a + 1 < n; ++a) {
      const size_t l = 2 * a, r = 2 * a + 1;
      if (!driven[l] || !driven[r]) continue;
      const double t = ClutchTorque(p.driveline.lock_coupling_nms_per_rad,
                                    wheel_speeds_radps[l] - wheel_speeds_radps[r], limit);
      (*torques)[l] -= t;
      (*torques)[r] += t;
    }
  }
  // Locked central differential: clutch between the front half and the rear half of the axles.
  if (p.driveline.lock_central_differential && n >= 4) {
    const size_t half = (n / 2 + 1) / 2 * 2;  // wheels of the front axles
    double front = 0.0, rear = 0.0;
    int nf = 0, nr = 0;
    for (size_t i = 0; i < n; ++i) {
      if (!driven[i]) continue;
      if (i < half) {
        front += wheel_speeds_radps[i];
        ++nf;
      } else {
        rear += wheel_speeds_radps[i];
        ++nr;
      }
    }
    if (nf > 0 && nr > 0) {
      // The central clutch sits between the front and rear driveshafts, before the conical gears:
      // shaft speed = wheel speed / conical ratio, wheel-side torque = shaft torque / ratio.
      const double k = p.driveline.conical_ratio;
      const double t = ClutchTorque(p.driveline.lock_coupling_nms_per_rad,
                                    (front / nf - rear / nr) / k, limit) / k;
      for (size_t i = 0; i < n; ++i) {
        if (!driven[i]) continue;
        (*torques)[i] += (i < half ? -t / nf : t / nr);
      }
    }
  }
}

double DrivelineInertiaPerDrivenWheel(const DrivelineParams& d, int driven_axles) {
  if (driven_axles <= 0) return 0.0;
  const double fast = d.driveshaft_inertia_kgm2 + d.central_box_inertia_kgm2 +
                      driven_axles * d.axle_shaft_inertia_kgm2;
  const double reflected =
      fast / (d.conical_ratio * d.conical_ratio) + driven_axles * d.axle_box_inertia_kgm2;
  return reflected / (2.0 * driven_axles);
}

}  // namespace vb::vehicles
