// A vehicle assembled from VehicleParams on the physics adapter, with vb's own ground contact:
// wheels (tire models or the soil per wheel) or, for a tracked vehicle, the running gear of
// track_running_gear.h (the seam: everything outside sees the same state, the road wheels
// standing in for wheels). Order per step (the runner calls it): SetInputs -> Synchronize (contact,
// tire, suspension, powertrain and brake forces for this step) -> world.Step(dt) -> UpdateState.
#pragma once

#include <memory>
#include <vector>

#include "vb/engine/physics_world.h"
#include "vb/engine/types.h"
#include "vb/soil/soil_contact.h"
#include "vb/terrain/obstacle_field.h"
#include "vb/terrain/surface_class.h"
#include "vb/terrain/terrain.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

// Driver inputs, as Chrono's DriverInputs.
struct DriverInputs {
  double throttle = 0.0;   // [0, 1]
  double steering = 0.0;   // [-1, 1], +1 = full left
  double braking = 0.0;    // [0, 1]
};

struct WheelState {
  bool in_contact = false;
  terrain::SurfaceClass surface = terrain::SurfaceClass::kDirt;
  double normal_force_n = 0.0;
  double sinkage_m = 0.0;          // rigid ground: 0 (the soil solver will fill it)
  double spin_radps = 0.0;
  // (omega r - v) / max(|omega r|, |v|, 0.1 m/s), v = wheel-centre speed along the wheel's
  // rolling direction (spin axis x chassis up): + when driving (the tread moves faster than the
  // wheel travels).
  double longitudinal_slip = 0.0;
  double suspension_travel_m = 0.0;
  Vec3 center_W = Vec3::Zero();
};

struct VehicleState {
  Pose pose_W;                      // chassis reference frame (not the COM)
  Vec3 velocity_W = Vec3::Zero();   // of the reference point
  Vec3 angular_velocity_W = Vec3::Zero();
  double forward_speed_mps = 0.0;   // velocity along chassis x
  Rpy rpy;
  int gear = 1;
  double engine_speed_radps = 0.0;
  double engine_torque_nm = 0.0;
  // Contacts of the chassis envelope generated for the last step: with the ground (a belly on a
  // crest, a body on its side) and with rocks and trees.
  int body_ground_contacts = 0;
  int body_obstacle_contacts = 0;
  std::vector<WheelState> wheels;   // axle-major: axle 0 left, axle 0 right, axle 1 left, ...
};

class Vehicle;
class TrackRunningGear;

// A vehicle's complete dynamic state: the multibody state and every internal state (tire
// bristles and relaxation, powertrain, inputs). Opaque; made by Vehicle::Snapshot, restored by
// Vehicle::Restore into a vehicle built from the same parameters.
class VehicleSnapshot {
 public:
  VehicleSnapshot();
  ~VehicleSnapshot();
  VehicleSnapshot(const VehicleSnapshot& other);
  VehicleSnapshot& operator=(const VehicleSnapshot& other);

 private:
  friend class Vehicle;
  struct Data;
  std::unique_ptr<Data> data_;
};

// What the vehicle derives from its parameters at build time and LoadVehicle checks at load
// (tools/io/vehicle_io.cc), so that a vehicle that loads always builds:
//
// The spacing of the chassis envelope's sample points for obstacle contact: a tenth of the wheel
// radius (a rock's edge may meet the body anywhere). At most engine::kMaxShapeSamples points per
// envelope piece at this spacing.
double EnvelopeObstacleSpacing_m(const VehicleParams& params);
// The wheel travel range of a corner's carrier joint: the stops' engagement and stroke plus a hard
// limit beyond them (a rigid axle: the hard limit only).
struct TravelRange {
  double lower_m = 0.0;   // rebound (negative)
  double upper_m = 0.0;   // bump
};
TravelRange CarrierTravel(const SuspensionParams& su);
// The shock length table of a double-wishbone corner over its CarrierTravel, sampled every ~5 mm.
// Throws std::runtime_error if the linkage does not assemble somewhere in the range.
Table1D CornerShockLengthTable(const SuspensionParams& su);

class Vehicle {
 public:
  // Adds the vehicle to the world with its chassis reference frame at `pose_W`, wheels at their
  // design position. The terrain is kept by reference and must outlive the vehicle.
  Vehicle(const VehicleParams& params, const terrain::Terrain& terrain, const Pose& pose_W,
          engine::PhysicsWorld* world);
  ~Vehicle();

  // Deformable ground (nullable, not owned, must outlive the vehicle). Wheels the soil claims get
  // the soil's force and torque; all others use the vehicle's tire model on the rigid terrain.
  void SetSoil(soil::SoilContact* soil) { soil_ = soil; }
  // Rocks and trees the chassis envelope and the wheels can hit (nullable, not owned, must outlive
  // the vehicle). The ground contact of the envelope needs nothing: it uses the terrain.
  void SetObstacles(const terrain::ObstacleField* obstacles) { obstacles_ = obstacles; }

  void SetInputs(const DriverInputs& inputs);
  // Computes and applies this step's forces (call right before world.Step(dt)).
  void Synchronize(double dt);
  // Reads the post-step state (call right after world.Step(dt)).
  void UpdateState();

  VehicleSnapshot Snapshot() const;
  // Continues from `snapshot` (which must come from a vehicle with the same parameters).
  void Restore(const VehicleSnapshot& snapshot);

  const VehicleState& state() const { return state_; }
  const VehicleParams& params() const { return params_; }
  const DriverInputs& inputs() const { return inputs_; }
  engine::MultiBodyId body() const { return body_; }
  // The running gear of a tracked vehicle (params().tracked), else null.
  const TrackRunningGear* track() const { return track_.get(); }

 private:
  friend class VehicleSnapshot;
  struct Internals;
  struct Body;
  // Contacts of the chassis envelope with the ground and the obstacles, and of the wheels with
  // the obstacles, for the coming step (vb's own contact generation, terrain/body_contact.h).
  void AddBodyContacts();
  VehicleParams params_;
  const terrain::Terrain& terrain_;
  engine::PhysicsWorld* world_;
  soil::SoilContact* soil_ = nullptr;
  const terrain::ObstacleField* obstacles_ = nullptr;
  engine::MultiBodyId body_ = -1;
  DriverInputs inputs_;
  VehicleState state_;
  std::unique_ptr<Internals> in_;
  std::unique_ptr<Body> body_contact_;
  std::unique_ptr<TrackRunningGear> track_;
};

}  // namespace vb::vehicles
