// A vehicle on a world with soil, stepped in the runner's order (SetInputs -> Synchronize -> soil
// EndStep -> Step -> UpdateState): the rig of the soil validation tests (the HMMWV's flat-soil
// runs against the original's, its static sinkage, ruts and gradeability, the ARTcar's grid check,
// the M113's static sinkage).
#pragma once

#include <memory>
#include <string>

#include "io/soil_io.h"
#include "support/vehicle_sim.h"
#include "vb/soil/scm_soil.h"

namespace vb::test {

// The benchmark's soil file (data/soils/verti_bench.yaml); grid_m > 0 replaces its node spacing.
inline soil::SoilConfig BenchSoil(double grid_m = 0.0) {
  soil::SoilConfig config =
      io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
  if (grid_m > 0.0) config.grid_spacing_m = grid_m;
  return config;
}

// Pose of a vehicle on the flat plane z = 0 at (x, 0), facing +x, its wheels `lift_m` above the
// ground (wheel-centre plane at the radius minus the first axle's height, plus the lift).
inline Pose FlatStart(const vehicles::VehicleParams& p, double x_m, double lift_m) {
  Pose pose;
  pose.position = Vec3(x_m, 0.0, p.wheel.radius_m - p.axles[0].z_m + lift_m);
  return pose;
}

struct SoilSim {
  terrain::TaskSpec task;
  terrain::Terrain ground;
  soil::SoilConfig config;
  std::unique_ptr<soil::ScmSoil> soil;   // null: the rigid tire everywhere (no soil attached)
  engine::PhysicsWorld world;
  vehicles::VehicleParams params;
  std::unique_ptr<vehicles::Vehicle> vehicle;

  // with_soil: build the soil solver from `cfg` and attach it to the vehicle.
  SoilSim(const terrain::TaskSpec& tk, const vehicles::VehicleParams& p, const Pose& pose,
          const soil::SoilConfig& cfg, bool with_soil = true)
      : task(tk), ground(task), config(cfg), params(p) {
    if (with_soil) soil = std::make_unique<soil::ScmSoil>(ground, config);
    vehicle = std::make_unique<vehicles::Vehicle>(params, ground, pose, &world);
    if (soil) vehicle->SetSoil(soil.get());
  }
  // The vehicle holds references to the ground and the world: a rig never moves.
  SoilSim(const SoilSim&) = delete;
  SoilSim& operator=(const SoilSim&) = delete;
  // One step; `base_force_W` (if not zero) acts on the chassis at its centre of mass during it.
  void Step(const vehicles::DriverInputs& in, const Vec3& base_force_W = Vec3::Zero(),
            double dt = kStep_s) {
    vehicle->SetInputs(in);
    vehicle->Synchronize(dt);
    if (soil) soil->EndStep(dt);
    if (base_force_W.squaredNorm() > 0.0) {
      world.ApplyBaseForce(vehicle->body(), base_force_W,
                           world.BasePose(vehicle->body()).position);
    }
    world.Step(dt);
    vehicle->UpdateState();
  }
  // Mean over the wheels of radius - spindle height above the undeformed flat surface (z = 0).
  double MeanSinkage() const {
    const auto& wheels = vehicle->state().wheels;
    double s = 0.0;
    for (const vehicles::WheelState& w : wheels) {
      s += (params.wheel.radius_m - w.center_W.z()) / static_cast<double>(wheels.size());
    }
    return s;
  }
  const vehicles::VehicleState& state() const { return vehicle->state(); }
};

}  // namespace vb::test
