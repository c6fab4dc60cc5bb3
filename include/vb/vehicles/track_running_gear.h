// The running gear of a tracked vehicle (TrackParams), vb's own design (docs/vehicles.md,
// "Tracked vehicles"). Per side, in the vehicle's multibody tree:
//   base (chassis) --revolute y--> sprocket  (spin: the belt's speed = spin x pitch radius; its
//                                            inertia carries the belt, road wheels and idler)
// and the idler on a carrier that slides along chassis x, pushed away from the sprocket by the
// tensioner; the carrier is light and stiffly held, so its travel is solved quasi-statically
// each step (tensioner force = the belt's pull on it) rather than as a link.
// The road-wheel arms (trailing arms, torsion bar at the pivot) are not links: they are members
// of the chassis whose angle vb integrates itself (docs/vehicles.md, "The road-wheel arms").
// The chassis carries each arm's mass rigidly at its design place (ChassisArmMasses, added to
// the base by vehicle.cc); each arm's angle q is a second-order state, I_p q'' = torsion bar +
// belt + ground force + weight and inertia in the chassis's (last step's) acceleration, and the
// chassis receives the ground force at its point minus what accelerates the arm relative to it
// (momentum balance), so the pair moves as the two-body system does to first order in the
// arm-to-chassis mass ratio (~1 %). The hard travel limits are inelastic clamps.
// A road wheel against a rock or tree: the arm yields. Each of the wheel's obstacle contacts
// (found at the step's start) is a non-penetration condition on the arm's rate, solved in the
// arm's own integration against the chassis's velocity at the step's start (frictionless: the
// wheel rolls); the force that took is applied to the chassis at the contact point like the
// ground force, so the chassis feels the obstacle only through the pivot and the torsion bar
// (the momentum balance above). Contacts the arm cannot take (a normal the arm's swing barely
// moves the wheel along, or the arm at its hard limit) are the solver's, on the chassis at the
// wheel, as before.
// The track is an elastic belt around sprocket, road wheels and idler (track_belt.h): its tension
// pulls the wheels and the idler (generalised forces), the tensioner balances it.
// Ground contact: the belt's ground run is the polyline through the bottoms of the sprocket, the
// road wheels and the idler (wheel centre minus radius plus shoe height along chassis -z), flat
// across the shoe width. Each segment between two of those points is either handed to the soil
// (soil_contact.h TrackContact: SCM pressure and Janosi shear node by node) or sampled every
// contact_spacing_m on rigid ground (normal penalty spring-damper per metre of belt, an elastic
// bristle per sample with a Coulomb limit). Every contact force is shared between the segment's
// two points with linear weights; its friction (soil: shear) component along the belt goes to
// the chassis and, times the pitch radius, against the sprocket (the belt carries it there), the
// rest to the body under that point (road-wheel arm, or the chassis at the sprocket and idler).
// Steering: differential, by braking the inner sprocket behind an open differential (Chrono's
// ChTrackDrivelineBDS: steering s > 0 adds s to the left sprocket's braking).
#pragma once

#include <vector>

#include "vb/engine/physics_world.h"
#include "vb/soil/soil_contact.h"
#include "vb/terrain/body_contact.h"
#include "vb/terrain/obstacle_field.h"
#include "vb/terrain/terrain.h"
#include "vb/vehicles/powertrain.h"
#include "vb/vehicles/track_belt.h"
#include "vb/vehicles/vehicle.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

constexpr int kMaxRoadWheels = kMaxBeltWheels - 2;

// A mass the chassis carries for the running gear: an arm with its road wheel at design.
struct LumpedMass {
  Vec3 com_B = Vec3::Zero();          // chassis reference frame
  double mass_kg = 0.0;
  Vec3 inertia_kgm2 = Vec3::Zero();   // principal moments about its COM (chassis axes)
};
// The arms with their road wheels, both sides (left first), at design: the chassis base must
// carry them (vehicle.cc adds them to its mass and inertia). Returns how many were written
// (2 x road wheels, at most 2 * kMaxRoadWheels).
int ChassisArmMasses(const TrackParams& tp, LumpedMass* out);

class TrackRunningGear {
 public:
  // Internal state a snapshot keeps: powertrain, the bristles of the rigid contact samples, the
  // arms' angles and rates, the chassis velocity of the last step (its acceleration for the arms).
  struct State {
    PowertrainState powertrain;
    std::vector<Vec3> bristle_W;    // per side and sample
    double tension_n[2] = {0.0, 0.0};
    double idler_travel_m[2] = {0.0, 0.0};   // carrier travel away from the sprocket
    double arm_q[2][kMaxRoadWheels] = {};    // rad, + lifts the wheel, 0 at design
    double arm_qd[2][kMaxRoadWheels] = {};   // rad/s
    Vec3 last_base_velocity_W = Vec3::Zero();   // at the COM, at the last Synchronize
    Vec3 last_base_omega_W = Vec3::Zero();
    bool has_last_base_velocity = false;
  };

  // Appends both tracks' links (the two sprockets, left first) to `links`; the base's COM is
  // com_B (chassis frame) and it carries the arms (ChassisArmMasses). Call Attach once the
  // multibody exists.
  TrackRunningGear(const VehicleParams& params, const Vec3& com_B,
                   std::vector<engine::MultiBodyLinkSpec>* links);
  void Attach(engine::PhysicsWorld* world, engine::MultiBodyId body);

  // This step's forces: belt tension, torsion bars, tensioner, ground contact, sprocket drive
  // and brakes; advances the arms by dt. Fills the road wheels' contact fields of `wheels`
  // (axle-major: station 0 left, station 0 right, ...).
  // `obstacles` may be null (no rocks or trees); `scratch` is the contact queries' scratch.
  void Synchronize(const DriverInputs& inputs, const terrain::Terrain& terrain,
                   soil::SoilContact* soil, const terrain::ObstacleField* obstacles,
                   terrain::ContactScratch* scratch, double dt, std::vector<WheelState>* wheels);
  // Post-step read-out of the road wheels (spin, slip, travel, centre).
  void UpdateWheelStates(std::vector<WheelState>* wheels) const;
  // Road wheels against rocks and trees, after Synchronize: the contacts the arms could not
  // take become the solver's (on the chassis at the wheel); the others are reported as touches.
  void AddObstacleContacts();

  const State& state() const { return state_; }
  void set_state(const State& s) { state_ = s; }
  double SprocketSpeed(int side) const;   // rad/s, + forward
  double BeltTension(int side) const { return state_.tension_n[side]; }
  double ArmAngle(int side, int wheel) const { return state_.arm_q[side][wheel]; }
  // Generalised force (N m about the pivot, + lifts) the obstacles put on an arm in the last
  // Synchronize (0 when none touched it or the solver took its contacts).
  double ArmObstacleTorque(int side, int wheel) const { return obstacle_torque_nm_[side][wheel]; }
  // The sprocket's link in the multibody (its joint velocity is the sprocket's spin).
  int SprocketLink(int side) const { return sides_[side].sprocket_link; }
  // Ground force along the belt on one track in the last Synchronize (N, + forward): the thrust.
  double GroundThrust(int side) const { return thrust_n_[side]; }
  double TorsionPreload(int side, int wheel) const { return preload_nm_[side][wheel]; }
  // Road-wheel station k of a side at design (chassis x; the right side's may be offset).
  double RoadWheelX(int side, int k) const;
  int num_road_wheels() const { return n_rw_; }

 private:
  struct Side {
    double sign = 1.0;                  // +1 left, -1 right
    int sprocket_link = -1;
  };
  // Ground-run points of one side: 0 sprocket, 1..n road wheels, n + 1 idler.
  struct RunPoint {
    Vec3 p_W, v_W, tangent_W;           // bottom point, structure velocity, belt direction (fwd)
    Vec3 force_W;                       // contact force on the structure under the point
    Vec3 along_W;                       // the part carried along the belt (to the chassis)
  };
  void SynchronizeSide(int s, const DriverInputs& inputs, const terrain::Terrain& terrain,
                       soil::SoilContact* soil, const terrain::ObstacleField* obstacles,
                       terrain::ContactScratch* scratch, double dt,
                       std::vector<WheelState>* wheels);
  // Arm k's pivot and road-wheel centre in the chassis reference frame at angle q.
  Vec3 ArmPivot_B(int s, int k) const;
  Vec3 RoadWheelCentre_B(int s, int k, double q) const;
  Vec3 IdlerCentre_B(int s) const;
  // Integrates arm k of side s over dt under the generalised force `torque` (all but its weight,
  // inertia and obstacle contacts), the wheel's obstacle contacts as conditions on its rate, and
  // applies its inertial reaction (and the obstacle force it took) to the chassis.
  void AdvanceArm(int s, int k, double torque, double dt);
  // A road wheel's obstacle contact of this step; on_arm: the arm takes it (else the solver).
  struct WheelObstacle {
    terrain::BodyContact contact;
    bool on_arm = false;
  };

  const TrackParams& tp_;
  const VehicleParams& params_;
  engine::PhysicsWorld* world_ = nullptr;
  engine::MultiBodyId body_ = -1;
  Vec3 com_B_ = Vec3::Zero();
  int n_rw_ = 0;
  Side sides_[2];
  Vec3 wheel_from_pivot_L_ = Vec3::Zero();  // road-wheel centre from the pivot at angle 0
  Vec3 com_from_pivot_L_ = Vec3::Zero();    // arm + road wheel COM from the pivot at angle 0
  double arm_mass_kg_ = 0.0;                // arm + road wheel
  double arm_pivot_inertia_kgm2_ = 0.0;     // about the pivot axis
  double arm_damping_inertia_kgm2_ = 0.0;   // for the implicit torsion damping
  double preload_nm_[2][kMaxRoadWheels] = {};
  double belt_rest_length_m_[2] = {0.0, 0.0};
  double vehicle_mass_kg_ = 0.0;
  int samples_per_segment_[2][kMaxBeltWheels] = {};
  int sample_offset_[2][kMaxBeltWheels] = {};   // into state_.bristle_W (both sides)
  State state_;
  double thrust_n_[2] = {0.0, 0.0};
  // Per-step scratch.
  RunPoint run_[kMaxBeltWheels];
  Vec3 accel_com_W_ = Vec3::Zero(), alpha_W_ = Vec3::Zero();   // the chassis's, lagged a step
  Vec3 gravity_W_ = Vec3::Zero();
  // This step's road-wheel obstacle contacts; those of wheel k of side s are
  // [obstacle_begin_[s][k], obstacle_begin_[s][k + 1]) (the right side's after the left's).
  std::vector<WheelObstacle> wheel_obstacles_;
  int obstacle_begin_[2][kMaxRoadWheels + 1] = {};
  std::vector<terrain::BodyContact> obstacle_query_;
  double obstacle_torque_nm_[2][kMaxRoadWheels] = {};
  std::vector<double> sprocket_speeds_, sprocket_torques_;
  std::vector<bool> driven_;
};

}  // namespace vb::vehicles
