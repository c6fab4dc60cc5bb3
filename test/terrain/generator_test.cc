// Tests for src/terrain/generator.cc: determinism and validity of generated tasks.
#include "vb/terrain/generator.h"

#include <cmath>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "io/task_io.h"
#include "vb/terrain/grid_planner.h"

namespace vb::terrain {
namespace {

bool SameTask(const TaskSpec& a, const TaskSpec& b) {
  if (a.heights.heights_m != b.heights.heights_m || a.max_height_m != b.max_height_m) return false;
  if (a.patches.classes != b.patches.classes) return false;
  if (a.patches.friction != b.patches.friction) return false;
  if (a.rocks.size() != b.rocks.size() || a.trees.size() != b.trees.size()) return false;
  for (size_t i = 0; i < a.rocks.size(); ++i) {
    if (a.rocks[i].x_m != b.rocks[i].x_m || a.rocks[i].y_m != b.rocks[i].y_m ||
        a.rocks[i].scale != b.rocks[i].scale) {
      return false;
    }
  }
  for (size_t j = 0; j < a.trees.size(); ++j) {
    if (a.trees[j].x_m != b.trees[j].x_m || a.trees[j].y_m != b.trees[j].y_m) return false;
  }
  if (a.pairs.size() != b.pairs.size()) return false;
  for (size_t k = 0; k < a.pairs.size(); ++k) {
    if (a.pairs[k].start_m != b.pairs[k].start_m || a.pairs[k].goal_m != b.pairs[k].goal_m ||
        a.pairs[k].path_m != b.pairs[k].path_m) {
      return false;
    }
  }
  return true;
}

GeneratorOptions Options(uint64_t seed, ElevationLevel e, TerrainType t, ObstacleDensity d) {
  GeneratorOptions o;
  o.seed = seed;
  o.name = "env" + std::to_string(seed);
  o.elevation = e;
  o.terrain = t;
  o.density = d;
  return o;
}

TEST(GeneratorTest, SameSeedSameTaskDifferentSeedDifferentTask) {
  const GeneratorOptions o =
      Options(42, ElevationLevel::kLow, TerrainType::kRigid, ObstacleDensity::kDense);
  const TaskSpec a = GenerateTask(o);
  const TaskSpec b = GenerateTask(o);
  EXPECT_TRUE(SameTask(a, b));
  GeneratorOptions o2 = o;
  o2.seed = 43;
  const TaskSpec c = GenerateTask(o2);
  EXPECT_FALSE(SameTask(a, c));
  EXPECT_NE(a.heights.heights_m, c.heights.heights_m);
  EXPECT_EQ(a.generator_seed, 42u);
  EXPECT_EQ(a.name, "env42");
}

class GeneratorValidityTest
    : public ::testing::TestWithParam<std::tuple<ElevationLevel, TerrainType, ObstacleDensity>> {};

TEST_P(GeneratorValidityTest, TaskIsValid) {
  const auto [elevation, terrain, density] = GetParam();
  for (uint64_t seed : {1u, 2u, 3u}) {
    const TaskSpec task = GenerateTask(Options(seed, elevation, terrain, density));
    // geometry
    ASSERT_EQ(task.heights.rows, 129);
    ASSERT_EQ(task.heights.cols, 129);
    EXPECT_DOUBLE_EQ(task.size_x_m, 128.0);
    EXPECT_DOUBLE_EQ(task.min_height_m, 0.0);
    double lo = 1e9, hi = -1e9;
    for (double h : task.heights.heights_m) {
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
    EXPECT_DOUBLE_EQ(lo, 0.0);
    EXPECT_DOUBLE_EQ(hi, task.max_height_m);
    EXPECT_EQ(task.labels.elevation, elevation);
    EXPECT_EQ(task.labels.terrain, terrain);
    EXPECT_EQ(task.labels.density, density);

    // semantics
    ASSERT_EQ(task.patches.rows, 16);
    ASSERT_EQ(task.patches.classes.size(), 256u);
    std::set<SurfaceClass> classes;
    for (size_t k = 0; k < 256; ++k) {
      const SurfaceClass c = task.patches.classes[k];
      classes.insert(c);
      if (IsDeformable(c)) {
        EXPECT_EQ(task.patches.friction[k], 0.0);
      } else {
        EXPECT_GE(task.patches.friction[k], 0.1);
        EXPECT_LE(task.patches.friction[k], 1.0);
      }
      if (terrain == TerrainType::kRigid) {
        EXPECT_FALSE(IsDeformable(c));
      } else if (terrain == TerrainType::kDeformable) {
        EXPECT_TRUE(IsDeformable(c));
      }
    }
    if (terrain == TerrainType::kRigid) {
      EXPECT_LE(classes.size(), 7u);
    } else if (terrain == TerrainType::kDeformable) {
      EXPECT_LE(classes.size(), 3u);
    }

    // obstacles: counts, bounds, clearances
    const int level = static_cast<int>(density);  // sparse, medium, dense
    ASSERT_EQ(task.rocks.size(), static_cast<size_t>(10 << level));  // 10, 20, 40
    ASSERT_EQ(task.trees.size(), static_cast<size_t>(level + 1));    // 1, 2, 3
    std::vector<Vec2> obstacles;
    for (const RockSpec& r : task.rocks) {
      EXPECT_GE(r.scale, 0.7);
      EXPECT_LT(r.scale, 1.2);
      obstacles.push_back(Vec2(r.x_m, r.y_m));
    }
    for (const TreeSpec& t : task.trees) obstacles.push_back(Vec2(t.x_m, t.y_m));
    for (size_t i = 0; i < obstacles.size(); ++i) {
      EXPECT_LE(obstacles[i].cwiseAbs().maxCoeff(), 58.0);
      for (size_t j = 0; j < i; ++j) EXPECT_GT((obstacles[i] - obstacles[j]).norm(), 10.0);
      for (const StartGoalPair& p : task.pairs) {
        EXPECT_GT((obstacles[i] - p.start_m).norm(), 12.0);
        EXPECT_GT((obstacles[i] - p.goal_m).norm(), 12.0);
      }
    }

    // pairs: on the 60 m circle, opposite, each with a collision-free path
    ASSERT_EQ(task.pairs.size(), 10u);
    const OccupancyGrid inflated = Inflate(RasterizeObstacles(task), 4);
    for (size_t k = 0; k < 10; ++k) {
      const StartGoalPair& p = task.pairs[k];
      const double angle = k * kPi / 5.0;
      EXPECT_NEAR(p.start_m.x(), 60.0 * std::cos(angle), 1e-9);
      EXPECT_NEAR(p.start_m.y(), 60.0 * std::sin(angle), 1e-9);
      EXPECT_TRUE(p.goal_m.isApprox(-p.start_m));
      ASSERT_GE(p.path_m.size(), 2u);
      EXPECT_LE((p.path_m.front() - p.start_m).norm(), 0.75);
      EXPECT_LE((p.path_m.back() - p.goal_m).norm(), 0.75);
      for (size_t i = 1; i < p.path_m.size(); ++i) {
        const Cell c = inflated.CellOf(p.path_m[i]);
        EXPECT_FALSE(inflated.Occupied(c.row, c.col));
        EXPECT_LE((p.path_m[i] - p.path_m[i - 1]).norm(), std::sqrt(2.0) + 1e-9);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Levels, GeneratorValidityTest,
    ::testing::Values(
        std::make_tuple(ElevationLevel::kLow, TerrainType::kRigid, ObstacleDensity::kDense),
        std::make_tuple(ElevationLevel::kMid, TerrainType::kDeformable, ObstacleDensity::kMedium),
        std::make_tuple(ElevationLevel::kHigh, TerrainType::kMixed, ObstacleDensity::kSparse),
        std::make_tuple(ElevationLevel::kHigh, TerrainType::kRigid, ObstacleDensity::kDense)));

TEST(GeneratorTest, MixedWorldsKeepOneRectanglePerSoil) {
  for (uint64_t seed = 0; seed < 20; ++seed) {
    const TaskSpec task = GenerateTask(
        Options(seed, ElevationLevel::kLow, TerrainType::kMixed, ObstacleDensity::kSparse));
    for (int label = 7; label <= 9; ++label) {
      int r0 = 16, r1 = -1, c0 = 16, c1 = -1, count = 0;
      for (int i = 0; i < 16; ++i) {
        for (int j = 0; j < 16; ++j) {
          if (static_cast<int>(task.patches.ClassAt(i, j)) != label) continue;
          ++count;
          r0 = std::min(r0, i);
          r1 = std::max(r1, i);
          c0 = std::min(c0, j);
          c1 = std::max(c1, j);
        }
      }
      if (count > 0) {
        EXPECT_EQ(count, (r1 - r0 + 1) * (c1 - c0 + 1)) << "seed " << seed;
      }
    }
  }
}

TEST(GeneratorTest, SavedTaskLoadsBackIdentically) {
  // heights are quantised to the 16-bit image levels, so the task read back from disk is the
  // generated one bit for bit
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "vb_generator_roundtrip";
  fs::create_directories(dir / "tasks");
  fs::create_directories(dir / "worlds");
  TaskSpec task = GenerateTask(
      Options(7, ElevationLevel::kMid, TerrainType::kMixed, ObstacleDensity::kMedium));
  task.height_image = "../worlds/env7.png";
  io::WriteHeightImage(task.heights, task.min_height_m, task.max_height_m,
                       (dir / "worlds" / "env7.png").string());
  io::SaveTask(task, (dir / "tasks" / "env7.yaml").string());
  const TaskSpec loaded = io::LoadTask((dir / "tasks" / "env7.yaml").string());
  EXPECT_TRUE(SameTask(task, loaded));
  EXPECT_EQ(loaded.labels.terrain, TerrainType::kMixed);
  fs::remove_all(dir);
}

TEST(ElevationStatsTest, PlaneHasConstantSlope) {
  HeightGrid g;
  g.rows = g.cols = 21;
  for (int r = 0; r < 21; ++r) {
    for (int c = 0; c < 21; ++c) g.heights_m.push_back(0.5 * c);  // 0.5 m per 2 m column
  }
  const ElevationStats s = ComputeElevationStats(g, 2.0);
  EXPECT_NEAR(s.mean_gradient, 0.25, 1e-12);
  EXPECT_NEAR(s.mean_slope_deg, std::atan(0.25) * 180.0 / kPi, 1e-9);
  EXPECT_NEAR(s.p95_slope_deg, s.mean_slope_deg, 1e-9);
  EXPECT_NEAR(s.range_m, 10.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.fraction_above_20deg, 0.0);
}

}  // namespace
}  // namespace vb::terrain
