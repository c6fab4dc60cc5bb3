// Obstacle touches resolved outside the solver (PhysicsWorld::ReportObstacleTouch: a tracked
// vehicle's road-wheel arm yielding to a rock) are reported with the solver's obstacle contacts
// for one step, sorted and without repeats, and do not act on the body.
#include <gtest/gtest.h>

#include <vector>

#include "vb/engine/physics_world.h"

namespace vb::engine {
namespace {

TEST(ObstacleTouchTest, ReportedWithTheContactsForOneStepAndInert) {
  PhysicsWorld world, reference;
  MultiBodyBaseSpec base;
  base.mass_kg = 100.0;
  base.inertia_kgm2 = Vec3(10.0, 20.0, 25.0);
  base.pose_W.position = Vec3(0.0, 0.0, 5.0);
  const MultiBodyId body = world.AddMultiBody(base, {});
  reference.AddMultiBody(base, {});
  world.ReportObstacleTouch(body, 7);
  world.ReportObstacleTouch(body, 2);
  world.ReportObstacleTouch(body, 7);
  world.AddContact({body, -1, Vec3(0.0, 0.0, 4.5), Vec3::UnitZ(), 0.0, 0.8, 2});
  reference.AddContact({body, -1, Vec3(0.0, 0.0, 4.5), Vec3::UnitZ(), 0.0, 0.8, 2});
  world.Step(0.005);
  reference.Step(0.005);
  const std::vector<ObstacleContact>& touched = world.ObstacleContacts();
  ASSERT_EQ(touched.size(), 2u);
  EXPECT_EQ(touched[0].obstacle_tag, 2);
  EXPECT_EQ(touched[1].obstacle_tag, 7);
  EXPECT_EQ(touched[0].body, body);
  EXPECT_EQ(world.BaseLinearVelocity(body), reference.BaseLinearVelocity(body));
  world.Step(0.005);
  EXPECT_TRUE(world.ObstacleContacts().empty());
}

}  // namespace
}  // namespace vb::engine
