// The original Verti-Bench worlds (reference_verti_bench.md §1, §2, §4.4): their task config as
// plain data, the original's derived grids (obstacle map, label grid) computed exactly by its
// rules, and the conversion to a vb task that reproduces the geometry (docs/importer.md).
// Reading the files is tools/io/original_io.h; this is the pure part.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/terrain/task.h"

namespace vb::terrain {

// An 8-bit grayscale image, row 0 on top (the original world and obstacle images).
struct GrayImage {
  int rows = 0;
  int cols = 0;
  std::vector<uint8_t> pixels;  // row-major
  uint8_t At(int r, int c) const { return pixels[static_cast<size_t>(r) * cols + c]; }
};

struct OriginalObstacle {
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;      // as stored (the original's mis-scaled height; not used by vb)
  double scale = 1.0;    // rocks 0.7-1.2; trees 1
};

// One config{N}_{level}.yaml (§1), already validated by the reader.
struct OriginalConfig {
  ElevationLevel difficulty = ElevationLevel::kLow;
  bool is_flat = false;
  double half_length_m = 64.5;  // half size in x ("length"); the image has 2 * 64.5 = 129 px
  double half_width_m = 64.5;
  double min_height_m = 0.0;    // height of pixel 0
  double max_height_m = 0.0;    // height of pixel 255
  TerrainType terrain_type = TerrainType::kRigid;
  ObstacleDensity density = ObstacleDensity::kSparse;
  bool obstacles_flag = true;
  std::vector<OriginalObstacle> rocks;
  std::vector<OriginalObstacle> trees;
  std::vector<StartGoalPair> pairs;  // start/goal x, y (z, an offset above ground, dropped)
  PatchGrid patches;                 // 16 x 16 from `textures` (friction 0 for deformable)
};

// Pixel of a world point by the original's transform_to_bmp with rounding (§2.2, §4.4):
// col = round(clip(x + L, 0, 2L - 1)), row = round(clip(L - y, 0, 2L - 1)), L the half length,
// round half to even as numpy.
void OriginalPixelOf(const OriginalConfig& config, double x_m, double y_m, int* row, int* col);

// The original's obstacle map obs{N}_{level}.bmp (§4.4): the world image with every obstacle
// footprint set to 255 (rocks: square [c - w/2, c + w/2] with w = int(4.4 * scale); trees: one
// pixel). Matches the shipped maps bit for bit.
GrayImage OriginalObstacleMap(const OriginalConfig& config, const GrayImage& world);

// The original's label grid labels{N}_{level}.npy (§4.3): image-sized, each patch writes its
// 9 x 9 block (rows 8i..8i+8, cols 8j..8j+8) in row-major patch order, later patches overwrite
// the shared row/column; the value is the class id. -1 where no patch wrote.
std::vector<int32_t> OriginalLabelGrid(const PatchGrid& patches, int rows, int cols);

// The vb task reproducing an original world: 128 m x 128 m (the built terrain, 2 L - 1), vertex
// (r, c) = pixel (r, c), h = min + p / 255 * (max - min) (all 0 if is_flat), the 16 x 16 patches
// with their classes and frictions, rocks and trees at their (x, y) with the rock scales (resting
// on the ground rather than at the stored z), the 10 pairs, each with an A* path on vb's
// inflated obstacle grid. height_image is left empty for the caller. Throws InputError (naming
// `config_file`) if a pair is not connected.
TaskSpec TaskFromOriginal(const OriginalConfig& config, const GrayImage& world,
                          const std::string& name, const std::string& config_file);

}  // namespace vb::terrain
