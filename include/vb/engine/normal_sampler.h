// Fast standard-normal draws from vb::Rng for samplers that need tens of thousands of them per
// call (the MPPI core: 800 samples x 20 steps x 2 controls every 50 ms). Rng::Normal (Box-Muller,
// a log, a sqrt and a cos per draw) costs ~30 ns; this is Marsaglia and Tsang's ziggurat
// ("The Ziggurat Method for Generating Random Variables", J. Stat. Softw. 5(8), 2000) with 128
// layers: one 64-bit draw, a table look-up and a multiply in ~99 % of the draws.
//
// Deterministic: the stream of normals depends only on the Rng's state (the tables are computed
// once from the published constants with IEEE double arithmetic).
#pragma once

#include "vb/engine/rng.h"

namespace vb {

class NormalSampler {
 public:
  // Standard normal N(0, 1), advancing *rng by one or more 64-bit draws.
  static double Draw(Rng* rng);
};

}  // namespace vb
