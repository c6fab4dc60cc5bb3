// Tests for the ground-truth maps (src/terrain/gt_maps.cc) on synthetic worlds where the answer
// is known: planes (elevation), split semantics, a single rock (occupancy); crops at several
// yaws to pin the axis conventions (row 0 ahead, column 0 on the vehicle's left).
#include "vb/terrain/gt_maps.h"

#include <cmath>

#include <gtest/gtest.h>

#include "support/worlds.h"

namespace vb::terrain {
namespace {

TEST(GtMapsTest, WorldGridsAreTheTaskGrids) {
  TaskSpec task = test::PlaneTask(64.0, 0.1, -0.05);
  task.rocks.push_back({10.0, 5.0, 1.0});  // 4 cells wide -> [c - 2, c + 2]
  const GroundTruthMaps maps(task, 0);
  const GridMap& e = maps.World(MapLayer::kElevation);
  ASSERT_EQ(e.rows, 65);
  EXPECT_EQ(e.resolution_m, 1.0);
  EXPECT_DOUBLE_EQ(e.At(0, 0), 0.1 * -32 - 0.05 * 32);  // north-west corner (x -32, y +32)
  const GridMap& o = maps.World(MapLayer::kOccupancy);
  // rock at x 10, y 5 -> column 42, row 27; footprint 5 x 5 cells
  int occupied = 0;
  for (double v : o.values) occupied += v != 0.0;
  EXPECT_EQ(occupied, 25);
  EXPECT_EQ(o.At(27, 42), 1.0);
  EXPECT_EQ(o.At(25, 40), 1.0);
  EXPECT_EQ(o.At(24, 42), 0.0);
  const GroundTruthMaps inflated(task, 2);
  occupied = 0;
  for (double v : inflated.World(MapLayer::kOccupancy).values) occupied += v != 0.0;
  EXPECT_EQ(occupied, 81);  // (5 + 2 * 2)^2
}

TEST(GtMapsTest, ResampledWorldGridAtTenCentimetres) {
  const TaskSpec task = test::PlaneTask(64.0, 0.1, -0.05);
  const GroundTruthMaps maps(task);
  const GridMap fine = maps.Resampled(MapLayer::kElevation, 0.1);
  ASSERT_EQ(fine.rows, 641);
  ASSERT_EQ(fine.cols, 641);
  for (int r = 0; r < fine.rows; r += 37) {
    for (int c = 0; c < fine.cols; c += 41) {
      const double x = -32.0 + 0.1 * c;
      const double y = 32.0 - 0.1 * r;
      EXPECT_NEAR(fine.At(r, c), 0.1 * x - 0.05 * y, 1e-9);
    }
  }
  // at the grid's own resolution it is the world grid
  EXPECT_EQ(maps.Resampled(MapLayer::kSemantics, 1.0).values,
            maps.World(MapLayer::kSemantics).values);
}

TEST(GtMapsTest, ElevationCropFollowsYaw) {
  // h = 0.2 x: rises to the east
  const TaskSpec task = test::PlaneTask(64.0, 0.2, 0.0);
  const GroundTruthMaps maps(task);
  const Vec2 pos(3.0, -4.0);
  constexpr int kSize = 9;
  constexpr double kRes = 0.5;
  for (double yaw : {0.0, 0.5 * kPi, kPi, -0.3}) {
    const GridMap crop = maps.Crop(MapLayer::kElevation, pos, yaw, kSize, kRes);
    for (int i = 0; i < kSize; ++i) {
      for (int j = 0; j < kSize; ++j) {
        const double forward = (4 - i) * kRes;
        const double left = (4 - j) * kRes;
        const double x = pos.x() + std::cos(yaw) * forward - std::sin(yaw) * left;
        EXPECT_NEAR(crop.At(i, j), 0.2 * x, 1e-9) << "yaw " << yaw << " cell " << i << "," << j;
      }
    }
  }
  // facing east: the first row (ahead) is highest; facing west it is lowest; facing north the
  // first column (left = west) is lowest
  const GridMap east = maps.Crop(MapLayer::kElevation, pos, 0.0, kSize, kRes);
  EXPECT_GT(east.At(0, 4), east.At(8, 4));
  const GridMap west = maps.Crop(MapLayer::kElevation, pos, kPi, kSize, kRes);
  EXPECT_LT(west.At(0, 4), west.At(8, 4));
  const GridMap north = maps.Crop(MapLayer::kElevation, pos, 0.5 * kPi, kSize, kRes);
  EXPECT_LT(north.At(4, 0), north.At(4, 8));
  EXPECT_NEAR(north.At(4, 0), north.At(4, 8) - 0.2 * 8 * kRes, 1e-9);
}

TEST(GtMapsTest, SemanticCropLeftIsNorthWhenFacingEast) {
  // northern half grass, southern half snow
  TaskSpec task = test::PlaneTask(64.0);
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const bool north = i < 8;
      task.patches.classes[i * 16 + j] = north ? SurfaceClass::kGrass : SurfaceClass::kSnow;
      task.patches.friction[i * 16 + j] = north ? 0.36 : 0.0;
    }
  }
  const GroundTruthMaps maps(task);
  const double grass = static_cast<double>(SurfaceClass::kGrass);
  const double snow = static_cast<double>(SurfaceClass::kSnow);
  const GridMap east = maps.Crop(MapLayer::kSemantics, Vec2(0.0, 0.0), 0.0, 8, 1.0);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(east.At(i, 0), grass);  // left = north
    EXPECT_EQ(east.At(i, 7), snow);   // right = south
  }
  const GridMap north = maps.Crop(MapLayer::kSemantics, Vec2(0.0, 0.0), 0.5 * kPi, 8, 1.0);
  for (int j = 0; j < 8; ++j) {
    EXPECT_EQ(north.At(0, j), grass);  // ahead = north
    EXPECT_EQ(north.At(7, j), snow);
  }
  EXPECT_EQ(maps.World(MapLayer::kSemantics).At(0, 0), grass);
  EXPECT_EQ(maps.World(MapLayer::kSemantics).At(64, 0), snow);
}

TEST(GtMapsTest, OccupancyCropSeesTheRockAheadAndOutsideIsBlocked) {
  TaskSpec task = test::PlaneTask(64.0);
  task.rocks.push_back({10.0, 0.0, 0.7});  // 3 cells wide: x 9..11, y -1..1
  const GroundTruthMaps maps(task, 0);
  constexpr int kSize = 32;  // 1 m cells, centre between cells 15 and 16
  const GridMap ahead = maps.Crop(MapLayer::kOccupancy, Vec2(0.0, 0.0), 0.0, kSize, 1.0);
  // forward = (15.5 - i) -> x 10.5 at row 5, 9.5 at row 6; left = 15.5 - j -> y +-0.5 at 15, 16
  EXPECT_EQ(ahead.At(5, 15), 1.0);
  EXPECT_EQ(ahead.At(6, 16), 1.0);
  EXPECT_EQ(ahead.At(20, 15), 0.0);  // behind: free
  int occupied = 0;
  for (double v : ahead.values) occupied += v != 0.0;
  EXPECT_GE(occupied, 4);
  EXPECT_LE(occupied, 9);
  const GridMap behind = maps.Crop(MapLayer::kOccupancy, Vec2(0.0, 0.0), kPi, kSize, 1.0);
  EXPECT_EQ(behind.At(5, 15), 0.0);
  EXPECT_EQ(behind.At(kSize - 1 - 5, kSize - 1 - 15), 1.0);  // now behind, mirrored
  // near the east edge facing east, the far rows are outside the world: blocked
  const GridMap edge = maps.Crop(MapLayer::kOccupancy, Vec2(30.0, 0.0), 0.0, kSize, 1.0);
  EXPECT_EQ(edge.At(0, 15), 1.0);
  EXPECT_EQ(edge.At(kSize - 1, 15), 0.0);
}

}  // namespace
}  // namespace vb::terrain
