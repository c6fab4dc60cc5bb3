// vb's Soil Contact Model: a sparse height grid over the deformable patches of a task, with the
// Bekker-Wong pressure-sinkage law, Mohr-Coulomb / Janosi-Hanamoto shear and bulldozing of the
// displaced soil to the rut rim (docs/soil.md). Wheels are rigid cylinders intersected
// analytically with the grid (no ray casting).
//
// Grid: node (i, j) at x = i * spacing, y = j * spacing (world frame). Nodes live in 16 x 16
// tiles allocated the first time a wheel or the material flow touches them and indexed by a
// dense table of tile slots over the world, so memory is proportional to the touched area and
// the visiting order is always the same (deterministic). Untouched ground is the task's terrain.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "vb/soil/soil_contact.h"
#include "vb/soil/soil_params.h"
#include "vb/terrain/terrain.h"

namespace vb::soil {

// Counters for benchmarks and tests.
struct ScmStats {
  long steps = 0;
  long wheel_queries = 0;
  long contact_nodes = 0;      // node-contacts summed over all wheel queries
  long eroded_node_visits = 0; // node visits of the erosion passes
  long tiles = 0;              // allocated tiles
  double lost_volume_m3 = 0.0; // displaced soil with no deformable rim to go to (rigid patch,
                               // world edge): the only way bulldozing loses volume
  size_t memory_bytes = 0;     // tiles + tile index
};

class ScmSoil;

// The soil's deformation state (opaque): every allocated tile, the tile table, the step counter
// and the erosion work carried over to the next step. Made by ScmSoil::Snapshot between steps;
// restored by ScmSoil::Restore into a solver of the same terrain and configuration.
class SoilSnapshot {
 public:
  SoilSnapshot();
  ~SoilSnapshot();
  SoilSnapshot(const SoilSnapshot& other);
  SoilSnapshot& operator=(const SoilSnapshot& other);

 private:
  friend class ScmSoil;
  struct Data;
  std::unique_ptr<Data> data_;
};

class ScmSoil : public SoilContact {
 public:
  // Throws InputError if the terrain has a deformable class the config does not describe, or the
  // config is unusable (spacing <= 0). The terrain must outlive the solver.
  ScmSoil(const terrain::Terrain& terrain, const SoilConfig& config);
  ~ScmSoil() override;

  WheelSoilOutput WheelContact(const WheelSoilInput& wheel, double dt) override;
  // The track's belt segments over deformable ground: the same node law as a wheel (Bekker
  // pressure with b = the belt width, Janosi shear on the node's accumulated displacement, which
  // for a track grows with the slip along the contact as in Wong's track theory).
  TrackSoilOutput TrackContact(const TrackSoilInput& track, double dt) override;
  void EndStep(double dt) override;

  // Current soil surface (unloaded) at grid node nearest to (x, y).
  double SurfaceHeight(double x_m, double y_m) const;
  // Sum over touched nodes of (current level - initial terrain level) * cell area (m^3). Material
  // flow with flow factor 1 conserves it; plastic compaction without flow lowers it.
  double VolumeChange_m3() const;
  // Sum over touched nodes of plastic sinkage * cell area (m^3): the compaction so far.
  double CompactedVolume_m3() const;
  const ScmStats& stats() const;
  // For tests: whether, for every node of every allocated tile inside the world, the
  // 4-neighbours the rim and erosion passes take from the node's links and the tiles' neighbour
  // pointers are the nodes the grid look-up finds (none where it finds none).
  bool NeighbourLinksMatchLookUps() const;

  // Between steps (after EndStep): copies of the touched tiles only.
  SoilSnapshot Snapshot() const;
  void Restore(const SoilSnapshot& snapshot);
  const SoilConfig& config() const { return config_; }
  double spacing_m() const { return config_.grid_spacing_m; }

 private:
  friend class SoilSnapshot;
  struct Impl;
  SoilConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vb::soil
