#include "app/terrain_scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "terrain/generators.h"

namespace tumble::app {

// ---- TerrainHeightField --------------------------------------------------------

void TerrainHeightField::visitTriangles(const Vec3& lo, const Vec3& hi, TriangleVisitor visit, void* ctx) const {
  terrain::Aabb box{lo, hi};
  m_terrain.forEachTriangleInBox(box, [&](const terrain::TerrainTriangle& t) {
    physics::HeightFieldTriangle h;
    h.v[0] = t.vertices[0];
    h.v[1] = t.vertices[1];
    h.v[2] = t.vertices[2];
    h.normal = t.normal;
    h.id = 2 * t.block + t.half;
    visit(ctx, h);
  });
}

bool TerrainHeightField::surfaceAt(Real x, Real z, Real* height, Vec3* normal) const {
  if (!m_terrain.contains(x, z)) return false;
  *height = m_terrain.heightAt(x, z);
  *normal = m_terrain.normalAt(x, z);
  return true;
}

Real TerrainHeightField::frictionAt(Real x, Real z) const { return m_terrain.frictionAt(x, z); }
Real TerrainHeightField::softnessAt(Real x, Real z) const { return m_terrain.softnessAt(x, z); }

bool TerrainHeightField::rayCast(const Vec3& origin, const Vec3& dir, Real maxDistance,
                                 physics::HeightFieldHit* hit) const {
  auto h = m_terrain.rayCast(origin, dir, maxDistance);
  if (!h) return false;
  hit->distance_m = h->distance_m;
  hit->point_m = h->point;
  hit->normal = h->normal;
  return true;
}

void TerrainHeightField::bounds(Vec3* lo, Vec3* hi) const {
  const terrain::Aabb b = m_terrain.bounds();
  *lo = b.min;
  *hi = b.max;
}

// ---- TerrainScene ----------------------------------------------------------------

namespace {

using Settings = std::map<std::string, std::string>;

Status parseNumber(const Settings& s, const std::string& key, double lo, double hi, double* out) {
  auto it = s.find(key);
  if (it == s.end()) return Ok{};
  std::istringstream in(it->second);
  double v = 0;
  in >> v;
  if (!in || !in.eof() || !(v >= lo && v <= hi)) {
    std::ostringstream msg;
    msg << "--set " << key << "=" << it->second << ": expected a number in [" << lo << ", " << hi << "]";
    return makeError(msg.str());
  }
  *out = v;
  return Ok{};
}

/// Island: fades the plasma to nothing towards the border (sea), then adds a
/// ridge across the middle and a ditch.
void shapeIsland(terrain::HeightMap& map, std::uint64_t seed) {
  const int w = map.width(), h = map.height();
  const double cx = (w - 1) / 2.0, cz = (h - 1) / 2.0, R = std::min(cx, cz);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double r = std::hypot(i - cx, j - cz) / R;
      const double t = std::clamp((0.95 - r) / 0.45, 0.0, 1.0);
      const double f = t * t * (3 - 2 * t);  // smoothstep: 1 inside r = 0.5, 0 beyond 0.95
      map.set(i, j, std::uint16_t(std::lround(map.at(i, j) * (0.15 + 0.85 * f) * f)));
    }
  terrain::RidgeParams ridge;
  ridge.fromX = 0.3 * w, ridge.fromZ = 0.35 * h, ridge.toX = 0.7 * w, ridge.toZ = 0.6 * h;
  ridge.height = 22000, ridge.halfWidth = w / 18.0, ridge.seed = seed + 1;
  terrain::addRidge(map, ridge);
  terrain::RidgeParams ditch;
  ditch.fromX = 0.35 * w, ditch.fromZ = 0.72 * h, ditch.toX = 0.68 * w, ditch.toZ = 0.52 * h;
  ditch.height = -12000, ditch.halfWidth = w / 40.0, ditch.seed = seed + 2;
  terrain::addRidge(map, ditch);
}

}  // namespace

bool TerrainScene::requested(const Settings& s) {
  return s.count("terrain.heightmap") > 0 || s.count("terrain.generate") > 0;
}

// Surface materials from the shape of the land, per block: rock where it is
// steep, snow high up, sand at the shore of an island, mud in patches on
// flat low ground, grass elsewhere. Each material sets the texture the
// renderer draws (render::TerrainSurface indices), the bump strength, the
// friction physics reads through the drag map, the surface sound, and the
// softness (rolling drag on soft ground) vehicles read.
struct Material {
  std::uint8_t texture, bump, friction, sound, softness;  // friction: mu * 100; softness * 100
};
constexpr Material kGrass{0, 80, 60, std::uint8_t(terrain::SurfaceSound::Grass), 40};
constexpr Material kRock{1, 220, 80, std::uint8_t(terrain::SurfaceSound::Rock), 0};
constexpr Material kSand{2, 40, 45, std::uint8_t(terrain::SurfaceSound::Sand), 55};
constexpr Material kMud{3, 60, 30, std::uint8_t(terrain::SurfaceSound::Mud), 70};
constexpr Material kSnow{4, 30, 20, std::uint8_t(terrain::SurfaceSound::Snow), 50};

void paintMaterials(terrain::Terrain& t, bool island) {
  const terrain::HeightMap& h = t.heights();
  const terrain::TerrainDesc& d = t.desc();
  terrain::MaterialMaps& m = t.createMaterials();
  auto& texture = m.layer(terrain::MaterialLayer::Texture);
  auto& bump = m.layer(terrain::MaterialLayer::Bump);
  auto& friction = m.layer(terrain::MaterialLayer::Friction);
  auto& sound = m.layer(terrain::MaterialLayer::Sound);
  auto& softness = m.layer(terrain::MaterialLayer::Softness);
  std::uint16_t lo = 65535, hi = 0;
  for (std::uint16_t v : h.samples()) lo = std::min(lo, v), hi = std::max(hi, v);
  const double range = std::max(1.0, double(hi) - double(lo));
  for (int bz = 0; bz < m.blocksZ(); ++bz)
    for (int bx = 0; bx < m.blocksX(); ++bx) {
      double h00 = h.at(bx, bz), h10 = h.at(bx + 1, bz), h01 = h.at(bx, bz + 1), h11 = h.at(bx + 1, bz + 1);
      double dx = (h10 + h11 - h00 - h01) / 2 * d.heightScale_m / d.spacing_m;  // rise per metre along x
      double dz = (h01 + h11 - h00 - h10) / 2 * d.heightScale_m / d.spacing_m;
      double slope = std::sqrt(dx * dx + dz * dz);
      double rel = ((h00 + h10 + h01 + h11) / 4 - lo) / range;  // 0 lowest .. 1 highest
      double y = d.baseHeight_m + (h00 + h10 + h01 + h11) / 4 * d.heightScale_m;
      // Patches 32 blocks across, chosen by a hash of the patch index.
      std::uint32_t patch = std::uint32_t(bx / 32) * 73856093u ^ std::uint32_t(bz / 32) * 19349663u;
      Material mat = kGrass;
      if (slope > 0.7) mat = kRock;                                 // steeper than ~35 degrees
      else if (rel > 0.85) mat = kSnow;
      else if (island && y < 0.02 * range * d.heightScale_m) mat = kSand;  // just above the sea
      else if (slope < 0.08 && rel < 0.3 && patch % 5 == 0) mat = kMud;
      std::size_t i = std::size_t(bz) * m.blocksX() + bx;
      texture[i] = mat.texture;
      bump[i] = mat.bump;
      friction[i] = mat.friction;
      sound[i] = mat.sound;
      softness[i] = mat.softness;
    }
}

Status TerrainScene::checkSettings(const Settings& s) {
  static const char* kKnown[] = {"terrain.heightmap", "terrain.generate", "terrain.size",   "terrain.roughness",
                                 "terrain.spacing",   "terrain.height",   "terrain.style"};
  for (const auto& [key, value] : s) {
    if (key.rfind("terrain.", 0) != 0) continue;
    if (std::find(std::begin(kKnown), std::end(kKnown), key) == std::end(kKnown))
      return makeError("--set " + key +
                       ": unknown terrain setting (known: terrain.heightmap, terrain.generate, terrain.size, "
                       "terrain.roughness, terrain.spacing, terrain.height, terrain.style)");
  }
  double unused = 0;
  if (auto st = parseNumber(s, "terrain.size", terrain::kMinHeightMapSide, terrain::kMaxHeightMapSide, &unused); !st)
    return st;
  if (auto st = parseNumber(s, "terrain.roughness", 0.01, 1, &unused); !st) return st;
  if (auto st = parseNumber(s, "terrain.spacing", 0.01, 1000, &unused); !st) return st;
  if (auto st = parseNumber(s, "terrain.height", 0.01, 10000, &unused); !st) return st;
  if (auto st = parseNumber(s, "terrain.generate", 0, 9.0e15, &unused); !st) return st;
  if (auto it = s.find("terrain.style"); it != s.end() && it->second != "hills" && it->second != "island")
    return makeError("--set terrain.style=" + it->second + ": expected hills or island");
  return Ok{};
}

Result<std::unique_ptr<TerrainScene>> TerrainScene::create(const Settings& s, terrain::HeightMap* built) {
  if (auto st = checkSettings(s); !st) return makeError(st.error());
  double size = 1025, roughness = 0.5, spacing = 1, height = 40, seed = 0;
  (void)parseNumber(s, "terrain.size", terrain::kMinHeightMapSide, terrain::kMaxHeightMapSide, &size);
  (void)parseNumber(s, "terrain.roughness", 0.01, 1, &roughness);
  (void)parseNumber(s, "terrain.spacing", 0.01, 1000, &spacing);
  (void)parseNumber(s, "terrain.height", 0.01, 10000, &height);
  const auto styleIt = s.find("terrain.style");
  const std::string style = styleIt == s.end() ? "hills" : styleIt->second;

  terrain::HeightMap map;
  terrain::TerrainDesc desc;
  desc.spacing_m = spacing;
  desc.heightScale_m = height / 65535.0;
  if (built && s.count("terrain.heightmap") == 0 && s.count("terrain.generate") == 0) {
    // Made by the scenario's terrain.build (script/terrain_build.h).
    map = std::move(*built);
    if (style == "island") desc.baseHeight_m = -0.1 * height;
    desc.originX_m = -(map.width() - 1) * spacing / 2;
    desc.originZ_m = -(map.height() - 1) * spacing / 2;
  } else if (auto it = s.find("terrain.heightmap"); it != s.end()) {
    const std::string& path = it->second;
    auto loaded = terrain::loadHeightMapPng(path);
    if (!loaded) return makeError("--set terrain.heightmap=" + path + ": " + loaded.error());
    map = std::move(loaded.value());
    // Without a sidecar: centred on the origin, the spacing and height asked for.
    desc.originX_m = -(map.width() - 1) * spacing / 2;
    desc.originZ_m = -(map.height() - 1) * spacing / 2;
    auto sidecar = terrain::loadSidecar(path, desc);
    if (!sidecar) return makeError("--set terrain.heightmap=" + path + ": " + sidecar.error());
    desc = sidecar.value();
  } else {
    (void)parseNumber(s, "terrain.generate", 0, 9.0e15, &seed);
    const int n = int(size);
    map = terrain::generatePlasma(n, n, {std::uint64_t(seed), roughness});
    if (style == "island") {
      shapeIsland(map, std::uint64_t(seed));
      desc.baseHeight_m = -0.1 * height;  // the sea (y < 0) around the island
    }
    desc.originX_m = -(n - 1) * spacing / 2;
    desc.originZ_m = -(n - 1) * spacing / 2;
  }
  auto created = terrain::Terrain::create(std::move(map), desc);
  if (!created) return makeError(created.error());
  auto scene = std::unique_ptr<TerrainScene>(new TerrainScene());
  scene->m_terrain = std::make_unique<terrain::Terrain>(std::move(created.value()));
  paintMaterials(*scene->m_terrain, style == "island");
  if (auto it = s.find("terrain.heightmap"); it != s.end()) {
    if (auto st = loadMaterialLayersBeside(*scene->m_terrain, it->second); !st)
      return makeError("--set terrain.heightmap=" + it->second + ": " + st.error());
  }
  scene->m_field = std::make_unique<TerrainHeightField>(*scene->m_terrain);
  scene->fillSurface();
  return scene;
}

std::string materialLayerPath(const std::string& heightMapPath, terrain::MaterialLayer layer) {
  std::string stem = heightMapPath;
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".png") == 0) stem.resize(stem.size() - 4);
  return stem + "." + terrain::materialLayerName(layer) + ".png";
}

Status loadMaterialLayersBeside(terrain::Terrain& terrain, const std::string& heightMapPath) {
  terrain::MaterialMaps* maps = terrain.materials();
  if (!maps) return makeError("the terrain has no material maps to load layers into");
  for (int l = 0; l < terrain::kMaterialLayerCount; ++l) {
    const auto layer = terrain::MaterialLayer(l);
    const std::string path = materialLayerPath(heightMapPath, layer);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) continue;
    if (auto st = maps->loadLayerPng(layer, path); !st)
      return makeError(std::string(terrain::materialLayerName(layer)) + " layer " + path + ": " + st.error() +
                       " (expected an 8-bit grey PNG of " + std::to_string(maps->blocksX()) + " x " +
                       std::to_string(maps->blocksZ()) + " pixels, one per block)");
  }
  return Ok();
}

Status saveMaterialLayersBeside(const terrain::Terrain& terrain, const std::string& heightMapPath) {
  const terrain::MaterialMaps* maps = terrain.materials();
  if (!maps) return makeError("the terrain has no material maps");
  for (int l = 0; l < terrain::kMaterialLayerCount; ++l) {
    const auto layer = terrain::MaterialLayer(l);
    if (auto st = maps->saveLayerPng(layer, materialLayerPath(heightMapPath, layer)); !st) return st;
  }
  return Ok();
}

void describeTerrainSurface(const terrain::Terrain& t, render::TerrainSurface& s) {
  const terrain::TerrainDesc& d = t.desc();
  s.samplesX = t.heights().width();
  s.samplesZ = t.heights().height();
  s.spacing_m = float(d.spacing_m);
  s.heightScale_m = float(d.heightScale_m);
  s.baseHeight_m = float(d.baseHeight_m);
  s.originX_m = float(d.originX_m);
  s.originZ_m = float(d.originZ_m);
  s.heights = t.heights().samples().data();
  if (const terrain::MaterialMaps* m = t.materials()) {
    s.textureIndex = m->layer(terrain::MaterialLayer::Texture).data();
    s.bump = m->layer(terrain::MaterialLayer::Bump).data();
  }
}

void TerrainScene::fillSurface() {
  describeTerrainSurface(*m_terrain, m_surface);
  ++m_surface.revision;
}

}  // namespace tumble::app
