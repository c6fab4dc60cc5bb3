// Bullet adapter: the only translation unit that includes Bullet. See physics_world.h.
#include "vb/engine/physics_world.h"

#include <algorithm>
#include <cmath>

#include <btBulletDynamicsCommon.h>
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

// Bullet's persistent manifolds hold at most 4 points (MANIFOLD_CACHE_SIZE).
constexpr int kPointsPerManifold = 4;

// Bullet's default pools hold 4096 manifolds and collision algorithms; vb uses a few manifolds
// per step and no algorithms, and a trial builds a world: small pools make that cheap.
btDefaultCollisionConstructionInfo SmallPools() {
  btDefaultCollisionConstructionInfo info;
  info.m_defaultMaxPersistentManifoldPoolSize = 64;
  info.m_defaultMaxCollisionAlgorithmPoolSize = 16;
  return info;
}

// Bullet's multibody world without the work whose results vb never reads. Every collider is in
// no collision group and every contact comes from AddContact, so the broadphase and narrowphase
// would find nothing: the per-step AABB update of every link collider, the broadphase's pair
// search and the dispatch over its (empty) pair list are skipped. The motion prediction before
// the solve writes only the interpolation transforms of the bodies and their colliders
// (m_*_interpolate), which continuous collision detection and deformable bodies read and vb has
// neither: skipped too. The dynamics (forces, solver, integration) are Bullet's, unchanged, so
// the results are bit-identical.
//
// The integration advances each multibody's positions (joint angles and base pose) by its
// velocities, and no more: Bullet's own also writes every link collider's world transform, which
// nothing reads during a step (the solver takes the links' cached transforms and the contacts'
// world points); the colliders keep the pose of the last state the adapter set (AddMultiBody,
// SetState, SetJointPosition update them). Bullet's other branches do not occur in vb: its
// multibodies cannot sleep (created with canSleep = false, so the world keeps their colliders
// active) and vb never asks for the RK4 integration that leaves a position change behind.
class VbMultiBodyWorld : public btMultiBodyDynamicsWorld {
 public:
  using btMultiBodyDynamicsWorld::btMultiBodyDynamicsWorld;
  void performDiscreteCollisionDetection() override {}
  void predictUnconstraintMotion(btScalar /*timeStep*/) override {}
  void integrateTransforms(btScalar timeStep) override {
    btDiscreteDynamicsWorld::integrateTransforms(timeStep);  // rigid bodies (vb has none)
    for (int i = 0; i < m_multiBodies.size(); ++i) {
      VB_DEMAND(!m_multiBodies[i]->isPosUpdated());
      m_multiBodies[i]->stepPositionsMultiDof(timeStep);
    }
  }
};

}  // namespace

struct PhysicsWorld::Impl {
  // Bullet world pieces; order of declaration = reverse order of destruction requirements.
  btDefaultCollisionConfiguration config{SmallPools()};
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  VbMultiBodyWorld world{&dispatcher, &broadphase, &solver, &config};

  // Owned objects (Bullet does not own what is added to it).
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  // The static side of every vb contact: a collision object that is never added to the world
  // (so Bullet's collision detection never sees it); the solver treats it as a fixed body.
  btSphereShape static_shape{0.01};
  btCollisionObject static_side;

  struct Body {
    std::unique_ptr<btMultiBody> mb;
    // One collider per link and the base: tiny spheres in no collision group. They exist because
    // Bullet solves a link's motors, limits and contacts in the simulation island of its own
    // collider, and a vb contact's manifold names the collider of the body it pushes.
    std::unique_ptr<btMultiBodyLinkCollider> base_collider;
    std::vector<std::unique_ptr<btMultiBodyLinkCollider>> link_colliders;
    std::vector<std::unique_ptr<btMultiBodyConstraint>> limits;
    std::vector<std::unique_ptr<btMultiBodyJointMotor>> motors;  // one per link, lazily made
    // Prescribed joints (JointType::kPrescribedRevolute): Bullet fixed links whose rotation from
    // the parent is rewritten by SetPrescribedJoint. Per link: whether prescribed, the axis in
    // the parent frame, the angle and the rate (both unused for other links).
    std::vector<char> prescribed;
    std::vector<btVector3> prescribed_axis_P;
    std::vector<double> prescribed_q, prescribed_qdot;
    bool any_prescribed_rate = false;
    // Link kinematics of the current state in the world frame, computed on the first request
    // after a change (the vehicle reads each wheel's pose and point velocities several times per
    // step; walking the chain per request was the costliest read-out). After a step or a state
    // change every link is recomputed; after a prescribed joint's change only that link and its
    // descendants (a steering angle moves the knuckle and its wheel): the other links' inputs are
    // unchanged, so recomputing them would give the same numbers. Poses: down the tree (parent
    // before child). Velocities: the link-frame COM and angular velocities (index 0 = base) by
    // the operations of btMultiBody::compTreeLinkVelocities, in the same order, then turned into
    // the world frame.
    std::vector<int> parent;                                         // per link, -1 = the base
    mutable btAlignedObjectArray<btQuaternion> link_world_to_local;  // index 0 = base
    mutable btAlignedObjectArray<btVector3> link_origin_W;           // link COM, index 0 = base
    mutable std::vector<Pose> link_pose;                             // index = link
    // Per index (0 = base, k + 1 = link k): pose, velocities to be recomputed; and whether any is.
    // The world-frame forms the caller reads (link_pose, omega_W and vel_W) are made on the first
    // request for that link only (the vehicle reads its wheels, not the carriers and knuckles).
    mutable std::vector<char> pose_stale, vel_stale, pose_out_stale, vel_W_stale;
    mutable bool any_pose_stale = true, any_vel_stale = true;
    mutable std::vector<char> in_subtree;                            // scratch of MarkStale
    mutable btAlignedObjectArray<btVector3> omega, vel;              // link frames
    mutable btAlignedObjectArray<btVector3> omega_W, vel_W;          // world frame
    mutable btAlignedObjectArray<btVector3> d_omega_W, d_vel_W;      // prescribed rates' share
    void Invalidate() const {
      std::fill(pose_stale.begin(), pose_stale.end(), 1);
      std::fill(vel_stale.begin(), vel_stale.end(), 1);
      any_pose_stale = any_vel_stale = true;
    }
    // Marks `link` and its descendants (all after it: a parent comes before its children) as
    // having new velocities, and with `pose` new poses too.
    void MarkStale(int link, bool pose) {
      const int n = static_cast<int>(parent.size());
      for (int k = link; k < n; ++k) {
        const size_t i = static_cast<size_t>(k);
        const int p = parent[i];
        in_subtree[i] = k == link || (p >= link && in_subtree[static_cast<size_t>(p)]);
        if (!in_subtree[i]) continue;
        vel_stale[i + 1] = 1;
        if (pose) pose_stale[i + 1] = 1;
      }
      any_vel_stale = true;
      if (pose) any_pose_stale = true;
    }
    // Scratch of forwardKinematics.
    btAlignedObjectArray<btQuaternion> world_to_local;
    btAlignedObjectArray<btVector3> local_origin;
  };
  std::vector<Body> bodies;
  std::vector<ContactConstraint> pending_contacts;   // for the next Step
  std::vector<ObstacleContact> pending_touches;      // ReportObstacleTouch, for the next Step
  std::vector<btPersistentManifold*> manifolds;      // made for the current Step
  std::vector<ObstacleContact> contacts;
  double last_dt = 0.005;

  Impl() { static_side.setCollisionShape(&static_shape); }

  Body& Get(MultiBodyId id) {
    VB_DEMAND(id >= 0 && id < static_cast<int>(bodies.size()));
    return bodies[id];
  }
  const Body& Get(MultiBodyId id) const {
    VB_DEMAND(id >= 0 && id < static_cast<int>(bodies.size()));
    return bodies[id];
  }
  void RefreshPoses(const Body& b) const {
    if (!b.any_pose_stale) return;
    const btMultiBody* mb = b.mb.get();
    if (b.pose_stale[0]) {
      b.link_world_to_local[0] = mb->getWorldToBaseRot();
      b.link_origin_W[0] = mb->getBasePos();
      b.pose_stale[0] = 0;
    }
    for (int k = 0; k < mb->getNumLinks(); ++k) {
      const size_t i = static_cast<size_t>(k);
      if (!b.pose_stale[i + 1]) continue;
      b.pose_stale[i + 1] = 0;
      const int parent = b.parent[i];
      const btQuaternion w2l = mb->getParentToLocalRot(k) * b.link_world_to_local[parent + 1];
      b.link_world_to_local[k + 1] = w2l;
      b.link_origin_W[k + 1] =
          b.link_origin_W[parent + 1] + quatRotate(w2l.inverse(), mb->getRVector(k));
      b.pose_out_stale[i] = 1;
    }
    b.any_pose_stale = false;
  }
  const Pose& LinkPose(const Body& b, int link) const {
    RefreshPoses(b);
    const size_t i = static_cast<size_t>(link);
    Pose& pose = b.link_pose[i];
    if (b.pose_out_stale[i]) {
      pose.position = FromBt(b.link_origin_W[link + 1]);
      pose.rotation = FromBt(b.link_world_to_local[link + 1].inverse()).normalized();
      b.pose_out_stale[i] = 0;
    }
    return pose;
  }
  void RefreshVelocities(const Body& b) const {
    if (!b.any_vel_stale) return;
    RefreshPoses(b);
    const btMultiBody* mb = b.mb.get();
    const int n = mb->getNumLinks();
    // link frames: btMultiBody::compTreeLinkVelocities, for the stale links
    if (b.vel_stale[0]) {
      const btQuaternion& base_rot = mb->getWorldToBaseRot();
      b.omega[0] = quatRotate(base_rot, mb->getBaseOmega());
      b.vel[0] = quatRotate(base_rot, mb->getBaseVel());
    }
    for (int k = 0; k < n; ++k) {
      if (!b.vel_stale[static_cast<size_t>(k) + 1]) continue;
      const btMultibodyLink& link = mb->getLink(k);
      const int p = link.m_parent;
      // btMultiBody::spatialTransform of the parent's velocities into this link's frame
      const btMatrix3x3 rot(link.m_cachedRotParentToThis);
      btVector3& w = b.omega[k + 1];
      btVector3& v = b.vel[k + 1];
      w = rot * b.omega[p + 1];
      v = -link.m_cachedRVector.cross(w) + rot * b.vel[p + 1];
      // plus the joint's rates along its axes
      const btScalar* joint_vel = mb->getJointVelMultiDof(k);
      for (int dof = 0; dof < link.m_dofCount; ++dof) {
        w += joint_vel[dof] * link.getAxisTop(dof);
        v += joint_vel[dof] * link.getAxisBottom(dof);
      }
    }
    if (b.any_prescribed_rate) AddPrescribedRates(b);
    for (size_t k = 0; k < b.vel_stale.size(); ++k) {
      b.vel_W_stale[k] = b.vel_W_stale[k] || b.vel_stale[k];
      b.vel_stale[k] = 0;
    }
    b.any_vel_stale = false;
  }
  // World-frame angular and COM velocity of index k (0 = base, link + 1): the link frame's turned
  // into the world frame, plus the prescribed rates' share.
  void WorldVelocities(const Body& b, int k) const {
    RefreshVelocities(b);
    if (!b.vel_W_stale[static_cast<size_t>(k)]) return;
    const btQuaternion local_to_world = b.link_world_to_local[k].inverse();
    b.omega_W[k] = quatRotate(local_to_world, b.omega[k]);
    b.vel_W[k] = quatRotate(local_to_world, b.vel[k]);
    if (b.any_prescribed_rate) {
      b.omega_W[k] += b.d_omega_W[k];
      b.vel_W[k] += b.d_vel_W[k];
    }
    b.vel_W_stale[static_cast<size_t>(k)] = 0;
  }
  // Bullet's fixed links move with their parent only: what the prescribed joints' rates give each
  // stale link, down the tree (parent before child), as a revolute joint's rate would (added to
  // its world-frame velocities by WorldVelocities). The shares of links that are not stale are
  // those of the last pass: a change of any rate from or to zero makes every link stale
  // (SetPrescribedJoint), so that pass computed them too.
  static void AddPrescribedRates(const Body& b) {
    const btMultiBody* mb = b.mb.get();
    if (b.vel_stale[0]) {
      b.d_omega_W[0].setZero();
      b.d_vel_W[0].setZero();
    }
    for (int k = 0; k < mb->getNumLinks(); ++k) {
      if (!b.vel_stale[static_cast<size_t>(k) + 1]) continue;
      const int p = b.parent[static_cast<size_t>(k)] + 1;
      const btVector3 lever = b.link_origin_W[k + 1] - b.link_origin_W[p];
      btVector3 dw = b.d_omega_W[p];
      btVector3 dv = b.d_vel_W[p] + dw.cross(lever);
      if (b.prescribed[static_cast<size_t>(k)] && b.prescribed_qdot[static_cast<size_t>(k)] != 0.0) {
        const btQuaternion parent_to_world = b.link_world_to_local[p].inverse();
        const btVector3 w = quatRotate(parent_to_world, b.prescribed_axis_P[static_cast<size_t>(k)]) *
                            b.prescribed_qdot[static_cast<size_t>(k)];
        // about the joint's pivot: parent COM + e (parent frame)
        const btVector3 pivot_W =
            b.link_origin_W[p] + quatRotate(parent_to_world, mb->getLink(k).m_eVector);
        dw += w;
        dv += w.cross(b.link_origin_W[k + 1] - pivot_W);
      }
      b.d_omega_W[k + 1] = dw;
      b.d_vel_W[k + 1] = dv;
    }
  }
  btMultiBodyJointMotor* Motor(MultiBodyId id, int link) {
    Body& b = Get(id);
    VB_DEMAND(link >= 0 && link < b.mb->getNumLinks() && !b.prescribed[static_cast<size_t>(link)]);
    if (!b.motors[link]) {
      b.motors[link] = std::make_unique<btMultiBodyJointMotor>(b.mb.get(), link, 0.0, 0.0);
      world.addMultiBodyConstraint(b.motors[link].get());
      b.motors[link]->finalizeMultiDof();
    }
    return b.motors[link].get();
  }
};

void PhysicsWorld::SetGravity(const Vec3& gravity_W) {
  impl_->world.setGravity(btVector3(gravity_W.x(), gravity_W.y(), gravity_W.z()));
}

Vec3 PhysicsWorld::Gravity() const { return FromBt(impl_->world.getGravity()); }

PhysicsWorld::PhysicsWorld(double gravity_mps2) : impl_(std::make_unique<Impl>()) {
  impl_->world.setGravity(btVector3(0, 0, -gravity_mps2));
  // No collision pairs ever exist (every collider is in no group), so Bullet's broadphase and
  // narrowphase find nothing; contacts come from AddContact.
  impl_->world.setForceUpdateAllAabbs(false);
  // Deterministic solver: no randomised constraint order.
  impl_->world.getSolverInfo().m_solverMode &= ~SOLVER_RANDMIZE_ORDER;
  impl_->world.getSolverInfo().m_numIterations = 30;
  // Stop iterating once a sweep changes no row's constraint-space velocity by more than 1 um/s
  // (Bullet's residual is the largest squared change, (m/s)^2): at 5 ms that is nm of drift.
  // Without it the sweeps run to 30 whenever a motor row is active (every step: steering),
  // long after the impulses have converged; with it the solver does ~60 % fewer sweeps.
  impl_->world.getSolverInfo().m_leastSquaresResidualThreshold = 1e-12;
}

PhysicsWorld::~PhysicsWorld() {
  // Remove everything from the Bullet world before the owned objects die.
  auto& w = impl_->world;
  for (btPersistentManifold* m : impl_->manifolds) impl_->dispatcher.releaseManifold(m);
  for (auto& b : impl_->bodies) {
    for (auto& m : b.motors)
      if (m) w.removeMultiBodyConstraint(m.get());
    for (auto& l : b.limits) w.removeMultiBodyConstraint(l.get());
    for (auto& c : b.link_colliders) w.removeCollisionObject(c.get());
    if (b.base_collider) w.removeCollisionObject(b.base_collider.get());
    w.removeMultiBody(b.mb.get());
  }
}

MultiBodyId PhysicsWorld::AddMultiBody(const MultiBodyBaseSpec& base,
                                       const std::vector<MultiBodyLinkSpec>& links) {
  const MultiBodyId id = static_cast<MultiBodyId>(impl_->bodies.size());
  Impl::Body body;
  const int n = static_cast<int>(links.size());
  body.mb = std::make_unique<btMultiBody>(n, base.mass_kg, ToBt(base.inertia_kgm2),
                                          /*fixedBase=*/false, /*canSleep=*/false);
  btMultiBody* mb = body.mb.get();
  for (int i = 0; i < n; ++i) {
    const MultiBodyLinkSpec& l = links[i];
    VB_DEMAND(l.parent < i);
    if (l.joint == JointType::kPrescribedRevolute) {
      VB_DEMAND(l.limit_lower > l.limit_upper);
      mb->setupFixed(i, l.mass_kg, ToBt(l.inertia_kgm2), l.parent, btQuaternion::getIdentity(),
                     ToBt(l.parent_com_to_joint_P), ToBt(l.joint_to_com_L));
    } else if (l.joint == JointType::kRevolute) {
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
  impl_->world.addMultiBody(mb, 0, 0);

  auto anchor = std::make_unique<btSphereShape>(0.01);
  body.base_collider = std::make_unique<btMultiBodyLinkCollider>(mb, -1);
  body.base_collider->setCollisionShape(anchor.get());
  body.base_collider->setWorldTransform(mb->getBaseWorldTransform());
  impl_->world.addCollisionObject(body.base_collider.get(), 0, 0);
  mb->setBaseCollider(body.base_collider.get());
  for (int i = 0; i < n; ++i) {
    auto col = std::make_unique<btMultiBodyLinkCollider>(mb, i);
    col->setCollisionShape(anchor.get());
    impl_->world.addCollisionObject(col.get(), 0, 0);
    mb->getLink(i).m_collider = col.get();
    body.link_colliders.push_back(std::move(col));
    const MultiBodyLinkSpec& l = links[i];
    if (l.limit_lower <= l.limit_upper) {
      auto lim = std::make_unique<btMultiBodyJointLimitConstraint>(mb, i, l.limit_lower,
                                                                   l.limit_upper);
      impl_->world.addMultiBodyConstraint(lim.get());
      body.limits.push_back(std::move(lim));
    }
  }
  impl_->shapes.push_back(std::move(anchor));
  body.world_to_local.resize(n + 1);
  body.local_origin.resize(n + 1);
  mb->forwardKinematics(body.world_to_local, body.local_origin);
  mb->updateCollisionObjectWorldTransforms(body.world_to_local, body.local_origin);
  body.motors.resize(n);
  body.prescribed.assign(static_cast<size_t>(n), 0);
  body.prescribed_axis_P.resize(n);
  body.prescribed_q.assign(static_cast<size_t>(n), 0.0);
  body.prescribed_qdot.assign(static_cast<size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    if (links[i].joint != JointType::kPrescribedRevolute) continue;
    body.prescribed[static_cast<size_t>(i)] = 1;
    body.prescribed_axis_P[i] = ToBt(links[i].axis_P.normalized());
  }
  body.parent.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) body.parent[static_cast<size_t>(i)] = links[i].parent;
  body.pose_stale.assign(static_cast<size_t>(n) + 1, 1);
  body.vel_stale.assign(static_cast<size_t>(n) + 1, 1);
  body.in_subtree.assign(static_cast<size_t>(n), 0);
  body.pose_out_stale.assign(static_cast<size_t>(n), 1);
  body.vel_W_stale.assign(static_cast<size_t>(n) + 1, 1);
  body.link_world_to_local.resize(n + 1);
  body.link_origin_W.resize(n + 1);
  body.link_pose.resize(static_cast<size_t>(n));
  body.omega.resize(n + 1);
  body.vel.resize(n + 1);
  body.omega_W.resize(n + 1);
  body.vel_W.resize(n + 1);
  body.d_omega_W.resize(n + 1);
  body.d_vel_W.resize(n + 1);
  impl_->bodies.push_back(std::move(body));
  return id;
}

namespace {

// Sets a prescribed joint's angle and rate on its Bullet fixed link (kinematic caches included;
// the caller refreshes the world transforms when it needs them).
void SetPrescribed(btMultiBody* mb, int link, const btVector3& axis_P, double q, double qdot,
                   std::vector<double>* qs, std::vector<double>* qdots) {
  btMultibodyLink& l = mb->getLink(link);
  // a revolute joint at angle q rotates parent-frame vectors into its frame by -q (Bullet)
  l.m_zeroRotParentToThis = btQuaternion(axis_P, -q);
  l.updateCacheMultiDof();
  (*qs)[static_cast<size_t>(link)] = q;
  (*qdots)[static_cast<size_t>(link)] = qdot;
}

}  // namespace

void PhysicsWorld::SetPrescribedJoint(MultiBodyId id, int link, double q, double qdot) {
  Impl::Body& b = impl_->Get(id);
  VB_DEMAND(link >= 0 && link < b.mb->getNumLinks() && b.prescribed[static_cast<size_t>(link)]);
  const size_t k = static_cast<size_t>(link);
  if (q == b.prescribed_q[k] && qdot == b.prescribed_qdot[k]) return;
  // only the link and its descendants move: their poses if the angle changed, their velocities
  b.MarkStale(link, /*pose=*/q != b.prescribed_q[k]);
  SetPrescribed(b.mb.get(), link, b.prescribed_axis_P[link], q, qdot, &b.prescribed_q,
                &b.prescribed_qdot);
  const bool had_rate = b.any_prescribed_rate;
  b.any_prescribed_rate = false;
  for (size_t i = 0; i < b.prescribed.size(); ++i)
    if (b.prescribed[i] && b.prescribed_qdot[i] != 0.0) b.any_prescribed_rate = true;
  // the rates' pass runs for all links or none: every link's velocities are recomputed
  if (b.any_prescribed_rate != had_rate) std::fill(b.vel_stale.begin(), b.vel_stale.end(), 1);
}

void PhysicsWorld::SetJointPosition(MultiBodyId id, int link, double q) {
  Impl::Body& b = impl_->Get(id);
  if (b.prescribed[static_cast<size_t>(link)])
    SetPrescribed(b.mb.get(), link, b.prescribed_axis_P[link], q, 0.0, &b.prescribed_q,
                  &b.prescribed_qdot);
  else
    b.mb->setJointPos(link, q);
  b.mb->forwardKinematics(b.world_to_local, b.local_origin);
  b.mb->updateCollisionObjectWorldTransforms(b.world_to_local, b.local_origin);
  b.Invalidate();
}

MultiBodyState PhysicsWorld::GetState(MultiBodyId id) const {
  const Impl::Body& b = impl_->Get(id);
  const btMultiBody* mb = b.mb.get();
  MultiBodyState s;
  s.base_position_W = FromBt(mb->getBasePos());
  s.base_rotation = FromBt(mb->getWorldToBaseRot());   // stored as is (world-to-base)
  s.base_velocity_W = FromBt(mb->getBaseVel());
  s.base_angular_velocity_W = FromBt(mb->getBaseOmega());
  s.q.resize(static_cast<size_t>(mb->getNumLinks()));
  s.qdot.resize(static_cast<size_t>(mb->getNumLinks()));
  for (int i = 0; i < mb->getNumLinks(); ++i) {
    const size_t k = static_cast<size_t>(i);
    s.q[k] = b.prescribed[k] ? b.prescribed_q[k] : mb->getJointPos(i);
    s.qdot[k] = b.prescribed[k] ? b.prescribed_qdot[k] : mb->getJointVel(i);
  }
  return s;
}

void PhysicsWorld::SetState(MultiBodyId id, const MultiBodyState& s) {
  Impl::Body& b = impl_->Get(id);
  btMultiBody* mb = b.mb.get();
  VB_DEMAND(s.q.size() == static_cast<size_t>(mb->getNumLinks()) && s.qdot.size() == s.q.size());
  mb->setBasePos(ToBt(s.base_position_W));
  mb->setWorldToBaseRot(ToBt(s.base_rotation));
  mb->setBaseVel(ToBt(s.base_velocity_W));
  mb->setBaseOmega(ToBt(s.base_angular_velocity_W));
  b.any_prescribed_rate = false;
  for (int i = 0; i < mb->getNumLinks(); ++i) {
    const size_t k = static_cast<size_t>(i);
    if (b.prescribed[k]) {
      SetPrescribed(mb, i, b.prescribed_axis_P[i], s.q[k], s.qdot[k], &b.prescribed_q,
                    &b.prescribed_qdot);
      if (s.qdot[k] != 0.0) b.any_prescribed_rate = true;
    } else {
      mb->setJointPos(i, s.q[k]);
      mb->setJointVel(i, s.qdot[k]);
    }
  }
  mb->clearForcesAndTorques();
  mb->forwardKinematics(b.world_to_local, b.local_origin);
  mb->updateCollisionObjectWorldTransforms(b.world_to_local, b.local_origin);
  b.Invalidate();
}

namespace {

// btMultiBody::localPosToWorld(link, origin): the link's COM in the world frame, by the same
// operations in the same order, reading the links' cached transforms directly (the library's
// version goes through an out-of-line accessor and quatRotate per level).
btVector3 LinkComWorld(const btMultiBody* mb, int i) {
  btVector3 result(0, 0, 0);
  while (i != -1) {
    const btMultibodyLink& link = mb->getLink(i);
    result += link.m_cachedRVector;
    result = quatRotate(link.m_cachedRotParentToThis.inverse(), result);
    i = link.m_parent;
  }
  result = quatRotate(mb->getWorldToBaseRot().inverse(), result);
  result += mb->getBasePos();
  return result;
}

}  // namespace

void PhysicsWorld::ApplyLinkForce(MultiBodyId id, int link, const Vec3& force_W,
                                  const Vec3& point_W) {
  btMultiBody* mb = impl_->Get(id).mb.get();
  VB_DEMAND(link >= 0 && link < mb->getNumLinks());
  const btVector3 com = LinkComWorld(mb, link);
  mb->addLinkForce(link, ToBt(force_W));
  mb->addLinkTorque(link, (ToBt(point_W) - com).cross(ToBt(force_W)));
}

void PhysicsWorld::ApplyLinkTorque(MultiBodyId id, int link, const Vec3& torque_W) {
  impl_->Get(id).mb->addLinkTorque(link, ToBt(torque_W));
}

void PhysicsWorld::ApplyBaseTorque(MultiBodyId id, const Vec3& torque_W) {
  impl_->Get(id).mb->addBaseTorque(ToBt(torque_W));
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
  const Impl::Body& b = impl_->Get(id);
  VB_DEMAND(link >= 0 && link < b.mb->getNumLinks());
  return impl_->LinkPose(b, link);
}

Vec3 PhysicsWorld::LinkPointVelocity(MultiBodyId id, int link, const Vec3& point_W) const {
  const Impl::Body& b = impl_->Get(id);
  VB_DEMAND(link >= 0 && link < b.mb->getNumLinks());
  const int k = link + 1;
  impl_->WorldVelocities(b, k);
  return FromBt(b.vel_W[k] + b.omega_W[k].cross(ToBt(point_W) - b.link_origin_W[k]));
}

Vec3 PhysicsWorld::LinkAngularVelocity(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  VB_DEMAND(link >= 0 && link < b.mb->getNumLinks());
  impl_->WorldVelocities(b, link + 1);
  return FromBt(b.omega_W[link + 1]);
}

double PhysicsWorld::JointPosition(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  if (b.prescribed[static_cast<size_t>(link)]) return b.prescribed_q[static_cast<size_t>(link)];
  return b.mb->getJointPos(link);
}

double PhysicsWorld::JointVelocity(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  if (b.prescribed[static_cast<size_t>(link)]) return b.prescribed_qdot[static_cast<size_t>(link)];
  return b.mb->getJointVel(link);
}

void PhysicsWorld::AddContact(const ContactConstraint& contact) {
  impl_->pending_contacts.push_back(contact);
}

void PhysicsWorld::ReportObstacleTouch(MultiBodyId body, int obstacle_tag) {
  VB_DEMAND(obstacle_tag >= 0);
  impl_->Get(body);
  impl_->pending_touches.push_back({body, obstacle_tag});
}

void PhysicsWorld::Step(double dt) {
  Impl& m = *impl_;
  // Motor impulse bounds were set for the previous dt; keep them consistent with this one.
  if (dt != m.last_dt) {
    const double ratio = dt / m.last_dt;
    for (auto& b : m.bodies)
      for (auto& motor : b.motors)
        if (motor) motor->setMaxAppliedImpulse(motor->getMaxAppliedImpulse() * ratio);
    m.last_dt = dt;
  }

  // vb's contacts become manifold points between the body's collider and the static side, in
  // the order they were added (deterministic), at most 4 per manifold. Nothing is cached from one
  // step to the next: no warm start, no persistent points.
  m.contacts.clear();
  const btCollisionObject* previous = nullptr;
  btPersistentManifold* manifold = nullptr;
  for (const ContactConstraint& c : m.pending_contacts) {
    Impl::Body& b = m.Get(c.body);
    VB_DEMAND(c.link >= -1 && c.link < b.mb->getNumLinks());
    btMultiBodyLinkCollider* col =
        c.link < 0 ? b.base_collider.get() : b.link_colliders[static_cast<size_t>(c.link)].get();
    if (col != previous || manifold == nullptr || manifold->getNumContacts() >= kPointsPerManifold) {
      manifold = m.dispatcher.getNewManifold(col, &m.static_side);
      m.manifolds.push_back(manifold);
      previous = col;
    }
    const btVector3 point_a = ToBt(c.point_W);
    const btVector3 normal = ToBt(c.normal_W);
    const btVector3 point_b = point_a + normal * c.depth_m;
    // the local points are Bullet's narrowphase's (contact caching), which vb does not run; the
    // multibody solver reads the world points
    btManifoldPoint pt(point_a, point_b, normal, -c.depth_m);
    pt.m_positionWorldOnA = point_a;
    pt.m_positionWorldOnB = point_b;
    pt.m_combinedFriction = c.friction;
    pt.m_combinedRestitution = 0.0;
    manifold->addManifoldPoint(pt);
    if (c.obstacle_tag >= 0) m.contacts.push_back({c.body, c.obstacle_tag});
  }
  m.pending_contacts.clear();
  for (const ObstacleContact& t : m.pending_touches) m.contacts.push_back(t);
  m.pending_touches.clear();

  // Exactly one fixed step: maxSubSteps = 0 means "step by dt", no interpolation.
  m.world.stepSimulation(dt, 0, dt);
  for (btPersistentManifold* mf : m.manifolds) m.dispatcher.releaseManifold(mf);
  m.manifolds.clear();
  for (auto& b : m.bodies) {
    b.Invalidate();
    b.mb->clearForcesAndTorques();
  }

  // Obstacle contacts of this step, in a deterministic order.
  SortObstacleContacts(&m.contacts);
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
      if (!b.prescribed[static_cast<size_t>(i)] &&
          (!std::isfinite(mb->getJointPos(i)) || !std::isfinite(mb->getJointVel(i))))
        return false;
  }
  return true;
}

}  // namespace vb::engine
