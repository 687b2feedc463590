#include "terrain/material_map.h"

#include <algorithm>

#include "core/assert.h"
#include "core/file_util.h"
#include "terrain/png_io.h"

namespace tumble::terrain {

namespace {
constexpr std::array<const char*, kMaterialLayerCount> kLayerNames = {"texture", "bump", "friction", "sound", "softness"};
}

const char* materialLayerName(MaterialLayer layer) { return kLayerNames[std::size_t(layer)]; }

Result<MaterialLayer> parseMaterialLayer(const std::string& name) {
  for (std::size_t k = 0; k < kLayerNames.size(); ++k)
    if (name == kLayerNames[k]) return MaterialLayer(k);
  return makeError("unknown material layer \"" + name + "\" (valid: texture, bump, friction, sound, softness)");
}

MaterialMaps::MaterialMaps(int blocksX, int blocksZ, const MaterialDefaults& d) : m_blocksX(blocksX), m_blocksZ(blocksZ) {
  TUMBLE_ASSERT(blocksX > 0 && blocksZ > 0, "MaterialMaps: need at least one block");
  const std::size_t n = std::size_t(blocksX) * std::size_t(blocksZ);
  m_layers[index(MaterialLayer::Texture)].assign(n, d.texture);
  m_layers[index(MaterialLayer::Bump)].assign(n, d.bump);
  m_layers[index(MaterialLayer::Friction)].assign(n, d.friction);
  m_layers[index(MaterialLayer::Sound)].assign(n, d.sound);
  m_layers[index(MaterialLayer::Softness)].assign(n, d.softness);
}

std::size_t MaterialMaps::offset(int bi, int bj) const {
  TUMBLE_ASSERT(bi >= 0 && bj >= 0 && bi < m_blocksX && bj < m_blocksZ, "MaterialMaps: block index out of range");
  return std::size_t(bj) * std::size_t(m_blocksX) + std::size_t(bi);
}

Status MaterialMaps::decodeLayerPng(MaterialLayer l, const std::vector<std::uint8_t>& png, const std::string& name) {
  // Refuse big images before decoding them; anything larger than the block grid is wrong anyway.
  auto img = decodePngGrey(png, name, std::max(m_blocksX, m_blocksZ));
  if (!img) {
    return makeError(img.error() + " (a " + materialLayerName(l) + " map must be " + std::to_string(m_blocksX) +
                     " x " + std::to_string(m_blocksZ) + " pixels: one per terrain block)");
  }
  if (img->width != m_blocksX || img->height != m_blocksZ)
    return makeError(name + ": " + materialLayerName(l) + " map is " + std::to_string(img->width) + " x " +
                     std::to_string(img->height) + " pixels; expected " + std::to_string(m_blocksX) + " x " +
                     std::to_string(m_blocksZ) + " (one pixel per block: height map size minus one)");
  auto& dst = m_layers[index(l)];
  for (std::size_t k = 0; k < dst.size(); ++k)
    dst[k] = std::uint8_t(img->bitDepth == 16 ? img->values[k] >> 8 : img->values[k]);
  return Ok{};
}

Status MaterialMaps::loadLayerPng(MaterialLayer l, const std::string& path) {
  auto bytes = readBinaryFile(path);
  if (!bytes) return makeError(bytes.error());
  return decodeLayerPng(l, *bytes, path);
}

Status MaterialMaps::saveLayerPng(MaterialLayer l, const std::string& path) const {
  auto png = encodePngGrey8(m_layers[index(l)].data(), m_blocksX, m_blocksZ);
  if (!png) return makeError(path + ": " + png.error());
  return writeFileAtomic(path, png->data(), png->size());
}

std::size_t MaterialMaps::bytes() const {
  std::size_t total = 0;
  for (const auto& layer : m_layers) total += layer.capacity();
  return total;
}

}  // namespace tumble::terrain
