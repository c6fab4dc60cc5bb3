// Prescribed joints of the physics adapter (JointType::kPrescribedRevolute: steering knuckles).
// Their read-out must be that of a revolute joint at the same angle and rate, and in the dynamics
// the link must ride rigidly on its parent (no degree of freedom: reactions go to the parent).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "vb/engine/physics_world.h"

namespace vb::engine {
namespace {

// base -> link 0 (knuckle about z, off the base's COM) -> link 1 (wheel about y, COM off its pivot)
std::vector<MultiBodyLinkSpec> Links(JointType knuckle_joint) {
  MultiBodyLinkSpec knuckle;
  knuckle.parent = -1;
  knuckle.joint = knuckle_joint;
  knuckle.axis_P = Vec3::UnitZ();
  knuckle.parent_com_to_joint_P = Vec3(1.0, 0.5, -0.2);
  knuckle.joint_to_com_L = Vec3(0.05, 0.1, 0.0);
  knuckle.mass_kg = 3.0;
  knuckle.inertia_kgm2 = Vec3(0.1, 0.2, 0.3);
  MultiBodyLinkSpec wheel;
  wheel.parent = 0;
  wheel.joint = JointType::kRevolute;
  wheel.axis_P = Vec3::UnitY();
  wheel.parent_com_to_joint_P = Vec3(0.0, 0.2, 0.0);
  wheel.joint_to_com_L = Vec3(0.01, 0.02, 0.03);
  wheel.mass_kg = 20.0;
  wheel.inertia_kgm2 = Vec3(1.0, 2.0, 1.0);
  return {knuckle, wheel};
}

MultiBodyBaseSpec Base() {
  MultiBodyBaseSpec base;
  base.mass_kg = 100.0;
  base.inertia_kgm2 = Vec3(10.0, 20.0, 25.0);
  return base;
}

MultiBodyState MovingState() {
  MultiBodyState s;
  s.base_position_W = Vec3(1.0, 2.0, 3.0);
  s.base_rotation = Quat(Eigen::AngleAxisd(0.3, Vec3(1.0, 2.0, 0.5).normalized()));
  s.base_velocity_W = Vec3(2.0, -1.0, 0.5);
  s.base_angular_velocity_W = Vec3(0.2, -0.4, 0.7);
  s.q = {0.35, 1.2};       // steer angle, wheel angle
  s.qdot = {-2.5, 30.0};   // steer rate, wheel spin
  return s;
}

TEST(PrescribedJointTest, ReadOutEqualsARevoluteJointAtTheSameAngleAndRate) {
  PhysicsWorld revolute_world(0.0), prescribed_world(0.0);
  const MultiBodyId r = revolute_world.AddMultiBody(Base(), Links(JointType::kRevolute));
  const MultiBodyId p =
      prescribed_world.AddMultiBody(Base(), Links(JointType::kPrescribedRevolute));
  const MultiBodyState s = MovingState();
  revolute_world.SetState(r, s);
  prescribed_world.SetState(p, s);
  const Vec3 point_W(1.7, 2.9, 2.4);
  for (int link : {0, 1}) {
    const Pose a = revolute_world.LinkPose(r, link), b = prescribed_world.LinkPose(p, link);
    EXPECT_LT((a.position - b.position).norm(), 1e-12) << link;
    EXPECT_LT(a.rotation.angularDistance(b.rotation), 1e-12) << link;
    EXPECT_LT((revolute_world.LinkAngularVelocity(r, link) -
               prescribed_world.LinkAngularVelocity(p, link)).norm(), 1e-12) << link;
    EXPECT_LT((revolute_world.LinkPointVelocity(r, link, point_W) -
               prescribed_world.LinkPointVelocity(p, link, point_W)).norm(), 1e-12) << link;
    EXPECT_EQ(prescribed_world.JointPosition(p, link), s.q[static_cast<size_t>(link)]);
    EXPECT_EQ(prescribed_world.JointVelocity(p, link), s.qdot[static_cast<size_t>(link)]);
  }
  // the state round trip keeps the prescribed angle and rate
  const MultiBodyState back = prescribed_world.GetState(p);
  EXPECT_EQ(back.q, s.q);
  EXPECT_EQ(back.qdot, s.qdot);

  // SetPrescribedJoint moves the link as SetState does
  PhysicsWorld set_world(0.0);
  const MultiBodyId q = set_world.AddMultiBody(Base(), Links(JointType::kPrescribedRevolute));
  MultiBodyState zero_steer = s;
  zero_steer.q[0] = 0.0;
  zero_steer.qdot[0] = 0.0;
  set_world.SetState(q, zero_steer);
  set_world.SetPrescribedJoint(q, 0, s.q[0], s.qdot[0]);
  EXPECT_LT((set_world.LinkPointVelocity(q, 1, point_W) -
             revolute_world.LinkPointVelocity(r, 1, point_W)).norm(), 1e-12);
  EXPECT_LT(set_world.LinkPose(q, 1).rotation.angularDistance(revolute_world.LinkPose(r, 1).rotation),
            1e-12);
}

// A vehicle's tree: per corner a carrier (prismatic z) on the base; the front two carry a knuckle
// (prescribed about z) and the wheel (revolute y) on it, the rear two the wheel directly.
std::vector<MultiBodyLinkSpec> VehicleLinks() {
  std::vector<MultiBodyLinkSpec> links;
  for (int corner = 0; corner < 4; ++corner) {
    const bool steered = corner < 2;
    MultiBodyLinkSpec carrier;
    carrier.parent = -1;
    carrier.joint = JointType::kPrismatic;
    carrier.axis_P = Vec3::UnitZ();
    carrier.parent_com_to_joint_P = Vec3(steered ? 1.6 : -1.7, corner % 2 ? -0.9 : 0.9, -0.3);
    carrier.mass_kg = 30.0;
    carrier.inertia_kgm2 = Vec3(0.5, 0.6, 0.7);
    const int carrier_index = static_cast<int>(links.size());
    links.push_back(carrier);
    int parent = carrier_index;
    if (steered) {
      MultiBodyLinkSpec knuckle;
      knuckle.parent = parent;
      knuckle.joint = JointType::kPrescribedRevolute;
      knuckle.axis_P = Vec3::UnitZ();
      knuckle.joint_to_com_L = Vec3(0.02, 0.03, -0.01);
      knuckle.mass_kg = 10.0;
      knuckle.inertia_kgm2 = Vec3(0.2, 0.3, 0.4);
      parent = static_cast<int>(links.size());
      links.push_back(knuckle);
    }
    MultiBodyLinkSpec wheel;
    wheel.parent = parent;
    wheel.joint = JointType::kRevolute;
    wheel.axis_P = Vec3::UnitY();
    wheel.parent_com_to_joint_P = Vec3(0.0, corner % 2 ? -0.1 : 0.1, 0.0);
    wheel.mass_kg = 60.0;
    wheel.inertia_kgm2 = Vec3(2.0, 4.0, 2.0);
    links.push_back(wheel);
  }
  return links;
}

bool SameBits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

TEST(PrescribedJointTest, ReadOutAfterAChangeIsBitIdenticalToAFullRecompute) {
  // The adapter recomputes only the changed knuckle's subtree after SetPrescribedJoint; a world
  // that read nothing before the change recomputes every link. Both must read the same bits,
  // through angle changes, rate changes, rates going to and from zero, and steps.
  PhysicsWorld partial(9.81), full(9.81), sparse(9.81);
  const MultiBodyId a = partial.AddMultiBody(Base(), VehicleLinks());
  const MultiBodyId b = full.AddMultiBody(Base(), VehicleLinks());
  const MultiBodyId c = sparse.AddMultiBody(Base(), VehicleLinks());
  const int n = static_cast<int>(VehicleLinks().size());
  const int knuckles[2] = {1, 4};
  const Vec3 point_W(0.7, -0.4, 0.2);
  auto read_all = [&](PhysicsWorld& w, MultiBodyId id, std::vector<Vec3>* out) {
    out->clear();
    for (int link = 0; link < n; ++link) {
      const Pose pose = w.LinkPose(id, link);
      out->push_back(pose.position);
      out->push_back(Vec3(pose.rotation.x(), pose.rotation.y(), pose.rotation.z()));
      out->push_back(Vec3(pose.rotation.w(), 0.0, 0.0));
      out->push_back(w.LinkAngularVelocity(id, link));
      out->push_back(w.LinkPointVelocity(id, link, point_W));
    }
  };
  // angle, rate per knuckle and round (rates to zero and back, angle-only and rate-only changes)
  const double q[6][2] = {{0.1, -0.1}, {0.12, -0.09}, {0.12, -0.09},
                          {0.3, 0.2},  {0.3, 0.25},   {0.0, 0.0}};
  const double qd[6][2] = {{0.0, 0.0}, {4.0, 2.0}, {0.0, 2.0}, {0.0, 0.0}, {1.5, 0.0}, {-1.0, 3.0}};
  std::vector<Vec3> before, got, want;
  for (int round = 0; round < 6; ++round) {
    for (PhysicsWorld* w : {&partial, &full, &sparse}) {
      const MultiBodyId id = w == &partial ? a : w == &full ? b : c;
      for (int link = 0; link < n; ++link) {
        if (link == 1 || link == 4) continue;
        w->AddJointForce(id, link, 50.0 * (link + 1));
      }
      w->ApplyBaseTorque(id, Vec3(30.0, -20.0, 40.0));
      w->Step(0.005);
    }
    read_all(partial, a, &before);  // the partial world reads every link before the change
    sparse.LinkPointVelocity(c, 2, point_W);  // the sparse one a front and a rear wheel
    sparse.LinkPose(c, 7);
    for (int i = 0; i < 2; ++i) {
      partial.SetPrescribedJoint(a, knuckles[i], q[round][i], qd[round][i]);
      full.SetPrescribedJoint(b, knuckles[i], q[round][i], qd[round][i]);
      sparse.SetPrescribedJoint(c, knuckles[i], q[round][i], qd[round][i]);
      if (i == 0) sparse.LinkAngularVelocity(c, 2);  // between the two changes
    }
    read_all(full, b, &want);
    for (PhysicsWorld* w : {&partial, &sparse}) {
      read_all(*w, w == &partial ? a : c, &got);
      ASSERT_EQ(got.size(), want.size());
      for (size_t k = 0; k < got.size(); ++k) {
        EXPECT_TRUE(SameBits(got[k], want[k]))
            << (w == &partial ? "partial" : "sparse") << ", round " << round << ", item " << k
            << ": " << got[k].transpose() << " vs " << want[k].transpose();
      }
    }
  }
}

TEST(PrescribedJointTest, TheLinkRidesRigidlyOnItsParent) {
  // A torque about the joint axis on the prescribed link turns the whole body (the parent takes
  // the reaction), and the angle stays where it was set.
  PhysicsWorld world(0.0);
  MultiBodyLinkSpec knuckle;
  knuckle.parent = -1;
  knuckle.joint = JointType::kPrescribedRevolute;
  knuckle.axis_P = Vec3::UnitZ();
  knuckle.parent_com_to_joint_P = Vec3(1.0, 0.0, 0.0);
  knuckle.mass_kg = 1.0;
  knuckle.inertia_kgm2 = Vec3(0.1, 0.1, 0.1);
  MultiBodyBaseSpec base;
  base.mass_kg = 10.0;
  base.inertia_kgm2 = Vec3::Ones();
  const MultiBodyId id = world.AddMultiBody(base, {knuckle});
  world.SetPrescribedJoint(id, 0, 0.2, 0.0);
  const double torque = 3.0, dt = 0.005;
  world.ApplyLinkTorque(id, 0, Vec3(0.0, 0.0, torque));
  world.Step(dt);
  // rigid assembly: COM at x = 1/11 from the base's; yaw inertia 1 + 0.1 + 10/121 + 100/121
  const double izz = 1.1 + 110.0 / 121.0;
  const double omega = torque * dt / izz;
  EXPECT_NEAR(world.BaseAngularVelocity(id).z(), omega, 1e-9 * omega);
  EXPECT_NEAR(world.LinkAngularVelocity(id, 0).z(), omega, 1e-9 * omega);
  // the base turns about the common COM: v = omega z x (-1/11, 0, 0)
  EXPECT_NEAR(world.BaseLinearVelocity(id).y(), -omega / 11.0, 1e-9 * omega);
  EXPECT_EQ(world.JointPosition(id, 0), 0.2);
  EXPECT_EQ(world.JointVelocity(id, 0), 0.0);
  EXPECT_TRUE(world.StateIsFinite());
}

}  // namespace
}  // namespace vb::engine
