#include "vb/terrain/surface_class.h"

#include <array>

namespace vb::terrain {
namespace {

// Indexed by the class id (the original label value), so lookups are a single array access.
constexpr std::array<std::string_view, kNumSurfaceClasses> kNames = {
    "clay", "concrete", "dirt", "grass", "gravel", "rock", "wood", "mud", "sand", "snow"};

// Reference §3: friction ~ Normal(mean, std) per rigid patch; deformable soils have no Coulomb
// coefficient (their forces come from the soil model).
constexpr std::array<FrictionDistribution, kNumSurfaceClasses> kFriction = {{
    {0.60, 0.05},  // clay
    {0.85, 0.08},  // concrete
    {0.60, 0.10},  // dirt
    {0.36, 0.07},  // grass
    {0.55, 0.10},  // gravel
    {0.65, 0.08},  // rock
    {0.45, 0.06},  // wood
    {0.0, 0.0},    // mud
    {0.0, 0.0},    // sand
    {0.0, 0.0},    // snow
}};

}  // namespace

std::string_view SurfaceClassName(SurfaceClass c) { return kNames[static_cast<int>(c)]; }

std::optional<SurfaceClass> SurfaceClassFromName(std::string_view name) {
  for (int i = 0; i < kNumSurfaceClasses; ++i) {
    if (kNames[i] == name) return static_cast<SurfaceClass>(i);
  }
  return std::nullopt;
}

std::string SurfaceClassNames() {
  std::string out;
  for (int i = 0; i < kNumSurfaceClasses; ++i) {
    if (i > 0) out += ", ";
    out += kNames[i];
  }
  return out;
}

FrictionDistribution ClassFriction(SurfaceClass c) { return kFriction[static_cast<int>(c)]; }

}  // namespace vb::terrain
