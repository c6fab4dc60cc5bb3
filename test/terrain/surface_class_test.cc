// Tests for src/terrain/surface_class.cc and the label names of src/terrain/task.cc.
#include "vb/terrain/surface_class.h"

#include <gtest/gtest.h>

#include "vb/terrain/task.h"

namespace vb::terrain {
namespace {

TEST(SurfaceClassTest, NamesRoundTripInLabelOrder) {
  const char* names[] = {"clay", "concrete", "dirt", "grass", "gravel",
                         "rock", "wood",     "mud",  "sand",  "snow"};
  for (int i = 0; i < kNumSurfaceClasses; ++i) {
    const auto c = static_cast<SurfaceClass>(i);
    EXPECT_EQ(SurfaceClassName(c), names[i]);
    EXPECT_EQ(SurfaceClassFromName(names[i]), c);
    EXPECT_EQ(IsDeformable(c), i >= 7);
  }
  EXPECT_FALSE(SurfaceClassFromName("lava"));
  EXPECT_FALSE(SurfaceClassFromName("Clay"));
  EXPECT_EQ(SurfaceClassNames(),
            "clay, concrete, dirt, grass, gravel, rock, wood, mud, sand, snow");
}

TEST(SurfaceClassTest, FrictionDistributionsOfTheReference) {
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kClay).mean, 0.60);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kConcrete).mean, 0.85);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kConcrete).std_dev, 0.08);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kDirt).std_dev, 0.10);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kGrass).mean, 0.36);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kGravel).mean, 0.55);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kRock).mean, 0.65);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kWood).std_dev, 0.06);
  EXPECT_DOUBLE_EQ(ClassFriction(SurfaceClass::kSand).mean, 0.0);
}

TEST(TaskLabelsTest, Names) {
  EXPECT_EQ(ElevationLevelName(ElevationLevel::kLow), "low");
  EXPECT_EQ(ElevationLevelName(ElevationLevel::kHigh), "high");
  EXPECT_EQ(TerrainTypeName(TerrainType::kMixed), "mixed");
  EXPECT_EQ(TerrainTypeName(TerrainType::kDeformable), "deformable");
  EXPECT_EQ(ObstacleDensityName(ObstacleDensity::kMedium), "medium");
  EXPECT_EQ(ObstacleDensityName(ObstacleDensity::kSparse), "sparse");
}

}  // namespace
}  // namespace vb::terrain
