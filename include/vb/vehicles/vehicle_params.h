// Vehicle description as plain data (loaded strictly from data/vehicles/<name>.yaml by
// tools/io/vehicle_io.h). Chassis frame: ISO, x forward, y left, z up; origin at the chassis
// reference point (midway between the outer axles, at wheel-centre height), which is also the
// point whose position is reported as the vehicle position. SI units, radians.
#pragma once

#include <string>
#include <vector>

#include "vb/engine/types.h"
#include "vb/vehicles/suspension_kinematics.h"

namespace vb::vehicles {

// One convex piece of the chassis envelope: the convex hull of its points (chassis reference
// frame, m). The envelope is what of the body touches the ground and the obstacles (wheels have
// their own contact); a few pieces describe a body with wheel wells (a belly between the wheels,
// a body above them).
struct EnvelopePiece {
  std::string name;
  std::vector<Vec3> points_B;
};

struct ChassisParams {
  double mass_kg = 0.0;
  Vec3 inertia_kgm2 = Vec3::Zero();     // principal moments about the COM
  Vec3 com_B = Vec3::Zero();            // COM in the chassis reference frame
  std::vector<EnvelopePiece> envelope;  // at least one piece
};

// Suspension of one axle. In the multibody tree every wheel carrier slides along chassis z (a
// closed wishbone loop cannot be a Bullet multibody tree); travel s is positive in compression
// (wheel up relative to the chassis), s = 0 at the design position.
//  - kStrut: the slider is the suspension: force on the wheel (down) = preload + k*s + c*ds/dt.
//  - kDoubleWishbone: Chrono's reduced double wishbone. The published hard points decide the
//    shock length L(s) (motion ratio -dL/ds, wheel lateral motion and camber are neglected) and,
//    on steered axles, the road-wheel angle vs rack travel. The spring-damper acts along the shock:
//    F = -k (L - L0) - c dL/dt (+ pushes the mounts apart), i.e. -F dL/ds on the slider.
// Both: progressive bump and rebound stops (table of force vs deflection beyond the stop) engage
// at s = +bump_travel_m and s = -rebound_travel_m.
//  - kSingleWishbone, kAirWishbone, kSolidAxle: the slider carries a spring and a damper whose
//    shock length is L = design_length - motion_ratio * s (constant motion ratio: the linkage's
//    hard points are not in the reference). kSingleWishbone: linear coil-over (Gator front);
//    kAirWishbone: a double wishbone whose spring is an air spring (FEDA; suspension_forces.h);
//    kSolidAxle: a 3-link solid axle reduced to one slider per wheel with the axle's progressive
//    spring and degressive damper at the wheel (MAN, Verti-Wheeler; the axle's roll is the two
//    sliders' travel difference, its camber is not modelled). A solid axle may carry a bellcrank
//    (the steering relay of a steered axle).
//  - kRigid: no suspension (Gator rear): the carrier is held at s = 0 by an implicit position
//    servo (a joint limit of zero travel leaks under load).
enum class SuspensionModel {
  kStrut, kDoubleWishbone, kSingleWishbone, kAirWishbone, kSolidAxle, kRigid
};

// Spring law along the shock (suspension_forces.h): linear F = k (L0 - L); progressive
// F = k1 x + k2 x^2 with x = L0 - L (>= 0); air spring F = F0 (h / (h - x))^1.4 with x the
// compression from the design length and h = 1.4 F0 / k (the gas column that has stiffness k at
// design).
enum class SpringLaw { kLinear, kProgressive, kAir };

struct SuspensionParams {
  SuspensionModel model = SuspensionModel::kStrut;
  // kStrut
  double stiffness_npm = 0.0;       // wheel rate
  double preload_n = 0.0;           // spring force at s = 0
  // kDoubleWishbone
  double spring_stiffness_npm = 0.0;   // along the shock
  double spring_free_length_m = 0.0;
  DoubleWishboneHardpoints hardpoints; // left side, suspension frame (only differences matter)
  // kSingleWishbone, kAirWishbone, kSolidAxle (shock along a constant motion ratio)
  SpringLaw spring_law = SpringLaw::kLinear;
  double motion_ratio = 1.0;           // shock travel per wheel travel
  double spring_design_length_m = 0.0; // shock length at s = 0
  double spring_k2_npm2 = 0.0;         // kProgressive quadratic term
  double spring_preload_n = 0.0;       // kAir: F0 at the design length
  // Degressive damper (kSolidAxle): F = c v / (1 + d |v|) per direction (compression, expansion);
  // the other models use damping_nspm with zero degression.
  double damping_expansion_nspm = 0.0;
  double degression_compression_spm = 0.0;
  double degression_expansion_spm = 0.0;
  bool bellcrank = false;              // kSolidAxle: steering relay on a steered axle
  double steering_arm_m = 0.0;         // kSingleWishbone: knuckle arm for rack_pinion steering
  // Anti-roll bar (independent suspensions): force k (s_this - s_other) against the travel
  // difference of the axle's two wheels, at the wheels. 0: none.
  double anti_roll_bar_npm = 0.0;
  // all
  double damping_nspm = 0.0;        // kStrut: at the wheel; others: along the shock (compression)
  double bump_travel_m = 0.0;       // stop engagement (compression)
  double rebound_travel_m = 0.0;    // stop engagement (extension)
  std::vector<double> stop_deflection_m;  // ascending, first 0
  std::vector<double> stop_force_n;       // same length, first 0
  double carrier_mass_kg = 0.0;     // upright + spindle
  Vec3 carrier_inertia_kgm2 = Vec3::Ones();
};

struct WheelParams {
  double radius_m = 0.0;
  double width_m = 0.0;
  // The width the soil feels (SCM contact); the loader sets it to width_m unless the file gives
  // it, and 0 (parameters built in code) means width_m. The original's Chrono widens it by its
  // collision envelope (docs/vehicles.md, "hmmwv_chrono").
  double soil_footprint_width_m = 0.0;
  double mass_kg = 0.0;             // rim + tire
  Vec3 inertia_kgm2 = Vec3::Ones(); // (x, spin y, z)
};

// Tire model.
//  - kRigid: Chrono's rigid tire: a cylinder (wheel radius_m, width_m) against the terrain
//    surface; normal penalty spring-damper, elastic bristle for static friction, Coulomb limit
//    mu = min(tire friction, patch mu) (Chrono's NSC composition rule).
//  - kTMeasy: handling tire with slip-force curves (tmeasy_tire.h); the patch mu scales the
//    force maxima by mu / mu_0.
enum class TireModel { kRigid, kTMeasy };

// One direction (longitudinal x or lateral y) of a TMeasy characteristic at one load.
struct TmeasyDirection {
  double df0 = 0.0;   // initial slope, N per unit slip
  double fm = 0.0;    // peak force, N
  double sm = 0.0;    // slip at the peak
  double fs = 0.0;    // sliding force, N
  double ss = 0.0;    // slip where sliding starts
};

struct TireParams {
  TireModel model = TireModel::kRigid;
  // kRigid
  double friction = 0.9;                 // tire material mu
  double normal_stiffness_npm = 0.0;
  double normal_damping_nspm = 0.0;
  double bristle_stiffness_npm = 0.0;    // tangential stiffness of the stick state
  double bristle_damping_nspm = 0.0;
  // kTMeasy
  double unloaded_radius_m = 0.0;
  double width_m = 0.0;
  double vertical_stiffness_npm = 0.0;
  double vertical_damping_nspm = 0.0;
  double rim_radius_m = 0.0;             // the tire bottoms out on the rim beyond r - rim radius
  double rim_stiffness_npm = 0.0;        // contact stiffness of the rim (like the rigid tire)
  double rated_load_n = 0.0;             // pn
  TmeasyDirection x_pn, x_2pn, y_pn, y_2pn;
  double mu_0 = 0.8;                     // road friction the curves were measured on
  double rolling_resistance = 0.0;       // coefficient
  double relaxation_x_m = 0.0;           // sigma: dF0 / sigma is the stiffness at rest
  double relaxation_y_m = 0.0;
  double slip_damping_nspm = 0.0;        // damping of the relaxation deflection
};

struct AxleParams {
  double x_m = 0.0;                 // wheel-centre x in chassis frame
  double half_track_m = 0.0;        // wheel-centre |y|
  double z_m = 0.0;                 // wheel-centre z at design position
  bool steered = false;
  bool driven = true;
  double brake_torque_nm = 0.0;     // max braking torque per wheel
  SuspensionParams suspension;
  WheelParams wheel;                // the vehicle's wheel unless the axle gives its own (Gator)
};

// kAckermann: ideal geometry, the inner wheel gets max_angle_rad. kRackPinion: Chrono's
// rack-pinion, rack travel = input * max_pinion_angle * pinion_radius, road-wheel angles from
// the steered axles' double-wishbone tie-rod geometry (kDoubleWishbone) or, on a single wishbone,
// from its knuckle arm: angle = asin(rack / steering_arm_m) on both wheels (parallel steer).
// kPitmanArm, kRotaryArm: an arm turning by input * max_angle_rad drives the road wheels through
// drag link and tie rods; their hard points are not in the reference, so the linkage is taken as
// ideal Ackermann with the inner wheel of the first steered axle at max_angle_rad *
// wheel_per_arm, further steered axles on the same turning centre (steering_linkage.h). A pitman
// arm steers independent suspensions, a rotary arm solid axles with a bellcrank.
enum class SteeringModel { kAckermann, kRackPinion, kPitmanArm, kRotaryArm };

struct SteeringParams {
  SteeringModel model = SteeringModel::kAckermann;
  double max_angle_rad = 0.0;          // kAckermann; kPitmanArm, kRotaryArm: the arm's
  double wheel_per_arm = 1.0;          // kPitmanArm, kRotaryArm: road-wheel / arm angle
  double max_pinion_angle_rad = 0.0;   // kRackPinion
  double pinion_radius_m = 0.0;        // kRackPinion
  // kRackPinion: the steering link (rack) moves only along y, so its mass is lumped into the
  // chassis (at this point, chassis frame; inertia (1,1,1) kg m^2 as Chrono's).
  double link_mass_kg = 0.0;
  Vec3 link_position_B = Vec3::Zero();
};

struct EngineMapPoint {
  double speed_radps = 0.0;
  double full_throttle_nm = 0.0;
  double zero_throttle_nm = 0.0;
};

// The loader turns every engine model into a map (engine_models.h): `map` as given, a DC motor
// (linear torque-speed line) and Chrono's simple engine (min(max torque, max power / w)).
struct EngineParams {
  double max_speed_radps = 0.0;
  std::vector<EngineMapPoint> map;  // ascending speed; linear interpolation
  // Rotor / flywheel inertia at engine speed (kg m^2), reflected onto the driven wheels through
  // the first gear and the conical ratio (exact for single-gear drives). 0: none.
  double rotor_inertia_kgm2 = 0.0;
};

struct TransmissionParams {
  std::vector<double> forward_ratios;   // output/input, gear 1 first
  double reverse_ratio = 0.0;           // magnitude (> 0) of the reverse gear ratio
  std::vector<double> upshift_rpm;      // per gear
  std::vector<double> downshift_rpm;    // per gear
  // Shift logic additions (see powertrain.h): a gear is held at least min_time_in_gear_s after a
  // shift (hysteresis against hunting); optionally upshifts are judged on the engine speed the
  // vehicle's ground speed implies, so wheels spinning against an obstacle do not upshift.
  double min_time_in_gear_s = 0.0;
  bool upshift_on_ground_speed = false;
};

struct DrivelineParams {
  double conical_ratio = 1.0;          // wheel speed / differential input shaft speed
  bool lock_axle_differentials = false;
  bool lock_central_differential = false;
  double lock_torque_limit_nm = 0.0;   // clutch torque of a "locked" differential
  // Viscous coupling of that clutch below its limit (N m s/rad, powertrain.cc): 400 (the
  // HMMWV's) unless the file says; small vehicles need one in proportion to their wheel inertia.
  double lock_coupling_nms_per_rad = 400.0;
  // The engine and gearbox react the driveshaft torque on the chassis (true: physical, the
  // propeller shafts' roll reaction at the conical gears is cancelled inside the chassis). false
  // reproduces Chrono's SIMPLE_MAP powertrain, which has no engine block: its conical gears
  // (ChShaftsGearboxAngled) leave the propeller shafts' torque on the chassis as a net roll torque
  // T_engine / gear ratio about chassis +x (wheeled vehicles; docs/validation.md "Why vb
  // out-climbs the original").
  bool engine_block_reaction = true;
  // Rotating inertia of the shafts (Chrono's ChShaftsDriveline4WD): the driveshaft and the
  // central differential box, one propeller shaft per driven axle (these turn 1/conical_ratio
  // times faster than the wheels), and one differential box per driven axle (at wheel speed).
  double driveshaft_inertia_kgm2 = 0.0;
  double central_box_inertia_kgm2 = 0.0;
  double axle_shaft_inertia_kgm2 = 0.0;
  double axle_box_inertia_kgm2 = 0.0;
};

// Running gear of a tracked vehicle (tracks.h, docs/vehicles.md "Tracked vehicles"): per side a
// drive sprocket, an idler on a sliding carrier pushed by the tensioner, and road wheels on
// trailing torsion-bar arms; the track is an elastic belt around them whose ground run carries
// the load between and under the road wheels. Chassis frame, left side (the right side mirrors
// y -> -y). The loader also describes each road-wheel station as an axle (VehicleParams::axles,
// wheel = road wheel with the shoe height added to its radius) so everything that counts or
// places wheels (runner start pose, observation, viewer) works unchanged.
struct TrackParams {
  double half_gauge_m = 0.0;           // track centre |y|
  double shoe_width_m = 0.0;           // contact width of the belt
  double shoe_height_m = 0.0;          // belt thickness under the road wheels
  double belt_mass_kg = 0.0;           // all shoes of one track
  double belt_stiffness_npm = 0.0;     // of the loop's length (tension per metre of stretch)
  // Sprocket: pitch radius (the belt's speed is spin x radius), spin inertia, mass.
  Vec3 sprocket_B = Vec3::Zero();
  double sprocket_radius_m = 0.0;
  double sprocket_mass_kg = 0.0;
  double sprocket_inertia_kgm2 = 0.0;
  double brake_torque_nm = 0.0;        // per sprocket (steering and service brakes)
  // Idler: centre at design, radius, wheel mass and spin inertia; the carrier slides along
  // chassis x and the tensioner pushes it away from the sprocket: F = preload - k (L - L0) - c dL/dt
  // with L = free_length + carrier travel (the carrier sits at L0 at design).
  Vec3 idler_B = Vec3::Zero();
  double idler_radius_m = 0.0;
  double idler_mass_kg = 0.0;
  double idler_inertia_kgm2 = 0.0;
  double tensioner_free_length_m = 0.0;
  double tensioner_preload_n = 0.0;
  double tensioner_stiffness_npm = 0.0;
  double tensioner_damping_nspm = 0.0;
  double tensioner_carrier_mass_kg = 0.0;
  // Road wheels: centres at design (front to rear), radius, width, mass, spin inertia; each on a
  // trailing arm whose chassis pivot is at wheel centre + arm_pivot_offset_B (x, z).
  std::vector<double> road_wheel_x_m;
  // The right side's road wheels (with their arm pivots) sit this far along x from the left's
  // (Chrono's M113: -0.085 m, the torsion bars pass each other under the hull).
  double right_road_wheel_offset_x_m = 0.0;
  double road_wheel_z_m = 0.0;
  double road_wheel_radius_m = 0.0;
  double road_wheel_width_m = 0.0;
  double road_wheel_mass_kg = 0.0;
  double road_wheel_inertia_kgm2 = 0.0;
  Vec3 arm_pivot_offset_B = Vec3::Zero();
  double arm_mass_kg = 0.0;
  Vec3 arm_inertia_kgm2 = Vec3::Ones();
  // Torsion bar: torque = preload - k angle - c rate (angle + lifts the wheel, 0 at design).
  // preload_nm 0 means "the static load": the loader sets it so the arms sit at design when the
  // vehicle rests on flat ground (docs/vehicles.md).
  double torsion_stiffness_nmprad = 0.0;
  double torsion_damping_nmsprad = 0.0;
  double torsion_preload_nm = 0.0;
  double bump_angle_rad = 0.0;         // stop engagement (wheel up)
  double rebound_angle_rad = 0.0;      // stop engagement (wheel down)
  double stop_stiffness_nmprad = 0.0;  // linear stop beyond either
  // Ground contact of the belt: samples along the ground run, each a normal penalty spring-
  // damper per metre of belt and an elastic bristle with a Coulomb limit (rigid ground); on soil
  // the SCM solver's pressure and Janosi shear (soil_contact.h TrackContact).
  double contact_spacing_m = 0.1;
  double friction = 0.8;
  double normal_stiffness_npm2 = 0.0;  // N/m of penetration per metre of belt
  double normal_damping_nspm2 = 0.0;
  double bristle_stiffness_npm2 = 0.0;
  double bristle_damping_nspm2 = 0.0;
};

struct VehicleParams {
  std::string name;
  // Largest physics step the vehicle is stable at (s); 0: any (the runner's 5 ms). The runner
  // splits its step into equal sub-steps no longer than this (docs/vehicles.md).
  double max_step_s = 0.0;
  // Coarsest deformable-soil grid its wheels are resolved on (m); 0: the soil file's spacing.
  // The runner uses the smaller of the two (docs/vehicles.md, "The soil grid of a small wheel").
  double max_soil_grid_m = 0.0;
  ChassisParams chassis;
  std::vector<AxleParams> axles;       // front to rear; each axle has a left and a right wheel
  SteeringParams steering;
  WheelParams wheel;
  TireParams tire;
  EngineParams engine;
  TransmissionParams transmission;
  DrivelineParams driveline;
  // A tracked vehicle (the M113): `tracks` describes the running gear, `axles` its road-wheel
  // stations (see TrackParams); steering is differential (steering.model unused).
  bool tracked = false;
  TrackParams tracks;
};

}  // namespace vb::vehicles
