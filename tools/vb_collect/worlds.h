// The generated worlds of vb_collect's explore and demos modes (docs/datasets.md): world w is
// the generator's seed world_seed + w with labels cycling through all 27 combinations, written
// as vb_gen writes it to DIR/worlds/<name>.yaml + .png and loaded back from there.
#pragma once

#include "options.h"
#include "vb/terrain/generator.h"
#include "vb/terrain/task.h"

namespace vb_collect {

struct GeneratedWorld {
  vb::terrain::GeneratorOptions options;
  vb::terrain::TaskSpec task;   // as loaded back from DIR/worlds/
};

// World w: seed world_seed + w, elevation = w mod 3, terrain = w/3 mod 3, density = w/9 mod 3.
vb::terrain::GeneratorOptions WorldOptions(const Options& o, long w);
// Generates world w, writes it to o.out_dir/worlds/ and loads it back.
GeneratedWorld WriteWorld(const Options& o, long w);

}  // namespace vb_collect
