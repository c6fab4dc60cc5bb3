#include "vb/terrain/task.h"

#include <array>

#include "vb/engine/file_name.h"

namespace vb::terrain {

std::string_view ElevationLevelName(ElevationLevel v) {
  switch (v) {
    case ElevationLevel::kLow: return "low";
    case ElevationLevel::kMid: return "mid";
    case ElevationLevel::kHigh: return "high";
  }
  return "unknown";
}

std::string_view TerrainTypeName(TerrainType v) {
  switch (v) {
    case TerrainType::kRigid: return "rigid";
    case TerrainType::kDeformable: return "deformable";
    case TerrainType::kMixed: return "mixed";
  }
  return "unknown";
}

std::string_view ObstacleDensityName(ObstacleDensity v) {
  switch (v) {
    case ObstacleDensity::kSparse: return "sparse";
    case ObstacleDensity::kMedium: return "medium";
    case ObstacleDensity::kDense: return "dense";
  }
  return "unknown";
}

std::vector<SurfaceClass> ClassesPresent(const PatchGrid& patches) {
  std::array<bool, kNumSurfaceClasses> seen{};
  for (SurfaceClass c : patches.classes) seen[static_cast<size_t>(c)] = true;
  std::vector<SurfaceClass> out;
  for (int k = 0; k < kNumSurfaceClasses; ++k) {
    if (seen[static_cast<size_t>(k)]) out.push_back(static_cast<SurfaceClass>(k));
  }
  return out;
}

std::string TaskNameProblem(const std::string& name) {
  return FileNameComponentProblem(name, TaskLimits::kMaxNameLength);
}

}  // namespace vb::terrain
