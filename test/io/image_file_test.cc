// vb's image codec (tools/io/image_file.h): PNG through libpng, uncompressed BMP by hand. The
// committed height images regenerate byte for byte (BenchmarkSetTest), so the encoder writes
// what OpenCV's imencode wrote; here: round trips, the BMP layouts the original worlds and
// tests use, and refusals of what it cannot read.
#include "io/image_file.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "support/bmp.h"

namespace vb::io {
namespace {

using test::BmpLayout;
using test::MakeBmp;

TEST(ImageFileTest, Png16GrayRoundTripsExactly) {
  const int rows = 5, cols = 7;
  std::vector<uint16_t> px(rows * cols);
  for (int i = 0; i < rows * cols; ++i) px[i] = static_cast<uint16_t>(i * 1871 + (i % 3) * 40000);
  const RasterImage back = DecodeRasterImage(EncodePng16Gray(px.data(), rows, cols));
  ASSERT_EQ(back.rows, rows);
  ASSERT_EQ(back.cols, cols);
  EXPECT_EQ(back.channels, 1);
  EXPECT_EQ(back.bit_depth, 16);
  for (int i = 0; i < rows * cols; ++i) EXPECT_EQ(back.samples[i], px[i]) << i;
}

TEST(ImageFileTest, Png8ColourKeepsChannelOrder) {
  // Two pixels stored blue first (OpenCV's order): the PNG holds red, green, blue.
  const std::vector<uint8_t> bgr = {10, 20, 30, 200, 150, 100};
  const RasterImage back = DecodeRasterImage(EncodePng8(bgr.data(), 1, 2, 3, 6, /*bgr=*/true));
  ASSERT_EQ(back.channels, 3);
  EXPECT_EQ(back.bit_depth, 8);
  EXPECT_EQ(back.At(0, 0, 0), 30);
  EXPECT_EQ(back.At(0, 0, 2), 10);
  EXPECT_EQ(back.At(0, 1, 0), 100);
  EXPECT_EQ(back.At(0, 1, 1), 150);
  // Gray, with a row stride wider than the row.
  const std::vector<uint8_t> gray = {1, 2, 99, 3, 4, 99};
  const RasterImage g = DecodeRasterImage(EncodePng8(gray.data(), 2, 2, 1, 3));
  ASSERT_EQ(g.channels, 1);
  EXPECT_EQ(g.At(1, 0), 3);
  EXPECT_EQ(g.At(1, 1), 4);
}

TEST(ImageFileTest, BmpRowsAndPalettes) {
  const std::vector<uint8_t> px = {0, 51, 255, 102, 0, 17};
  for (bool top_down : {false, true}) {
    const RasterImage g = DecodeRasterImage(MakeBmp(3, 2, px, BmpLayout{8, top_down}));
    ASSERT_EQ(g.channels, 1) << top_down;
    ASSERT_EQ(g.rows, 2);
    ASSERT_EQ(g.cols, 3);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(g.samples[i], px[i]) << top_down << " " << i;
  }
  // A palette with one coloured entry is a colour image, as is a 24-bit BMP.
  const RasterImage p =
      DecodeRasterImage(MakeBmp(3, 2, px, BmpLayout{8, false, /*colour_palette=*/true}));
  EXPECT_EQ(p.channels, 3);
  const RasterImage c = DecodeRasterImage(MakeBmp(3, 2, px, BmpLayout{24}));
  ASSERT_EQ(c.channels, 3);
  EXPECT_EQ(c.At(0, 1, 0), 25);         // red
  EXPECT_EQ(c.At(0, 1, 1), 255 - 51);   // green
  EXPECT_EQ(c.At(0, 1, 2), 51);         // blue
}

TEST(ImageFileTest, TheOriginalWorldsDecode) {
  const RasterImage w = ReadRasterImage(VB_SHARED_DIR "/verti_bench_samples/world42.bmp");
  EXPECT_EQ(w.rows, 129);
  EXPECT_EQ(w.cols, 129);
  EXPECT_EQ(w.channels, 1);
  EXPECT_EQ(w.bit_depth, 8);
}

TEST(ImageFileTest, RefusesWhatItCannotRead) {
  const std::string png = [] {
    const std::vector<uint16_t> px(16, 7);
    return EncodePng16Gray(px.data(), 4, 4);
  }();
  const std::string bmp = MakeBmp(3, 2, {0, 1, 2, 3, 4, 5});
  const std::vector<std::string> bad = {
      "",                                   // empty
      "GIF89a....",                         // another format
      png.substr(0, png.size() / 2),        // truncated PNG
      png.substr(0, 40),                    // header only
      bmp.substr(0, 60),                    // truncated BMP header + palette
      bmp.substr(0, bmp.size() - 4),        // truncated BMP pixels
      MakeBmp(3, 2, {0, 1, 2, 3, 4, 5}, BmpLayout{16}),   // 16-bit
  };
  for (size_t k = 0; k < bad.size(); ++k) {
    EXPECT_THROW(DecodeRasterImage(bad[k]), ImageDecodeError) << k;
  }
  std::string corrupt = png;
  corrupt[corrupt.size() - 20] ^= 0x55;   // inside the image data: CRC or zlib fails
  EXPECT_THROW(DecodeRasterImage(corrupt), ImageDecodeError);
  // A header claiming an enormous image is refused before anything is allocated.
  std::string huge = bmp;
  huge[18] = huge[19] = huge[20] = '\xff';
  huge[21] = '\x00';
  EXPECT_THROW(DecodeRasterImage(huge), ImageDecodeError);
  EXPECT_THROW(ReadRasterImage("/nonexistent/world.png"), ImageDecodeError);
}

}  // namespace
}  // namespace vb::io
