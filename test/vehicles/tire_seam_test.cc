// The rigid tire at a soil/rigid seam (tire_contact.h, GroundScope::kRigidOnly), closed form:
// a flat world z = 0, mud for x < 0, dirt for x >= 0; a wheel r = 0.5 m in a rut in the mud.
#include <gtest/gtest.h>

#include <cmath>

#include "support/worlds.h"
#include "vb/terrain/terrain.h"
#include "vb/vehicles/tire_contact.h"

namespace vb::vehicles {
namespace {

constexpr double kR = 0.5, kW = 0.3;

terrain::TaskSpec MudWestDirtEast() {
  terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.8, terrain::SurfaceClass::kMud);
  for (int r = 0; r < 16; ++r) {
    for (int c = 8; c < 16; ++c) {
      task.patches.classes[static_cast<size_t>(r * 16 + c)] = terrain::SurfaceClass::kDirt;
      task.patches.friction[static_cast<size_t>(r * 16 + c)] = 0.8;
    }
  }
  return task;
}

TEST(TireSeam, TheWheelsReachDecidesWhichGroundModels) {
  const terrain::Terrain ground(MudWestDirtEast());
  EXPECT_EQ(ground.MixAround(-5.0, 0.0, 0.7), terrain::GroundMix::kDeformable);
  EXPECT_EQ(ground.MixAround(5.0, 0.0, 0.7), terrain::GroundMix::kRigid);
  EXPECT_EQ(ground.MixAround(-0.3, 0.0, 0.7), terrain::GroundMix::kMixed);
  EXPECT_EQ(ground.MixAround(0.6, 0.0, 0.7), terrain::GroundMix::kMixed);
  EXPECT_EQ(ground.SurfaceAt(-0.01, 0.0), terrain::SurfaceClass::kMud);
  EXPECT_EQ(ground.SurfaceAt(0.01, 0.0), terrain::SurfaceClass::kDirt);
}

// Centre 0.3 m before the seam, bottom 0.2 m below the rigid surface (a 0.2 m rut): the rigid
// patch is an edge at (0.3 ahead, 0.3 below the centre): penetration r - 0.3 sqrt(2) along the
// normal from the edge to the centre (45 deg, pushing back and up). Against the whole height
// field (the old contact) it was the flat ground 0.2 m deep under the centre.
TEST(TireSeam, AWheelInARutMeetsTheRigidEdgeAsACorner) {
  const terrain::Terrain ground(MudWestDirtEast());
  const Vec3 c(-0.3, 0.0, kR - 0.2);
  const ContactGeometry edge =
      FindWheelContact(ground, c, Vec3::UnitY(), kR, kW, GroundScope::kRigidOnly);
  ASSERT_TRUE(edge.in_contact);
  EXPECT_NEAR(edge.penetration_m, kR - 0.3 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(edge.normal_W.x(), -std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(edge.normal_W.z(), std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(edge.point_W.x(), c.x() + kR * std::sqrt(0.5), 1e-9);  // on the tread, towards it
  EXPECT_EQ(edge.surface, terrain::SurfaceClass::kDirt);
  EXPECT_NEAR(edge.patch_friction, 0.8, 1e-12);
  const ContactGeometry all = FindWheelContact(ground, c, Vec3::UnitY(), kR, kW);
  EXPECT_NEAR(all.penetration_m, 0.2, 1e-9);
  EXPECT_NEAR(all.normal_W.z(), 1.0, 1e-9);
}

// Centre 0.2 m past the seam, 0.05 m deep: the rigid face under the centre only (the edge behind
// is not the closest point of the rigid surface).
TEST(TireSeam, PastTheEdgeTheRigidFaceCarriesTheWheel) {
  const terrain::Terrain ground(MudWestDirtEast());
  const ContactGeometry g = FindWheelContact(ground, Vec3(0.2, 0.0, kR - 0.05), Vec3::UnitY(), kR,
                                             kW, GroundScope::kRigidOnly);
  ASSERT_TRUE(g.in_contact);
  EXPECT_NEAR(g.penetration_m, 0.05, 1e-9);
  EXPECT_NEAR(g.normal_W.z(), 1.0, 1e-9);
}

// A rut deeper than the radius (centre 0.1 m below the rigid surface, 0.3 m before it): the
// vertical face below the edge, horizontal normal, penetration r - 0.3.
TEST(TireSeam, BelowTheEdgeTheVerticalFacePushesBack) {
  const terrain::Terrain ground(MudWestDirtEast());
  const ContactGeometry g = FindWheelContact(ground, Vec3(-0.3, 0.0, -0.1), Vec3::UnitY(), kR, kW,
                                             GroundScope::kRigidOnly);
  ASSERT_TRUE(g.in_contact);
  EXPECT_NEAR(g.penetration_m, kR - 0.3, 1e-9);
  EXPECT_NEAR(g.normal_W.x(), -1.0, 1e-9);
}

// Over the mud, away from the seam's reach, or moving away from it: the rigid tire has nothing.
TEST(TireSeam, OverSoilOnlyTheRigidTireHasNoContact) {
  const terrain::Terrain ground(MudWestDirtEast());
  EXPECT_FALSE(FindWheelContact(ground, Vec3(-0.6, 0.0, kR - 0.2), Vec3::UnitY(), kR, kW,
                                GroundScope::kRigidOnly)
                   .in_contact);
  // the same wheel facing west (axis -y): the seam is behind it, still 0.6 m away
  EXPECT_FALSE(FindWheelContact(ground, Vec3(-0.6, 0.0, kR - 0.2), -Vec3::UnitY(), kR, kW,
                                GroundScope::kRigidOnly)
                   .in_contact);
}

}  // namespace
}  // namespace vb::vehicles
