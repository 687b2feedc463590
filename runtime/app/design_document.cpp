#include "app/design_document.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <optional>
#include <sstream>

#include "app/paths.h"
#include "app/terrain_scene.h"
#include "core/file_util.h"
#include "core/hash.h"
#include "render/renderer.h"
#include "terrain/filters.h"
#include "terrain/generators.h"
#include "terrain/png_io.h"

namespace tumble::app {

// ---- surfaces ------------------------------------------------------------------------

namespace {

using terrain::SurfaceSound;

terrain::SurfaceMaterial material(std::uint8_t texture, std::uint8_t friction, std::uint8_t bump,
                                  std::uint8_t softness, SurfaceSound sound) {
  return {texture, friction, bump, softness, std::uint8_t(sound)};
}

}  // namespace

// Textures are render::TerrainSurface's (0 grass, 1 rock, 2 sand, 3 mud,
// 4 snow, 5 gravel, 6 dirt, 7 moss). Grass, rock, sand, mud and snow are the
// bytes paintMaterials (terrain_scene.cpp) gives generated terrains, so a
// painted patch matches the land around it. Friction is mu against a tyre
// (x 100), softness the rolling drag on soft ground (x 100, docs/vehicles.md):
// dry asphalt grips best and is hard, ice is slippery and hard, gravel and
// dirt are loose. The renderer has no asphalt texture yet: asphalt draws as
// gravel without bump detail (smooth, dark).
const std::vector<Surface>& surfacePalette() {
  static const std::vector<Surface> kPalette = {
      {"grass", material(0, 60, 80, 40, SurfaceSound::Grass)},
      {"rock", material(1, 80, 220, 0, SurfaceSound::Rock)},
      {"sand", material(2, 45, 40, 55, SurfaceSound::Sand)},
      {"mud", material(3, 30, 60, 70, SurfaceSound::Mud)},
      {"snow", material(4, 20, 30, 50, SurfaceSound::Snow)},
      {"gravel", material(5, 55, 140, 20, SurfaceSound::Gravel)},
      {"dirt", material(6, 55, 90, 30, SurfaceSound::Gravel)},
      {"moss", material(7, 45, 50, 45, SurfaceSound::Grass)},
      {"asphalt", material(5, 100, 0, 0, SurfaceSound::Asphalt)},
      {"ice", material(4, 10, 0, 0, SurfaceSound::Snow)},
  };
  return kPalette;
}

const Surface* findSurface(const std::string& name) {
  for (const Surface& s : surfacePalette())
    if (s.name == name) return &s;
  return nullptr;
}

const char* placedKindName(PlacedKind kind) {
  switch (kind) {
    case PlacedKind::Model: return "model";
    case PlacedKind::Box: return "box";
    case PlacedKind::Barrel: return "barrel";
    case PlacedKind::Ragdoll: return "ragdoll";
    case PlacedKind::Gate: return "gate";
    case PlacedKind::Trigger: return "trigger";
    case PlacedKind::Emitter: return "emitter";
  }
  return "?";
}

// ---- state -----------------------------------------------------------------------------

namespace {

/// Undo tiles: a stroke saves the samples (and blocks) of each kTile x kTile
/// tile the first time it is about to touch it; at its end only the
/// rectangle inside each tile that really changed is kept.
constexpr int kTile = 32;

struct HeightPatch {
  SampleRect rect;  // samples
  std::vector<std::uint16_t> before, after;
};

struct MaterialPatch {
  SampleRect blocks;  // inclusive block rectangle
  std::array<std::vector<std::uint8_t>, terrain::kMaterialLayerCount> before, after;
};

struct Step {
  std::vector<HeightPatch> heights;
  std::vector<MaterialPatch> materials;
  std::optional<DesignMeta> metaBefore, metaAfter;
  std::size_t bytes = 0;
};

std::size_t metaBytes(const DesignMeta& m) {
  std::size_t n = sizeof(DesignMeta) + m.vehicle.size() + m.title.size();
  for (const auto& [id, o] : m.objects) n += sizeof(id) + sizeof(PlacedObject) + o.asset.size() + o.collision.size() + 32;
  return n;
}

}  // namespace

struct DesignDocument::State {
  std::unique_ptr<terrain::Terrain> terrain;
  DesignMeta meta;
  terrain::BrushScratch scratch;
  std::deque<Step> undo;
  std::vector<Step> redo;
  std::size_t stepBytes = 0;  // undo + redo
  std::size_t budget = kDefaultUndoBudgetBytes;
  // The open stroke.
  bool strokeOpen = false;
  std::map<std::uint32_t, std::vector<std::uint16_t>> heightTiles;
  std::map<std::uint32_t, std::array<std::vector<std::uint8_t>, terrain::kMaterialLayerCount>> materialTiles;
  std::optional<DesignMeta> metaBefore;
  std::uint64_t revision = 1;
  SampleRect changed;
  std::vector<std::string> modFolders;
  bool modFoldersSet = false;

  int tilesX() const { return (terrain->heights().width() + kTile - 1) / kTile; }

  SampleRect tileSamples(int tx, int tz) const {
    return {tx * kTile, tz * kTile, std::min(tx * kTile + kTile - 1, terrain->heights().width() - 1),
            std::min(tz * kTile + kTile - 1, terrain->heights().height() - 1)};
  }
  SampleRect tileBlocks(int tx, int tz) const {
    return {tx * kTile, tz * kTile, std::min(tx * kTile + kTile - 1, terrain->blocksX() - 1),
            std::min(tz * kTile + kTile - 1, terrain->blocksZ() - 1)};
  }

  void saveHeightTiles(const SampleRect& r) {
    if (r.empty()) return;
    const terrain::HeightMap& h = terrain->heights();
    for (int tz = r.j0 / kTile; tz <= r.j1 / kTile; ++tz)
      for (int tx = r.i0 / kTile; tx <= r.i1 / kTile; ++tx) {
        const std::uint32_t key = std::uint32_t(tz * tilesX() + tx);
        if (heightTiles.count(key)) continue;
        const SampleRect t = tileSamples(tx, tz);
        std::vector<std::uint16_t>& v = heightTiles[key];
        v.reserve(std::size_t(t.sampleCount()));
        for (int j = t.j0; j <= t.j1; ++j)
          for (int i = t.i0; i <= t.i1; ++i) v.push_back(h.at(i, j));
      }
  }

  /// `blocks`: inclusive block rectangle.
  void saveMaterialTiles(const SampleRect& blocks) {
    if (blocks.empty()) return;
    const terrain::MaterialMaps& m = *terrain->materials();
    for (int tz = blocks.j0 / kTile; tz <= blocks.j1 / kTile; ++tz)
      for (int tx = blocks.i0 / kTile; tx <= blocks.i1 / kTile; ++tx) {
        const std::uint32_t key = std::uint32_t(tz * tilesX() + tx);
        if (materialTiles.count(key)) continue;
        const SampleRect t = tileBlocks(tx, tz);
        auto& layers = materialTiles[key];
        for (int l = 0; l < terrain::kMaterialLayerCount; ++l) {
          layers[std::size_t(l)].reserve(std::size_t(t.sampleCount()));
          for (int j = t.j0; j <= t.j1; ++j)
            for (int i = t.i0; i <= t.i1; ++i) layers[std::size_t(l)].push_back(m.get(terrain::MaterialLayer(l), i, j));
        }
      }
  }

  void begin() {
    if (strokeOpen) return;
    strokeOpen = true;
    heightTiles.clear();
    materialTiles.clear();
    metaBefore.reset();
  }

  void end();
  void push(Step step);
  void applyHeights(const std::vector<HeightPatch>& patches, bool useBefore);
  void applyMaterials(const std::vector<MaterialPatch>& patches, bool useBefore);
  void touched(const SampleRect& r) {
    changed.include(r);
    if (!r.empty()) ++revision;
  }
  /// Puts every object and the start back on the ground after the heights
  /// changed (a brush, a line, undo, redo): their y is the terrain's at
  /// their (x, z), never a height the ground has left.
  void resnap() {
    for (auto& [id, o] : meta.objects) o.position_m.y() = terrain->heightAt(o.position_m.x(), o.position_m.z());
    meta.start.position_m.y() = terrain->heightAt(meta.start.position_m.x(), meta.start.position_m.z());
  }
};

void DesignDocument::State::end() {
  if (!strokeOpen) return;
  strokeOpen = false;
  Step step;
  const terrain::HeightMap& h = terrain->heights();
  const int tx = tilesX();
  for (const auto& [key, before] : heightTiles) {
    const SampleRect t = tileSamples(int(key) % tx, int(key) / tx);
    const int w = t.i1 - t.i0 + 1;
    SampleRect diff;
    for (int j = t.j0; j <= t.j1; ++j)
      for (int i = t.i0; i <= t.i1; ++i)
        if (before[std::size_t(j - t.j0) * w + (i - t.i0)] != h.at(i, j)) diff.include({i, j, i, j});
    if (diff.empty()) continue;
    HeightPatch p;
    p.rect = diff;
    for (int j = diff.j0; j <= diff.j1; ++j)
      for (int i = diff.i0; i <= diff.i1; ++i) {
        p.before.push_back(before[std::size_t(j - t.j0) * w + (i - t.i0)]);
        p.after.push_back(h.at(i, j));
      }
    step.bytes += (p.before.size() + p.after.size()) * sizeof(std::uint16_t) + sizeof(HeightPatch);
    step.heights.push_back(std::move(p));
  }
  if (const terrain::MaterialMaps* m = terrain->materials()) {
    for (const auto& [key, before] : materialTiles) {
      const SampleRect t = tileBlocks(int(key) % tx, int(key) / tx);
      const int w = t.i1 - t.i0 + 1;
      SampleRect diff;
      for (int l = 0; l < terrain::kMaterialLayerCount; ++l)
        for (int j = t.j0; j <= t.j1; ++j)
          for (int i = t.i0; i <= t.i1; ++i)
            if (before[std::size_t(l)][std::size_t(j - t.j0) * w + (i - t.i0)] != m->get(terrain::MaterialLayer(l), i, j))
              diff.include({i, j, i, j});
      if (diff.empty()) continue;
      MaterialPatch p;
      p.blocks = diff;
      for (int l = 0; l < terrain::kMaterialLayerCount; ++l)
        for (int j = diff.j0; j <= diff.j1; ++j)
          for (int i = diff.i0; i <= diff.i1; ++i) {
            p.before[std::size_t(l)].push_back(before[std::size_t(l)][std::size_t(j - t.j0) * w + (i - t.i0)]);
            p.after[std::size_t(l)].push_back(m->get(terrain::MaterialLayer(l), i, j));
          }
      step.bytes += 2 * terrain::kMaterialLayerCount * std::size_t(diff.sampleCount()) + sizeof(MaterialPatch);
      step.materials.push_back(std::move(p));
    }
  }
  if (metaBefore && !(*metaBefore == meta)) {
    step.metaBefore = std::move(*metaBefore);
    step.metaAfter = meta;
    step.bytes += metaBytes(*step.metaBefore) + metaBytes(*step.metaAfter);
  }
  heightTiles.clear();
  materialTiles.clear();
  metaBefore.reset();
  if (step.heights.empty() && step.materials.empty() && !step.metaBefore) return;
  step.bytes += sizeof(Step);
  push(std::move(step));
}

void DesignDocument::State::push(Step step) {
  for (const Step& s : redo) stepBytes -= s.bytes;
  redo.clear();
  stepBytes += step.bytes;
  undo.push_back(std::move(step));
  // The newest step always stays (the last edit can be undone).
  while (stepBytes > budget && undo.size() > 1) {
    stepBytes -= undo.front().bytes;
    undo.pop_front();
  }
}

void DesignDocument::State::applyHeights(const std::vector<HeightPatch>& patches, bool useBefore) {
  for (const HeightPatch& p : patches) {
    const std::vector<std::uint16_t>& v = useBefore ? p.before : p.after;
    terrain->editHeights(p.rect.i0, p.rect.j0, p.rect.i1, p.rect.j1, [&](terrain::HeightMap& h) {
      std::size_t k = 0;
      for (int j = p.rect.j0; j <= p.rect.j1; ++j)
        for (int i = p.rect.i0; i <= p.rect.i1; ++i) h.set(i, j, v[k++]);
    });
    changed.include(p.rect);
  }
}

void DesignDocument::State::applyMaterials(const std::vector<MaterialPatch>& patches, bool useBefore) {
  terrain::MaterialMaps* m = terrain->materials();
  if (!m) return;
  for (const MaterialPatch& p : patches) {
    for (int l = 0; l < terrain::kMaterialLayerCount; ++l) {
      const std::vector<std::uint8_t>& v = useBefore ? p.before[std::size_t(l)] : p.after[std::size_t(l)];
      std::size_t k = 0;
      for (int j = p.blocks.j0; j <= p.blocks.j1; ++j)
        for (int i = p.blocks.i0; i <= p.blocks.i1; ++i) m->set(terrain::MaterialLayer(l), i, j, v[k++]);
    }
    changed.include({p.blocks.i0, p.blocks.j0, p.blocks.i1 + 1, p.blocks.j1 + 1});
  }
}

// ---- creation ------------------------------------------------------------------------

DesignDocument::DesignDocument() : m(std::make_unique<State>()) {}
DesignDocument::DesignDocument(DesignDocument&&) noexcept = default;
DesignDocument& DesignDocument::operator=(DesignDocument&&) noexcept = default;
DesignDocument::~DesignDocument() = default;

namespace {

std::string numberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

Result<terrain::HeightMap> importImage(const NewMapOptions& o, double* spacing_m) {
  const std::string what = "imagePath " + o.imagePath;
  if (o.imagePath.empty()) return makeError("imagePath: the image generator needs a PNG file");
  // A 8193^2 16-bit PNG compresses to at most ~135 MB; refuse bigger files before reading them.
  auto bytes = readBinaryFile(o.imagePath, kMaxReadBytes);
  if (!bytes) return makeError(what + ": " + bytes.error());
  auto img = terrain::decodePngGrey(*bytes, o.imagePath, kMaxImportSide);
  if (!img) return makeError(what + ": " + img.error() + " (largest accepted: " + std::to_string(kMaxImportSide) +
                             " x " + std::to_string(kMaxImportSide) + " pixels)");
  if (img->width < terrain::kMinHeightMapSide || img->height < terrain::kMinHeightMapSide)
    return makeError(what + ": the image is " + std::to_string(img->width) + " x " + std::to_string(img->height) +
                     " pixels; a height map needs at least 2 x 2");
  terrain::HeightMap map(img->width, img->height);
  const bool widen = img->bitDepth == 8;
  for (std::size_t k = 0; k < map.samples().size(); ++k)
    map.samples()[k] = widen ? std::uint16_t(img->values[k] * 257u) : img->values[k];
  img->values = {};
  const int longSide = std::max(map.width(), map.height());
  int target = o.size_samples;
  if (target == 0 && longSide > terrain::kMaxHeightMapSide) {
    target = terrain::kMaxHeightMapSide;
    *spacing_m *= double(longSide - 1) / double(target - 1);  // the same ground, fewer samples
  }
  if (target != 0 && target != longSide) {
    auto side = [&](int n) { return std::max(2, int(std::lround(1.0 + double(n - 1) * (target - 1) / (longSide - 1)))); };
    map = terrain::resampleBicubic(map, side(map.width()), side(map.height()));
  }
  return map;
}

}  // namespace

Result<DesignDocument> DesignDocument::create(const NewMapOptions& o) {
  const bool image = o.generator == "image";
  if (o.generator != "flat" && o.generator != "plasma" && !image)
    return makeError("generator \"" + o.generator + "\": expected flat, plasma or image");
  if (!(image && o.size_samples == 0) &&
      (o.size_samples < terrain::kMinHeightMapSide || o.size_samples > terrain::kMaxHeightMapSide))
    return makeError("size_samples " + std::to_string(o.size_samples) + ": expected " +
                     std::to_string(terrain::kMinHeightMapSide) + " to " + std::to_string(terrain::kMaxHeightMapSide) +
                     " samples per side" + (image ? " (or 0: the image's own size)" : ""));
  if (!(o.spacing_m > 0 && o.spacing_m <= 1000))
    return makeError("spacing_m " + numberText(o.spacing_m) + ": expected metres between samples in (0, 1000]");
  if (!std::isfinite(o.minHeight_m) || !std::isfinite(o.maxHeight_m) || !(o.maxHeight_m > o.minHeight_m) ||
      std::abs(o.minHeight_m) > 1e6 || std::abs(o.maxHeight_m) > 1e6 || (o.maxHeight_m - o.minHeight_m) / 65535 > 15)
    return makeError("minHeight_m " + numberText(o.minHeight_m) + ", maxHeight_m " + numberText(o.maxHeight_m) +
                     ": expected finite heights within +-1e6 m with max > min and max - min <= 983025 m");
  if (o.generator == "plasma" && !(o.roughness > 0 && o.roughness <= 1))
    return makeError("roughness " + numberText(o.roughness) + ": expected a number in (0, 1]");
  if (o.generator == "flat" && !(o.flatHeight_m >= o.minHeight_m && o.flatHeight_m <= o.maxHeight_m))
    return makeError("flatHeight_m " + numberText(o.flatHeight_m) + ": expected a height within [minHeight_m, maxHeight_m] = [" +
                     numberText(o.minHeight_m) + ", " + numberText(o.maxHeight_m) + "]");
  if (!o.centred && (!std::isfinite(o.originX_m) || !std::isfinite(o.originZ_m) || std::abs(o.originX_m) > 1e6 ||
                     std::abs(o.originZ_m) > 1e6))
    return makeError("originX_m, originZ_m: expected finite numbers within +-1e6 m");

  terrain::TerrainDesc desc;
  desc.spacing_m = o.spacing_m;
  desc.baseHeight_m = o.minHeight_m;
  desc.heightScale_m = (o.maxHeight_m - o.minHeight_m) / 65535.0;
  terrain::HeightMap map;
  if (o.generator == "flat") {
    const double v = std::clamp(std::round((o.flatHeight_m - desc.baseHeight_m) / desc.heightScale_m), 0.0, 65535.0);
    map = terrain::HeightMap(o.size_samples, o.size_samples, std::uint16_t(v));
  } else if (o.generator == "plasma") {
    map = terrain::generatePlasma(o.size_samples, o.size_samples, {o.seed, o.roughness});
  } else {
    auto imported = importImage(o, &desc.spacing_m);
    if (!imported) return makeError(imported.error());
    map = std::move(imported.value());
  }
  if (o.centred) {
    desc.originX_m = -(map.width() - 1) * desc.spacing_m / 2;
    desc.originZ_m = -(map.height() - 1) * desc.spacing_m / 2;
  } else {
    desc.originX_m = o.originX_m;
    desc.originZ_m = o.originZ_m;
  }
  auto t = terrain::Terrain::create(std::move(map), desc);
  if (!t) return makeError(t.error());
  DesignDocument doc;
  doc.m->terrain = std::make_unique<terrain::Terrain>(std::move(t.value()));
  if (o.generator == "flat") {
    const terrain::SurfaceMaterial& g = surfacePalette().front().material;  // grass
    doc.m->terrain->createMaterials({g.texture, g.bump, g.friction, g.sound, g.softness});
  } else {
    paintMaterials(*doc.m->terrain, false);  // rock on steep slopes, snow high up, mud in low flat patches
  }
  doc.m->meta.start.position_m.y() = Real(doc.groundHeight_m(0, 0));
  return doc;
}

DesignDocument DesignDocument::fromParts(std::unique_ptr<terrain::Terrain> terrain, DesignMeta meta) {
  DesignDocument doc;
  doc.m->terrain = std::move(terrain);
  doc.m->meta = std::move(meta);
  return doc;
}

const DesignMeta& DesignDocument::meta() const { return m->meta; }

// ---- terrain ---------------------------------------------------------------------------

terrain::Terrain& DesignDocument::terrain() { return *m->terrain; }
const terrain::Terrain& DesignDocument::terrain() const { return *m->terrain; }

double DesignDocument::groundHeight_m(double x, double z) const { return m->terrain->heightAt(Real(x), Real(z)); }

void DesignDocument::fillSurface(render::TerrainSurface& s) const {
  describeTerrainSurface(*m->terrain, s);
  s.revision = m->revision;
}

void DesignDocument::beginStroke() { m->begin(); }
void DesignDocument::endStroke() { m->end(); }
bool DesignDocument::inStroke() const { return m->strokeOpen; }

SampleRect DesignDocument::dab(const Brush& brush, double x, double z, double dt) {
  const bool implicit = !m->strokeOpen;
  m->begin();
  m->saveHeightTiles(terrain::samplesInRadius(*m->terrain, x, z, brush.radius_m));
  const SampleRect r = terrain::applyBrush(*m->terrain, brush, x, z, dt, m->scratch);
  m->touched(r);
  if (!r.empty()) m->resnap();
  if (implicit) m->end();
  return r;
}

SampleRect DesignDocument::line(bool ridge, Vec2 from, Vec2 to, double width, double height) {
  const bool implicit = !m->strokeOpen;
  m->begin();
  const double hw = width / 2;
  SampleRect area = terrain::samplesInRadius(*m->terrain, from.x(), from.y(), hw);
  area.include(terrain::samplesInRadius(*m->terrain, to.x(), to.y(), hw));
  m->saveHeightTiles(area);  // the box around both end discs holds the whole band
  const SampleRect r = terrain::applyLine(*m->terrain, ridge, from.x(), from.y(), to.x(), to.y(), width, height);
  m->touched(r);
  if (!r.empty()) m->resnap();
  if (implicit) m->end();
  return r;
}

SampleRect DesignDocument::paint(const Surface& surface, double x, double z, double radius) {
  const bool implicit = !m->strokeOpen;
  m->begin();
  // Blocks whose centres are within the radius have both corners within radius + one spacing.
  SampleRect corners = terrain::samplesInRadius(*m->terrain, x, z, radius + m->terrain->desc().spacing_m);
  if (!corners.empty())
    m->saveMaterialTiles({corners.i0, corners.j0, std::min(corners.i1, m->terrain->blocksX() - 1),
                          std::min(corners.j1, m->terrain->blocksZ() - 1)});
  const SampleRect r = terrain::paintSurface(*m->terrain, surface.material, x, z, radius);
  m->touched(r);
  if (implicit) m->end();
  return r;
}

SampleRect DesignDocument::takeChangedSamples() {
  SampleRect r = m->changed;
  m->changed = {};
  return r;
}

// ---- objects, start and car ---------------------------------------------------------------

namespace {

bool placeable(const PlacedObject& o) {
  return std::isfinite(o.position_m.x()) && std::isfinite(o.position_m.z()) && std::isfinite(o.yaw_rad) &&
         o.scale.allFinite() && (o.scale.array() > 0).all() && std::isfinite(o.mass_kg) && o.mass_kg >= 0;
}

}  // namespace

template <typename Fn>
void DesignDocument::editMeta(Fn&& fn) {
  const bool implicit = !m->strokeOpen;
  m->begin();
  if (!m->metaBefore) m->metaBefore = m->meta;
  fn(m->meta);
  ++m->revision;
  if (implicit) m->end();
}

std::uint32_t DesignDocument::addObject(const PlacedObject& object) {
  if (!placeable(object)) return 0;
  std::uint32_t id = 0;
  editMeta([&](DesignMeta& meta) {
    id = meta.nextId++;
    PlacedObject o = object;
    o.position_m.y() = Real(groundHeight_m(o.position_m.x(), o.position_m.z()));
    meta.objects[id] = o;
  });
  return id;
}

bool DesignDocument::moveObject(std::uint32_t id, const PlacedObject& object) {
  if (!placeable(object) || !m->meta.objects.count(id)) return false;
  editMeta([&](DesignMeta& meta) {
    PlacedObject o = object;
    o.position_m.y() = Real(groundHeight_m(o.position_m.x(), o.position_m.z()));
    meta.objects[id] = o;
  });
  return true;
}

bool DesignDocument::removeObject(std::uint32_t id) {
  if (!m->meta.objects.count(id)) return false;
  editMeta([&](DesignMeta& meta) { meta.objects.erase(id); });
  return true;
}

std::uint32_t DesignDocument::duplicateObject(std::uint32_t id) {
  auto it = m->meta.objects.find(id);
  if (it == m->meta.objects.end()) return 0;
  return addObject(it->second);
}

const std::map<std::uint32_t, PlacedObject>& DesignDocument::objects() const { return m->meta.objects; }

void DesignDocument::setStart(Vec3 position, double heading) {
  if (!std::isfinite(position.x()) || !std::isfinite(position.z()) || !std::isfinite(heading)) return;
  editMeta([&](DesignMeta& meta) {
    meta.start.position_m = position;
    meta.start.position_m.y() = Real(groundHeight_m(position.x(), position.z()));
    meta.start.heading_rad = heading;
  });
}

const VehicleStart& DesignDocument::start() const { return m->meta.start; }

void DesignDocument::setVehicle(const std::string& vehicle) {
  editMeta([&](DesignMeta& meta) { meta.vehicle = vehicle; });
}
const std::string& DesignDocument::vehicle() const { return m->meta.vehicle; }

std::string checkSky(const DesignSky& sky) {
  if (!std::isfinite(sky.timeOfDay_h) || sky.timeOfDay_h < 0 || sky.timeOfDay_h > 24)
    return "'sky.time_of_day_h': expected hours in [0, 24]";
  if (sky.weather != "clear" && sky.weather != "cloudy" && sky.weather != "storm")
    return "'sky.weather': expected \"clear\", \"cloudy\" or \"storm\"";
  if (!std::isfinite(sky.cloudCover) || sky.cloudCover < 0 || sky.cloudCover > 1)
    return "'sky.clouds': expected a fraction in [0, 1]";
  return {};
}

bool DesignDocument::setSky(const DesignSky& sky) {
  if (!checkSky(sky).empty()) return false;
  if (sky == m->meta.sky) return true;
  editMeta([&](DesignMeta& meta) { meta.sky = sky; });
  return true;
}
const DesignSky& DesignDocument::sky() const { return m->meta.sky; }

void DesignDocument::setTitle(const std::string& title) {
  editMeta([&](DesignMeta& meta) { meta.title = title; });
}
const std::string& DesignDocument::title() const { return m->meta.title; }

// ---- undo ---------------------------------------------------------------------------------

bool DesignDocument::undo() {
  m->end();
  if (m->undo.empty()) return false;
  Step step = std::move(m->undo.back());
  m->undo.pop_back();
  m->applyHeights(step.heights, true);
  m->applyMaterials(step.materials, true);
  if (step.metaBefore) m->meta = *step.metaBefore;
  if (!step.heights.empty()) m->resnap();
  m->redo.push_back(std::move(step));
  ++m->revision;
  return true;
}

bool DesignDocument::redo() {
  m->end();
  if (m->redo.empty()) return false;
  Step step = std::move(m->redo.back());
  m->redo.pop_back();
  m->applyHeights(step.heights, false);
  m->applyMaterials(step.materials, false);
  if (step.metaAfter) m->meta = *step.metaAfter;
  if (!step.heights.empty()) m->resnap();
  m->undo.push_back(std::move(step));
  ++m->revision;
  return true;
}

bool DesignDocument::canUndo() const { return !m->undo.empty() || m->strokeOpen; }
bool DesignDocument::canRedo() const { return !m->redo.empty(); }
std::size_t DesignDocument::undoBytes() const { return m->stepBytes; }

void DesignDocument::setUndoBudget(std::size_t bytes) {
  m->budget = bytes;
  while (m->stepBytes > m->budget && m->undo.size() + m->redo.size() > 1) {
    if (!m->undo.empty()) {
      m->stepBytes -= m->undo.front().bytes;
      m->undo.pop_front();
    } else {
      m->stepBytes -= m->redo.front().bytes;  // the redo step furthest from now
      m->redo.erase(m->redo.begin());
    }
  }
}
std::size_t DesignDocument::undoBudget() const { return m->budget; }

std::uint64_t DesignDocument::revision() const { return m->revision; }

std::uint64_t DesignDocument::contentHash() const {
  Hasher h;
  const terrain::Terrain& t = *m->terrain;
  const terrain::TerrainDesc& d = t.desc();
  h.value(t.heights().width());
  h.value(t.heights().height());
  h.bytes(t.heights().samples().data(), t.heights().samples().size() * sizeof(std::uint16_t));
  for (double v : {d.spacing_m, d.heightScale_m, d.baseHeight_m, d.originX_m, d.originZ_m}) h.value(v);
  if (const terrain::MaterialMaps* mm = t.materials())
    for (int l = 0; l < terrain::kMaterialLayerCount; ++l) {
      const auto& layer = mm->layer(terrain::MaterialLayer(l));
      h.bytes(layer.data(), layer.size());
    }
  const DesignMeta& meta = m->meta;
  for (const auto& [id, o] : meta.objects) {
    h.value(id);
    h.value(int(o.kind));
    h.bytes(o.asset.data(), o.asset.size());
    h.value(o.asset.size());
    for (int k = 0; k < 3; ++k) h.value(o.position_m[k]), h.value(o.scale[k]);
    h.value(o.yaw_rad);
    h.bytes(o.collision.data(), o.collision.size());
    h.value(o.collision.size());
    h.value(o.order);
    h.value(o.mass_kg);
  }
  for (int k = 0; k < 3; ++k) h.value(meta.start.position_m[k]);
  h.value(meta.start.heading_rad);
  h.bytes(meta.vehicle.data(), meta.vehicle.size());
  h.value(meta.vehicle.size());
  h.bytes(meta.title.data(), meta.title.size());
  h.value(meta.title.size());
  h.value(meta.sky.timeOfDay_h);
  h.bytes(meta.sky.weather.data(), meta.sky.weather.size());
  h.value(meta.sky.weather.size());
  h.value(meta.sky.cloudCover);
  return h.digest();
}

std::vector<std::string> DesignDocument::modFolders() const {
  return m->modFoldersSet ? m->modFolders : modSearchDirs({});
}

void DesignDocument::setModFolders(std::vector<std::string> folders) {
  m->modFolders = std::move(folders);
  m->modFoldersSet = true;
}

}  // namespace tumble::app
