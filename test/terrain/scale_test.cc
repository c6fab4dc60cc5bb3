// Tests for scale variants (src/terrain/scale.cc) and for obstacles resting on the ground
// (terrain_physics.h): every length scales by the factor, grids in cells stay the same, and a
// scaled world is the unscaled one shrunk (heights, obstacle boxes, planner inflation, paths).
#include "vb/terrain/scale.h"

#include <cmath>

#include <gtest/gtest.h>

#include "vb/terrain/generator.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/terrain.h"
#include "vb/terrain/terrain_physics.h"

namespace vb::terrain {
namespace {

TEST(ScaleTest, ParsesFractionsAndDecimals) {
  EXPECT_DOUBLE_EQ(*ParseScaleFactor("1/6"), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(*ParseScaleFactor("1/10"), 0.1);
  EXPECT_DOUBLE_EQ(*ParseScaleFactor("0.5"), 0.5);
  EXPECT_DOUBLE_EQ(*ParseScaleFactor("1"), 1.0);
  for (const char* bad : {"", "0", "-1", "1/0", "a", "1/", "/6", "1/6x", "nan", "inf"}) {
    EXPECT_FALSE(ParseScaleFactor(bad).has_value()) << bad;
  }
}

TEST(ScaleTest, EveryLengthScalesAndCellGridsStayTheSame) {
  const TaskSpec task = GenerateTask(BenchmarkEnvironment(42));
  for (double f : {1.0 / 6.0, 0.1}) {
    const TaskSpec s = ScaleTask(task, f);
    EXPECT_DOUBLE_EQ(s.scale, f);
    EXPECT_DOUBLE_EQ(s.size_x_m, 128.0 * f);
    EXPECT_DOUBLE_EQ(s.max_height_m, task.max_height_m * f);
    ASSERT_EQ(s.heights.rows, task.heights.rows);
    for (size_t i = 0; i < task.heights.heights_m.size(); i += 97) {
      EXPECT_DOUBLE_EQ(s.heights.heights_m[i], task.heights.heights_m[i] * f);
    }
    // the terrain surface is the unscaled one shrunk: h_s(f p) = f h(p)
    const Terrain t0(task), t1(s);
    for (const Vec2& p : {Vec2(3.3, -7.1), Vec2(-40.2, 22.7), Vec2(60.0, 0.0)}) {
      EXPECT_NEAR(t1.Height(f * p.x(), f * p.y()), f * t0.Height(p.x(), p.y()), 1e-9);
    }
    EXPECT_DOUBLE_EQ(s.rocks[3].x_m, task.rocks[3].x_m * f);
    EXPECT_EQ(s.rocks[3].scale, task.rocks[3].scale);  // the shape scale is not a length
    EXPECT_TRUE(RockBoxSize(s, s.rocks[3]).isApprox(RockBoxSize(task, task.rocks[3]) * f));
    EXPECT_TRUE(TreeBoxSize(s).isApprox(TreeBoxSize(task) * f));
    EXPECT_TRUE(s.pairs[2].start_m.isApprox(task.pairs[2].start_m * f));
    EXPECT_TRUE(s.pairs[2].path_m.back().isApprox(task.pairs[2].path_m.back() * f));
    // obstacle grid and inflation in cells unchanged (4 m * f at cells of f m); the original's
    // int(4 * sf) would be 0 here
    EXPECT_EQ(PlannerInflationCells(s), 4);
    EXPECT_EQ(RasterizeObstacles(s).occupied, RasterizeObstacles(task).occupied);
    // planning in the scaled world gives the scaled path
    const auto path = PlanPath(Inflate(RasterizeObstacles(s), PlannerInflationCells(s)),
                               s.pairs[0].start_m, s.pairs[0].goal_m);
    ASSERT_TRUE(path.has_value());
    ASSERT_EQ(path->size(), task.pairs[0].path_m.size());
    for (size_t i = 0; i < path->size(); i += 7) {
      EXPECT_TRUE((*path)[i].isApprox(task.pairs[0].path_m[i] * f, 1e-12));
    }
  }
}

TEST(ObstacleRestingTest, RocksTouchTheGroundAndNowhereHangAboveIt) {
  for (int k : {5, 50}) {  // high elevation worlds: the steepest ground under rocks
    const TaskSpec task = GenerateTask(BenchmarkEnvironment(k));
    const Terrain terrain(task);
    for (const RockSpec& rock : task.rocks) {
      const double side = RockBoxSize(task, rock).x();
      const double base = ObstacleBaseHeight(terrain, rock.x_m, rock.y_m, side);
      double lowest = 1e9;
      // an independent dense sampling (every ~6 cm) of the footprint
      for (int i = 0; i <= 80; ++i) {
        for (int j = 0; j <= 80; ++j) {
          const double h = terrain.Height(rock.x_m + side * (i / 80.0 - 0.5),
                                          rock.y_m + side * (j / 80.0 - 0.5));
          lowest = std::min(lowest, h);
          EXPECT_GE(h, base - 0.01);  // bottom face at or below the ground (1 cm)
        }
      }
      EXPECT_NEAR(base, lowest, 0.01);  // and touching it: no gap at the lowest point
    }
  }
}

}  // namespace
}  // namespace vb::terrain
