// Bullet adapter: the only translation unit that includes Bullet. See physics_world.h.
#include "vb/engine/physics_world.h"

#include <algorithm>
#include <cmath>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "vb/engine/error.h"

namespace vb::engine {
namespace {

btVector3 ToBt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }
Vec3 FromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }
btQuaternion ToBt(const Quat& q) { return btQuaternion(q.x(), q.y(), q.z(), q.w()); }
Quat FromBt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }
Quat FromBt(const btMatrix3x3& m) {
  btQuaternion q;
  m.getRotation(q);
  return FromBt(q);
}

constexpr int kGroupTerrain = static_cast<int>(CollisionGroup::kTerrain);
constexpr int kGroupObstacle = static_cast<int>(CollisionGroup::kObstacle);
constexpr int kGroupChassis = static_cast<int>(CollisionGroup::kChassis);
constexpr int kGroupWheel = static_cast<int>(CollisionGroup::kWheel);

// userIndex of collision objects: obstacle tag for obstacles; -1 for the terrain.
// userIndex2: multibody id for vehicle colliders, -1 otherwise.
constexpr int kNoTag = -1;

}  // namespace

struct PhysicsWorld::Impl {
  // Bullet world pieces; order of declaration = reverse order of destruction requirements.
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};

  // Owned objects (Bullet does not own what is added to it).
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> static_objects;
  std::vector<std::unique_ptr<btTriangleIndexVertexArray>> meshes;
  std::vector<std::vector<btScalar>> mesh_vertices;
  std::vector<std::vector<int>> mesh_indices;

  struct Body {
    std::unique_ptr<btMultiBody> mb;
    std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
    std::vector<std::unique_ptr<btMultiBodyConstraint>> limits;
    std::vector<std::unique_ptr<btMultiBodyJointMotor>> motors;  // one per link, lazily made
    // Link velocities in link frames (index 0 = base), refreshed lazily after each Step.
    mutable btAlignedObjectArray<btVector3> omega, vel;
    mutable bool velocities_valid = false;
  };
  std::vector<Body> bodies;
  std::vector<ObstacleContact> contacts;
  double last_dt = 0.005;

  Body& Get(MultiBodyId id) {
    VB_DEMAND(id >= 0 && id < static_cast<int>(bodies.size()));
    return bodies[id];
  }
  const Body& Get(MultiBodyId id) const {
    VB_DEMAND(id >= 0 && id < static_cast<int>(bodies.size()));
    return bodies[id];
  }
  void RefreshVelocities(const Body& b) const {
    if (b.velocities_valid) return;
    b.mb->compTreeLinkVelocities(&b.omega[0], &b.vel[0]);
    b.velocities_valid = true;
  }
  btMultiBodyJointMotor* Motor(MultiBodyId id, int link) {
    Body& b = Get(id);
    if (!b.motors[link]) {
      b.motors[link] = std::make_unique<btMultiBodyJointMotor>(b.mb.get(), link, 0.0, 0.0);
      world.addMultiBodyConstraint(b.motors[link].get());
      b.motors[link]->finalizeMultiDof();
    }
    return b.motors[link].get();
  }
};

PhysicsWorld::PhysicsWorld(double gravity_mps2) : impl_(std::make_unique<Impl>()) {
  impl_->world.setGravity(btVector3(0, 0, -gravity_mps2));
  // Deterministic solver: no randomised constraint order.
  impl_->world.getSolverInfo().m_solverMode &= ~SOLVER_RANDMIZE_ORDER;
  impl_->world.getSolverInfo().m_numIterations = 30;
}

PhysicsWorld::~PhysicsWorld() {
  // Remove everything from the Bullet world before the owned objects die.
  auto& w = impl_->world;
  for (auto& b : impl_->bodies) {
    for (auto& m : b.motors)
      if (m) w.removeMultiBodyConstraint(m.get());
    for (auto& l : b.limits) w.removeMultiBodyConstraint(l.get());
    for (auto& c : b.colliders) w.removeCollisionObject(c.get());
    w.removeMultiBody(b.mb.get());
  }
  for (auto& o : impl_->static_objects) w.removeCollisionObject(o.get());
}

void PhysicsWorld::AddTerrainMesh(const std::vector<Vec3>& vertices_W,
                                  const std::vector<int>& triangles, double friction) {
  VB_DEMAND(triangles.size() % 3 == 0 && !vertices_W.empty());
  auto& verts = impl_->mesh_vertices.emplace_back();
  verts.reserve(vertices_W.size() * 3);
  for (const Vec3& v : vertices_W) {
    verts.push_back(v.x());
    verts.push_back(v.y());
    verts.push_back(v.z());
  }
  auto& idx = impl_->mesh_indices.emplace_back(triangles);
  auto array = std::make_unique<btTriangleIndexVertexArray>(
      static_cast<int>(idx.size() / 3), idx.data(), 3 * static_cast<int>(sizeof(int)),
      static_cast<int>(vertices_W.size()), verts.data(), 3 * static_cast<int>(sizeof(btScalar)));
  auto shape = std::make_unique<btBvhTriangleMeshShape>(array.get(), true);
  auto obj = std::make_unique<btCollisionObject>();
  obj->setCollisionShape(shape.get());
  obj->setFriction(friction);
  obj->setRestitution(0.0);
  obj->setUserIndex(kNoTag);
  obj->setUserIndex2(-1);
  impl_->world.addCollisionObject(obj.get(), kGroupTerrain, kGroupChassis);
  impl_->meshes.push_back(std::move(array));
  impl_->shapes.push_back(std::move(shape));
  impl_->static_objects.push_back(std::move(obj));
}

void PhysicsWorld::AddStaticBox(const Pose& pose_W, const Vec3& half_extents_m, double friction,
                                int obstacle_tag) {
  auto shape = std::make_unique<btBoxShape>(ToBt(half_extents_m));
  auto obj = std::make_unique<btCollisionObject>();
  obj->setCollisionShape(shape.get());
  obj->setWorldTransform(btTransform(ToBt(pose_W.rotation), ToBt(pose_W.position)));
  obj->setFriction(friction);
  obj->setRestitution(0.0);
  obj->setUserIndex(obstacle_tag);
  obj->setUserIndex2(-1);
  impl_->world.addCollisionObject(obj.get(), kGroupObstacle, kGroupChassis | kGroupWheel);
  impl_->shapes.push_back(std::move(shape));
  impl_->static_objects.push_back(std::move(obj));
}

MultiBodyId PhysicsWorld::AddMultiBody(const MultiBodyBaseSpec& base,
                                       const std::vector<MultiBodyLinkSpec>& links,
                                       double contact_friction) {
  const MultiBodyId id = static_cast<MultiBodyId>(impl_->bodies.size());
  Impl::Body body;
  const int n = static_cast<int>(links.size());
  body.mb = std::make_unique<btMultiBody>(n, base.mass_kg, ToBt(base.inertia_kgm2),
                                          /*fixedBase=*/false, /*canSleep=*/false);
  btMultiBody* mb = body.mb.get();
  for (int i = 0; i < n; ++i) {
    const MultiBodyLinkSpec& l = links[i];
    VB_DEMAND(l.parent < i);
    if (l.joint == JointType::kRevolute) {
      mb->setupRevolute(i, l.mass_kg, ToBt(l.inertia_kgm2), l.parent, btQuaternion::getIdentity(),
                        ToBt(l.axis_P), ToBt(l.parent_com_to_joint_P), ToBt(l.joint_to_com_L),
                        /*disableParentCollision=*/true);
    } else {
      mb->setupPrismatic(i, l.mass_kg, ToBt(l.inertia_kgm2), l.parent,
                         btQuaternion::getIdentity(), ToBt(l.axis_P), ToBt(l.parent_com_to_joint_P),
                         ToBt(l.joint_to_com_L), /*disableParentCollision=*/true);
    }
  }
  mb->finalizeMultiDof();
  // No artificial damping, no sleeping, no velocity caps below what a vehicle reaches (wheels spin
  // at up to ~100 rad/s): Bullet's defaults (0.04 damping, 100 rad/s cap) would bias the physics.
  mb->setLinearDamping(0.0);
  mb->setAngularDamping(0.0);
  mb->setMaxCoordinateVelocity(1000.0);
  mb->setMaxAppliedImpulse(1e9);
  mb->setUseGyroTerm(true);
  mb->setHasSelfCollision(false);
  mb->setBaseWorldTransform(btTransform(ToBt(base.pose_W.rotation), ToBt(base.pose_W.position)));
  impl_->world.addMultiBody(mb, kGroupChassis, kGroupTerrain | kGroupObstacle);

  // Base collider: a compound of boxes offset from the COM.
  if (!base.boxes.empty()) {
    auto compound = std::make_unique<btCompoundShape>();
    for (const BoxShape& b : base.boxes) {
      auto box = std::make_unique<btBoxShape>(ToBt(b.half_extents_m));
      compound->addChildShape(btTransform(btQuaternion::getIdentity(), ToBt(b.center_B)),
                              box.get());
      impl_->shapes.push_back(std::move(box));
    }
    auto col = std::make_unique<btMultiBodyLinkCollider>(mb, -1);
    col->setCollisionShape(compound.get());
    col->setWorldTransform(mb->getBaseWorldTransform());
    col->setFriction(contact_friction);
    col->setUserIndex(kNoTag);
    col->setUserIndex2(id);
    impl_->world.addCollisionObject(col.get(), kGroupChassis, kGroupTerrain | kGroupObstacle);
    mb->setBaseCollider(col.get());
    impl_->shapes.push_back(std::move(compound));
    body.colliders.push_back(std::move(col));
  }

  // Link colliders (wheel cylinders, obstacles only) and joint limits.
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  world_to_local.resize(n + 1);
  local_origin.resize(n + 1);
  mb->forwardKinematics(world_to_local, local_origin);
  for (int i = 0; i < n; ++i) {
    const MultiBodyLinkSpec& l = links[i];
    if (l.has_cylinder) {
      auto cyl = std::make_unique<btCylinderShape>(
          btVector3(l.cylinder.radius_m, l.cylinder.half_width_m, l.cylinder.radius_m));
      auto col = std::make_unique<btMultiBodyLinkCollider>(mb, i);
      col->setCollisionShape(cyl.get());
      col->setFriction(contact_friction);
      col->setUserIndex(kNoTag);
      col->setUserIndex2(id);
      impl_->world.addCollisionObject(col.get(), kGroupWheel, kGroupObstacle);
      mb->getLink(i).m_collider = col.get();
      impl_->shapes.push_back(std::move(cyl));
      body.colliders.push_back(std::move(col));
    }
    if (!l.has_cylinder) {
      // Bullet solves a link's motors and limits in the simulation island of that link's own
      // collider; a link without one gets island -1 and its motors are silently skipped. A tiny
      // sphere that collides with nothing (group 0, mask 0) puts the link in its body's island.
      auto anchor = std::make_unique<btSphereShape>(0.01);
      auto col = std::make_unique<btMultiBodyLinkCollider>(mb, i);
      col->setCollisionShape(anchor.get());
      col->setUserIndex(kNoTag);
      col->setUserIndex2(-1);
      impl_->world.addCollisionObject(col.get(), 0, 0);
      mb->getLink(i).m_collider = col.get();
      impl_->shapes.push_back(std::move(anchor));
      body.colliders.push_back(std::move(col));
    }
    if (l.limit_lower <= l.limit_upper) {
      auto lim = std::make_unique<btMultiBodyJointLimitConstraint>(mb, i, l.limit_lower,
                                                                   l.limit_upper);
      impl_->world.addMultiBodyConstraint(lim.get());
      body.limits.push_back(std::move(lim));
    }
  }
  mb->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
  body.motors.resize(n);
  body.omega.resize(n + 1);
  body.vel.resize(n + 1);
  impl_->bodies.push_back(std::move(body));
  return id;
}

void PhysicsWorld::SetJointPosition(MultiBodyId id, int link, double q) {
  Impl::Body& b = impl_->Get(id);
  b.mb->setJointPos(link, q);
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  world_to_local.resize(b.mb->getNumLinks() + 1);
  local_origin.resize(b.mb->getNumLinks() + 1);
  b.mb->forwardKinematics(world_to_local, local_origin);
  b.mb->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
  b.velocities_valid = false;
}

void PhysicsWorld::ApplyLinkForce(MultiBodyId id, int link, const Vec3& force_W,
                                  const Vec3& point_W) {
  btMultiBody* mb = impl_->Get(id).mb.get();
  const btVector3 com = mb->localPosToWorld(link, btVector3(0, 0, 0));
  mb->addLinkForce(link, ToBt(force_W));
  mb->addLinkTorque(link, (ToBt(point_W) - com).cross(ToBt(force_W)));
}

void PhysicsWorld::ApplyLinkTorque(MultiBodyId id, int link, const Vec3& torque_W) {
  impl_->Get(id).mb->addLinkTorque(link, ToBt(torque_W));
}

void PhysicsWorld::ApplyBaseForce(MultiBodyId id, const Vec3& force_W, const Vec3& point_W) {
  btMultiBody* mb = impl_->Get(id).mb.get();
  mb->addBaseForce(ToBt(force_W));
  mb->addBaseTorque((ToBt(point_W) - mb->getBasePos()).cross(ToBt(force_W)));
}

void PhysicsWorld::AddJointForce(MultiBodyId id, int link, double force) {
  impl_->Get(id).mb->addJointTorque(link, force);
}

void PhysicsWorld::SetJointVelocityMotor(MultiBodyId id, int link, double target_velocity,
                                         double max_force) {
  btMultiBodyJointMotor* m = impl_->Motor(id, link);
  m->setVelocityTarget(target_velocity, 1.0);
  m->setPositionTarget(0.0, 0.0);
  // Bullet's multibody motors bound an impulse per step, not a force.
  m->setMaxAppliedImpulse(std::max(0.0, max_force) * impl_->last_dt);
}

void PhysicsWorld::SetJointPositionMotor(MultiBodyId id, int link, double target_q,
                                         double max_force) {
  btMultiBodyJointMotor* m = impl_->Motor(id, link);
  // Position error corrected over ~5 steps, velocity error damped fully each step. The motor's
  // error-reduction parameter must be 1 for the position term to count at all.
  m->setErp(1.0);
  m->setPositionTarget(target_q, 0.2);
  m->setVelocityTarget(0.0, 1.0);
  m->setMaxAppliedImpulse(std::max(0.0, max_force) * impl_->last_dt);
}

Pose PhysicsWorld::BasePose(MultiBodyId id) const {
  const btMultiBody* mb = impl_->Get(id).mb.get();
  Pose p;
  p.position = FromBt(mb->getBasePos());
  p.rotation = FromBt(mb->getWorldToBaseRot().inverse());
  return p;
}

Vec3 PhysicsWorld::BaseLinearVelocity(MultiBodyId id) const {
  return FromBt(impl_->Get(id).mb->getBaseVel());
}

Vec3 PhysicsWorld::BaseAngularVelocity(MultiBodyId id) const {
  return FromBt(impl_->Get(id).mb->getBaseOmega());
}

Pose PhysicsWorld::LinkPose(MultiBodyId id, int link) const {
  const btMultiBody* mb = impl_->Get(id).mb.get();
  Pose p;
  p.position = FromBt(mb->localPosToWorld(link, btVector3(0, 0, 0)));
  p.rotation = FromBt(mb->localFrameToWorld(link, btMatrix3x3::getIdentity()));
  return p;
}

Vec3 PhysicsWorld::LinkPointVelocity(MultiBodyId id, int link, const Vec3& point_W) const {
  const Impl::Body& b = impl_->Get(id);
  impl_->RefreshVelocities(b);
  // compTreeLinkVelocities returns COM velocity and angular velocity in the link frame.
  const btVector3 r_L = b.mb->worldPosToLocal(link, ToBt(point_W));
  const btVector3 v_L = b.vel[link + 1] + b.omega[link + 1].cross(r_L);
  return FromBt(b.mb->localDirToWorld(link, v_L));
}

Vec3 PhysicsWorld::LinkAngularVelocity(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  impl_->RefreshVelocities(b);
  return FromBt(b.mb->localDirToWorld(link, b.omega[link + 1]));
}

double PhysicsWorld::JointPosition(MultiBodyId id, int link) const {
  return impl_->Get(id).mb->getJointPos(link);
}

double PhysicsWorld::JointVelocity(MultiBodyId id, int link) const {
  return impl_->Get(id).mb->getJointVel(link);
}

void PhysicsWorld::Step(double dt) {
  // Motor impulse bounds were set for the previous dt; keep them consistent with this one.
  if (dt != impl_->last_dt) {
    const double ratio = dt / impl_->last_dt;
    for (auto& b : impl_->bodies)
      for (auto& m : b.motors)
        if (m) m->setMaxAppliedImpulse(m->getMaxAppliedImpulse() * ratio);
    impl_->last_dt = dt;
  }
  // Exactly one fixed step: maxSubSteps = 0 means "step by dt", no interpolation.
  impl_->world.stepSimulation(dt, 0, dt);
  for (auto& b : impl_->bodies) {
    b.velocities_valid = false;
    b.mb->clearForcesAndTorques();
  }

  // Obstacle contacts of this step, in a deterministic order.
  impl_->contacts.clear();
  const int n_manifolds = impl_->dispatcher.getNumManifolds();
  for (int i = 0; i < n_manifolds; ++i) {
    const btPersistentManifold* m = impl_->dispatcher.getManifoldByIndexInternal(i);
    bool touching = false;
    for (int k = 0; k < m->getNumContacts(); ++k)
      if (m->getContactPoint(k).getDistance() <= 0.0) touching = true;
    if (!touching) continue;
    const btCollisionObject* a = m->getBody0();
    const btCollisionObject* b = m->getBody1();
    if (a->getUserIndex() < 0) std::swap(a, b);
    if (a->getUserIndex() < 0 || b->getUserIndex2() < 0) continue;
    impl_->contacts.push_back({b->getUserIndex2(), a->getUserIndex()});
  }
  std::sort(impl_->contacts.begin(), impl_->contacts.end(),
            [](const ObstacleContact& x, const ObstacleContact& y) {
              return x.body != y.body ? x.body < y.body : x.obstacle_tag < y.obstacle_tag;
            });
  impl_->contacts.erase(std::unique(impl_->contacts.begin(), impl_->contacts.end(),
                                    [](const ObstacleContact& x, const ObstacleContact& y) {
                                      return x.body == y.body && x.obstacle_tag == y.obstacle_tag;
                                    }),
                        impl_->contacts.end());
}

const std::vector<ObstacleContact>& PhysicsWorld::ObstacleContacts() const {
  return impl_->contacts;
}

bool PhysicsWorld::StateIsFinite() const {
  for (const auto& b : impl_->bodies) {
    const btMultiBody* mb = b.mb.get();
    const btVector3 p = mb->getBasePos();
    const btVector3 v = mb->getBaseVel();
    const btVector3 w = mb->getBaseOmega();
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(p[k]) || !std::isfinite(v[k]) || !std::isfinite(w[k])) return false;
    for (int i = 0; i < mb->getNumLinks(); ++i)
      if (!std::isfinite(mb->getJointPos(i)) || !std::isfinite(mb->getJointVel(i))) return false;
  }
  return true;
}

}  // namespace vb::engine
