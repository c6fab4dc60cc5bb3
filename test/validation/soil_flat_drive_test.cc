// The HMMWV driven on flat snow, mud and sand against the original's own runs (Chrono 9.0.1
// HMMWV_Reduced on SCM with the original's soil files, ../shared/spec/reference_chrono_runs.md
// "Flat deformable soil"): the vehicle settles for 2 s, then the proportional speed controller
// (gain 1, target 4 m/s) drives straight for 10 s. Sinkage = wheel radius minus the spindle height
// above the undeformed surface, mean of the four wheels. Run on vb's default soil grid (0.05 m)
// and on the original's (0.1 m): a model that converges must agree on both.
// Tolerances (issue 11): speed within 10 %, sinkage while driving within 25 %, except sand's 6 mm
// (held to 5 mm: vb rides at 10 mm, not met at 25 %. The reference's measure reads -1.5 mm on
// ground that does not sink, from its front camber (VehicleStatic.TheReferencesSpindleHeights-
// AreItsFrontCamber); read like for like sand is +19 ... +34 %, docs/validation.md "Sand's 6 mm").
// The rest is the reference's soil footprint: Chrono's SCM finds a wheel by ray casts against its
// Bullet collision cylinder, which Chrono builds with the collision envelope (0.03 m, the original
// leaves the default) added to its radius and half-width and then moves each hit back along the
// surface normal: the radius comes out right, the width does not (0.254 + 2 x 0.03 m). With that
// footprint vb meets 25 % on every soil and grid (TheOriginalsFootprintExplainsItsSinkage).
// Also: at high drive slip on snow the steering keeps its sense (full left lock, full throttle:
// the vehicle turns left, however slowly; it once reversed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "support/soil_sim.h"

namespace vb::soil {
namespace {

using terrain::SurfaceClass;
constexpr double kDt = 0.005;

struct Reference {
  SurfaceClass surface;
  const char* name;
  double static_sinkage_m, driving_sinkage_m, speed_mps;
};
// reference_chrono_runs.md, "Flat deformable soil".
constexpr Reference kReferences[] = {{SurfaceClass::kSnow, "snow", 0.261, 0.108, 3.78},
                                     {SurfaceClass::kMud, "mud", 0.113, 0.043, 3.85},
                                     {SurfaceClass::kSand, "sand", 0.045, 0.006, 3.96}};

// The HMMWV at x = -20 m on a 128 m plane of `surface`, the soil at `grid_m`, wheels 1 cm up.
// `soil_footprint_m` > 0 replaces the width the soil feels (the tire's 0.254 m).
test::SoilSim FlatDrive(SurfaceClass surface, double grid_m, double soil_footprint_m = 0.0) {
  vehicles::VehicleParams hmmwv = test::Hmmwv();
  if (soil_footprint_m > 0.0) hmmwv.wheel.soil_footprint_width_m = soil_footprint_m;
  return test::SoilSim(test::PlaneTask(128.0, 0.0, 0.0, 0.8, surface), hmmwv,
                       test::FlatStart(hmmwv, -20.0, 0.01), test::BenchSoil(grid_m));
}

struct DriveResult {
  double static_sinkage_m, driving_sinkage_m, speed_mps;
  double throttle = 0.0, slip = 0.0, gear = 0.0;  // means over the window (diagnostics)
};

// Settle 2 s, then P speed control (target 4 m/s) for 10 s; speed and sinkage averaged over the
// last 5 s.
DriveResult DriveFlat(SurfaceClass surface, double grid_m, double soil_footprint_m = 0.0) {
  test::SoilSim d = FlatDrive(surface, grid_m, soil_footprint_m);
  vehicles::DriverInputs idle;
  for (int k = 0; k < 400; ++k) d.Step(idle);
  DriveResult r{d.MeanSinkage(), 0.0, 0.0};
  int n = 0;
  for (int k = 0; k < 2000; ++k) {
    const vehicles::DriverInputs in = test::SpeedControl(4.0, d.vehicle->state().forward_speed_mps);
    d.Step(in);
    if (k >= 1000) {
      const vehicles::VehicleState& s = d.vehicle->state();
      r.driving_sinkage_m += d.MeanSinkage();
      r.speed_mps += s.forward_speed_mps;
      r.throttle += in.throttle;
      r.gear += s.gear;
      for (const vehicles::WheelState& w : s.wheels) r.slip += w.longitudinal_slip / 4.0;
      ++n;
    }
  }
  r.driving_sinkage_m /= n;
  r.speed_mps /= n;
  r.throttle /= n;
  r.gear /= n;
  r.slip /= n;
  return r;
}

class SoilFlatDrive : public ::testing::TestWithParam<double> {};

TEST_P(SoilFlatDrive, SpeedAndSinkageMatchTheOriginalsRuns) {
  const double grid_m = GetParam();
  for (const Reference& ref : kReferences) {
    const DriveResult r = DriveFlat(ref.surface, grid_m);
    std::printf("grid %.2f m %-4s: static sinkage %.3f m (ref %.3f), driving sinkage %.3f m "
                "(ref %.3f, %+.0f %%), speed %.2f m/s (ref %.2f, %+.1f %%); throttle %.2f, slip %.2f, "
                "gear %.1f\n",
                grid_m, ref.name, r.static_sinkage_m, ref.static_sinkage_m, r.driving_sinkage_m,
                ref.driving_sinkage_m, 100.0 * (r.driving_sinkage_m / ref.driving_sinkage_m - 1.0),
                r.speed_mps, ref.speed_mps, 100.0 * (r.speed_mps / ref.speed_mps - 1.0), r.throttle,
                r.slip, r.gear);
    EXPECT_NEAR(r.speed_mps, ref.speed_mps, 0.10 * ref.speed_mps) << ref.name;
    EXPECT_NEAR(r.driving_sinkage_m, ref.driving_sinkage_m,
                std::max(0.25 * ref.driving_sinkage_m, 0.005))
        << ref.name;
  }
}

// The reference's own footprint and zero. Chrono's rigid tire is a Bullet cylinder built with
// the model's collision envelope e (Chrono's default 0.03 m; reference_vehicle_soil.md §1.1: the
// original changes no collision setting) added to its radius and half-width; SCM casts a vertical
// ray per node against it and moves the hit back by e along the surface normal
// (ChCollisionSystemBullet::RayHit). On the curved tread that restores the radius; across the
// axle it does not, so the soil feels a wheel 0.254 + 2e = 0.314 m wide (less ~1 cm of rounding
// at each rim, by Bullet's 0.04 m margin: ~0.29 m at sand's depth, 0.31 m at snow's; 0.289, 0.307,
// 0.312 m give the same figures within 1 mm). And the reference's sinkage, r minus the spindle
// height, reads -1.5 mm on its own flat rigid run (front spindles 0.470 m, rear 0.467 m = r: its
// front camber, VehicleStatic.TheReferencesSpindleHeightsAreItsFrontCamber), so its zero is
// -1.5 mm. With both, vb meets the 25 % on every soil and grid, sand included; vb's
// default keeps the tire's true width (data/vehicles/hmmwv_chrono.yaml has the original's).
TEST_P(SoilFlatDrive, TheOriginalsFootprintExplainsItsSinkage) {
  const double grid_m = GetParam();
  constexpr double kChronoEnvelope_m = 0.03;
  constexpr double kReferenceZero_m = 0.0015;  // r - mean spindle height on rigid ground: -1.5 mm
  const double footprint_m = test::Hmmwv().wheel.width_m + 2.0 * kChronoEnvelope_m;
  for (const Reference& ref : kReferences) {
    const DriveResult r = DriveFlat(ref.surface, grid_m, footprint_m);
    const double reference_m = ref.driving_sinkage_m + kReferenceZero_m;
    std::printf("grid %.2f m %-4s, soil footprint %.3f m: driving sinkage %.4f m (reference read "
                "from its zero %.4f m, %+.0f %%), speed %.2f m/s (ref %.2f)\n",
                grid_m, ref.name, footprint_m, r.driving_sinkage_m, reference_m,
                100.0 * (r.driving_sinkage_m / reference_m - 1.0), r.speed_mps, ref.speed_mps);
    EXPECT_NEAR(r.speed_mps, ref.speed_mps, 0.10 * ref.speed_mps) << ref.name;
    EXPECT_NEAR(r.driving_sinkage_m, reference_m, 0.25 * reference_m) << ref.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Grids, SoilFlatDrive, ::testing::Values(0.05, 0.1),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return info.param < 0.075 ? std::string("Default005")
                                                     : std::string("Original010");
                         });

// Full left lock at full throttle on snow (drive slip near 1): the yaw rate stays left. The
// steered front wheels' soil side force keeps its sign at every slip (soil_turning_test), so the
// turn may widen but not reverse.
TEST(SoilFlatDriveSteering, FullLockAtHighSlipOnSnowStillTurnsLeft) {
  for (double grid_m : {0.05, 0.1}) {
    test::SoilSim d = FlatDrive(SurfaceClass::kSnow, grid_m);
    vehicles::DriverInputs in;
    for (int k = 0; k < 400; ++k) d.Step(in);
    in.throttle = 1.0;
    in.steering = 1.0;  // + = left (ISO 8855)
    double yaw_rate_sum = 0.0, slip_sum = 0.0, min_yaw_rate = 1e9;
    int n = 0;
    // 2 ... 6 s after the throttle: the circle (R ~ 50 m at ~15 m/s) stays on the 128 m world
    for (int k = 0; k < 1200; ++k) {
      d.Step(in);
      if (k < 400) continue;
      const double wz = d.vehicle->state().angular_velocity_W.z();
      yaw_rate_sum += wz;
      min_yaw_rate = std::min(min_yaw_rate, wz);
      for (const vehicles::WheelState& w : d.vehicle->state().wheels) {
        slip_sum += w.longitudinal_slip / 4.0;
      }
      ++n;
    }
    std::printf("grid %.2f m snow, full left lock, full throttle: mean drive slip %.2f, mean yaw "
                "rate %+.3f rad/s (min %+.3f), speed %.2f m/s\n",
                grid_m, slip_sum / n, yaw_rate_sum / n, min_yaw_rate,
                d.vehicle->state().forward_speed_mps);
    EXPECT_GT(yaw_rate_sum / n, 0.0);
    EXPECT_GT(min_yaw_rate, -0.02);
  }
}

}  // namespace
}  // namespace vb::soil
