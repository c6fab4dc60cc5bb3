// A first world generator (vb_gen v0): seeded rugged height field, clustered semantics patches,
// obstacles placed with the original's rules, 10 start/goal pairs on the 60 m circle with an A*
// path each. The calibrated benchmark generator is a later issue; this one makes valid example
// worlds for every elevation level and density.
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
