#include "worlds.h"

#include <filesystem>
#include <string>

#include "io/task_io.h"

namespace vb_collect {

namespace fs = std::filesystem;
using vb::terrain::ElevationLevel;
using vb::terrain::ObstacleDensity;
using vb::terrain::TerrainType;

// World w: seed world_seed + w, labels cycling through all 27 combinations (elevation fastest).
vb::terrain::GeneratorOptions WorldOptions(const Options& o, long w) {
  static constexpr ElevationLevel kElev[] = {ElevationLevel::kLow, ElevationLevel::kMid,
                                             ElevationLevel::kHigh};
  static constexpr TerrainType kTerr[] = {TerrainType::kRigid, TerrainType::kDeformable,
                                          TerrainType::kMixed};
  static constexpr ObstacleDensity kDens[] = {ObstacleDensity::kSparse, ObstacleDensity::kMedium,
                                              ObstacleDensity::kDense};
  vb::terrain::GeneratorOptions g;
  g.seed = o.world_seed + static_cast<uint64_t>(w);
  g.elevation = kElev[w % 3];
  g.terrain = kTerr[(w / 3) % 3];
  g.density = kDens[(w / 9) % 3];
  g.name = "gen_" + std::string(vb::terrain::ElevationLevelName(g.elevation)) + "_" +
           std::string(vb::terrain::TerrainTypeName(g.terrain)) + "_" +
           std::string(vb::terrain::ObstacleDensityName(g.density)) + "_s" +
           std::to_string(g.seed);
  return g;
}

GeneratedWorld WriteWorld(const Options& o, long w) {
  GeneratedWorld world;
  world.options = WorldOptions(o, w);
  const vb::terrain::GeneratorOptions& gen = world.options;
  // The world as vb_gen writes it (task file + 16-bit height image), loaded back as every tool
  // loads tasks, so vb_run on DIR/worlds/NAME.yaml drives the same world.
  const fs::path worlds = fs::path(o.out_dir) / "worlds";
  std::error_code ec;
  fs::create_directories(worlds, ec);
  vb::terrain::TaskSpec generated = vb::terrain::GenerateTask(gen);
  generated.height_image = gen.name + ".png";
  const fs::path task_path = worlds / (gen.name + ".yaml");
  vb::io::WriteHeightImage(generated.heights, generated.min_height_m, generated.max_height_m,
                           (worlds / generated.height_image).string());
  vb::io::SaveTask(generated, task_path.string());
  world.task = vb::io::LoadTask(task_path.string());
  return world;
}

}  // namespace vb_collect
