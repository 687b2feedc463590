#include "render/internal/terrain_textures.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tumble::render {

namespace {

// Two linear colours per material: the noise blends between them.
struct Palette {
  const char* name;
  Eigen::Vector3f dark, light;
};
constexpr int kLayers = kTerrainTextureCount;
const std::array<Palette, kLayers> kPalettes = {{
    {"grass", {0.05f, 0.14f, 0.02f}, {0.20f, 0.36f, 0.07f}},
    {"rock", {0.13f, 0.12f, 0.11f}, {0.42f, 0.40f, 0.37f}},
    {"sand", {0.45f, 0.35f, 0.19f}, {0.66f, 0.56f, 0.36f}},
    {"mud", {0.06f, 0.04f, 0.025f}, {0.19f, 0.13f, 0.08f}},
    {"snow", {0.70f, 0.74f, 0.82f}, {0.95f, 0.96f, 0.98f}},
    {"gravel", {0.16f, 0.15f, 0.14f}, {0.45f, 0.43f, 0.40f}},
    {"dirt", {0.17f, 0.10f, 0.05f}, {0.36f, 0.24f, 0.13f}},
    {"moss", {0.06f, 0.09f, 0.03f}, {0.22f, 0.24f, 0.09f}},
}};

std::uint32_t hash3(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
  std::uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return h;
}

float lattice(int x, int y, int period, std::uint32_t seed) {
  const auto wrap = [period](int v) { return static_cast<std::uint32_t>(((v % period) + period) % period); };
  return static_cast<float>(hash3(wrap(x), wrap(y), seed) >> 8) * (1.0f / 16777216.0f);
}

// Value noise with `period` lattice cells across the unit square, so it
// tiles; u, v in [0, 1).
float valueNoise(float u, float v, int period, std::uint32_t seed) {
  const float x = u * static_cast<float>(period), y = v * static_cast<float>(period);
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(ix), fy = y - static_cast<float>(iy);
  const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const float a = lattice(ix, iy, period, seed), b = lattice(ix + 1, iy, period, seed);
  const float c = lattice(ix, iy + 1, period, seed), d = lattice(ix + 1, iy + 1, period, seed);
  return a + (b - a) * sx + (c - a) * sy + (a - b - c + d) * sx * sy;
}

// Fractal sum, 0..1, starting at `period` cells and doubling per octave.
float fbm(float u, float v, int period, int octaves, std::uint32_t seed, float gain = 0.5f) {
  float sum = 0, amplitude = 1, total = 0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * valueNoise(u, v, period << o, seed + static_cast<std::uint32_t>(o) * 101u);
    total += amplitude;
    amplitude *= gain;
  }
  return sum / total;
}

// 0..1 material pattern of each layer at (u, v).
float pattern(int layer, float u, float v) {
  const auto seed = static_cast<std::uint32_t>(layer + 1) * 7919u;
  switch (layer) {
    case 0: {  // grass: soft patches with fine blade speckle
      const float patches = fbm(u, v, 4, 4, seed);
      const float blades = valueNoise(u, v, 128, seed + 7);
      return std::clamp(0.65f * patches + 0.45f * blades - 0.05f, 0.0f, 1.0f);
    }
    case 1: {  // rock: strong fractal contrast cut by dark cracks
      const float body = fbm(u, v, 4, 6, seed, 0.6f);
      const float ridge = 1.0f - std::abs(2.0f * fbm(u, v, 6, 3, seed + 3) - 1.0f);
      const float crack = std::clamp((ridge - 0.92f) * 12.0f, 0.0f, 1.0f);
      return std::clamp((body - 0.5f) * 2.2f + 0.5f - 0.6f * crack, 0.0f, 1.0f);
    }
    case 2: {  // sand: wind ripples, a little grain
      const float warp = fbm(u, v, 4, 2, seed);
      const float ripple = 0.5f + 0.5f * std::sin(2.0f * static_cast<float>(kPi) * (12.0f * v + 2.0f * warp));
      return 0.35f * ripple + 0.45f * valueNoise(u, v, 128, seed + 5) + 0.2f * warp;
    }
    case 3: {  // mud: smooth blotches, wet darker pools
      const float blotch = fbm(u, v, 4, 4, seed);
      return std::clamp((blotch - 0.5f) * 2.5f + 0.5f, 0.0f, 1.0f);
    }
    case 4:  // snow: nearly flat, faint sparkle
      return 0.6f + 0.25f * fbm(u, v, 8, 3, seed) + 0.15f * valueNoise(u, v, 128, seed + 9);
    case 5: {  // gravel: stones as plateaus of coarse noise, gaps dark
      const float stones = valueNoise(u, v, 48, seed);
      const float shade = valueNoise(u, v, 24, seed + 1);
      return std::clamp(0.3f + 0.7f * shade * std::clamp((stones - 0.3f) * 4.0f, 0.0f, 1.0f), 0.0f, 1.0f);
    }
    case 6:  // dirt: medium clods
      return fbm(u, v, 8, 5, seed, 0.55f);
    default:  // moss: lumpy, fine fibres
      return std::clamp(0.7f * fbm(u, v, 8, 3, seed) + 0.3f * valueNoise(u, v, 96, seed + 2), 0.0f, 1.0f);
  }
}

std::uint8_t encodeSrgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(s * 255.0f));
}

}  // namespace

Eigen::Vector3f terrainTextureMeanColor(int layer) {
  const Palette& p = kPalettes[static_cast<std::size_t>(((layer % kLayers) + kLayers) % kLayers)];
  return 0.5f * (p.dark + p.light);
}

const char* terrainTextureName(int layer) {
  return kPalettes[static_cast<std::size_t>(((layer % kLayers) + kLayers) % kLayers)].name;
}

std::vector<std::uint8_t> generateTerrainTexture(int layer, int size) {
  const Palette& p = kPalettes[static_cast<std::size_t>(((layer % kLayers) + kLayers) % kLayers)];
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(size) * size * 4);
  const float inv = 1.0f / static_cast<float>(size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float t = pattern(layer % kLayers, static_cast<float>(x) * inv, static_cast<float>(y) * inv);
      const Eigen::Vector3f c = p.dark + (p.light - p.dark) * std::clamp(t, 0.0f, 1.0f);
      std::uint8_t* out = &rgba[(static_cast<std::size_t>(y) * size + x) * 4];
      for (int k = 0; k < 3; ++k) out[k] = encodeSrgb(c[k]);
      out[3] = 255;
    }
  }
  return rgba;
}

}  // namespace tumble::render
