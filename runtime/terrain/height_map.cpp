#include "terrain/height_map.h"

#include <algorithm>

#include "core/file_util.h"
#include "terrain/png_io.h"

namespace tumble::terrain {

HeightMap::HeightMap(int width, int height, std::uint16_t fill)
    : m_width(width), m_height(height), m_samples(std::size_t(width) * std::size_t(height), fill) {
  TUMBLE_ASSERT(width >= 0 && height >= 0, "HeightMap size must not be negative");
}

std::uint16_t HeightMap::clampedAt(int i, int j) const {
  i = std::clamp(i, 0, m_width - 1);
  j = std::clamp(j, 0, m_height - 1);
  return m_samples[std::size_t(j) * std::size_t(m_width) + std::size_t(i)];
}

Status checkHeightMapSize(int width, int height, const std::string& what) {
  if (width < kMinHeightMapSide || height < kMinHeightMapSide || width > kMaxHeightMapSide ||
      height > kMaxHeightMapSide)
    return makeError(what + ": height map is " + std::to_string(width) + " x " + std::to_string(height) +
                     " samples; expected each side between " + std::to_string(kMinHeightMapSide) + " and " +
                     std::to_string(kMaxHeightMapSide));
  return Ok{};
}

Result<HeightMap> decodeHeightMapPng(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  auto img = decodePngGrey(bytes, name, kMaxHeightMapSide);
  if (!img) return makeError(img.error());
  if (auto ok = checkHeightMapSize(img->width, img->height, name); !ok) return makeError(ok.error());
  HeightMap map(img->width, img->height);
  auto& out = map.samples();
  const bool widen = img->bitDepth == 8;
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = widen ? std::uint16_t(img->values[k] * 257u) : img->values[k];
  return map;
}

Result<HeightMap> loadHeightMapPng(const std::string& path) {
  auto bytes = readBinaryFile(path);
  if (!bytes) return makeError(bytes.error());
  return decodeHeightMapPng(*bytes, path);
}

Result<std::vector<std::uint8_t>> encodeHeightMapPng(const HeightMap& map) {
  return encodePngGrey16(map.samples().data(), map.width(), map.height());
}

Status saveHeightMapPng(const HeightMap& map, const std::string& path) {
  auto png = encodeHeightMapPng(map);
  if (!png) return makeError(path + ": " + png.error());
  return writeFileAtomic(path, png->data(), png->size());
}

HeightMap importImage8(const std::uint8_t* pixels, int width, int height, int channels) {
  TUMBLE_ASSERT(channels == 1 || channels == 3 || channels == 4, "importImage8: channels must be 1, 3 or 4");
  HeightMap map(width, height);
  auto& out = map.samples();
  for (std::size_t k = 0; k < out.size(); ++k) {
    const std::uint8_t* p = pixels + k * std::size_t(channels);
    std::uint32_t y = p[0];
    if (channels >= 3) y = (6966u * p[0] + 23436u * p[1] + 2366u * p[2] + 16384u) >> 15;
    out[k] = std::uint16_t(y * 257u);
  }
  return map;
}

}  // namespace tumble::terrain
