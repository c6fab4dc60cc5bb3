// The vehicle library's sub-models against their closed forms: spring laws (linear, progressive,
// air), the degressive damper, the DC motor and simple engine maps, and the steering linkages
// (all wheels of all steered axles on one turning centre; a rack on knuckle arms).
#include <cmath>

#include <gtest/gtest.h>

#include "vb/vehicles/engine_models.h"
#include "vb/vehicles/powertrain.h"
#include "vb/vehicles/steering_linkage.h"
#include "vb/vehicles/suspension_forces.h"

namespace vb::vehicles {
namespace {

TEST(SubModels, AirSpringHasItsPreloadAndStiffnessAtDesignAndHardens) {
  SuspensionParams su;
  su.spring_law = SpringLaw::kAir;
  su.spring_stiffness_npm = 76000.0;     // FEDA
  su.spring_preload_n = 9541.87;
  su.spring_design_length_m = 0.60208;
  EXPECT_NEAR(SpringForce(su, 0.60208), 9541.87, 1e-6);
  const double h = 1e-6;
  const double k = (SpringForce(su, 0.60208 - h) - SpringForce(su, 0.60208 + h)) / (2 * h);
  EXPECT_NEAR(k, 76000.0, 1.0);
  // progressive: 5 cm of compression is stiffer than at design, extension softer
  const double k_bump = (SpringForce(su, 0.55208 - h) - SpringForce(su, 0.55208 + h)) / (2 * h);
  EXPECT_GT(k_bump, 1.5 * 76000.0);
  // F0 (h0/(h0-x))^1.4 with h0 = 1.4 F0 / k = 0.17577 m, at x = 0.05: 15 044 N
  EXPECT_NEAR(SpringForce(su, 0.55208), 9541.87 * std::pow(0.175771 / 0.125771, 1.4), 1.0);
}

TEST(SubModels, ProgressiveSpringLiftsOffItsSeat) {
  SuspensionParams su;
  su.spring_law = SpringLaw::kProgressive;
  su.spring_stiffness_npm = 85490.0;  // MAN 5t front
  su.spring_k2_npm2 = 495208.0;
  su.spring_free_length_m = 0.667;
  EXPECT_NEAR(SpringForce(su, 0.529), 85490.0 * 0.138 + 495208.0 * 0.138 * 0.138, 1e-6);
  EXPECT_EQ(SpringForce(su, 0.7), 0.0);
}

TEST(SubModels, DegressiveDamper) {
  SuspensionParams su;
  su.damping_nspm = 52526.6;           // compression
  su.degression_compression_spm = 3.0;
  su.damping_expansion_nspm = 98727.9;
  su.degression_expansion_spm = 4.77954;
  // expansion at 1 m/s: c v / (1 + d v) = 17 086 N, resisting (pulls the mounts together)
  EXPECT_NEAR(DamperForce(su, 1.0), -98727.9 / 5.77954, 1e-6);
  // compression at 0.5 m/s: pushes apart
  EXPECT_NEAR(DamperForce(su, -0.5), 52526.6 * 0.5 / 2.5, 1e-6);
  EXPECT_NEAR(DamperSecant(su, 0.0), 52526.6, 1e-9);
}

TEST(SubModels, DcMotorIsALineThroughStallAndNoLoadSpeed) {
  EngineParams e;
  e.map = DcMotorMap(1.0, 1007.4);  // ARTcar
  e.max_speed_radps = DcMotorMapEnd(1007.4);
  EXPECT_NEAR(EngineTorque(e, 0.0, 1.0), 1.0, 1e-12);
  EXPECT_NEAR(EngineTorque(e, 503.7, 1.0), 0.5, 1e-12);
  EXPECT_NEAR(EngineTorque(e, 1007.4, 1.0), 0.0, 1e-12);
  EXPECT_NEAR(EngineTorque(e, 1511.1, 1.0), -0.5, 1e-12);  // beyond no-load: it brakes
  EXPECT_NEAR(EngineTorque(e, 503.7, 0.5), 0.25, 1e-12);
  EXPECT_NEAR(EngineTorque(e, 503.7, 0.0), 0.0, 1e-12);
}

TEST(SubModels, SimpleEngineIsTorqueThenPowerLimited) {
  EngineParams e;
  e.map = SimpleEngineMap(200.0, 14000.0, 366.52);  // Gator
  e.max_speed_radps = SimpleEngineMapEnd(366.52);
  EXPECT_NEAR(EngineTorque(e, 30.0, 1.0), 200.0, 1e-9);
  EXPECT_NEAR(EngineTorque(e, 70.0, 1.0), 200.0, 1e-9);  // the corner P / T = 70 rad/s
  // power-limited: sampled every ~15.6 rad/s, linear in between (within 1.5 % of P / w)
  for (double w : {100.0, 200.0, 300.0}) {
    EXPECT_NEAR(EngineTorque(e, w, 1.0), 14000.0 / w, 0.015 * 14000.0 / w) << w;
  }
  EXPECT_NEAR(EngineTorque(e, 366.52, 1.0), 0.0, 1e-9);
  EXPECT_LT(EngineTorque(e, 375.0, 1.0), 0.0);  // governor
}

TEST(SubModels, AckermannLinkageSharesOneTurningCentreAcrossSteeredAxles) {
  SteeringParams s;
  s.model = SteeringModel::kRotaryArm;
  s.max_angle_rad = 0.4951;
  s.wheel_per_arm = 1.0;
  TurnGeometry g;  // man10t: steered axles at 3.5 and 1.57, unsteered at -2.1 and -3.5
  g.first_steered_x_m = 3.5;
  g.centre_x_m = -2.8;
  const double track = 2.066;
  double l1, r1, l2, r2;
  LinkageSteerAngles(s, g, 1.0, 3.5, track, 0.0, &l1, &r1);
  LinkageSteerAngles(s, g, 1.0, 1.57, track, 0.0, &l2, &r2);
  EXPECT_NEAR(l1, 0.4951, 1e-12);  // left turn: the left wheel is inside and gets the full angle
  // every wheel's axis passes through the centre (x = -2.8, y = R on the left)
  const double radius = 6.3 / std::tan(0.4951);  // from the inner wheel of the first axle
  EXPECT_NEAR(std::tan(r1), 6.3 / (radius + track), 1e-12);
  EXPECT_NEAR(std::tan(l2), 4.37 / radius, 1e-12);
  EXPECT_NEAR(std::tan(r2), 4.37 / (radius + track), 1e-12);
  LinkageSteerAngles(s, g, -1.0, 3.5, track, 0.0, &l1, &r1);
  EXPECT_NEAR(r1, -0.4951, 1e-12);
}

TEST(SubModels, RackOnKnuckleArmsSteersBothWheelsAlike) {
  SteeringParams s;
  s.model = SteeringModel::kRackPinion;
  s.max_pinion_angle_rad = 1.0;  // Gator: rack +-0.035 m
  s.pinion_radius_m = 0.035;
  double l, r;
  LinkageSteerAngles(s, TurnGeometry(), 1.0, 0.97, 1.12, 0.0828, &l, &r);
  EXPECT_NEAR(l, std::asin(0.035 / 0.0828), 1e-12);
  EXPECT_NEAR(r, l, 1e-12);
  EXPECT_NEAR(MaxInnerSteerAngle(s, 0.0828), 25.0 * M_PI / 180.0, 0.001);
}

}  // namespace
}  // namespace vb::vehicles
