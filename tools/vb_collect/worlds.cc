#include "worlds.h"

#include <algorithm>
#include <filesystem>
#include <string>

#include "io/result_io.h"
#include "io/soil_io.h"
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

std::vector<WorkItem> WorldWorkItems(const Options& o) {
  std::vector<WorkItem> items;
  const long k = o.episodes_per_world;
  for (long first = 0; first < o.episodes; first += k) {
    WorkItem item;
    for (long e = first; e < std::min(o.episodes, first + k); ++e) item.episodes.push_back(e);
    items.push_back(item);
  }
  return items;
}

WorldEpisodes::WorldEpisodes(const Options& o, const WorkItem& item,
                             const vb::vehicles::VehicleParams& vehicle,
                             const vb::runner::EpisodeRules& rules)
    : o_(o),
      first_episode_(item.episodes.front()),
      world_(WriteWorld(o, item.episodes.front() / o.episodes_per_world)),
      soil_(vb::io::LoadSoilIfNeeded(world_.task, DataDir() + "/soils/" + o.soil + ".yaml")),
      episode_(std::make_unique<vb::runner::Episode>(world_.task, vehicle, rules,
                                                     soil_ ? &*soil_ : nullptr)) {}

vb::runner::TrialSpec WorldEpisodes::Spec(long e, const std::string& system) const {
  const int j = static_cast<int>(e - first_episode_);
  vb::runner::TrialSpec spec;
  spec.pair_index = j % static_cast<int>(world_.task.pairs.size());
  spec.seed = world_.options.seed * 100 + static_cast<uint64_t>(j);
  spec.system = system;
  spec.vehicle = o_.vehicle;
  return spec;
}

void WorldEpisodes::Describe(long e, const vb::runner::TrialSpec& spec, const std::string& mode,
                             vb::dataset::EpisodeRecord* r) const {
  const vb::terrain::GeneratorOptions& gen = world_.options;
  AddCommonAttributes(o_, e, spec.seed, r);
  r->SetText("mode", mode);
  r->SetText("task", world_.task.name);
  r->SetText("task_file", "worlds/" + gen.name + ".yaml");
  r->SetText("task_fnv1a64", vb::io::TaskFnv1a64(world_.task));
  r->SetInt("pair", spec.pair_index);
  r->SetText("vehicle", o_.vehicle);
  r->SetText("vehicle_fnv1a64",
             vb::io::FileFnv1a64Hex(DataDir() + "/vehicles/" + o_.vehicle + ".yaml"));
  r->SetText("soil", soil_ ? o_.soil : "");
  r->SetText("system", spec.system);
  r->SetInt("world_seed", static_cast<int64_t>(gen.seed));
  r->SetText("elevation", std::string(vb::terrain::ElevationLevelName(gen.elevation)));
  r->SetText("terrain", std::string(vb::terrain::TerrainTypeName(gen.terrain)));
  r->SetText("density", std::string(vb::terrain::ObstacleDensityName(gen.density)));
}

}  // namespace vb_collect
