// Strict reading of the original Verti-Bench files (reference_verti_bench.md §1): task configs
// config{N}_{level}.yaml, 8-bit world/obstacle images (.bmp) and label grids (.npy, int32), for
// vb_import (docs/importer.md). Errors are InputErrors naming file, line and key.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/terrain/original_world.h"

namespace vb::io {

// An original world: config, its world image (validated against each other) and, if a labels
// path was given, the label grid (checked against the config's patches).
struct OriginalWorldFiles {
  terrain::OriginalConfig config;
  terrain::GrayImage world;
  std::vector<int32_t> labels;  // empty if no labels file was given
};

// Reads and cross-checks the files. Checks: every key of the config schema, classes known,
// patch indices and centres (x = -60 + 8j, y = 60 - 8i), friction of rigid patches in [0.1, 1],
// max_height = 16 * {0.3, 0.6, 1.0} for the difficulty, the image 8-bit single-channel of
// exactly 2 * length x 2 * width pixels (129 x 129), labels of the image's shape and equal to the
// patch classes at every patch's top-left pixel.
OriginalWorldFiles LoadOriginalWorld(const std::string& config_path, const std::string& world_path,
                                     const std::string& labels_path);

// An 8-bit single-channel image; anything else is an InputError naming the path.
terrain::GrayImage ReadGrayImage(const std::string& path);
// Writes an 8-bit grayscale PNG (atomically).
void WriteGrayImage(const terrain::GrayImage& image, const std::string& path);

// A 2-D little-endian int32 .npy array (C order); *rows, *cols receive its shape.
std::vector<int32_t> ReadNpyInt32(const std::string& path, int* rows, int* cols);

}  // namespace vb::io
