#pragma once
// Material maps: one byte per block per layer (a block is the cell between
// four samples, see height_map.h), so a 4096 x 4096-block terrain costs
// 16 MiB per layer. Each layer is an 8-bit grey PNG of blocksX x blocksZ
// pixels that a designer paints in any image editor.
//
// Layers and how a byte is read:
//   Texture  -- index into the renderer's terrain texture array (0..255)
//   Bump     -- strength of the fine shading detail, 0 = flat, 255 = strongest
//   Friction -- Coulomb friction coefficient mu = value * 0.01 (0..2.55);
//               paint mud or puddles darker. Physics reads it via frictionAt().
//   Sound    -- SurfaceSound (grass, gravel, mud, ...), values above the
//               last enum are kept and passed to the sound code unchanged.
//   Softness -- how far a tyre sinks into the ground, s = value * 0.01
//               (unitless; 0 hard: asphalt, rock, ice; 0.4 grass; 0.7 mud;
//               up to 2.55). Vehicles add tyre.soft_ground_drag * s to their
//               rolling resistance coefficient (docs/vehicles.md); separate
//               from friction, so ice is slippery but drags like asphalt.
// Layers are kept separate (structure of arrays) because physics reads only
// friction (and vehicles softness) every step and the renderer reads only
// texture and bump.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::terrain {

enum class MaterialLayer : std::uint8_t { Texture = 0, Bump = 1, Friction = 2, Sound = 3, Softness = 4 };
constexpr int kMaterialLayerCount = 5;

enum class SurfaceSound : std::uint8_t { Grass = 0, Gravel, Mud, Water, Rock, Sand, Snow, Asphalt, Wood, Metal };

/// mu per unit of the Friction layer.
constexpr double kFrictionPerUnit = 0.01;
/// Softness (unitless) per unit of the Softness layer.
constexpr double kSoftnessPerUnit = 0.01;

/// Name used on the command line and in messages: "texture", "bump", "friction", "sound", "softness".
const char* materialLayerName(MaterialLayer layer);
/// Parse a layer name; error lists the valid names.
Result<MaterialLayer> parseMaterialLayer(const std::string& name);

struct MaterialDefaults {
  std::uint8_t texture = 0;
  std::uint8_t bump = 0;
  std::uint8_t friction = 60;  ///< mu = 0.6: dry grass and packed dirt against rubber
  std::uint8_t sound = std::uint8_t(SurfaceSound::Grass);
  std::uint8_t softness = 40;  ///< s = 0.4: grass, as the default friction
};

class MaterialMaps {
 public:
  MaterialMaps() = default;
  MaterialMaps(int blocksX, int blocksZ, const MaterialDefaults& defaults = {});

  int blocksX() const { return m_blocksX; }
  int blocksZ() const { return m_blocksZ; }

  std::uint8_t get(MaterialLayer layer, int bi, int bj) const { return m_layers[index(layer)][offset(bi, bj)]; }
  void set(MaterialLayer layer, int bi, int bj, std::uint8_t v) { m_layers[index(layer)][offset(bi, bj)] = v; }
  double frictionCoefficient(int bi, int bj) const {
    return kFrictionPerUnit * m_layers[index(MaterialLayer::Friction)][offset(bi, bj)];
  }

  double softness(int bi, int bj) const {
    return kSoftnessPerUnit * m_layers[index(MaterialLayer::Softness)][offset(bi, bj)];
  }

  const std::vector<std::uint8_t>& layer(MaterialLayer l) const { return m_layers[index(l)]; }
  std::vector<std::uint8_t>& layer(MaterialLayer l) { return m_layers[index(l)]; }

  /// Replace one layer from an 8-bit PNG (16-bit is reduced to its top byte,
  /// RGB to luminance). The image must be exactly blocksX x blocksZ pixels.
  Status loadLayerPng(MaterialLayer layer, const std::string& path);
  Status decodeLayerPng(MaterialLayer layer, const std::vector<std::uint8_t>& png, const std::string& name);
  /// Write one layer as an 8-bit grey PNG, atomically.
  Status saveLayerPng(MaterialLayer layer, const std::string& path) const;

  std::size_t bytes() const;

 private:
  static std::size_t index(MaterialLayer l) { return std::size_t(l); }
  std::size_t offset(int bi, int bj) const;

  int m_blocksX = 0;
  int m_blocksZ = 0;
  std::array<std::vector<std::uint8_t>, kMaterialLayerCount> m_layers;
};

}  // namespace tumble::terrain
