// The ten terrain semantics of Verti-Bench: 7 rigid classes with a sampled Coulomb friction per
// patch, 3 deformable soils. The numeric values are the original label ids (labels*.npy).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace vb::terrain {

enum class SurfaceClass : int {
  kClay = 0,
  kConcrete = 1,
  kDirt = 2,
  kGrass = 3,
  kGravel = 4,
  kRock = 5,
  kWood = 6,
  kMud = 7,
  kSand = 8,
  kSnow = 9,
};
constexpr int kNumSurfaceClasses = 10;

inline bool IsDeformable(SurfaceClass c) { return static_cast<int>(c) >= 7; }

// Lower-case name as used in task files ("clay", ..., "snow").
std::string_view SurfaceClassName(SurfaceClass c);
// Inverse of SurfaceClassName; nullopt for an unknown name.
std::optional<SurfaceClass> SurfaceClassFromName(std::string_view name);
// "clay, concrete, ..., snow" for error messages.
std::string SurfaceClassNames();

// Per-class friction distribution of the original generator (reference_verti_bench.md §3):
// friction ~ Normal(mean, std) clipped to [0.1, 1.0]. Deformable classes have none (mean 0).
struct FrictionDistribution {
  double mean = 0.0;
  double std_dev = 0.0;
};
FrictionDistribution ClassFriction(SurfaceClass c);

}  // namespace vb::terrain
