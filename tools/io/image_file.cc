#include "io/image_file.h"

#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "vb/engine/error.h"

namespace vb::io {
namespace {

[[noreturn]] void Unreadable(const std::string& why) { throw ImageDecodeError(why); }

uint32_t Le(const std::string& b, size_t at, int n) {
  uint32_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}

// ---- PNG ----

// libpng reports errors through a callback that must not return; it jumps back to the setjmp in
// the decoder with the message kept here. Only plain data lives between the two points.
struct PngIo {
  const std::string* bytes = nullptr;   // reading
  size_t pos = 0;
  std::string* out = nullptr;           // writing
  char message[200] = {};
};

void PngError(png_structp png, png_const_charp msg) {
  PngIo* io = static_cast<PngIo*>(png_get_error_ptr(png));
  std::snprintf(io->message, sizeof(io->message), "%s", msg);
  png_longjmp(png, 1);
}

void PngWarning(png_structp, png_const_charp) {}

void PngRead(png_structp png, png_bytep data, size_t length) {
  PngIo* io = static_cast<PngIo*>(png_get_io_ptr(png));
  if (length > io->bytes->size() - io->pos) png_error(png, "the file is truncated");
  std::memcpy(data, io->bytes->data() + io->pos, length);
  io->pos += length;
}

void PngWrite(png_structp png, png_bytep data, size_t length) {
  PngIo* io = static_cast<PngIo*>(png_get_io_ptr(png));
  io->out->append(reinterpret_cast<const char*>(data), length);
}

void PngFlush(png_structp) {}

// The libpng calls, in a function of their own: after an error libpng jumps back to the setjmp
// here, and only objects outside this function (reached through the pointers) carry state.
bool ReadPng(png_structp png, png_infop info, PngIo* io, RasterImage* image,
             std::vector<uint8_t>* raw, std::vector<png_bytep>* row_pointers) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_set_read_fn(png, io, PngRead);
  png_set_user_limits(png, kMaxRasterSide, kMaxRasterSide);
  png_read_info(png, info);
  const int colour = png_get_color_type(png, info);
  const int depth = png_get_bit_depth(png, info);
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (depth == 16) png_set_swap(png);   // PNG stores big-endian samples
  png_read_update_info(png, info);
  image->cols = static_cast<int>(png_get_image_width(png, info));
  image->rows = static_cast<int>(png_get_image_height(png, info));
  image->channels = png_get_channels(png, info);
  image->bit_depth = png_get_bit_depth(png, info);
  const size_t row_bytes = png_get_rowbytes(png, info);
  raw->resize(row_bytes * image->rows);
  row_pointers->resize(image->rows);
  for (int r = 0; r < image->rows; ++r) (*row_pointers)[r] = raw->data() + row_bytes * r;
  png_read_image(png, row_pointers->data());
  png_read_end(png, nullptr);
  return true;
}

RasterImage DecodePng(const std::string& bytes) {
  PngIo io;
  io.bytes = &bytes;
  RasterImage image;
  std::vector<png_bytep> row_pointers;
  std::vector<uint8_t> raw;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, PngError, PngWarning);
  if (png == nullptr) Unreadable("out of memory");
  png_infop info = png_create_info_struct(png);
  const bool ok = info != nullptr && ReadPng(png, info, &io, &image, &raw, &row_pointers);
  png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr);
  if (!ok) Unreadable(io.message[0] != '\0' ? io.message : "not a valid PNG");
  const size_t n = static_cast<size_t>(image.rows) * image.cols * image.channels;
  image.samples.resize(n);
  if (image.bit_depth == 16) {
    for (size_t i = 0; i < n; ++i) {
      uint16_t v;
      std::memcpy(&v, raw.data() + 2 * i, 2);
      image.samples[i] = v;
    }
  } else {
    for (size_t i = 0; i < n; ++i) image.samples[i] = raw[i];
  }
  return image;
}

// ---- BMP (uncompressed, BITMAPINFOHEADER or later) ----

RasterImage DecodeBmp(const std::string& b) {
  if (b.size() < 54) Unreadable("the BMP file is truncated");
  const uint32_t data_offset = Le(b, 10, 4);
  const uint32_t header_size = Le(b, 14, 4);
  if (header_size < 40) Unreadable("BMP core headers (OS/2) are not supported");
  const int32_t width = static_cast<int32_t>(Le(b, 18, 4));
  const int32_t height_signed = static_cast<int32_t>(Le(b, 22, 4));
  const int bits = static_cast<int>(Le(b, 28, 2));
  const uint32_t compression = Le(b, 30, 4);
  uint32_t colours_used = Le(b, 46, 4);
  if (compression != 0) Unreadable("compressed BMPs are not supported");
  if (bits != 8 && bits != 24 && bits != 32) {
    Unreadable("BMPs of " + std::to_string(bits) + " bits per pixel are not supported");
  }
  if (width <= 0 || height_signed == 0 || height_signed == INT32_MIN) {
    Unreadable("the BMP header gives no size");
  }
  const bool top_down = height_signed < 0;
  const int64_t height = top_down ? -static_cast<int64_t>(height_signed) : height_signed;
  if (width > kMaxRasterSide || height > kMaxRasterSide) {
    Unreadable("the BMP is " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels; at most " + std::to_string(kMaxRasterSide) + " per side");
  }
  RasterImage image;
  image.cols = width;
  image.rows = static_cast<int>(height);
  image.bit_depth = 8;
  std::vector<uint8_t> palette_gray;
  std::vector<uint8_t> palette_rgb;
  bool gray = false;
  if (bits == 8) {
    if (colours_used == 0 || colours_used > 256) colours_used = 256;
    const size_t palette_at = 14 + static_cast<size_t>(header_size);
    if (palette_at + 4 * static_cast<size_t>(colours_used) > b.size()) {
      Unreadable("the BMP palette is truncated");
    }
    gray = true;
    palette_rgb.assign(3 * 256, 0);
    palette_gray.assign(256, 0);
    for (uint32_t i = 0; i < colours_used; ++i) {
      const uint8_t blue = static_cast<uint8_t>(b[palette_at + 4 * i]);
      const uint8_t green = static_cast<uint8_t>(b[palette_at + 4 * i + 1]);
      const uint8_t red = static_cast<uint8_t>(b[palette_at + 4 * i + 2]);
      gray = gray && blue == green && green == red;
      palette_gray[i] = red;
      palette_rgb[3 * i] = red;
      palette_rgb[3 * i + 1] = green;
      palette_rgb[3 * i + 2] = blue;
    }
  }
  image.channels = gray ? 1 : 3;
  const size_t bytes_per_pixel = static_cast<size_t>(bits) / 8;
  const size_t stride = (static_cast<size_t>(width) * bytes_per_pixel + 3) / 4 * 4;
  if (data_offset > b.size() || stride * image.rows > b.size() - data_offset) {
    Unreadable("the BMP pixel data is truncated");
  }
  image.samples.resize(static_cast<size_t>(image.rows) * image.cols * image.channels);
  for (int r = 0; r < image.rows; ++r) {
    const size_t stored_row = top_down ? r : image.rows - 1 - r;
    const unsigned char* row =
        reinterpret_cast<const unsigned char*>(b.data()) + data_offset + stride * stored_row;
    uint16_t* out = image.samples.data() + static_cast<size_t>(r) * image.cols * image.channels;
    for (int c = 0; c < image.cols; ++c) {
      if (bits == 8) {
        if (gray) {
          out[c] = palette_gray[row[c]];
        } else {
          for (int k = 0; k < 3; ++k) out[3 * c + k] = palette_rgb[3 * row[c] + k];
        }
      } else {   // stored blue, green, red (and a reserved or alpha byte)
        const unsigned char* p = row + bytes_per_pixel * c;
        out[3 * c] = p[2];
        out[3 * c + 1] = p[1];
        out[3 * c + 2] = p[0];
      }
    }
  }
  return image;
}

struct PngLayout {
  const uint8_t* pixels;
  int rows, cols, channels;
  size_t row_stride;
  int bit_depth;
  bool bgr;
};

// As ReadPng: the libpng calls alone, so that an error's jump back finds no local state.
bool WritePng(png_structp png, png_infop info, PngIo* io, const PngLayout* l) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_set_write_fn(png, io, PngWrite, PngFlush);
  // OpenCV's imencode(".png") defaults, so that files written before keep their bytes.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_level(png, Z_BEST_SPEED);
  png_set_compression_strategy(png, Z_RLE);
  const int colour = l->channels == 1   ? PNG_COLOR_TYPE_GRAY
                     : l->channels == 3 ? PNG_COLOR_TYPE_RGB
                                        : PNG_COLOR_TYPE_RGB_ALPHA;
  png_set_IHDR(png, info, static_cast<png_uint_32>(l->cols), static_cast<png_uint_32>(l->rows),
               l->bit_depth, colour, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (l->bit_depth == 16) png_set_swap(png);
  if (l->bgr) png_set_bgr(png);
  for (int r = 0; r < l->rows; ++r) {
    png_write_row(png, const_cast<png_bytep>(l->pixels + l->row_stride * r));
  }
  png_write_end(png, info);
  return true;
}

std::string EncodePng(const PngLayout& layout) {
  std::string out;
  PngIo io;
  io.out = &out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, PngError, PngWarning);
  if (png == nullptr) throw std::runtime_error("PNG encoder: out of memory");
  png_infop info = png_create_info_struct(png);
  const bool ok = info != nullptr && WritePng(png, info, &io, &layout);
  png_destroy_write_struct(&png, info != nullptr ? &info : nullptr);
  if (!ok) throw std::runtime_error(std::string("PNG encoder: ") + io.message);
  return out;
}

}  // namespace

RasterImage DecodeRasterImage(const std::string& bytes) {
  static const char kPng[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPng, 8) == 0) return DecodePng(bytes);
  if (bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M') return DecodeBmp(bytes);
  Unreadable("not a PNG or BMP file");
}

RasterImage ReadRasterImage(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) Unreadable("the file cannot be opened");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return DecodeRasterImage(bytes);
}

std::string EncodePng8(const uint8_t* pixels, int rows, int cols, int channels, size_t row_stride,
                       bool bgr) {
  VB_DEMAND(channels == 1 || channels == 3 || channels == 4);
  return EncodePng(PngLayout{pixels, rows, cols, channels, row_stride, 8, bgr && channels > 1});
}

std::string EncodePng16Gray(const uint16_t* pixels, int rows, int cols) {
  return EncodePng(PngLayout{reinterpret_cast<const uint8_t*>(pixels), rows, cols, 1,
                             sizeof(uint16_t) * static_cast<size_t>(cols), 16, false});
}

}  // namespace vb::io
