// The benchmark generator (vb_gen, docs/generator.md): a seeded rugged height field calibrated
// per elevation level against the original worlds' statistics, clustered semantics patches,
// obstacles placed with the original's rules, 10 start/goal pairs on the 60 m circle with an A*
// path each; and the fixed assignment of seeds and labels to the 100 benchmark environments.
#pragma once

#include <cstdint>

#include "vb/terrain/task.h"

namespace vb::terrain {

struct GeneratorOptions {
  uint64_t seed = 0;
  std::string name = "env000";
  ElevationLevel elevation = ElevationLevel::kLow;
  TerrainType terrain = TerrainType::kRigid;
  ObstacleDensity density = ObstacleDensity::kSparse;
  int grid_vertices = 129;      // height grid is grid_vertices^2 at 1 m spacing
};

// The 100 environments of the vb benchmark (tasks/env000.yaml ... env099.yaml): env id k in
// [0, 100) has seed k, name "envKKK" and labels fixed by its id (docs/generator.md):
//   terrain: 0-59 rigid, 60-89 deformable, 90-99 mixed (the original's 60/30/10 split by id);
//   elevation: low, mid, high by k % 3; density: sparse, medium, dense by (k / 3) % 3.
constexpr int kBenchmarkEnvironments = 100;
GeneratorOptions BenchmarkEnvironment(int env_id);

// Generates only the height field of GenerateTask(options) (same draws, same result), for
// statistics over many worlds without obstacles and planning.
HeightGrid GenerateElevation(const GeneratorOptions& options);

// Generates a complete task; heights are in task.heights, height_image is "" (the caller writes
// the image and sets the path). Every pair is guaranteed connected on the inflated grid.
TaskSpec GenerateTask(const GeneratorOptions& options);

// Elevation statistics computed as reference_verti_bench.md §9 does for the original worlds
// (central-difference gradients, one-sided at the border; roughness = std of h minus its 9x9 box
// mean with clamped borders), so generated worlds can be compared with its per-level table.
struct ElevationStats {
  double range_m = 0.0;
  double mean_m = 0.0;
  double std_m = 0.0;
  double mean_gradient = 0.0;       // mean |grad h| (m/m)
  double mean_slope_deg = 0.0;
  double p95_slope_deg = 0.0;
  double max_slope_deg = 0.0;
  double fraction_above_20deg = 0.0;
  double fraction_above_30deg = 0.0;
  double roughness_m = 0.0;
};
ElevationStats ComputeElevationStats(const HeightGrid& heights, double spacing_m);

}  // namespace vb::terrain
