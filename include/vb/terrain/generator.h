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

}  // namespace vb::terrain
