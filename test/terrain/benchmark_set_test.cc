// Tests of the committed benchmark set (tasks/env000.yaml ... env099.yaml, data/worlds/*.png):
// calibration of the elevation statistics against the original worlds per level, the fixed
// assignment of labels to environment ids, byte-identical regeneration of committed files, and
// validity of every committed task (labels, connected paths on the inflated grid).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "io/task_io.h"
#include "vb/terrain/generator.h"
#include "vb/terrain/grid_planner.h"

namespace vb::terrain {
namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

uint64_t Fnv1a64(const std::string& bytes) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : bytes) h = (h ^ ch) * 1099511628211ull;
  return h;
}

std::string TaskPath(int k) {
  char name[64];
  std::snprintf(name, sizeof(name), "/tasks/env%03d.yaml", k);
  return VB_SOURCE_DIR + std::string(name);
}

TEST(BenchmarkSetTest, ElevationStatisticsMatchOriginalPerLevelWithin15Percent) {
  // reference_verti_bench.md §9: per-level means over the 100 original worlds
  struct Reference {
    ElevationLevel level;
    double mean_slope_deg, p95_slope_deg, std_m, roughness_m;
  };
  const Reference refs[3] = {{ElevationLevel::kLow, 5.4, 11.9, 0.17, 0.125},
                             {ElevationLevel::kMid, 10.3, 22.0, 0.32, 0.243},
                             {ElevationLevel::kHigh, 16.5, 34.2, 0.55, 0.410}};
  for (const Reference& ref : refs) {
    double mean_slope = 0.0, p95 = 0.0, std_m = 0.0, rough = 0.0;
    int n = 0;
    for (int k = 0; k < kBenchmarkEnvironments; ++k) {  // the whole set: ~0.6 s
      const GeneratorOptions o = BenchmarkEnvironment(k);
      if (o.elevation != ref.level) continue;
      const ElevationStats s = ComputeElevationStats(GenerateElevation(o), 1.0);
      mean_slope += s.mean_slope_deg;
      p95 += s.p95_slope_deg;
      std_m += s.std_m;
      rough += s.roughness_m;
      ++n;
    }
    ASSERT_GE(n, 33);
    const std::string level(ElevationLevelName(ref.level));
    EXPECT_NEAR(mean_slope / n, ref.mean_slope_deg, 0.15 * ref.mean_slope_deg) << level;
    EXPECT_NEAR(p95 / n, ref.p95_slope_deg, 0.15 * ref.p95_slope_deg) << level;
    EXPECT_NEAR(std_m / n, ref.std_m, 0.15 * ref.std_m) << level;
    EXPECT_NEAR(rough / n, ref.roughness_m, 0.15 * ref.roughness_m) << level;
  }
}

TEST(BenchmarkSetTest, AssignmentIsFixedAndBalanced) {
  std::map<TerrainType, int> terrain;
  std::map<ElevationLevel, int> elevation;
  std::map<ObstacleDensity, int> density;
  for (int k = 0; k < kBenchmarkEnvironments; ++k) {
    const GeneratorOptions o = BenchmarkEnvironment(k);
    EXPECT_EQ(o.seed, static_cast<uint64_t>(k));
    ++terrain[o.terrain];
    ++elevation[o.elevation];
    ++density[o.density];
  }
  EXPECT_EQ(BenchmarkEnvironment(42).name, "env042");
  EXPECT_EQ(BenchmarkEnvironment(7).name, "env007");
  // the original's split by id: 60 rigid, 30 deformable, 10 mixed
  EXPECT_EQ(terrain[TerrainType::kRigid], 60);
  EXPECT_EQ(terrain[TerrainType::kDeformable], 30);
  EXPECT_EQ(terrain[TerrainType::kMixed], 10);
  EXPECT_EQ(BenchmarkEnvironment(59).terrain, TerrainType::kRigid);
  EXPECT_EQ(BenchmarkEnvironment(60).terrain, TerrainType::kDeformable);
  EXPECT_EQ(BenchmarkEnvironment(90).terrain, TerrainType::kMixed);
  for (const auto& [level, count] : elevation) EXPECT_GE(count, 33);
  for (const auto& [d, count] : density) EXPECT_GE(count, 33);
  // README's main command runs env042: it must stay a rigid world
  EXPECT_EQ(BenchmarkEnvironment(42).terrain, TerrainType::kRigid);
}

TEST(BenchmarkSetTest, CommittedFilesRegenerateByteIdentically) {
  const fs::path dir = fs::path(::testing::TempDir()) / "vb_benchmark_regen";
  fs::remove_all(dir);
  fs::create_directories(dir / "tasks");
  fs::create_directories(dir / "data" / "worlds");
  for (int k : {0, 42, 61, 95}) {  // rigid, rigid (README's), deformable, mixed
    const GeneratorOptions o = BenchmarkEnvironment(k);
    TaskSpec task = GenerateTask(o);
    task.height_image = "../data/worlds/" + o.name + ".png";  // as vb_gen writes it
    const fs::path yaml = dir / "tasks" / (o.name + ".yaml");
    const fs::path png = dir / "data" / "worlds" / (o.name + ".png");
    io::WriteHeightImage(task.heights, task.min_height_m, task.max_height_m, png.string());
    io::SaveTask(task, yaml.string());
    const fs::path committed_yaml = TaskPath(k);
    const fs::path committed_png =
        fs::path(VB_SOURCE_DIR) / "data" / "worlds" / (o.name + ".png");
    ASSERT_TRUE(fs::exists(committed_yaml)) << committed_yaml;
    EXPECT_EQ(Fnv1a64(ReadAll(yaml)), Fnv1a64(ReadAll(committed_yaml)))
        << committed_yaml << " differs from a fresh generation (scripts/make_benchmark_tasks.sh)";
    EXPECT_EQ(Fnv1a64(ReadAll(png)), Fnv1a64(ReadAll(committed_png))) << committed_png;
  }
  fs::remove_all(dir);
}

TEST(BenchmarkSetTest, EveryCommittedTaskIsValidAndConnected) {
  for (int k = 0; k < kBenchmarkEnvironments; ++k) {
    const GeneratorOptions o = BenchmarkEnvironment(k);
    const TaskSpec task = io::LoadTask(TaskPath(k));
    SCOPED_TRACE(task.name);
    EXPECT_EQ(task.name, o.name);
    EXPECT_EQ(task.generator_seed, o.seed);
    EXPECT_EQ(task.labels.elevation, o.elevation);
    EXPECT_EQ(task.labels.terrain, o.terrain);
    EXPECT_EQ(task.labels.density, o.density);
    EXPECT_EQ(task.labels.classes, ClassesPresent(task.patches));
    EXPECT_EQ(task.heights.rows, 129);
    EXPECT_EQ(task.size_x_m, 128.0);
    ASSERT_EQ(task.pairs.size(), 10u);
    const OccupancyGrid inflated = Inflate(RasterizeObstacles(task), PlannerInflationCells(task));
    for (const StartGoalPair& pair : task.pairs) {
      ASSERT_GE(pair.path_m.size(), 2u);
      EXPECT_EQ(inflated.CellOf(pair.path_m.front()), inflated.CellOf(pair.start_m));
      EXPECT_EQ(inflated.CellOf(pair.path_m.back()), inflated.CellOf(pair.goal_m));
      for (size_t i = 1; i < pair.path_m.size(); ++i) {
        const Cell c = inflated.CellOf(pair.path_m[i]);
        EXPECT_FALSE(inflated.Occupied(c.row, c.col));
      }
    }
  }
}

}  // namespace
}  // namespace vb::terrain
