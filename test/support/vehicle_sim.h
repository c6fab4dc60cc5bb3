// A vehicle on a synthetic world, stepped in the runner's order (SetInputs -> Synchronize ->
// Step -> UpdateState) at the runner's 5 ms step, plus small helpers the vehicle tests share.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>

#include "support/worlds.h"
#include "vb/engine/physics_world.h"
#include "vb/terrain/terrain.h"
#include "vb/terrain/obstacle_field.h"
#include "vb/vehicles/vehicle.h"

namespace vb::test {

constexpr double kStep_s = 0.005;

// A planar world like PlaneTask but with `vertices` x `vertices` height samples, so that large
// flat worlds (straight-line tests need ~1 km) stay cheap.
inline terrain::TaskSpec LargePlaneTask(double size_m, int vertices, double slope_x = 0.0,
                                        double slope_y = 0.0, double mu = 0.9) {
  terrain::TaskSpec t = PlaneTask(16.0, slope_x, slope_y, mu);
  t.size_x_m = t.size_y_m = size_m;
  t.heights.rows = t.heights.cols = vertices;
  t.heights.heights_m.assign(static_cast<size_t>(vertices) * vertices, 0.0);
  const double spacing = size_m / (vertices - 1);
  double lo = 1e300, hi = -1e300;
  for (int r = 0; r < vertices; ++r) {
    for (int c = 0; c < vertices; ++c) {
      const double h = slope_x * (-size_m / 2 + c * spacing) + slope_y * (size_m / 2 - r * spacing);
      t.heights.heights_m[static_cast<size_t>(r) * vertices + c] = h;
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
  }
  t.min_height_m = lo;
  t.max_height_m = hi > lo ? hi : lo + 1.0;
  return t;
}

// Chassis pose on the plane z = sx*x + sy*y: body z along the plane normal, body x along the
// heading `yaw_rad` projected on the plane, reference point (wheel-centre plane) one wheel radius
// plus `lift_m` above the plane.
inline Pose PoseOnPlane(double x, double y, double sx, double sy, double yaw_rad, double radius_m,
                        double lift_m) {
  const Vec3 n = Vec3(-sx, -sy, 1.0).normalized();
  const Vec3 h0(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
  const Vec3 h = (h0 - h0.dot(n) * n).normalized();
  Mat3 r;
  r.col(0) = h;
  r.col(1) = n.cross(h);
  r.col(2) = n;
  Pose p;
  p.rotation = Quat(r);
  p.position = Vec3(x, y, sx * x + sy * y) + n * (radius_m + lift_m);
  return p;
}

struct VehicleSim {
  terrain::TaskSpec task;
  terrain::Terrain terrain;
  terrain::ObstacleField obstacles;
  engine::PhysicsWorld world;
  vehicles::VehicleParams params;
  std::unique_ptr<vehicles::Vehicle> vehicle;
  double t = 0.0;

  VehicleSim(const terrain::TaskSpec& tk, const vehicles::VehicleParams& p, const Pose& pose)
      : task(tk), terrain(task), obstacles(task, terrain), params(p) {
    vehicle = std::make_unique<vehicles::Vehicle>(params, terrain, pose, &world);
    vehicle->SetObstacles(&obstacles);
  }
  void Step(const vehicles::DriverInputs& in, double dt = kStep_s) {
    vehicle->SetInputs(in);
    vehicle->Synchronize(dt);
    world.Step(dt);
    vehicle->UpdateState();
    t += dt;
  }
  void Run(double seconds, const vehicles::DriverInputs& in, double dt = kStep_s) {
    const long n = std::lround(seconds / dt);
    for (long i = 0; i < n; ++i) Step(in, dt);
  }
  const vehicles::VehicleState& state() const { return vehicle->state(); }
};

inline double UnsprungMass(const vehicles::VehicleParams& p, const vehicles::AxleParams& a) {
  return a.suspension.carrier_mass_kg + p.wheel.mass_kg;
}

inline double TotalMass(const vehicles::VehicleParams& p) {
  double m = p.chassis.mass_kg + p.steering.link_mass_kg;
  for (const auto& a : p.axles) m += 2.0 * UnsprungMass(p, a);
  return m;
}

// Proportional speed controller (the original's, Kp = 1) as driver inputs.
inline vehicles::DriverInputs SpeedControl(double target_mps, double speed_mps,
                                           double steering = 0.0) {
  const double out = std::clamp(1.0 * (target_mps - speed_mps), -1.0, 1.0);
  vehicles::DriverInputs in;
  in.throttle = out > 0 ? out : 0.0;
  in.braking = out > 0 ? 0.0 : -out;
  in.steering = steering;
  return in;
}

constexpr double kDeg = kPi / 180.0;

}  // namespace vb::test
