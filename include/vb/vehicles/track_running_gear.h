// The running gear of a tracked vehicle (TrackParams), vb's own design (docs/vehicles.md,
// "Tracked vehicles"). Per side, in the vehicle's multibody tree:
//   base (chassis) --revolute y--> sprocket  (spin: the belt's speed = spin x pitch radius; its
//                                            inertia carries the belt, road wheels and idler)
// and the idler on a carrier that slides along chassis x, pushed away from the sprocket by the
// tensioner; the carrier is light and stiffly held, so its travel is solved quasi-statically
// each step (tensioner force = the belt's pull on it) rather than as a link.
//   base --revolute y--> road-wheel arm x N  (trailing arm, torsion bar at the pivot)
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

class TrackRunningGear {
 public:
  // Internal state a snapshot keeps: powertrain, the bristles of the rigid contact samples.
  struct State {
    PowertrainState powertrain;
    std::vector<Vec3> bristle_W;    // per side and sample
    double tension_n[2] = {0.0, 0.0};
    double idler_travel_m[2] = {0.0, 0.0};   // carrier travel away from the sprocket
  };

  // Appends both tracks' links (left side first) to `links`; the base's COM is com_B (chassis
  // frame). Call Attach once the multibody exists.
  TrackRunningGear(const VehicleParams& params, const Vec3& com_B,
                   std::vector<engine::MultiBodyLinkSpec>* links);
  void Attach(engine::PhysicsWorld* world, engine::MultiBodyId body);

  // This step's forces: belt tension, torsion bars, tensioner, ground contact, sprocket drive
  // and brakes. Fills the road wheels' contact fields of `wheels` (axle-major: station 0 left,
  // station 0 right, ...).
  void Synchronize(const DriverInputs& inputs, const terrain::Terrain& terrain,
                   soil::SoilContact* soil, double dt, std::vector<WheelState>* wheels);
  // Post-step read-out of the road wheels (spin, slip, travel, centre).
  void UpdateWheelStates(std::vector<WheelState>* wheels) const;
  // Road wheels against rocks and trees (as the wheels of a wheeled vehicle).
  void AddObstacleContacts(const terrain::ObstacleField& obstacles, terrain::ContactScratch* scratch,
                           std::vector<terrain::BodyContact>* contacts);

  const State& state() const { return state_; }
  void set_state(const State& s) { state_ = s; }
  double SprocketSpeed(int side) const;   // rad/s, + forward
  double BeltTension(int side) const { return state_.tension_n[side]; }
  double ArmAngle(int side, int wheel) const;
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
    int arm_link[kMaxRoadWheels] = {};
  };
  // Ground-run points of one side: 0 sprocket, 1..n road wheels, n + 1 idler.
  struct RunPoint {
    Vec3 p_W, v_W, tangent_W;           // bottom point, structure velocity, belt direction (fwd)
    Vec3 force_W;                       // contact force on the structure under the point
    Vec3 along_W;                       // the part carried along the belt (to the chassis)
  };
  void SynchronizeSide(int s, const DriverInputs& inputs, const terrain::Terrain& terrain,
                       soil::SoilContact* soil, double dt, std::vector<WheelState>* wheels);
  Vec3 RoadWheelCentre(int s, int k) const;
  Vec3 IdlerCentre_B(int s) const;

  const TrackParams& tp_;
  const VehicleParams& params_;
  engine::PhysicsWorld* world_ = nullptr;
  engine::MultiBodyId body_ = -1;
  Vec3 com_B_ = Vec3::Zero();
  int n_rw_ = 0;
  Side sides_[2];
  Vec3 wheel_from_com_L_[kMaxRoadWheels];   // road-wheel centre from the arm link's COM
  double preload_nm_[2][kMaxRoadWheels] = {};
  double belt_rest_length_m_[2] = {0.0, 0.0};
  double vehicle_mass_kg_ = 0.0;
  int samples_per_segment_[2][kMaxBeltWheels] = {};
  int sample_offset_[2][kMaxBeltWheels] = {};   // into state_.bristle_W (both sides)
  State state_;
  double thrust_n_[2] = {0.0, 0.0};
  // Per-step scratch.
  RunPoint run_[kMaxBeltWheels];
  std::vector<double> sprocket_speeds_, sprocket_torques_;
  std::vector<bool> driven_;
};

}  // namespace vb::vehicles
