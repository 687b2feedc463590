#include "terrain/png_io.h"

#include <png.h>
#include <zlib.h>

#include <cstdio>
#include <cstring>

namespace tumble::terrain {

namespace {

// libpng reports errors by calling onError, which must not return: we copy
// the message and longjmp back to the setjmp in decodeRaw/encodeRaw. Those
// two functions hold no C++ objects with destructors in their own frame, so
// the longjmp never skips a destructor; all C++ state lives in the caller.
struct ErrorText {
  char text[256] = {};
};

void onError(png_structp png, png_const_charp message) {
  auto* err = static_cast<ErrorText*>(png_get_error_ptr(png));
  std::snprintf(err->text, sizeof(err->text), "%s", message ? message : "unknown libpng error");
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

struct ReadState {
  ErrorText error;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::size_t pos = 0;
  int maxSide = 0;
  // Outputs.
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bitDepth = 0;  // after transforms: 8 or 16
  int channels = 0;  // after transforms: 1 or 3
  bool tooLarge = false;
  std::vector<std::uint8_t>* pixels = nullptr;
  std::vector<png_bytep>* rows = nullptr;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t count) {
  auto* st = static_cast<ReadState*>(png_get_io_ptr(png));
  if (count > st->size - st->pos) png_error(png, "unexpected end of file (the file is truncated)");
  std::memcpy(out, st->data + st->pos, count);
  st->pos += count;
}

bool decodeRaw(ReadState* st) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &st->error, onError, onWarning);
  if (!png) {
    std::snprintf(st->error.text, sizeof(st->error.text), "libpng could not start (out of memory)");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    std::snprintf(st->error.text, sizeof(st->error.text), "libpng could not start (out of memory)");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, st, readFromMemory);
  png_read_info(png, info);
  st->width = png_get_image_width(png, info);
  st->height = png_get_image_height(png, info);
  if (st->width > png_uint_32(st->maxSide) || st->height > png_uint_32(st->maxSide)) {
    st->tooLarge = true;
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  const int colorType = png_get_color_type(png, info);
  const int depth = png_get_bit_depth(png, info);
  if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colorType == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (colorType & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  st->bitDepth = png_get_bit_depth(png, info);
  st->channels = png_get_channels(png, info);
  const std::size_t rowBytes = png_get_rowbytes(png, info);
  st->pixels->resize(rowBytes * st->height);
  st->rows->resize(st->height);
  for (png_uint_32 y = 0; y < st->height; ++y) (*st->rows)[y] = st->pixels->data() + rowBytes * y;
  png_read_image(png, st->rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

struct WriteState {
  ErrorText error;
  int width = 0;
  int height = 0;
  int bitDepth = 8;
  int colorType = PNG_COLOR_TYPE_GRAY;
  std::vector<png_bytep>* rows = nullptr;
  std::vector<std::uint8_t>* out = nullptr;
  PngEncoding encoding;
};

void writeToMemory(png_structp png, png_bytep data, png_size_t count) {
  auto* st = static_cast<WriteState*>(png_get_io_ptr(png));
  st->out->insert(st->out->end(), data, data + count);
}

void flushNothing(png_structp) {}

bool encodeRaw(WriteState* st) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &st->error, onError, onWarning);
  if (!png) {
    std::snprintf(st->error.text, sizeof(st->error.text), "libpng could not start (out of memory)");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(st->error.text, sizeof(st->error.text), "libpng could not start (out of memory)");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, st, writeToMemory, flushNothing);
  // Level 3 is ~3x faster than the default 6 on 16-bit terrain and only a few
  // percent bigger; height maps are rewritten often by the tools.
  png_set_compression_level(png, st->encoding.zlibLevel);
  if (st->encoding.filter >= 0) {
    static const int kFilters[] = {PNG_FILTER_NONE, PNG_FILTER_SUB, PNG_FILTER_UP, PNG_FILTER_AVG, PNG_FILTER_PAETH};
    png_set_filter(png, PNG_FILTER_TYPE_BASE, kFilters[st->encoding.filter]);
  }
  if (st->encoding.runLength) png_set_compression_strategy(png, Z_RLE);
  png_set_IHDR(png, info, png_uint_32(st->width), png_uint_32(st->height), st->bitDepth, st->colorType,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, st->rows->data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

Result<std::vector<std::uint8_t>> encode(std::vector<std::uint8_t>& packed, int width, int height,
                                         int bitDepth, int colorType, int bytesPerPixel,
                                         const PngEncoding& encoding = {}) {
  if (width <= 0 || height <= 0) return makeError("cannot encode an empty image as PNG");
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  const std::size_t rowBytes = std::size_t(width) * std::size_t(bytesPerPixel);
  for (int y = 0; y < height; ++y) rows[std::size_t(y)] = packed.data() + rowBytes * std::size_t(y);
  std::vector<std::uint8_t> out;
  out.reserve(packed.size() / 2 + 1024);
  WriteState st;
  st.width = width;
  st.height = height;
  st.bitDepth = bitDepth;
  st.colorType = colorType;
  st.rows = &rows;
  st.out = &out;
  st.encoding = encoding;
  if (!encodeRaw(&st)) return makeError(std::string("PNG encoding failed: ") + st.error.text);
  return out;
}

}  // namespace

Result<GreyImage> decodePngGrey(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                int maxSide) {
  if (bytes.empty()) return makeError(name + ": the file is empty (expected a PNG image)");
  if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0)
    return makeError(name + ": not a PNG file (expected a PNG image, 16-bit or 8-bit grey)");
  std::vector<std::uint8_t> pixels;
  std::vector<png_bytep> rows;
  ReadState st;
  st.data = bytes.data();
  st.size = bytes.size();
  st.maxSide = maxSide;
  st.pixels = &pixels;
  st.rows = &rows;
  if (!decodeRaw(&st)) {
    if (st.tooLarge)
      return makeError(name + ": image is " + std::to_string(st.width) + " x " + std::to_string(st.height) +
                       " pixels; at most " + std::to_string(maxSide) + " x " + std::to_string(maxSide) +
                       " is supported");
    return makeError(name + ": broken PNG (" + st.error.text + ")");
  }
  GreyImage img;
  img.width = int(st.width);
  img.height = int(st.height);
  img.bitDepth = st.bitDepth;
  const std::size_t n = std::size_t(img.width) * std::size_t(img.height);
  img.values.resize(n);
  const int bytesPerValue = st.bitDepth == 16 ? 2 : 1;
  auto value = [&](std::size_t k) -> std::uint32_t {
    if (bytesPerValue == 1) return pixels[k];
    return (std::uint32_t(pixels[2 * k]) << 8) | pixels[2 * k + 1];  // PNG is big-endian
  };
  if (st.channels == 1) {
    for (std::size_t k = 0; k < n; ++k) img.values[k] = std::uint16_t(value(k));
  } else if (st.channels == 3) {
    // Rec.709 luminance with integer weights that sum to 2^15: the same
    // result on every machine, and white stays exactly white.
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t y = (6966u * value(3 * k) + 23436u * value(3 * k + 1) + 2366u * value(3 * k + 2) +
                               16384u) >> 15;
      img.values[k] = std::uint16_t(y);
    }
  } else {
    return makeError(name + ": unsupported PNG layout (" + std::to_string(st.channels) + " channels after decoding)");
  }
  return img;
}

Result<std::vector<std::uint8_t>> encodePngGrey16(const std::uint16_t* values, int width, int height,
                                                  const PngEncoding& encoding) {
  std::vector<std::uint8_t> packed(std::size_t(width) * std::size_t(height) * 2);
  for (std::size_t k = 0; k < packed.size() / 2; ++k) {
    packed[2 * k] = std::uint8_t(values[k] >> 8);
    packed[2 * k + 1] = std::uint8_t(values[k] & 0xff);
  }
  return encode(packed, width, height, 16, PNG_COLOR_TYPE_GRAY, 2, encoding);
}

Result<std::vector<std::uint8_t>> encodePngGrey8(const std::uint8_t* values, int width, int height,
                                                 const PngEncoding& encoding) {
  std::vector<std::uint8_t> packed(values, values + std::size_t(width) * std::size_t(height));
  return encode(packed, width, height, 8, PNG_COLOR_TYPE_GRAY, 1, encoding);
}

Result<std::vector<std::uint8_t>> encodePngRgb8(const std::uint8_t* rgb, int width, int height) {
  std::vector<std::uint8_t> packed(rgb, rgb + std::size_t(width) * std::size_t(height) * 3);
  return encode(packed, width, height, 8, PNG_COLOR_TYPE_RGB, 3);
}

}  // namespace tumble::terrain
