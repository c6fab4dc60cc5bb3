// Raster image files: decoding PNG and BMP, encoding PNG. libpng and a small BMP reader instead
// of OpenCV's imgcodecs, whose dependencies (GDAL, GDCM, HEIF, ... ~120 shared libraries) cost
// every vb process ~0.15 s of dynamic linking before main (docs/benchmarks.md, "Process start").
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vb::io {

// A decoded image as stored: no colour conversion, no gamma.
struct RasterImage {
  int rows = 0, cols = 0;
  int channels = 0;    // 1 gray, 2 gray + alpha, 3 RGB, 4 RGBA
  int bit_depth = 0;   // 8 or 16 (PNGs of 1, 2 or 4 bits are widened to 8)
  std::vector<uint16_t> samples;   // rows x cols x channels, top row first
  uint16_t At(int r, int c, int channel = 0) const {
    return samples[(static_cast<size_t>(r) * cols + c) * channels + channel];
  }
};

// Largest image accepted by ReadRasterImage (pixels per side): bigger than any vb or original
// world, small enough that a header claiming more is refused before anything is allocated.
constexpr int kMaxRasterSide = 1 << 14;

// Why a file could not be decoded (the reason only; callers name the file and key).
class ImageDecodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Decodes a PNG (any colour type and depth; palette images come out RGB) or an uncompressed BMP
// (8-bit palette: gray when every entry is gray, else RGB; 24- and 32-bit: RGB). Throws
// ImageDecodeError for anything else, a truncated or corrupt file, or more than kMaxRasterSide
// pixels per side.
RasterImage ReadRasterImage(const std::string& path);
// The same for bytes already in memory.
RasterImage DecodeRasterImage(const std::string& bytes);

// PNG bytes of an 8-bit image of 1 (gray), 3 (colour) or 4 (colour + alpha) channels, rows
// `row_stride` bytes apart; `bgr` when the colour channels are stored blue first (OpenCV's
// order). Written as OpenCV's imencode(".png") writes it (sub filter, zlib level 1, run-length
// strategy), so files made before keep their bytes.
std::string EncodePng8(const uint8_t* pixels, int rows, int cols, int channels, size_t row_stride,
                       bool bgr = false);
// PNG bytes of a 16-bit gray image (host byte order in memory).
std::string EncodePng16Gray(const uint16_t* pixels, int rows, int cols);

}  // namespace vb::io
