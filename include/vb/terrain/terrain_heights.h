// Batched height queries on a Terrain (terrain.h): the sampling planners' terrain features ask
// for 240,000 scattered heights per update, and Terrain::Height's branch on the triangle under
// the point depends on where in its cell each point falls: no pattern for a branch predictor.
#pragma once

#include "vb/terrain/terrain.h"

namespace vb::terrain {

// out[i] = terrain.Height(x_m[i], y_m[i]) bit for bit, for i < n: both triangles' planes
// computed as Height computes them, then a select by bit mask instead of a branch.
void Heights(const Terrain& terrain, const double* x_m, const double* y_m, int n, double* out);

}  // namespace vb::terrain
