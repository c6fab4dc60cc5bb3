// The dynamics/collision adapter: the only door to the multibody dynamics. Everything above the
// engine core talks to rigid and articulated bodies through this class, in vb types; no type of
// the implementation escapes.
//
// Two implementations (src/engine/CMakeLists.txt, VB_PHYSICS): vb's own joint-space dynamics
// (src/engine/dynamics/physics_world_vb.cc, the default) and Bullet's btMultiBody with its
// constraint solver (src/engine/physics/physics_world.cc). What they do for vb: articulated
// vehicles and their constraints: joint limits, implicit joint motors (brakes) and the body-body
// contacts that vb generates itself each step (AddContact: chassis against the terrain and the
// obstacles, wheels against the obstacles; terrain/body_contact.h), solved as non-penetration
// and Coulomb friction constraints (vb's: two friction directions in a cone; Bullet's default
// mode: one). What they do NOT do: collision detection (no broadphase, contact caches or meshes,
// so a step depends only on the bodies' state: GetState/SetState restore it bit for bit) and
// wheel-ground contact, which vb computes from the terrain query and applies as external forces
// (docs/architecture.md).
#pragma once

#include <memory>
#include <vector>

#include "vb/engine/types.h"

namespace vb::engine {

// kPrescribedRevolute: a revolute joint whose angle is set from outside every step
// (SetPrescribedJoint: steering, as the original's kinematic rack), not integrated: it adds no
// degree of freedom and no constraint row to the dynamics, the link rides rigidly on its parent
// at the angle set. Its rate enters the read-out velocities of the link and its descendants
// (LinkPointVelocity, LinkAngularVelocity, JointVelocity), not the dynamics' momentum.
enum class JointType { kRevolute, kPrismatic, kPrescribedRevolute };

// Base body of an articulated system. Its frame is the body's centre of mass frame.
struct MultiBodyBaseSpec {
  double mass_kg = 1.0;
  Vec3 inertia_kgm2 = Vec3::Ones();  // principal moments about the COM axes
  Pose pose_W;                       // initial COM pose in world
};

// One link attached to its parent (-1 = base) through a single-DoF joint.
struct MultiBodyLinkSpec {
  int parent = -1;
  JointType joint = JointType::kRevolute;
  Vec3 axis_P = Vec3::UnitY();        // joint axis in the parent frame (unit)
  Vec3 parent_com_to_joint_P = Vec3::Zero();  // from parent COM to joint pivot, parent frame
  Vec3 joint_to_com_L = Vec3::Zero();         // from joint pivot to this link's COM, link frame
  double mass_kg = 1.0;
  Vec3 inertia_kgm2 = Vec3::Ones();
  // Optional joint limits (prismatic: m; revolute: rad); lower > upper means none. Not allowed
  // on a prescribed joint.
  double limit_lower = 1.0;
  double limit_upper = -1.0;
};

// Handle to an articulated body owned by the world.
using MultiBodyId = int;

// A contact between a multibody and a static obstacle during the last step.
struct ObstacleContact {
  MultiBodyId body = -1;
  int obstacle_tag = -1;
};

// Sorts by body, then tag, and drops repeats: the order of PhysicsWorld::ObstacleContacts() (for
// the adapters).
void SortObstacleContacts(std::vector<ObstacleContact>* contacts);

// A unilateral contact of a body with the static world for the next step (from vb's own contact
// generation): non-penetration along normal_W with Coulomb friction, solved implicitly with the
// joints. The static side is the point point_W + normal_W * depth_m.
struct ContactConstraint {
  MultiBodyId body = -1;
  int link = -1;                  // -1: the base
  Vec3 point_W = Vec3::Zero();    // on the body's surface
  Vec3 normal_W = Vec3::UnitZ();  // unit: the direction the contact pushes the body
  double depth_m = 0.0;           // penetration (>= 0)
  double friction = 0.8;
  int obstacle_tag = -1;          // reported in ObstacleContacts when >= 0
};

// The full dynamic state of an articulated body: what a snapshot must keep.
struct MultiBodyState {
  Vec3 base_position_W = Vec3::Zero();   // COM of the base
  Quat base_rotation = Quat::Identity();
  Vec3 base_velocity_W = Vec3::Zero();
  Vec3 base_angular_velocity_W = Vec3::Zero();
  std::vector<double> q;      // joint coordinates, one per link (prescribed joints included)
  std::vector<double> qdot;
};

class PhysicsWorld {
 public:
  explicit PhysicsWorld(double gravity_mps2 = kGravity);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  // Gravity as a world-frame vector (default (0, 0, -gravity_mps2)). Tilting it is a tilt table
  // that turns slowly under a vehicle settled on flat ground (validation tests); the terrain
  // contact never reads gravity, so the two are the same experiment.
  void SetGravity(const Vec3& gravity_W);
  Vec3 Gravity() const;

  // Articulated bodies. Link i of the returned body is links[i].
  MultiBodyId AddMultiBody(const MultiBodyBaseSpec& base, const std::vector<MultiBodyLinkSpec>& links);

  // Sets the initial joint coordinates (after AddMultiBody, before the first Step).
  void SetJointPosition(MultiBodyId mb, int link, double q);
  // Angle q (rad) and rate qdot (rad/s) of a kPrescribedRevolute joint, for the next Step and the
  // read-out until then; persistent until changed. Part of the state (GetState/SetState).
  void SetPrescribedJoint(MultiBodyId mb, int link, double q, double qdot);

  // Forces for the next Step only (cleared after it). World-frame force applied at a world point.
  void ApplyLinkForce(MultiBodyId mb, int link, const Vec3& force_W, const Vec3& point_W);
  void ApplyBaseForce(MultiBodyId mb, const Vec3& force_W, const Vec3& point_W);
  // World-frame pure torque on a link or the base, for the next Step only.
  void ApplyLinkTorque(MultiBodyId mb, int link, const Vec3& torque_W);
  void ApplyBaseTorque(MultiBodyId mb, const Vec3& torque_W);
  // Generalised joint force (N for prismatic, N·m for revolute), for the next Step only.
  void AddJointForce(MultiBodyId mb, int link, double force);
  // Implicit joint motors, solved inside the constraint solver, so they hold static loads without
  // creep: drive the joint velocity to target_velocity with at most max_force (N or N·m).
  // A max_force of 0 disables the motor. Persistent until changed.
  void SetJointVelocityMotor(MultiBodyId mb, int link, double target_velocity, double max_force);
  // Stiff position servo: drives q to target with a critically damped implicit motor (rigid
  // suspensions hold their slider with it).
  void SetJointPositionMotor(MultiBodyId mb, int link, double target_q, double max_force);

  // State read-out (valid after AddMultiBody and after every Step).
  Pose BasePose(MultiBodyId mb) const;            // COM frame of the base
  Vec3 BaseLinearVelocity(MultiBodyId mb) const;  // world frame, at the COM
  Vec3 BaseAngularVelocity(MultiBodyId mb) const; // world frame
  Pose LinkPose(MultiBodyId mb, int link) const;  // COM frame of the link
  Vec3 LinkPointVelocity(MultiBodyId mb, int link, const Vec3& point_W) const;
  Vec3 LinkAngularVelocity(MultiBodyId mb, int link) const;  // world frame
  double JointPosition(MultiBodyId mb, int link) const;
  double JointVelocity(MultiBodyId mb, int link) const;

  // A contact for the next Step only.
  void AddContact(const ContactConstraint& contact);
  // A touch of an obstacle that vb resolved itself, outside the solver (a tracked vehicle's
  // road-wheel arm yielding to a rock, track_running_gear.h): no constraint, only reported in the
  // next Step's ObstacleContacts as an AddContact with that tag would be.
  void ReportObstacleTouch(MultiBodyId body, int obstacle_tag);

  // Advances by dt seconds (exactly one internal step).
  void Step(double dt);

  // Bodies touching obstacles during the last Step: its contacts with a tag and the touches
  // reported for it (sorted by body, then tag; no repeats).
  const std::vector<ObstacleContact>& ObstacleContacts() const;

  // Snapshot and restore of a body's dynamic state. A world whose bodies were all restored steps
  // exactly as the world the states came from (motor targets and forces are set anew every step).
  MultiBodyState GetState(MultiBodyId mb) const;
  void SetState(MultiBodyId mb, const MultiBodyState& state);

  // False if any body state is NaN/inf (numerical trouble; the caller ends the trial).
  bool StateIsFinite() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vb::engine
