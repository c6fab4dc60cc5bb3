// The HMMWV on flat and sloped soil (the original's snow, mud and sand) against the rigid case:
// static sinkage per wheel vs Bekker, rut depth and berms after a pass, and the steepest slope it
// climbs (docs/validation.md, "Soil"). Vehicle + soil + physics stepped as the runner does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "support/soil_sim.h"
#include "vb/soil/bekker.h"
#include "vb/terrain/terrain_physics.h"

namespace vb::soil {
namespace {

using terrain::SurfaceClass;

const char* Name(SurfaceClass c) {
  switch (c) {
    case SurfaceClass::kSnow: return "snow";
    case SurfaceClass::kMud: return "mud";
    case SurfaceClass::kSand: return "sand";
    default: return "rigid";
  }
}

// One HMMWV on a plane z = tan(slope) x of one surface, facing +x (uphill), wheels just touching;
// the soil solver only on a deformable surface.
test::SoilSim Drive(SurfaceClass surface, double slope_rad, double x0) {
  const vehicles::VehicleParams params = test::Hmmwv();
  Pose pose;
  pose.rotation = Quat(Eigen::AngleAxisd(-slope_rad, Vec3::UnitY()));
  pose.position = Vec3(x0, 0.0,
                       std::tan(slope_rad) * x0 + params.wheel.radius_m / std::cos(slope_rad) + 0.01);
  return test::SoilSim(test::PlaneTask(128.0, std::tan(slope_rad), 0.0, 0.8, surface), params, pose,
                       test::BenchSoil(), terrain::IsDeformable(surface));
}

// Driver inputs of throttle and braking alone.
vehicles::DriverInputs Pedals(double throttle, double braking) {
  vehicles::DriverInputs in;
  in.throttle = throttle;
  in.braking = braking;
  return in;
}

// Does the HMMWV, starting from rest with full throttle, climb 8 m up the slope within 12 s?
bool Climbs(SurfaceClass surface, double slope_deg) {
  const double slope = slope_deg * kPi / 180.0;
  test::SoilSim d = Drive(surface, slope, -20.0);
  const double x0 = d.vehicle->state().pose_W.position.x();
  for (int k = 0; k < 2400; ++k) {
    d.Step(Pedals(1.0, 0.0));
    if (d.vehicle->state().pose_W.position.x() - x0 > 8.0 * std::cos(slope)) return true;
  }
  return false;
}

// Steepest climbable slope by bisection on [0, 40] deg to 0.5 deg.
double Gradeability(SurfaceClass surface) {
  double lo = 0.0, hi = 40.0;
  if (!Climbs(surface, lo)) return 0.0;
  while (hi - lo > 0.5) {
    const double mid = 0.5 * (lo + hi);
    (Climbs(surface, mid) ? lo : hi) = mid;
  }
  return lo;
}

// Static: the vehicle is lowered onto flat soil over 2 s (a lift force fading out), then rests
// braked; each wheel's sinkage against Bekker's static sinkage for its measured load.
TEST(SoilHmmwvValidation, StaticSinkageAgreesWithBekkerForEachWheelLoad) {
  const SoilConfig config = test::BenchSoil();
  const vehicles::VehicleParams hmmwv = test::Hmmwv();
  double previous = 1e9;
  for (SurfaceClass c : {SurfaceClass::kSnow, SurfaceClass::kMud, SurfaceClass::kSand}) {
    test::SoilSim d = Drive(c, 0.0, 0.0);
    const double weight = hmmwv.chassis.mass_kg * kGravity;
    for (int k = 0; k < 600; ++k) {
      d.Step(Pedals(0.0, 1.0), Vec3(0.0, 0.0, weight * std::max(0.0, 1.0 - k / 400.0)));  // lowered
    }
    double mean_sinkage = 0.0;
    for (const vehicles::WheelState& w : d.vehicle->state().wheels) {
      const double bekker = WheelSinkageExact(*config.For(c), hmmwv.wheel.radius_m, hmmwv.wheel.width_m, w.normal_force_n);
      std::printf("%-4s load %6.0f N  sinkage %.4f m  Bekker %.4f m (%+.1f %%)\n", Name(c), w.normal_force_n,
                  w.sinkage_m, bekker, 100.0 * (w.sinkage_m / bekker - 1.0));
      EXPECT_GT(w.sinkage_m, 0.75 * bekker) << Name(c);
      EXPECT_LT(w.sinkage_m, 1.10 * bekker) << Name(c);
      mean_sinkage += w.sinkage_m / 4.0;
    }
    EXPECT_LT(mean_sinkage, previous) << Name(c);  // snow > mud > sand
    previous = mean_sinkage;
  }
}

// A pass at ~3 m/s leaves ruts with berms beside them; deeper in softer soil; soil conserved.
TEST(SoilHmmwvValidation, PassLeavesRutsWithBerms) {
  double previous = 1e9;
  for (SurfaceClass c : {SurfaceClass::kSnow, SurfaceClass::kMud, SurfaceClass::kSand}) {
    test::SoilSim d = Drive(c, 0.0, -10.0);
    for (int k = 0; k < 2400 && d.vehicle->state().pose_W.position.x() < 10.0; ++k) {
      d.Step(Pedals(std::clamp(3.0 - d.vehicle->state().forward_speed_mps, 0.0, 1.0), 0.0));
    }
    ASSERT_GT(d.vehicle->state().pose_W.position.x(), 5.0) << Name(c) << " did not get through";
    // Across the left track at x = -2 (passed by both axles): deepest point and highest berm.
    const double half_track = 0.9097;
    double rut = 0.0, berm = 0.0;
    for (double y = half_track - 0.6; y <= half_track + 0.6; y += 0.05) {
      const double h = d.soil->SurfaceHeight(-2.0, y);
      rut = std::max(rut, -h);
      berm = std::max(berm, h);
    }
    std::printf("%-4s rut depth %.4f m, berm %.4f m, compacted %.3f m^3, volume change %.2e m^3\n",
                Name(c), rut, berm, d.soil->CompactedVolume_m3(), d.soil->VolumeChange_m3());
    EXPECT_GT(rut, 0.005) << Name(c);
    EXPECT_GT(berm, 0.3 * rut) << Name(c);
    EXPECT_LT(rut, previous) << Name(c);
    EXPECT_NEAR(d.soil->VolumeChange_m3(), 0.0, 1e-12 * d.soil->CompactedVolume_m3() + 1e-15);
    previous = rut;
  }
}

TEST(SoilHmmwvValidation, GradeabilityRigidAboveSandAboveMudAboveSnow) {
  const double rigid = Gradeability(SurfaceClass::kConcrete);
  const double sand = Gradeability(SurfaceClass::kSand);
  const double mud = Gradeability(SurfaceClass::kMud);
  const double snow = Gradeability(SurfaceClass::kSnow);
  std::printf("steepest slope climbed: rigid (mu 0.8) %.1f deg, sand %.1f, mud %.1f, snow %.1f\n",
              rigid, sand, mud, snow);
  EXPECT_GT(rigid, sand);
  EXPECT_GT(sand, mud);
  EXPECT_GT(mud, snow);
}

}  // namespace
}  // namespace vb::soil
