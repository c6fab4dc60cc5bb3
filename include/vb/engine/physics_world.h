// The dynamics/collision adapter: the only door to Bullet. Everything above the engine core talks
// to rigid and articulated bodies through this class, in vb types; no Bullet type escapes.
//
// What Bullet does for vb: articulated vehicles (btMultiBody, Featherstone), body-body contact
// (chassis and wheels against rocks and trees, chassis against the terrain mesh), joint limits and
// implicit joint motors (brakes, steering). What it does NOT do: wheel-ground contact, which vb
// computes itself from the terrain query and applies as external forces (docs/architecture.md).
#pragma once

#include <memory>
#include <vector>

#include "vb/engine/types.h"

namespace vb::engine {

// Collision groups: wheels collide only with obstacles (the ground under a wheel is vb's own
// contact model), chassis-like bodies collide with both the terrain mesh and obstacles.
enum class CollisionGroup : int { kTerrain = 1, kObstacle = 2, kChassis = 4, kWheel = 8 };

enum class JointType { kRevolute, kPrismatic };

struct BoxShape {
  Vec3 center_B = Vec3::Zero();   // box centre in the body frame (m)
  Vec3 half_extents_m = Vec3::Ones();
};

struct CylinderShape {
  double radius_m = 0.5;
  double half_width_m = 0.1;      // along the body y axis (wheel spin axis)
};

// Base body of an articulated system. Its frame is the body's centre of mass frame.
struct MultiBodyBaseSpec {
  double mass_kg = 1.0;
  Vec3 inertia_kgm2 = Vec3::Ones();  // principal moments about the COM axes
  Pose pose_W;                       // initial COM pose in world
  std::vector<BoxShape> boxes;       // collision boxes (collide with terrain mesh and obstacles)
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
  // Optional joint limits (prismatic: m; revolute: rad); lower > upper means none.
  double limit_lower = 1.0;
  double limit_upper = -1.0;
  // Optional collision cylinder (wheels): collides with obstacles only.
  bool has_cylinder = false;
  CylinderShape cylinder;
};

// Handle to an articulated body owned by the world.
using MultiBodyId = int;

// A contact between a multibody and a static obstacle during the last step.
struct ObstacleContact {
  MultiBodyId body = -1;
  int obstacle_tag = -1;
};

class PhysicsWorld {
 public:
  explicit PhysicsWorld(double gravity_mps2 = kGravity);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  // Static geometry. The terrain mesh is given as vertices and triangle vertex indices (counter-
  // clockwise seen from above). Obstacles carry a tag reported back in ObstacleContact.
  void AddTerrainMesh(const std::vector<Vec3>& vertices_W, const std::vector<int>& triangles,
                      double friction);
  void AddStaticBox(const Pose& pose_W, const Vec3& half_extents_m, double friction,
                    int obstacle_tag);

  // Articulated bodies. Link i of the returned body is links[i].
  MultiBodyId AddMultiBody(const MultiBodyBaseSpec& base, const std::vector<MultiBodyLinkSpec>& links,
                           double contact_friction);

  // Sets the initial joint coordinates (after AddMultiBody, before the first Step).
  void SetJointPosition(MultiBodyId mb, int link, double q);

  // Forces for the next Step only (cleared after it). World-frame force applied at a world point.
  void ApplyLinkForce(MultiBodyId mb, int link, const Vec3& force_W, const Vec3& point_W);
  void ApplyBaseForce(MultiBodyId mb, const Vec3& force_W, const Vec3& point_W);
  // World-frame pure torque on a link, for the next Step only.
  void ApplyLinkTorque(MultiBodyId mb, int link, const Vec3& torque_W);
  // Generalised joint force (N for prismatic, N·m for revolute), for the next Step only.
  void AddJointForce(MultiBodyId mb, int link, double force);
  // Implicit joint motors, solved inside the constraint solver, so they hold static loads without
  // creep: drive the joint velocity to target_velocity with at most max_force (N or N·m).
  // A max_force of 0 disables the motor. Persistent until changed.
  void SetJointVelocityMotor(MultiBodyId mb, int link, double target_velocity, double max_force);
  // Stiff position servo (steering): drives q to target with a critically damped implicit motor.
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

  // Advances by dt seconds (exactly one internal step).
  void Step(double dt);

  // Contacts with obstacles found during the last Step (deterministic order).
  const std::vector<ObstacleContact>& ObstacleContacts() const;

  // False if any body state is NaN/inf (numerical trouble; the caller ends the trial).
  bool StateIsFinite() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vb::engine
