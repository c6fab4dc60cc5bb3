// The generated worlds of vb_collect's explore and demos modes (docs/datasets.md): world w is
// the generator's seed world_seed + w with labels cycling through all 27 combinations, written
// as vb_gen writes it to DIR/worlds/<name>.yaml + .png and loaded back from there. Both modes
// run episodes_per_world episodes per world (one work item), episode j of a world starting at
// pair j with seed 100 x world seed + j: WorldEpisodes is that shared setup.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mode.h"
#include "options.h"
#include "vb/dataset/episode_record.h"
#include "vb/engine/runner/episode.h"
#include "vb/soil/soil_params.h"
#include "vb/terrain/generator.h"
#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb_collect {

struct GeneratedWorld {
  vb::terrain::GeneratorOptions options;
  vb::terrain::TaskSpec task;   // as loaded back from DIR/worlds/
};

// World w: seed world_seed + w, elevation = w mod 3, terrain = w/3 mod 3, density = w/9 mod 3.
vb::terrain::GeneratorOptions WorldOptions(const Options& o, long w);
// Generates world w, writes it to o.out_dir/worlds/ and loads it back.
GeneratedWorld WriteWorld(const Options& o, long w);

// The work items of --episodes episodes, --episodes-per-world consecutive ones per world.
std::vector<WorkItem> WorldWorkItems(const Options& o);

// One work item's world, its soil and the Episode that runs its episodes with `rules`.
class WorldEpisodes {
 public:
  WorldEpisodes(const Options& o, const WorkItem& item, const vb::vehicles::VehicleParams& vehicle,
                const vb::runner::EpisodeRules& rules);
  vb::runner::Episode& episode() { return *episode_; }
  const GeneratedWorld& world() const { return world_; }
  // Dataset episode e of the item: pair j mod pairs, seed 100 x world seed + j (j = e - first).
  vb::runner::TrialSpec Spec(long e, const std::string& system) const;
  // The attributes every episode of a generated world carries, in this order (docs/datasets.md):
  // the common ones (id, seed, ...), mode, task, task_file, task_fnv1a64, pair, vehicle,
  // vehicle_fnv1a64, soil, system, world_seed, elevation, terrain, density.
  void Describe(long e, const vb::runner::TrialSpec& spec, const std::string& mode,
                vb::dataset::EpisodeRecord* r) const;

 private:
  const Options& o_;
  long first_episode_;
  GeneratedWorld world_;
  std::optional<vb::soil::SoilConfig> soil_;
  std::unique_ptr<vb::runner::Episode> episode_;
};

}  // namespace vb_collect
