// A vehicle leaving a rut in soil onto rigid ground (docs/vehicles.md, "The soil/rigid seam";
// docs/validation.md). A flat world whose western half (x < 0) is mud and eastern half dirt: the
// vehicle starts 12 m inside the mud and drives east at a set speed, so every wheel sinks into
// its rut and then meets the rigid patch's edge at x = 0. The rigid patch is at the undisturbed
// height, so the edge is a step as high as the rut is deep, and the wheel must climb it: the
// rigid tire meets the edge as a convex corner (normal from the edge to the wheel centre), never
// as the rigid surface's full height above the wheel's bottom. Before that model (FEDA, env099
// pair 0) the rigid contact of a wheel the soil had just released met the undisturbed surface
// 0.24 m above its bottom: 1.24 MN (20 vehicle weights) in one step and a diverged state.
// Asserted per vehicle: the state stays finite, the deepest wheel sinkage on the way to the seam
// (the step height met), the peak normal force of any wheel while crossing the seam stays below
// 3 vehicle weights (a wheel meeting a curb at speed; the defect gave 20), and the vehicle gets
// its rear axle 3 m onto the rigid patch within 25 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "io/soil_io.h"
#include "support/vehicle_sim.h"
#include "support/worlds.h"
#include "vb/engine/physics_world.h"
#include "vb/soil/scm_soil.h"
#include "vb/terrain/terrain.h"
#include "vb/vehicles/vehicle.h"

namespace vb {
namespace {

constexpr double kDt = test::kStep_s;

struct SeamRun {
  double max_sinkage_m = 0.0;      // deepest wheel sinkage before the seam
  double peak_force_weights = 0.0; // largest wheel normal force, in vehicle weights
  double peak_at_x_m = 0.0;        // where the chassis reference point was then
  double t_out_s = -1.0;           // rear axle 3 m past the seam (-1: never)
  bool finite = true;
};

SeamRun DriveOutOfMud(const std::string& vehicle_name, double speed_mps) {
  terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.8, terrain::SurfaceClass::kMud);
  for (int r = 0; r < 16; ++r) {  // patch columns 8..15 (x >= 0): dirt
    for (int c = 8; c < 16; ++c) {
      task.patches.classes[static_cast<size_t>(r * 16 + c)] = terrain::SurfaceClass::kDirt;
      task.patches.friction[static_cast<size_t>(r * 16 + c)] = 0.8;
    }
  }
  const terrain::Terrain ground(task);
  const vehicles::VehicleParams params =
      io::LoadVehicle(std::string(VB_SOURCE_DIR) + "/data/vehicles/" + vehicle_name + ".yaml");
  soil::ScmSoil soil(ground,
                     io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml"));
  engine::PhysicsWorld world;
  vehicles::Vehicle vehicle(params, ground,
                            test::PoseOnPlane(-12.0, 0.0, 0.0, 0.0, 0.0, params.wheel.radius_m, 0.02),
                            &world);
  vehicle.SetSoil(&soil);
  double mass_kg = params.chassis.mass_kg;
  for (const vehicles::AxleParams& a : params.axles) {
    mass_kg += 2.0 * (a.suspension.carrier_mass_kg +
                      (a.wheel.radius_m > 0.0 ? a.wheel.mass_kg : params.wheel.mass_kg));
  }
  const double weight_n = mass_kg * kGravity;
  double rear_x_m = 0.0;
  for (const vehicles::AxleParams& a : params.axles) rear_x_m = std::min(rear_x_m, a.x_m);
  SeamRun run;
  for (int k = 0; k < static_cast<int>(25.0 / kDt); ++k) {
    const vehicles::VehicleState& s = vehicle.state();
    vehicle.SetInputs(test::SpeedControl(speed_mps, s.forward_speed_mps));
    vehicle.Synchronize(kDt);
    soil.EndStep(kDt);
    world.Step(kDt);
    vehicle.UpdateState();
    const vehicles::VehicleState& st = vehicle.state();
    const double x = st.pose_W.position.x();
    if (!std::isfinite(x) || !std::isfinite(st.velocity_W.norm()) || st.velocity_W.norm() > 50.0) {
      run.finite = false;
      break;
    }
    for (const vehicles::WheelState& w : st.wheels) {
      if (w.center_W.x() < -0.2) run.max_sinkage_m = std::max(run.max_sinkage_m, w.sinkage_m);
      // the seam crossing: any wheel within 1.5 m of the edge
      if (std::abs(w.center_W.x()) < 1.5 && w.normal_force_n / weight_n > run.peak_force_weights) {
        run.peak_force_weights = w.normal_force_n / weight_n;
        run.peak_at_x_m = x;
      }
    }
    if (x + rear_x_m > 3.0) {
      run.t_out_s = (k + 1) * kDt;
      break;
    }
  }
  std::printf("%s at %.1f m/s out of mud onto dirt: deepest sinkage %.3f m, peak wheel force "
              "%.2f vehicle weights (at x = %.2f m), rear axle 3 m onto the rigid patch at %.1f s%s\n",
              vehicle_name.c_str(), speed_mps, run.max_sinkage_m, run.peak_force_weights,
              run.peak_at_x_m, run.t_out_s, run.finite ? "" : " (state diverged)");
  return run;
}

TEST(SoilSeamValidation, FedaClimbsOutOfItsMudRutOntoRigidGround) {
  const SeamRun run = DriveOutOfMud("feda", 1.5);
  EXPECT_TRUE(run.finite);
  EXPECT_GT(run.max_sinkage_m, 0.05);  // a real step to climb
  EXPECT_LT(run.peak_force_weights, 3.0);
  EXPECT_GT(run.t_out_s, 0.0);
}

TEST(SoilSeamValidation, HmmwvClimbsOutOfItsMudRutOntoRigidGround) {
  const SeamRun run = DriveOutOfMud("hmmwv", 1.5);
  EXPECT_TRUE(run.finite);
  EXPECT_GT(run.max_sinkage_m, 0.05);
  EXPECT_LT(run.peak_force_weights, 3.0);
  EXPECT_GT(run.t_out_s, 0.0);
}

}  // namespace
}  // namespace vb
