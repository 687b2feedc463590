#pragma once
// PNG encode/decode through libpng's classic API (the simplified png_image
// API gamma-converts 16-bit data, which would break exact round trips).
// libpng reports errors by longjmp; that is contained inside png_io.cpp and
// every failure comes back as a Result naming the file.
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::terrain {

/// A decoded image reduced to one channel. `bitDepth` is 8 or 16 and tells
/// the range of `values` (0..255 or 0..65535).
struct GreyImage {
  int width = 0;
  int height = 0;
  int bitDepth = 8;
  std::vector<std::uint16_t> values;
};

/// Decode any PNG colour type into grey: grey kept, palette/RGB reduced to
/// Rec.709 luminance (integer weights, deterministic), alpha dropped.
/// Images bigger than `maxSide` on either side are refused before decoding.
Result<GreyImage> decodePngGrey(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                int maxSide);

/// How an image is compressed. The default (zlib level 3, libpng's choice
/// of row filter by trying each) suits the tools; the designer's save of a
/// 4097^2 map picks one filter for every row (no trial) and, for the
/// material layers (long runs of one byte), run-length matching only.
struct PngEncoding {
  int zlibLevel = 3;       ///< 0 (store) .. 9 (smallest)
  int filter = -1;         ///< -1: adaptive; 0 none, 1 sub, 2 up, 3 average, 4 Paeth for every row
  bool runLength = false;  ///< zlib's Z_RLE strategy: matches only repeats of the previous byte
};

/// `values` row-major, width*height entries.
Result<std::vector<std::uint8_t>> encodePngGrey16(const std::uint16_t* values, int width, int height,
                                                  const PngEncoding& encoding = {});
Result<std::vector<std::uint8_t>> encodePngGrey8(const std::uint8_t* values, int width, int height,
                                                 const PngEncoding& encoding = {});
/// `rgb` interleaved, width*height*3 bytes.
Result<std::vector<std::uint8_t>> encodePngRgb8(const std::uint8_t* rgb, int width, int height);

}  // namespace tumble::terrain
