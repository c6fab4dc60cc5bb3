// Uncompressed BMP files written by hand, so tests of image input need no image library.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vb::test {

inline void PutLe(std::string& out, uint32_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

struct BmpLayout {
  int bits = 8;                 // 8 (palette), 24 (colour); anything else for refusal tests
  bool top_down = false;        // rows stored top-down (negative height) instead of bottom-up
  bool colour_palette = false;  // palette entry 7 is blue instead of gray
};

// pixels[r * width + c] is the value of pixel (r, c), row 0 on top: the palette index (8-bit,
// a gray palette i -> (i, i, i)), or for 24 bits the colour (blue p, green 255 - p, red p / 2),
// distinct channels so that no decoder can mistake it for gray.
inline std::string MakeBmp(int width, int height, const std::vector<uint8_t>& pixels,
                           BmpLayout layout = {}) {
  const int bytes_per_pixel = layout.bits / 8;
  const int stride = (width * bytes_per_pixel + 3) / 4 * 4;
  const uint32_t palette_size = layout.bits == 8 ? 256 * 4 : 0;
  const uint32_t offset = 14 + 40 + palette_size;
  std::string out = "BM";
  PutLe(out, offset + stride * height, 4);
  PutLe(out, 0, 4);
  PutLe(out, offset, 4);
  PutLe(out, 40, 4);
  PutLe(out, width, 4);
  PutLe(out, static_cast<uint32_t>(layout.top_down ? -height : height), 4);
  PutLe(out, 1, 2);
  PutLe(out, layout.bits, 2);
  PutLe(out, 0, 4);
  PutLe(out, stride * height, 4);
  PutLe(out, 2835, 4);
  PutLe(out, 2835, 4);
  PutLe(out, layout.bits == 8 ? 256 : 0, 4);
  PutLe(out, 0, 4);
  for (uint32_t i = 0; i < palette_size / 4; ++i) {
    PutLe(out, layout.colour_palette && i == 7 ? 0x000000ffu : i * 0x010101u, 4);
  }
  for (int k = 0; k < height; ++k) {
    const int r = layout.top_down ? k : height - 1 - k;
    std::string row;
    for (int c = 0; c < width; ++c) {
      const uint8_t p = pixels[r * width + c];
      row += static_cast<char>(p);
      if (layout.bits != 8) row += static_cast<char>(255 - p), row += static_cast<char>(p / 2);
    }
    row.resize(stride, '\0');
    out += row;
  }
  return out;
}

}  // namespace vb::test
