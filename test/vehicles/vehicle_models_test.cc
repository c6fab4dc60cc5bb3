// Unit tests of the vehicle sub-models: double-wishbone linkage solver (against the spec's derived
// numbers), TMeasy force curve and load interpolation, shift logic.
#include <cmath>

#include <gtest/gtest.h>

#include "support/worlds.h"
#include "vb/vehicles/powertrain.h"
#include "vb/vehicles/suspension_kinematics.h"
#include "vb/vehicles/tmeasy_tire.h"

namespace vb::vehicles {
namespace {

constexpr double kDeg = kPi / 180.0;

TEST(DoubleWishbone, RackPinionRoadWheelAnglesMatchSpec) {
  // spec §1.6: rack +-0.05236 m -> left road wheel about +22.2 / -21.2 deg (derived there); vb's
  // solve gives the same magnitudes (21.18 deg when the left wheel is inside the turn).
  const VehicleParams p = test::Hmmwv();
  const auto& hp = p.axles[0].suspension.hardpoints;
  const double a_plus = SolveDoubleWishbone(hp, 0.0, 0.05236).steer_angle_rad / kDeg;
  const double a_minus = SolveDoubleWishbone(hp, 0.0, -0.05236).steer_angle_rad / kDeg;
  EXPECT_NEAR(std::max(std::abs(a_plus), std::abs(a_minus)), 22.2, 0.1);
  EXPECT_NEAR(std::min(std::abs(a_plus), std::abs(a_minus)), 21.2, 0.1);
  EXPECT_LT(a_plus * a_minus, 0.0);
}

TEST(DoubleWishbone, DesignPoseAndMotionRatio) {
  const VehicleParams p = test::Hmmwv();
  // at zero travel the solver returns the design shock length of the spec (0.37023 / 0.36823 m)
  const UprightSolution f = SolveDoubleWishbone(p.axles[0].suspension.hardpoints, 0.0, 0.0);
  const UprightSolution r = SolveDoubleWishbone(p.axles[1].suspension.hardpoints, 0.0, 0.0);
  ASSERT_TRUE(f.ok && r.ok);
  EXPECT_NEAR(f.shock_length_m, 0.37023, 5e-5);
  EXPECT_NEAR(r.shock_length_m, 0.36823, 5e-5);
  // every link keeps its length over the travel: tables by continuation = direct solves
  const Table1D t = ShockLengthTable(p.axles[0].suspension.hardpoints, -0.1, 0.2, 61);
  for (double s : {-0.1, -0.03, 0.05, 0.2}) {
    EXPECT_NEAR(t(s), SolveDoubleWishbone(p.axles[0].suspension.hardpoints, s, 0.0).shock_length_m,
                1e-9);
  }
  // motion ratio -dL/ds at design: front ~0.96, rear ~0.88 (shock mounted on the upright)
  EXPECT_NEAR(-t.Slope(0.0), 0.96, 0.01);
}

TEST(Tmeasy, CurveShapeAndLoadInterpolation) {
  const VehicleParams p = test::HmmwvTmeasy();
  const TireParams& t = p.tire;
  // at pn and 2 pn the interpolation returns the given characteristics exactly
  const SlipCurve at_pn = CurveAtLoad(t.x_pn, t.x_2pn, t.rated_load_n, t.rated_load_n);
  const SlipCurve at_2pn = CurveAtLoad(t.x_pn, t.x_2pn, t.rated_load_n, 2.0 * t.rated_load_n);
  EXPECT_NEAR(at_pn.fm, t.x_pn.fm, 1e-9);
  EXPECT_NEAR(at_2pn.df0, t.x_2pn.df0, 1e-6);
  EXPECT_NEAR(at_2pn.sm, t.x_2pn.sm, 1e-12);
  // degressive: doubling the load less than doubles the peak force
  EXPECT_LT(at_2pn.fm, 2.0 * at_pn.fm);
  // curve: initial slope dF0, peak FM at sM, sliding FS beyond sS, continuous
  EXPECT_NEAR(GeneralisedForce(at_pn, 1e-6) / 1e-6, at_pn.df0, 1e-3 * at_pn.df0);
  EXPECT_NEAR(GeneralisedForce(at_pn, at_pn.sm), at_pn.fm, 1e-9);
  EXPECT_NEAR(GeneralisedForce(at_pn, at_pn.ss + 1.0), at_pn.fs, 1e-9);
  EXPECT_NEAR(GeneralisedForce(at_pn, at_pn.sm * (1 + 1e-9)), at_pn.fm, 1e-3);
  EXPECT_LT(GeneralisedForce(at_pn, 0.5 * (at_pn.sm + at_pn.ss)), at_pn.fm);
}

// What a variant of the HMMWV file (hmmwv_tmeasy, hmmwv_chrono) keeps from hmmwv.yaml: chassis
// mass properties, axles and suspensions, steering, wheel mass, engine, gearbox ratios and
// driveline parameters.
void ExpectTheSameHmmwv(const VehicleParams& a, const VehicleParams& b) {
  EXPECT_EQ(a.chassis.mass_kg, b.chassis.mass_kg);
  EXPECT_EQ(a.chassis.com_B, b.chassis.com_B);
  EXPECT_EQ(a.chassis.inertia_kgm2, b.chassis.inertia_kgm2);
  ASSERT_EQ(a.axles.size(), b.axles.size());
  for (size_t i = 0; i < a.axles.size(); ++i) {
    EXPECT_EQ(a.axles[i].x_m, b.axles[i].x_m);
    EXPECT_EQ(a.axles[i].half_track_m, b.axles[i].half_track_m);
    EXPECT_EQ(a.axles[i].suspension.spring_stiffness_npm, b.axles[i].suspension.spring_stiffness_npm);
    EXPECT_EQ(a.axles[i].suspension.bump_travel_m, b.axles[i].suspension.bump_travel_m);
    EXPECT_EQ(a.axles[i].brake_torque_nm, b.axles[i].brake_torque_nm);
  }
  EXPECT_EQ(a.steering.max_pinion_angle_rad, b.steering.max_pinion_angle_rad);
  EXPECT_EQ(a.wheel.mass_kg, b.wheel.mass_kg);
  EXPECT_EQ(a.engine.map.size(), b.engine.map.size());
  EXPECT_EQ(a.transmission.forward_ratios, b.transmission.forward_ratios);
  EXPECT_EQ(a.transmission.upshift_rpm, b.transmission.upshift_rpm);
  EXPECT_EQ(a.driveline.conical_ratio, b.driveline.conical_ratio);
  EXPECT_EQ(a.driveline.lock_torque_limit_nm, b.driveline.lock_torque_limit_nm);
  EXPECT_EQ(a.driveline.driveshaft_inertia_kgm2, b.driveline.driveshaft_inertia_kgm2);
  EXPECT_EQ(a.driveline.central_box_inertia_kgm2, b.driveline.central_box_inertia_kgm2);
  EXPECT_EQ(a.driveline.axle_shaft_inertia_kgm2, b.driveline.axle_shaft_inertia_kgm2);
  EXPECT_EQ(a.driveline.axle_box_inertia_kgm2, b.driveline.axle_box_inertia_kgm2);
}

// data/vehicles/hmmwv_tmeasy.yaml must stay the HMMWV of hmmwv.yaml with another tire.
TEST(VehicleData, TmeasyVariantMatchesHmmwvExceptTire) {
  const VehicleParams a = test::Hmmwv(), b = test::HmmwvTmeasy();
  ExpectTheSameHmmwv(a, b);
  EXPECT_EQ(a.transmission.min_time_in_gear_s, b.transmission.min_time_in_gear_s);
  EXPECT_EQ(a.tire.model, TireModel::kRigid);
  EXPECT_EQ(b.tire.model, TireModel::kTMeasy);
}

// data/vehicles/hmmwv_chrono.yaml must stay the HMMWV of hmmwv.yaml with exactly the original's
// four artefacts (its header): Chrono's chassis box, the unreacted shaft torque, no hold after a
// shift, the envelope-widened soil footprint.
TEST(VehicleData, ChronoVariantIsTheHmmwvWithTheOriginalsFourArtefacts) {
  const VehicleParams a = test::Hmmwv();
  const VehicleParams b =
      io::LoadVehicle(std::string(VB_SOURCE_DIR) + "/data/vehicles/hmmwv_chrono.yaml");
  ExpectTheSameHmmwv(a, b);
  EXPECT_EQ(a.wheel.radius_m, b.wheel.radius_m);
  EXPECT_EQ(a.wheel.width_m, b.wheel.width_m);
  EXPECT_EQ(a.tire.model, b.tire.model);
  EXPECT_EQ(a.tire.friction, b.tire.friction);
  // the four artefacts
  ASSERT_EQ(b.chassis.envelope.size(), 1u);  // Chrono's 2.0 x 1.0 x 0.2 m box at (0, 0, 0.1)
  for (const Vec3& p : b.chassis.envelope[0].points_B) {
    EXPECT_EQ(std::abs(p.x()), 1.0);
    EXPECT_EQ(std::abs(p.y()), 0.5);
    EXPECT_TRUE(p.z() == 0.0 || p.z() == 0.2);
  }
  EXPECT_TRUE(a.driveline.engine_block_reaction);
  EXPECT_FALSE(b.driveline.engine_block_reaction);
  EXPECT_EQ(a.transmission.min_time_in_gear_s, 0.3);
  EXPECT_EQ(b.transmission.min_time_in_gear_s, 0.0);
  EXPECT_EQ(a.wheel.soil_footprint_width_m, a.wheel.width_m);
  EXPECT_DOUBLE_EQ(b.wheel.soil_footprint_width_m, b.wheel.width_m + 2.0 * 0.03);
}

TEST(ShiftLogic, HoldTimeAndGroundSpeedUpshift) {
  TransmissionParams tr;
  tr.forward_ratios = {0.2, 0.4};
  tr.upshift_rpm = {2000.0, 3000.0};
  tr.downshift_rpm = {0.0, 1000.0};
  tr.min_time_in_gear_s = 0.3;
  const double rpm = kPi / 30.0;
  PowertrainState s;
  s.engine_speed_radps = 2500.0 * rpm;  // above the upshift speed
  UpdateGear(tr, 2500.0 * rpm, 0.1, &s);
  EXPECT_EQ(s.gear, 1);  // held: only 0.1 s in gear
  UpdateGear(tr, 2500.0 * rpm, 0.25, &s);
  EXPECT_EQ(s.gear, 2);
  // wheels spinning in place: engine fast, ground slow
  tr.upshift_on_ground_speed = true;
  PowertrainState spin;
  spin.engine_speed_radps = 2500.0 * rpm;
  UpdateGear(tr, 100.0 * rpm, 1.0, &spin);
  EXPECT_EQ(spin.gear, 1);
  tr.upshift_on_ground_speed = false;
  UpdateGear(tr, 100.0 * rpm, 1.0, &spin);
  EXPECT_EQ(spin.gear, 2);
}

}  // namespace
}  // namespace vb::vehicles

namespace vb::vehicles {
namespace {

// HMMWV_Driveline4WD: driveshaft 0.5, central box 0.6, two propeller shafts 0.5, two axle boxes
// 0.6 kg m^2, conical ratio 0.2: (0.5 + 0.6 + 2 * 0.5) / 0.04 + 2 * 0.6 = 53.7 over 4 wheels.
TEST(Driveline, ShaftInertiaReflectedThroughTheConicalGears) {
  DrivelineParams d;
  d.conical_ratio = 0.2;
  d.driveshaft_inertia_kgm2 = 0.5;
  d.central_box_inertia_kgm2 = 0.6;
  d.axle_shaft_inertia_kgm2 = 0.5;
  d.axle_box_inertia_kgm2 = 0.6;
  EXPECT_NEAR(DrivelineInertiaPerDrivenWheel(d, 2), 53.7 / 4.0, 1e-12);
  // one driven axle: (0.5 + 0.6 + 0.5) / 0.04 + 0.6 = 40.6 over 2 wheels
  EXPECT_NEAR(DrivelineInertiaPerDrivenWheel(d, 1), 40.6 / 2.0, 1e-12);
  EXPECT_EQ(DrivelineInertiaPerDrivenWheel(d, 0), 0.0);
  EXPECT_NEAR(DrivelineInertiaPerDrivenWheel(test::Hmmwv().driveline, 2), 53.7 / 4.0, 1e-12);
}

}  // namespace
}  // namespace vb::vehicles
