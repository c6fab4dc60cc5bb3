// The 1/6-scale ARTcar on flat snow, mud and sand: is its soil grid fine enough? (issue 11,
// docs/vehicles.md "The soil grid of a small wheel"). On the soil file's 0.05 m grid the 0.0855 m
// tread spans 1.7 node columns and the 0.085 m radius 1.7 cells; the static sinkage in mud and
// sand then reads 43-46 % above the grid-converged value (6.7 mm against 4.6 mm in mud). The car
// asks for 0.025 m (max_soil_grid_m, 3.4 columns across the tread, as the Verti-Wheeler's 3.3).
// Asserted: on the grid the runner builds for it (the smaller of the soil file's spacing and the
// vehicle's max_soil_grid_m), static sinkage, driving sinkage and speed agree with a 0.0125 m grid
// within the HMMWV's flat-soil tolerances against the original (sinkage 25 %, speed 10 %), at the
// benchmark's 4 m/s and at the Froude-equivalent 1.633 m/s. No Chrono figures exist for the
// ARTcar on soil, so grid convergence is the check. (Below 0.01 m the driving sinkage on snow
// grows again, 7.7 -> 10.6 mm at 0.003 m: the soil spring's per-wheel stiffness cap spreads over
// more nodes, docs/soil.md; hence 0.0125 m, not the finest grid, as the reference.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "io/vehicle_io.h"
#include "support/soil_sim.h"

namespace vb::soil {
namespace {

using terrain::SurfaceClass;

struct FlatResult {
  double static_sinkage_m = 0.0, driving_sinkage_m = 0.0, speed_mps = 0.0;
};

// Settle 2 s, then the P speed controller (gain 1) for 8 s; driving figures are the means of the
// last 4 s. Sinkage = wheel radius minus the spindle height above the undeformed surface (z = 0),
// mean of the four wheels.
FlatResult DriveFlat(const vehicles::VehicleParams& p, SurfaceClass surface, double grid_m,
                     double target_mps) {
  test::SoilSim d(test::PlaneTask(32.0, 0.0, 0.0, 0.8, surface), p, test::FlatStart(p, -10.0, 0.01),
                  test::BenchSoil(grid_m));
  FlatResult r;
  const vehicles::DriverInputs idle;
  for (int k = 0; k < 400; ++k) d.Step(idle);
  r.static_sinkage_m = d.MeanSinkage();
  int n = 0;
  for (int k = 0; k < 1600; ++k) {
    d.Step(test::SpeedControl(target_mps, d.state().forward_speed_mps));
    if (k >= 800) {
      r.driving_sinkage_m += d.MeanSinkage();
      r.speed_mps += d.state().forward_speed_mps;
      ++n;
    }
  }
  r.driving_sinkage_m /= n;
  r.speed_mps /= n;
  return r;
}

TEST(ArtSoilGrid, ItsGridAgreesWithAFineGridOnFlatSoil) {
  const vehicles::VehicleParams art = io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/art.yaml");
  const SoilConfig file = test::BenchSoil();
  // As Episode::Reset builds it.
  const double grid_m = art.max_soil_grid_m > 0.0
                            ? std::min(file.grid_spacing_m, art.max_soil_grid_m)
                            : file.grid_spacing_m;
  EXPECT_DOUBLE_EQ(grid_m, 0.025);
  constexpr double kFineGrid_m = 0.0125;
  for (SurfaceClass s : {SurfaceClass::kSnow, SurfaceClass::kMud, SurfaceClass::kSand}) {
    for (double target_mps : {1.633, 4.0}) {
      const FlatResult r = DriveFlat(art, s, grid_m, target_mps);
      const FlatResult f = DriveFlat(art, s, kFineGrid_m, target_mps);
      const std::string name(terrain::SurfaceClassName(s));
      std::printf("%-4s target %.3f m/s, grid %.4f vs %.4f m: static sinkage %.2f vs %.2f mm, "
                  "driving sinkage %.2f vs %.2f mm, speed %.3f vs %.3f m/s\n",
                  name.c_str(), target_mps, grid_m, kFineGrid_m,
                  1e3 * r.static_sinkage_m, 1e3 * f.static_sinkage_m, 1e3 * r.driving_sinkage_m,
                  1e3 * f.driving_sinkage_m, r.speed_mps, f.speed_mps);
      SCOPED_TRACE(name + " at " + std::to_string(target_mps));
      EXPECT_NEAR(r.static_sinkage_m, f.static_sinkage_m, 0.25 * f.static_sinkage_m);
      EXPECT_NEAR(r.driving_sinkage_m, f.driving_sinkage_m, 0.25 * f.driving_sinkage_m);
      EXPECT_NEAR(r.speed_mps, f.speed_mps, 0.10 * f.speed_mps);
    }
  }
}

}  // namespace
}  // namespace vb::soil
