#pragma once
// HeightMap: a width x height grid of uint16 samples, row-major with rows
// along +Z (see terrain_desc.h for the world mapping). 2 bytes per sample and
// nothing else: this is the memory the 2.1 bytes/sample budget is about.
//
// A "block" is the grid cell between samples (i, j), (i+1, j), (i, j+1),
// (i+1, j+1); there are (width-1) x (height-1) blocks, indexed
// block = bj * (width-1) + bi.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/assert.h"
#include "core/result.h"
#include "terrain/terrain_desc.h"

namespace tumble::terrain {

/// Largest supported side, in samples (a few km at 1 m, ARCHITECTURE).
constexpr int kMaxHeightMapSide = 4097;
/// Smallest side: one block needs 2 samples.
constexpr int kMinHeightMapSide = 2;

class HeightMap {
 public:
  HeightMap() = default;
  /// All samples set to `fill`. Sizes are checked by the caller (see checkSize).
  HeightMap(int width, int height, std::uint16_t fill = 0);

  int width() const { return m_width; }
  int height() const { return m_height; }
  int blocksX() const { return m_width - 1; }
  int blocksZ() const { return m_height - 1; }
  std::size_t sampleCount() const { return m_samples.size(); }
  bool empty() const { return m_samples.empty(); }

  std::uint16_t at(int i, int j) const {
    TUMBLE_ASSERT(i >= 0 && j >= 0 && i < m_width && j < m_height, "HeightMap::at out of range");
    return m_samples[std::size_t(j) * std::size_t(m_width) + std::size_t(i)];
  }
  void set(int i, int j, std::uint16_t v) {
    TUMBLE_ASSERT(i >= 0 && j >= 0 && i < m_width && j < m_height, "HeightMap::set out of range");
    m_samples[std::size_t(j) * std::size_t(m_width) + std::size_t(i)] = v;
  }
  /// Clamped read: indices outside the grid read the nearest edge sample.
  std::uint16_t clampedAt(int i, int j) const;

  const std::vector<std::uint16_t>& samples() const { return m_samples; }
  std::vector<std::uint16_t>& samples() { return m_samples; }

  /// Bytes held by the sample container (capacity, not size: what is really allocated).
  std::size_t bytes() const { return m_samples.capacity() * sizeof(std::uint16_t); }

  bool operator==(const HeightMap& o) const = default;

 private:
  int m_width = 0;
  int m_height = 0;
  std::vector<std::uint16_t> m_samples;
};

/// Checks a size against [kMinHeightMapSide, kMaxHeightMapSide]; `what`
/// names the file or command in the message.
Status checkHeightMapSize(int width, int height, const std::string& what);

/// Load a height map PNG: 16-bit grey read exactly; 8-bit grey, palette and
/// RGB(A) accepted (RGB -> Rec.709 luminance, alpha ignored) and widened to 16 bit
/// by v * 257. Never crashes on bad files; the error names the file and what
/// was expected.
Result<HeightMap> loadHeightMapPng(const std::string& path);
Result<HeightMap> decodeHeightMapPng(const std::vector<std::uint8_t>& bytes, const std::string& name);

/// Encode as 16-bit grey PNG (exact) / write it atomically.
Result<std::vector<std::uint8_t>> encodeHeightMapPng(const HeightMap& map);
Status saveHeightMapPng(const HeightMap& map, const std::string& path);

/// Import an 8-bit image made elsewhere (grey or interleaved RGB/RGBA, row-major),
/// widened to 16 bit by v * 257.
HeightMap importImage8(const std::uint8_t* pixels, int width, int height, int channels);

}  // namespace tumble::terrain
