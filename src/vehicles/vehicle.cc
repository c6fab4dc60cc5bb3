// Wheeled vehicle on the physics adapter. Multibody topology per wheel (axle-major order):
//   base (chassis COM) --prismatic z--> carrier --[prescribed z: steering knuckle]--> wheel (revolute y)
// The carrier slides along chassis z (strut suspension, travel limited by joint limits = bump and
// rebound stops); steered axles have a knuckle link whose angle is prescribed from the steering
// linkage every step (as the original's kinematic rack or arm: no steering compliance, no
// degree of freedom or constraint row in the dynamics); wheels spin about their y axis.
#include "vb/vehicles/vehicle.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "vb/engine/convex_shape.h"
#include "vb/engine/error.h"
#include "vb/terrain/body_contact.h"
#include "vb/vehicles/powertrain.h"
#include "vb/vehicles/steering_linkage.h"
#include "vb/vehicles/suspension_forces.h"
#include "vb/vehicles/suspension_kinematics.h"
#include "vb/vehicles/tire_contact.h"
#include "vb/vehicles/tmeasy_tire.h"
#include "vb/vehicles/track_running_gear.h"

namespace vb::vehicles {

struct Vehicle::Internals {
  struct Corner {
    int carrier_link = -1;
    int knuckle_link = -1;  // -1 if not steered
    int wheel_link = -1;
    double side = 1.0;      // +1 left, -1 right
    const AxleParams* axle = nullptr;
    const WheelParams* wheel = nullptr;  // the axle's own or the vehicle's
    double spin_inertia_kgm2 = 0.0;  // the wheel link's: tire, driveline share, rotor reflected
    BristleState bristle;
    TmeasyState tmeasy;
    Table1D shock_length;   // kDoubleWishbone: shock length vs wheel travel (m)
  };
  std::vector<Corner> corners;
  PowertrainState powertrain;
  double corner_sprung_mass_kg = 0.0;   // chassis mass per wheel
  Vec3 com_B = Vec3::Zero();
  double steer_wheelbase_m = 0.0;  // steered axle to the turning-centre line (unsteered axles)
  bool linkage_steering = false;   // angles from steering_linkage.h (not the tie-rod solver)
  TurnGeometry turn;               // for linkage_steering
  Table1D left_steer_angle;        // kRackPinion: left road-wheel angle vs rack travel
  double rack_sign = 1.0;          // rack direction that turns the wheels left
  double rack_max_m = 0.0;
  double rack_steering = 0.0;      // kRackPinion: the steering input the rack has reached
  // Per-step scratch (allocated once).
  std::vector<double> wheel_speeds;
  std::vector<bool> driven;
  std::vector<double> wheel_torques;
};

namespace {

// Damping coefficient to use with explicit forces so that a damper c acting on a mode of mass m
// behaves as if integrated implicitly: F = -c v / (1 + c dt / m). Explicit dampers with
// c dt / m near 2 ring at the step frequency (the stiff wheel-hop mode of a heavy truck at 5 ms
// does); this form is stable for any c and tends to the plain damper as dt -> 0.
double ImplicitDamping(double c, double dt, double mass_kg) { return c / (1.0 + c * dt / mass_kg); }

// Ideal Ackermann road-wheel angles (left, right) for a steering input in [-1, 1]: the inner
// wheel gets the full angle, the outer one the angle that shares its turning centre.
void AckermannAngles(const SteeringParams& s, double input, double wheelbase_m, double track_m,
                     double* left, double* right) {
  const double inner = std::clamp(input, -1.0, 1.0) * s.max_angle_rad;
  if (std::abs(inner) < 1e-9 || wheelbase_m <= 0.0) {
    *left = *right = inner;
    return;
  }
  const double radius = wheelbase_m / std::tan(std::abs(inner));  // at the inner wheel
  const double outer = std::atan(wheelbase_m / (radius + track_m));
  if (inner > 0) {  // left turn: left wheel inside
    *left = inner;
    *right = outer;
  } else {
    *right = inner;
    *left = -outer;
  }
}

// Progressive stop force (N, >= 0) for a deflection beyond the stop (m); the last segment's
// slope continues beyond the table.
double StopForce(const SuspensionParams& su, double deflection_m) {
  if (deflection_m <= 0.0) return 0.0;
  const std::vector<double>& d = su.stop_deflection_m;
  const std::vector<double>& f = su.stop_force_n;
  size_t i = 1;
  while (i + 1 < d.size() && deflection_m > d[i]) ++i;
  return f[i - 1] + (deflection_m - d[i - 1]) * (f[i] - f[i - 1]) / (d[i] - d[i - 1]);
}

// Hard end of travel (Bullet joint limit) beyond the stop table, as a last resort only.
constexpr double kHardLimitBeyondStops_m = 0.03;
// A rigid suspension's carrier is held at s = 0 by an implicit position servo of at most this
// many chassis weights (it carries a share of one, plus the impacts).
constexpr double kRigidHoldWeights = 20.0;

// The original drives its rack by a kinematic actuator (a constraint on the rack's travel) in a
// Chrono NSC system, which corrects a constraint's error at most at its
// max_penetration_recovery_speed, 0.6 (m/s for the rack's travel;
// reference_vehicle_soil.md 1.1): a step in the steering input moves the rack at 0.6 m/s.
// A controller's rate-limited steering (PID: 0.05 per 5 ms, 0.52 m/s of HMMWV rack) is followed
// exactly.
constexpr double kRackRecoverySpeed_mps = 0.6;

// The wheel of an axle: its own if it gives one, else the vehicle's.
const WheelParams& WheelOf(const VehicleParams& p, const AxleParams& a) {
  return a.wheel.radius_m > 0.0 ? a.wheel : p.wheel;
}

// Body-body contact (terrain/body_contact.h). The envelope's surface friction (painted steel on
// rock or ground), combined with the other surface's by the minimum.
constexpr double kBodyFriction = 0.8;
// Contacts kept per envelope piece and ground, per piece and obstacle, per wheel and obstacle: a
// well-spread support polygon is enough for the solver.
constexpr int kMaxGroundContactsPerPiece = 8;
constexpr int kMaxObstacleContactsPerPiece = 8;
constexpr int kMaxObstacleContactsPerWheel = 4;
// Margin (m) around a wheel's reach within which a soil/rigid seam makes it use both contact
// models: more than half the soil grid's node cell (0.05 m at the coarsest, the original's 0.1 m
// grid), so that the soil's edge nodes and the rigid tire's samples are all inside.
constexpr double kSeamMargin_m = 0.1;

}  // namespace

// The chassis envelope as convex shapes: sampled finely for obstacles (0.1 wheel radius: a rock's
// edge meets the body anywhere) and coarsely for the ground (a quarter of the terrain grid: the
// ground is piecewise linear between its vertices, which are tested themselves), and the posed
// copies of the current step.
struct Vehicle::Body {
  std::vector<engine::ConvexShape> for_ground_B, for_obstacles_B;
  engine::ConvexShape posed;   // scratch
  terrain::ContactScratch scratch;
  std::vector<terrain::BodyContact> contacts;
};

struct VehicleSnapshot::Data {
  engine::MultiBodyState body;
  Vehicle::Internals internals;
  DriverInputs inputs;
  VehicleState state;
  TrackRunningGear::State track;   // tracked vehicles only
};

VehicleSnapshot::VehicleSnapshot() = default;
VehicleSnapshot::~VehicleSnapshot() = default;
VehicleSnapshot::VehicleSnapshot(const VehicleSnapshot& other)
    : data_(other.data_ ? std::make_unique<Data>(*other.data_) : nullptr) {}
VehicleSnapshot& VehicleSnapshot::operator=(const VehicleSnapshot& other) {
  if (this != &other) data_ = other.data_ ? std::make_unique<Data>(*other.data_) : nullptr;
  return *this;
}

double EnvelopeObstacleSpacing_m(const VehicleParams& params) {
  return 0.1 * params.wheel.radius_m;
}

TravelRange CarrierTravel(const SuspensionParams& su) {
  TravelRange r;
  if (su.model == SuspensionModel::kRigid) {
    r.lower_m = -kHardLimitBeyondStops_m;
    r.upper_m = kHardLimitBeyondStops_m;
  } else {
    r.lower_m = -su.rebound_travel_m - su.stop_deflection_m.back() - kHardLimitBeyondStops_m;
    r.upper_m = su.bump_travel_m + su.stop_deflection_m.back() + kHardLimitBeyondStops_m;
  }
  return r;
}

Table1D CornerShockLengthTable(const SuspensionParams& su) {
  const TravelRange travel = CarrierTravel(su);
  // sampled every ~5 mm over the whole possible travel
  const int samples = 2 + static_cast<int>((travel.upper_m - travel.lower_m) / 0.005);
  return ShockLengthTable(su.hardpoints, travel.lower_m, travel.upper_m, samples);
}

Vehicle::Vehicle(const VehicleParams& params, const terrain::Terrain& terrain, const Pose& pose_W,
                 engine::PhysicsWorld* world)
    : params_(params),
      terrain_(terrain),
      world_(world),
      in_(std::make_unique<Internals>()),
      body_contact_(std::make_unique<Body>()) {
  const double ground_spacing_m =
      0.25 * std::min(terrain.spacing_x_m(), terrain.spacing_y_m());
  const double obstacle_spacing_m = EnvelopeObstacleSpacing_m(params_);
  for (const EnvelopePiece& piece : params_.chassis.envelope) {
    body_contact_->for_ground_B.push_back(
        engine::MakeConvexHull(piece.points_B, ground_spacing_m, "chassis.envelope." + piece.name));
    body_contact_->for_obstacles_B.push_back(engine::MakeConvexHull(
        piece.points_B, obstacle_spacing_m, "chassis.envelope." + piece.name));
  }
  // chassis plus the steering link (rides with the chassis): one rigid base body
  ChassisParams ch = params_.chassis;
  if (params_.steering.link_mass_kg > 0.0) {
    const double m1 = ch.mass_kg, m2 = params_.steering.link_mass_kg, m = m1 + m2;
    const Vec3 p2 = params_.steering.link_position_B;
    const Vec3 com = (m1 * ch.com_B + m2 * p2) / m;
    auto parallel_axis = [](double mass, const Vec3& d) {  // diagonal terms only
      return Vec3(mass * (d.y() * d.y() + d.z() * d.z()), mass * (d.x() * d.x() + d.z() * d.z()),
                  mass * (d.x() * d.x() + d.y() * d.y()));
    };
    ch.inertia_kgm2 += Vec3::Ones() + parallel_axis(m1, ch.com_B - com) + parallel_axis(m2, p2 - com);
    ch.mass_kg = m;
    ch.com_B = com;
  }
  in_->com_B = ch.com_B;

  // chassis: base body at the COM
  engine::MultiBodyBaseSpec base;
  base.mass_kg = ch.mass_kg;
  base.inertia_kgm2 = ch.inertia_kgm2;
  base.pose_W.rotation = pose_W.rotation;
  base.pose_W.position = pose_W.position + pose_W.rotation * ch.com_B;

  if (params_.tracked) {
    // The belts and the idlers (with their tensioner carriers) ride with the chassis: point
    // masses on each side, the belt at its loop's centre (its motion along the loop is the
    // sprocket's spin inertia, track_running_gear.cc). So do the road-wheel arms, at design
    // (their swing is vb's, track_running_gear.h).
    const TrackParams& tp = params_.tracks;
    const Vec3 belt_B(0.5 * (tp.sprocket_B.x() + tp.idler_B.x()), tp.half_gauge_m,
                      0.5 * (tp.sprocket_B.z() + tp.road_wheel_z_m));
    const Vec3 idler_B(tp.idler_B.x(), tp.half_gauge_m, tp.idler_B.z());
    const double idler_kg = tp.idler_mass_kg + tp.tensioner_carrier_mass_kg;
    LumpedMass points[4 + 2 * kMaxRoadWheels];
    points[0] = {belt_B, tp.belt_mass_kg, Vec3::Zero()};
    points[1] = {Vec3(belt_B.x(), -belt_B.y(), belt_B.z()), tp.belt_mass_kg, Vec3::Zero()};
    points[2] = {idler_B, idler_kg, Vec3::Zero()};
    points[3] = {Vec3(idler_B.x(), -idler_B.y(), idler_B.z()), idler_kg, Vec3::Zero()};
    const int n_points = 4 + ChassisArmMasses(tp, points + 4);
    double m = ch.mass_kg;
    Vec3 mc = ch.mass_kg * ch.com_B;
    for (int i = 0; i < n_points; ++i) {
      m += points[i].mass_kg;
      mc += points[i].mass_kg * points[i].com_B;
    }
    const Vec3 com = mc / m;
    auto parallel_axis = [](double mass, const Vec3& d) {  // diagonal terms only
      return Vec3(mass * (d.y() * d.y() + d.z() * d.z()), mass * (d.x() * d.x() + d.z() * d.z()),
                  mass * (d.x() * d.x() + d.y() * d.y()));
    };
    ch.inertia_kgm2 += parallel_axis(ch.mass_kg, ch.com_B - com);
    for (int i = 0; i < n_points; ++i) {
      ch.inertia_kgm2 +=
          points[i].inertia_kgm2 + parallel_axis(points[i].mass_kg, points[i].com_B - com);
    }
    ch.mass_kg = m;
    ch.com_B = com;
    in_->com_B = com;
    base.mass_kg = ch.mass_kg;
    base.inertia_kgm2 = ch.inertia_kgm2;
    base.pose_W.position = pose_W.position + pose_W.rotation * ch.com_B;
    std::vector<engine::MultiBodyLinkSpec> links;
    track_ = std::make_unique<TrackRunningGear>(params_, ch.com_B, &links);
    body_ = world_->AddMultiBody(base, links);
    track_->Attach(world_, body_);
    state_.wheels.resize(2 * static_cast<size_t>(track_->num_road_wheels()));
    UpdateState();
    return;
  }

  // wheels, axle-major, left then right; driven wheels also carry the driveline's shafts
  const int driven_axles = static_cast<int>(std::count_if(
      params_.axles.begin(), params_.axles.end(), [](const AxleParams& a) { return a.driven; }));
  const double driveline_inertia_per_wheel =
      DrivelineInertiaPerDrivenWheel(params_.driveline, driven_axles);
  // A motor's rotor turns 1 / (first gear x conical ratio) times faster than the wheels.
  double rotor_inertia_per_wheel = 0.0;
  if (params_.engine.rotor_inertia_kgm2 > 0.0 && driven_axles > 0) {
    const double ratio =
        params_.transmission.forward_ratios.front() * params_.driveline.conical_ratio;
    rotor_inertia_per_wheel =
        params_.engine.rotor_inertia_kgm2 / (ratio * ratio) / (2.0 * driven_axles);
  }
  std::vector<engine::MultiBodyLinkSpec> links;
  double steered_x_sum = 0.0, fixed_x_sum = 0.0;
  int n_steered = 0, n_fixed = 0;
  for (const AxleParams& axle : params_.axles) {
    if (axle.steered) {
      steered_x_sum += axle.x_m;
      ++n_steered;
    } else {
      fixed_x_sum += axle.x_m;
      ++n_fixed;
    }
    for (double side : {1.0, -1.0}) {
      Internals::Corner corner;
      corner.side = side;
      corner.axle = &axle;
      corner.wheel = &WheelOf(params_, axle);
      const Vec3 center_B(axle.x_m, side * axle.half_track_m, axle.z_m);
      const SuspensionParams& su = axle.suspension;

      engine::MultiBodyLinkSpec carrier;
      carrier.parent = -1;
      carrier.joint = engine::JointType::kPrismatic;
      carrier.axis_P = Vec3::UnitZ();
      carrier.parent_com_to_joint_P = center_B - ch.com_B;
      carrier.mass_kg = axle.steered ? su.carrier_mass_kg / 2.0 : su.carrier_mass_kg;
      carrier.inertia_kgm2 = su.carrier_inertia_kgm2;
      const TravelRange travel = CarrierTravel(su);
      carrier.limit_lower = travel.lower_m;
      carrier.limit_upper = travel.upper_m;
      if (su.model == SuspensionModel::kDoubleWishbone) {
        corner.shock_length = CornerShockLengthTable(su);
      }
      corner.carrier_link = static_cast<int>(links.size());
      links.push_back(carrier);
      int parent = corner.carrier_link;

      if (axle.steered) {
        engine::MultiBodyLinkSpec knuckle;
        knuckle.parent = parent;
        knuckle.joint = engine::JointType::kPrescribedRevolute;
        knuckle.axis_P = Vec3::UnitZ();
        knuckle.mass_kg = su.carrier_mass_kg / 2.0;
        knuckle.inertia_kgm2 = su.carrier_inertia_kgm2;
        corner.knuckle_link = static_cast<int>(links.size());
        links.push_back(knuckle);
        parent = corner.knuckle_link;
      }

      engine::MultiBodyLinkSpec wheel;
      wheel.parent = parent;
      wheel.joint = engine::JointType::kRevolute;
      wheel.axis_P = Vec3::UnitY();
      wheel.mass_kg = corner.wheel->mass_kg;
      wheel.inertia_kgm2 = corner.wheel->inertia_kgm2;
      if (axle.driven) wheel.inertia_kgm2.y() += driveline_inertia_per_wheel;
      if (axle.driven && rotor_inertia_per_wheel > 0.0)
        wheel.inertia_kgm2.y() += rotor_inertia_per_wheel;
      corner.spin_inertia_kgm2 = wheel.inertia_kgm2.y();
      corner.wheel_link = static_cast<int>(links.size());
      links.push_back(wheel);
      in_->corners.push_back(corner);
    }
  }
  if (n_steered > 0 && n_fixed > 0)
    in_->steer_wheelbase_m = std::abs(steered_x_sum / n_steered - fixed_x_sum / n_fixed);
  for (const AxleParams& axle : params_.axles) {
    if (!axle.steered) continue;
    in_->linkage_steering = params_.steering.model != SteeringModel::kAckermann &&
                            (params_.steering.model != SteeringModel::kRackPinion ||
                             axle.suspension.model != SuspensionModel::kDoubleWishbone);
    in_->turn.first_steered_x_m = axle.x_m;
    in_->turn.centre_x_m = n_fixed > 0 ? fixed_x_sum / n_fixed : axle.x_m;
    break;
  }
  if (params_.steering.model == SteeringModel::kRackPinion && !in_->linkage_steering) {
    // All steered axles share the rack; the first steered axle's tie-rod geometry is used.
    for (const AxleParams& axle : params_.axles) {
      if (!axle.steered) continue;
      in_->rack_max_m = params_.steering.max_pinion_angle_rad * params_.steering.pinion_radius_m;
      in_->left_steer_angle = SteerAngleTable(axle.suspension.hardpoints, in_->rack_max_m,
                                               kSteerAngleTableSamples);
      in_->rack_sign = in_->left_steer_angle(in_->rack_max_m) > 0.0 ? 1.0 : -1.0;
      break;
    }
  }

  body_ = world_->AddMultiBody(base, links);
  in_->corner_sprung_mass_kg = ch.mass_kg / static_cast<double>(in_->corners.size());

  const size_t n = in_->corners.size();
  in_->wheel_speeds.assign(n, 0.0);
  in_->wheel_torques.assign(n, 0.0);
  in_->driven.assign(n, false);
  for (size_t i = 0; i < n; ++i) in_->driven[i] = in_->corners[i].axle->driven;
  state_.wheels.resize(n);
  UpdateState();
}

Vehicle::~Vehicle() = default;

void Vehicle::SetInputs(const DriverInputs& inputs) {
  inputs_.throttle = std::clamp(inputs.throttle, 0.0, 1.0);
  inputs_.steering = std::clamp(inputs.steering, -1.0, 1.0);
  inputs_.braking = std::clamp(inputs.braking, 0.0, 1.0);
}

void Vehicle::Synchronize(double dt) {
  if (track_) {
    track_->Synchronize(inputs_, terrain_, soil_, obstacles_, &body_contact_->scratch, dt,
                        &state_.wheels);
    AddBodyContacts();
    return;
  }
  const size_t n = in_->corners.size();

  // steering: road-wheel angles, prescribed on the knuckles (their rate from the change since the
  // last step: it moves the wheel's tread points as a steering joint's rate would)
  double steering = inputs_.steering;
  if (params_.steering.model == SteeringModel::kRackPinion) {
    const double travel_m = params_.steering.max_pinion_angle_rad * params_.steering.pinion_radius_m;
    const double max_change = travel_m > 0.0 ? kRackRecoverySpeed_mps * dt / travel_m : 2.0;
    in_->rack_steering +=
        std::clamp(inputs_.steering - in_->rack_steering, -max_change, max_change);
    steering = in_->rack_steering;
  }
  double left = 0.0, right = 0.0;
  if (in_->linkage_steering) {
    // per steered axle, below
  } else if (params_.steering.model == SteeringModel::kRackPinion) {
    // rack travel from the pinion; the right wheel mirrors the left one (y -> -y)
    const double rack = in_->rack_sign * steering * in_->rack_max_m;
    left = in_->left_steer_angle(rack);
    right = -in_->left_steer_angle(-rack);
  } else {
    const double track = params_.axles.empty() ? 0.0 : 2.0 * params_.axles.front().half_track_m;
    AckermannAngles(params_.steering, steering, in_->steer_wheelbase_m, track, &left,
                    &right);
  }
  for (const Internals::Corner& c : in_->corners) {
    if (c.knuckle_link < 0) continue;
    if (in_->linkage_steering) {
      LinkageSteerAngles(params_.steering, in_->turn, steering, c.axle->x_m,
                         2.0 * c.axle->half_track_m, c.axle->suspension.steering_arm_m, &left,
                         &right);
    }
    const double angle = c.side > 0 ? left : right;
    const double rate = dt > 0.0 ? (angle - world_->JointPosition(body_, c.knuckle_link)) / dt : 0.0;
    world_->SetPrescribedJoint(body_, c.knuckle_link, angle, rate);
  }

  // powertrain: wheel drive torques from the engine map through gears and differentials
  for (size_t i = 0; i < n; ++i)
    in_->wheel_speeds[i] = world_->JointVelocity(body_, in_->corners[i].wheel_link);
  const Pose chassis = world_->BasePose(body_);
  const double ground_speed_mps =
      world_->BaseLinearVelocity(body_).dot(chassis.rotation * Vec3::UnitX());
  ComputeWheelTorques(params_, inputs_.throttle, in_->wheel_speeds, in_->driven,
                      ground_speed_mps, dt, &in_->powertrain, &in_->wheel_torques);
  if (!params_.driveline.engine_block_reaction) {
    // the original's unreacted propeller-shaft torque (vehicle_params.h DrivelineParams)
    world_->ApplyBaseTorque(body_,
                            chassis.rotation * Vec3(in_->powertrain.driveshaft_torque_nm, 0, 0));
  }

  for (size_t i = 0; i < n; ++i) {
    Internals::Corner& c = in_->corners[i];
    const AxleParams& axle = *c.axle;
    const SuspensionParams& su = axle.suspension;

    // suspension: spring-damper on the slider (strut) or along the shock (double wishbone), the
    // damper implicit on the reduced mass of the wheel carrier against its share of the chassis
    const WheelParams& wp = *c.wheel;
    const double unsprung_kg = su.carrier_mass_kg + wp.mass_kg;
    const double strut_mass_kg =
        unsprung_kg * in_->corner_sprung_mass_kg / (unsprung_kg + in_->corner_sprung_mass_kg);
    const double s = world_->JointPosition(body_, c.carrier_link);
    const double s_dot = world_->JointVelocity(body_, c.carrier_link);
    double force_up = 0.0;  // generalised force on the slider, + = compression direction
    if (su.model == SuspensionModel::kRigid) {
      world_->SetJointPositionMotor(body_, c.carrier_link, 0.0,
                                    kRigidHoldWeights * params_.chassis.mass_kg * kGravity);
    } else if (su.model == SuspensionModel::kStrut) {
      const double c_strut = ImplicitDamping(su.damping_nspm, dt, strut_mass_kg);
      force_up = -(su.preload_n + su.stiffness_npm * s + c_strut * s_dot);
    } else if (su.model != SuspensionModel::kDoubleWishbone) {
      // shock along a constant motion ratio: spring, then the damper implicit at the wheel
      const double mr = su.motion_ratio;
      const double c_wheel = DamperSecant(su, -mr * s_dot) * mr * mr;
      force_up = -mr * SpringForce(su, ShockLength(su, s)) -
                 ImplicitDamping(c_wheel, dt, strut_mass_kg) * s_dot;
    } else {
      const double length = c.shock_length(s);
      const double dl_ds = c.shock_length.Slope(s);  // -motion ratio
      const double spring = -su.spring_stiffness_npm * (length - su.spring_free_length_m);
      const double c_wheel = ImplicitDamping(su.damping_nspm * dl_ds * dl_ds, dt, strut_mass_kg);
      force_up = spring * dl_ds - c_wheel * s_dot;
    }
    if (su.model != SuspensionModel::kRigid) {
      // bump and rebound stops: progressive springs beyond the stop travel
      force_up -= StopForce(su, s - su.bump_travel_m);
      force_up += StopForce(su, -su.rebound_travel_m - s);
      // anti-roll bar: against the travel difference of the axle's two wheels
      if (su.anti_roll_bar_npm > 0.0) {
        const double s_other = world_->JointPosition(body_, in_->corners[i ^ 1].carrier_link);
        force_up -= su.anti_roll_bar_npm * (s - s_other);
      }
      world_->AddJointForce(body_, c.carrier_link, force_up);
    }

    // drive torque on the wheel joint. The brake is an implicit velocity motor (no creep when
    // held), except while it slips: if its torque cannot stop even the free wheel within the step
    // (I |w| / dt above it), the motor row would only sit at its limit, so the same torque goes
    // in as a force against the spin and the solver has one row less (issue 24; a brake that is
    // always a torque lets a parked vehicle creep: it only damps the wheel's own I w per step).
    world_->AddJointForce(body_, c.wheel_link, in_->wheel_torques[i]);
    const double brake_nm = inputs_.braking * axle.brake_torque_nm;
    const double spin_radps = in_->wheel_speeds[i];
    if (brake_nm > 0.0 && c.spin_inertia_kgm2 * std::abs(spin_radps) > brake_nm * dt) {
      world_->SetJointVelocityMotor(body_, c.wheel_link, 0.0, 0.0);
      world_->AddJointForce(body_, c.wheel_link, spin_radps > 0.0 ? -brake_nm : brake_nm);
    } else {
      world_->SetJointVelocityMotor(body_, c.wheel_link, 0.0, brake_nm);
    }

    // wheel-ground contact: the soil for the deformable patches under the wheel, the rigid tire
    // for the rigid ones; near a seam, both (each for its own side, tire_contact.h)
    const Pose wheel = world_->LinkPose(body_, c.wheel_link);
    const Vec3 axis_W = wheel.rotation * Vec3::UnitY();
    WheelState& ws = state_.wheels[i];
    const bool tmeasy = params_.tire.model == TireModel::kTMeasy;
    const double contact_radius_m = tmeasy ? params_.tire.unloaded_radius_m : wp.radius_m;
    const double contact_width_m = tmeasy ? params_.tire.width_m : wp.width_m;
    terrain::GroundMix mix = terrain::GroundMix::kRigid;
    if (soil_ != nullptr) {
      // the wheel's reach: along its plane (radius), across it (half width, and the tilted
      // wheel plane's sideways reach at its bottom), with a margin for the soil's node cells
      const double reach_m = std::max(contact_radius_m, wp.radius_m) *
                                 (1.0 + std::abs(axis_W.z())) +
                             0.5 * std::max({contact_width_m, wp.width_m,
                                             wp.soil_footprint_width_m}) +
                             kSeamMargin_m;
      mix = terrain_.MixAround(wheel.position.x(), wheel.position.y(), reach_m);
    }
    soil::WheelSoilOutput soil_out;
    if (mix != terrain::GroundMix::kRigid) {
      soil::WheelSoilInput in;
      in.wheel_id = static_cast<int>(i);
      in.center_W = wheel.position;
      in.axis_W = axis_W;
      in.velocity_W = world_->LinkPointVelocity(body_, c.wheel_link, wheel.position);
      in.angular_velocity_W = world_->LinkAngularVelocity(body_, c.wheel_link);
      in.radius_m = wp.radius_m;
      in.width_m = wp.soil_footprint_width_m > 0.0 ? wp.soil_footprint_width_m : wp.width_m;
      in.mass_kg = unsprung_kg;
      in.spin_inertia_kgm2 = wp.inertia_kgm2.y();
      soil_out = soil_->WheelContact(in, dt);
      if (soil_out.on_soil) {
        world_->ApplyLinkForce(body_, c.wheel_link, soil_out.force_W, wheel.position);
        world_->ApplyLinkTorque(body_, c.wheel_link, soil_out.torque_W);
        if (mix == terrain::GroundMix::kDeformable) {
          c.bristle = BristleState();
          c.tmeasy = TmeasyState();
          ws.in_contact = soil_out.normal_force_n > 0.0;
          ws.surface = soil_out.surface;
          ws.normal_force_n = soil_out.normal_force_n;
          ws.sinkage_m = soil_out.sinkage_m;
          continue;
        }
      }
    }
    const ContactGeometry geo =
        FindWheelContact(terrain_, wheel.position, axis_W, contact_radius_m, contact_width_m,
                         mix == terrain::GroundMix::kMixed ? GroundScope::kRigidOnly
                                                           : GroundScope::kAll);
    Vec3 v_point = Vec3::Zero();
    if (geo.in_contact) v_point = world_->LinkPointVelocity(body_, c.wheel_link, geo.point_W);
    TireParams tire = params_.tire;
    ContactForce f;
    if (tmeasy) {
      tire.vertical_damping_nspm = ImplicitDamping(tire.vertical_damping_nspm, dt, unsprung_kg);
      const Vec3 v_center =
          geo.in_contact ? world_->LinkPointVelocity(body_, c.wheel_link, wheel.position)
                         : Vec3::Zero();
      f = ComputeTmeasyForce(tire, geo, axis_W, v_point, v_center, in_->wheel_speeds[i], dt,
                             &c.tmeasy);
      if (geo.in_contact) world_->ApplyLinkTorque(body_, c.wheel_link, f.torque_W);
    } else {
      tire.normal_damping_nspm = ImplicitDamping(tire.normal_damping_nspm, dt, unsprung_kg);
      f = ComputeContactForce(tire, geo, v_point, dt, &c.bristle);
    }
    if (geo.in_contact) world_->ApplyLinkForce(body_, c.wheel_link, f.force_W, geo.point_W);

    const bool rigid_contact = geo.in_contact && f.normal_force_n > 0.0;
    const bool soil_contact = soil_out.on_soil && soil_out.normal_force_n > 0.0;
    // at a seam: the surface that carries more of the wheel, with the soil's sinkage only if
    // that is the soil (a wheel reported on rigid ground has no sinkage)
    const bool soil_carries_most = soil_contact && soil_out.normal_force_n >= f.normal_force_n;
    ws.in_contact = rigid_contact || soil_contact;
    ws.surface = soil_carries_most ? soil_out.surface : geo.surface;
    ws.normal_force_n = f.normal_force_n + (soil_out.on_soil ? soil_out.normal_force_n : 0.0);
    ws.sinkage_m = soil_carries_most ? soil_out.sinkage_m : 0.0;
  }
  AddBodyContacts();
}

void Vehicle::AddBodyContacts() {
  Body& b = *body_contact_;
  b.contacts.clear();
  const Pose com = world_->BasePose(body_);
  Pose reference;
  reference.rotation = com.rotation;
  reference.position = com.position - com.rotation * in_->com_B;
  // Each piece is posed without its sample points first: most steps the quick rejects (above the
  // ground under it, no obstacle near) end there.
  for (size_t k = 0; k < b.for_ground_B.size(); ++k) {
    b.for_ground_B[k].TransformInto(reference, &b.posed, /*with_samples=*/false);
    const double max_ground_h =
        terrain::MaxGroundHeightUnder(b.posed.aabb_min, b.posed.aabb_max, terrain_);
    if (b.posed.aabb_min.z() <= max_ground_h &&
        !terrain::GroundBeyondLowestFace(b.posed, terrain_)) {
      // the samples posed on the way, only those below the highest ground vertex under the piece
      terrain::GroundContacts(b.posed, b.for_ground_B[k].samples, reference, terrain_,
                              max_ground_h, kBodyFriction, kMaxGroundContactsPerPiece, &b.scratch,
                              &b.contacts);
    }
    if (obstacles_ != nullptr) {
      obstacles_->Overlapping(b.posed.aabb_min, b.posed.aabb_max, &b.scratch.obstacles);
      if (!b.scratch.obstacles.empty()) {
        // the samples (thousands near a boulder) only once a face test leaves a touch possible
        b.for_obstacles_B[k].TransformInto(reference, &b.posed, /*with_samples=*/false);
        if (terrain::MayTouchAnObstacle(b.posed, *obstacles_, &b.scratch)) {
          terrain::ObstacleContacts(b.posed, b.for_obstacles_B[k].samples, reference,
                                    *obstacles_, kBodyFriction, kMaxObstacleContactsPerPiece,
                                    &b.scratch, &b.contacts);
        }
      }
    }
  }
  state_.body_ground_contacts = 0;
  state_.body_obstacle_contacts = 0;
  for (const terrain::BodyContact& c : b.contacts) {
    world_->AddContact({body_, -1, c.point_W, c.normal_W, c.depth_m, c.friction, c.obstacle_tag});
    ++(c.obstacle_tag < 0 ? state_.body_ground_contacts : state_.body_obstacle_contacts);
  }
  if (obstacles_ == nullptr) return;
  if (track_) {
    track_->AddObstacleContacts();
    return;
  }
  for (const Internals::Corner& corner : in_->corners) {
    b.contacts.clear();
    const Pose wheel = world_->LinkPose(body_, corner.wheel_link);
    terrain::WheelObstacleContacts(wheel.position, wheel.rotation * Vec3::UnitY(),
                                   corner.wheel->radius_m, 0.5 * corner.wheel->width_m, *obstacles_,
                                   params_.tire.friction, kMaxObstacleContactsPerWheel, &b.scratch,
                                   &b.contacts);
    for (const terrain::BodyContact& c : b.contacts) {
      world_->AddContact({body_, corner.wheel_link, c.point_W, c.normal_W, c.depth_m, c.friction,
                          c.obstacle_tag});
    }
  }
}

VehicleSnapshot Vehicle::Snapshot() const {
  VehicleSnapshot snapshot;
  snapshot.data_ = std::make_unique<VehicleSnapshot::Data>(
      VehicleSnapshot::Data{world_->GetState(body_), *in_, inputs_, state_,
                            track_ ? track_->state() : TrackRunningGear::State()});
  return snapshot;
}

void Vehicle::Restore(const VehicleSnapshot& snapshot) {
  VB_DEMAND(snapshot.data_ != nullptr);
  const VehicleSnapshot::Data& d = *snapshot.data_;
  VB_DEMAND(d.internals.corners.size() == in_->corners.size());
  // The corners point at this vehicle's own axle parameters: keep those pointers.
  std::vector<const AxleParams*> axles(in_->corners.size());
  std::vector<const WheelParams*> wheels(in_->corners.size());
  for (size_t i = 0; i < axles.size(); ++i) {
    axles[i] = in_->corners[i].axle;
    wheels[i] = in_->corners[i].wheel;
  }
  *in_ = d.internals;
  for (size_t i = 0; i < axles.size(); ++i) {
    in_->corners[i].axle = axles[i];
    in_->corners[i].wheel = wheels[i];
  }
  world_->SetState(body_, d.body);
  inputs_ = d.inputs;
  state_ = d.state;
  if (track_) track_->set_state(d.track);
}

void Vehicle::UpdateState() {
  const Pose com = world_->BasePose(body_);
  const Vec3 v_com = world_->BaseLinearVelocity(body_);
  const Vec3 w = world_->BaseAngularVelocity(body_);
  state_.pose_W.rotation = com.rotation;
  state_.pose_W.position = com.position - com.rotation * in_->com_B;
  state_.velocity_W = v_com + w.cross(state_.pose_W.position - com.position);
  state_.angular_velocity_W = w;
  state_.forward_speed_mps = state_.velocity_W.dot(com.rotation * Vec3::UnitX());
  state_.rpy = ToRpy(com.rotation);
  const PowertrainState& pt = track_ ? track_->state().powertrain : in_->powertrain;
  state_.gear = pt.gear;
  state_.engine_speed_radps = pt.engine_speed_radps;
  state_.engine_torque_nm = pt.engine_torque_nm;
  if (track_) {
    track_->UpdateWheelStates(&state_.wheels);
    return;
  }
  for (size_t i = 0; i < in_->corners.size(); ++i) {
    const Internals::Corner& c = in_->corners[i];
    WheelState& ws = state_.wheels[i];
    ws.spin_radps = world_->JointVelocity(body_, c.wheel_link);
    ws.suspension_travel_m = world_->JointPosition(body_, c.carrier_link);
    const Pose wheel = world_->LinkPose(body_, c.wheel_link);
    ws.center_W = wheel.position;
    // heading: the wheel's rolling direction, the spin axis crossed with the chassis' up (on a
    // slope the ground's direction, not the horizontal one: that would read 1 - cos(slope) of
    // slip on a wheel that rolls, 0.13 at 30 deg)
    const Vec3 axis_W = wheel.rotation * Vec3::UnitY();
    Vec3 heading_W = axis_W.cross(com.rotation * Vec3::UnitZ());
    const double heading_norm = heading_W.norm();
    if (heading_norm > 1e-6) {
      heading_W /= heading_norm;
      const double v = world_->LinkPointVelocity(body_, c.wheel_link, wheel.position).dot(heading_W);
      const double wr = ws.spin_radps * c.wheel->radius_m;
      ws.longitudinal_slip = (wr - v) / std::max({std::abs(wr), std::abs(v), 0.1});
    } else {
      ws.longitudinal_slip = 0.0;  // wheel on its side: no rolling direction
    }
  }
}

}  // namespace vb::vehicles
