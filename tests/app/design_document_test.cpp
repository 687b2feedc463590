// The scenario designer's document, headless: new maps, brushes, painting,
// objects and undo. What a brush changes is checked against the map before
// it, the collision tree against a tree built from scratch, and what a ray
// and the physics height field see.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <vector>

#include "app/design_document.h"
#include "app/terrain_scene.h"
#include "core/file_util.h"
#include "core/random.h"
#include "terrain/height_map.h"
#include "terrain/png_io.h"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  struct Dir {
    fs::path path = fs::temp_directory_path() / ("tumble_design_test_" + std::to_string(::getpid()));
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

DesignDocument flatDoc(int size = 129, double spacing = 1.0, double flat = 10.0) {
  NewMapOptions o;
  o.size_samples = size;
  o.spacing_m = spacing;
  o.minHeight_m = 0;
  o.maxHeight_m = 100;
  o.flatHeight_m = flat;
  auto d = DesignDocument::create(o);
  EXPECT_TRUE(d.ok()) << (d.ok() ? "" : d.error());
  return std::move(d.value());
}

/// The rectangle of samples that differ between two maps of one size.
SampleRect diffRect(const terrain::HeightMap& a, const terrain::HeightMap& b) {
  SampleRect r;
  for (int j = 0; j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i)
      if (a.at(i, j) != b.at(i, j)) r.include({i, j, i, j});
  return r;
}

/// Every node of the document's tree equals the node of a tree built from scratch.
void expectTreeMatchesRebuild(const terrain::Terrain& t) {
  terrain::HeightTree fresh;
  fresh.build(t.heights(), t.tree().leafBlocks());
  ASSERT_EQ(fresh.nodeCount(), t.tree().nodeCount());
  for (std::uint32_t n = 0; n < fresh.nodeCount(); ++n) {
    ASSERT_EQ(fresh.node(n).minHeight, t.tree().node(n).minHeight) << "node " << n;
    ASSERT_EQ(fresh.node(n).maxHeight, t.tree().node(n).maxHeight) << "node " << n;
  }
}

void writeGrey8(const std::string& path, int w, int h, auto&& value) {
  std::vector<std::uint8_t> px(std::size_t(w) * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) px[std::size_t(j) * w + i] = std::uint8_t(value(i, j));
  auto png = terrain::encodePngGrey8(px.data(), w, h);
  ASSERT_TRUE(png.ok());
  ASSERT_TRUE(writeFileAtomic(path, png->data(), png->size()).ok());
}

}  // namespace

// ---- new maps --------------------------------------------------------------------------

TEST(DesignNewMap, FlatIsLevelAtTheHeightAskedAndCentred) {
  DesignDocument d = flatDoc(65, 2.0, 12.5);
  const terrain::Terrain& t = d.terrain();
  EXPECT_EQ(t.heights().width(), 65);
  EXPECT_DOUBLE_EQ(t.desc().originX_m, -64.0);  // 64 spacings of 2 m, centred
  EXPECT_DOUBLE_EQ(t.desc().originZ_m, -64.0);
  const double unit = 100.0 / 65535;
  for (double x : {-64.0, 0.0, 17.3, 64.0}) EXPECT_NEAR(t.heightAt(Real(x), Real(-x / 2)), 12.5, unit / 2 + 1e-4);
}


TEST(DesignNewMap, PlasmaSpansTheHeightRangeAndRepeatsForASeed) {
  NewMapOptions o;
  o.generator = "plasma";
  o.size_samples = 257;
  o.seed = 42;
  o.roughness = 0.6;
  o.minHeight_m = -5;
  o.maxHeight_m = 35;
  auto a = DesignDocument::create(o), b = DesignDocument::create(o);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->contentHash(), b->contentHash());
  // The plasma is normalised to the whole 16-bit range: its lowest and
  // highest points are the heights asked for.
  const terrain::Aabb box = a->terrain().bounds();
  EXPECT_NEAR(box.min.y(), -5.0, 1e-4);
  EXPECT_NEAR(box.max.y(), 35.0, 1e-4);
  o.seed = 43;
  auto c = DesignDocument::create(o);
  ASSERT_TRUE(c.ok());
  EXPECT_NE(a->contentHash(), c->contentHash());
}

TEST(DesignNewMap, ImageOfAnySizeKeepsItsShapeAndHeightRange) {
  const std::string path = (tempDir() / "ramp.png").string();
  // 300 x 200 pixels: brightness grows along x (0 .. 255).
  writeGrey8(path, 300, 200, [](int i, int) { return i * 255 / 299; });
  NewMapOptions o;
  o.generator = "image";
  o.imagePath = path;
  o.size_samples = 0;  // its own size
  o.spacing_m = 0.5;
  o.minHeight_m = 2;
  o.maxHeight_m = 22;
  auto d = DesignDocument::create(o);
  ASSERT_TRUE(d.ok()) << d.error();
  const terrain::Terrain& t = d->terrain();
  EXPECT_EQ(t.heights().width(), 300);
  EXPECT_EQ(t.heights().height(), 200);
  EXPECT_DOUBLE_EQ(t.desc().originX_m, -299 * 0.5 / 2);  // centred
  EXPECT_DOUBLE_EQ(t.desc().originZ_m, -199 * 0.5 / 2);
  EXPECT_NEAR(t.heightAt(Real(t.desc().originX_m), 0), 2.0, 1e-4);                 // black: min
  EXPECT_NEAR(t.heightAt(Real(-t.desc().originX_m), 0), 22.0, 1e-4);               // white: max
  // Resampled: the longer side to 151 samples, the same ramp.
  o.size_samples = 151;
  o.centred = false;
  o.originX_m = 100;
  o.originZ_m = -50;
  auto r = DesignDocument::create(o);
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->terrain().heights().width(), 151);
  EXPECT_EQ(r->terrain().heights().height(), 101);
  EXPECT_DOUBLE_EQ(r->terrain().desc().originX_m, 100);
  EXPECT_DOUBLE_EQ(r->terrain().desc().originZ_m, -50);
  const double mid = r->groundHeight_m(100 + 75 * 0.5, -50 + 10);
  EXPECT_NEAR(mid, 12.0, 0.1) << "the middle of a 2..22 m ramp";
}

TEST(DesignNewMap, BadOptionsNameTheFieldAndTheFile) {
  NewMapOptions o;
  o.generator = "noise";
  auto r = DesignDocument::create(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("generator \"noise\""), std::string::npos) << r.error();
  o = {};
  o.size_samples = 5000;
  r = DesignDocument::create(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("size_samples 5000"), std::string::npos) << r.error();
  o = {};
  o.maxHeight_m = o.minHeight_m;
  r = DesignDocument::create(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("maxHeight_m"), std::string::npos) << r.error();
  // A missing, a broken and a huge image.
  o = {};
  o.generator = "image";
  o.imagePath = (tempDir() / "missing.png").string();
  r = DesignDocument::create(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("missing.png"), std::string::npos) << r.error();
  const std::string broken = (tempDir() / "broken.png").string();
  ASSERT_TRUE(writeFileAtomic(broken, std::string("\x89PNG\r\n\x1a\nnot really a png at all")).ok());
  o.imagePath = broken;
  r = DesignDocument::create(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("broken.png"), std::string::npos) << r.error();
  // A valid PNG whose header claims 20000 x 20000 pixels: refused before decoding.
  const std::string huge = (tempDir() / "huge.png").string();
  writeGrey8(huge, 2, 2, [](int, int) { return 0; });
  auto bytes = readBinaryFile(huge);
  ASSERT_TRUE(bytes.ok());
  std::vector<std::uint8_t> png = *bytes;
  // IHDR data starts at byte 16: width, height (big-endian), then its CRC at 29..32.
  for (int k : {16, 20}) png[k] = 0, png[k + 1] = 0, png[k + 2] = 0x4E, png[k + 3] = 0x20;
  std::uint32_t crc = 0xFFFFFFFFu;
  for (int k = 12; k < 29; ++k) {  // CRC-32 over "IHDR" and its 13 data bytes
    crc ^= png[k];
    for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  crc ^= 0xFFFFFFFFu;
  for (int k = 0; k < 4; ++k) png[29 + k] = std::uint8_t(crc >> (24 - 8 * k));
  ASSERT_TRUE(writeFileAtomic(huge, png.data(), png.size()).ok());
  o.imagePath = huge;
  r = DesignDocument::create(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("huge.png"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("20000"), std::string::npos) << r.error();
}

// A height map drawn elsewhere, given with --set terrain.heightmap= and no
// sidecar: centred on the origin with the terrain.height range (40 m by
// default), so a scenario's start at (0, 0) is on the map.
TEST(DesignNewMap, SidecarlessImportIsCentredWithAHeightScale) {
  const std::string path = (tempDir() / "drawn512.png").string();
  writeGrey8(path, 512, 512, [](int i, int j) { return (i + j) % 256; });
  auto scene = TerrainScene::create({{"terrain.heightmap", path}});
  ASSERT_TRUE(scene.ok()) << scene.error();
  const terrain::Terrain& t = (*scene)->terrain();
  EXPECT_DOUBLE_EQ(t.desc().originX_m, -255.5);
  EXPECT_DOUBLE_EQ(t.desc().originZ_m, -255.5);
  EXPECT_TRUE(t.contains(0, 0));
  EXPECT_NEAR(t.desc().heightScale_m * 65535, 40.0, 1e-9);
  EXPECT_LE(t.bounds().max.y(), 40.0 + 1e-4);
}

// ---- brushes ---------------------------------------------------------------------------

TEST(DesignBrush, RaiseChangesOnlyTheDiscItReturnsAndTheTreeAndRaysFollow) {
  DesignDocument d = flatDoc(129, 1.0, 10.0);
  const terrain::HeightMap before = d.terrain().heights();
  Brush b;
  b.kind = BrushKind::Raise;
  b.radius_m = 6;
  b.strength_m_per_s = 3;
  b.falloff = 0.5;
  const SampleRect r = d.dab(b, 4.0, -7.0, 0.5);  // 1.5 m at the centre
  ASSERT_FALSE(r.empty());
  EXPECT_EQ(r, diffRect(before, d.terrain().heights())) << "the rectangle returned is exactly what changed";
  EXPECT_LE(r.i1 - r.i0 + 1, 13);  // a 6 m radius at 1 m spacing: at most 13 samples across
  EXPECT_NEAR(d.groundHeight_m(4, -7), 11.5, 100.0 / 65535);
  EXPECT_NEAR(d.groundHeight_m(4 + 6.5, -7), 10.0, 100.0 / 65535) << "outside the radius: unchanged";
  expectTreeMatchesRebuild(d.terrain());
  // A ray straight down and a box query see the hill.
  auto hit = d.terrain().rayCast(Vec3(4, 50, -7), Vec3(0, -1, 0), 100);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->point.y(), 11.5, 2e-3);
  double highest = 0;
  d.terrain().forEachTriangleInBox({Vec3(2, 0, -9), Vec3(6, 20, -5)}, [&](const terrain::TerrainTriangle& t) {
    for (const Vec3& v : t.vertices) highest = std::max(highest, double(v.y()));
  });
  EXPECT_NEAR(highest, 11.5, 2e-3);
  // The physics height field reads the same terrain.
  TerrainHeightField field(d.terrain());
  Real h = 0;
  Vec3 n;
  ASSERT_TRUE(field.surfaceAt(4, -7, &h, &n));
  EXPECT_NEAR(h, 11.5, 2e-3);
}

TEST(DesignBrush, FalloffShapesTheDab) {
  for (double falloff : {0.0, 1.0}) {
    DesignDocument d = flatDoc(65, 1.0, 10.0);
    Brush b;
    b.radius_m = 8;
    b.strength_m_per_s = 2;
    b.falloff = falloff;
    d.dab(b, 0, 0, 1);
    if (falloff == 0) {
      // Hard edge: 2 m everywhere inside.
      EXPECT_NEAR(d.groundHeight_m(0, 0), 12.0, 2e-3);
      EXPECT_NEAR(d.groundHeight_m(7, 0), 12.0, 2e-3);
      EXPECT_NEAR(d.groundHeight_m(0, -7), 12.0, 2e-3);
    } else {
      // Smooth: falls from 2 m at the centre to 0 at the rim, never rising outward.
      double last = 1e9;
      for (int x = 0; x <= 8; ++x) {
        const double h = d.groundHeight_m(x, 0);
        EXPECT_LE(h, last + 1e-9);
        last = h;
      }
      EXPECT_NEAR(d.groundHeight_m(0, 0), 12.0, 2e-3);
      EXPECT_NEAR(d.groundHeight_m(4, 0), 11.0, 2e-3);  // smoothstep(0.5) = 0.5
      EXPECT_NEAR(d.groundHeight_m(8, 0), 10.0, 2e-3);
    }
  }
}

TEST(DesignBrush, LowerFlattenSmoothAndNoise) {
  DesignDocument d = flatDoc(65, 1.0, 10.0);
  Brush b;
  b.radius_m = 5;
  b.falloff = 0;
  b.strength_m_per_s = 4;
  b.kind = BrushKind::Lower;
  d.dab(b, 0, 0, 0.5);
  EXPECT_NEAR(d.groundHeight_m(0, 0), 8.0, 2e-3);
  // Flatten to 9 m: moves by at most strength * dt, then stays at 9 m.
  b.kind = BrushKind::Flatten;
  b.flattenHeight_m = 9;
  b.strength_m_per_s = 1;
  d.dab(b, 0, 0, 0.25);
  EXPECT_NEAR(d.groundHeight_m(0, 0), 8.25, 2e-3);
  for (int k = 0; k < 10; ++k) d.dab(b, 0, 0, 0.25);
  EXPECT_NEAR(d.groundHeight_m(0, 0), 9.0, 2e-3);
  // Smooth: a one-sample spike sinks towards its neighbours' level and the
  // neighbours rise; the total is nearly kept (the binomial kernel sums to 1).
  DesignDocument s = flatDoc(65, 1.0, 10.0);
  Brush spike;
  spike.radius_m = 0.5;
  spike.falloff = 0;
  spike.strength_m_per_s = 8;
  s.dab(spike, 0, 0, 1);  // a single sample at 18 m
  ASSERT_NEAR(s.groundHeight_m(0, 0), 18.0, 2e-3);
  ASSERT_NEAR(s.groundHeight_m(1, 0), 10.0, 2e-3);
  Brush smooth;
  smooth.kind = BrushKind::Smooth;
  smooth.radius_m = 3;
  smooth.falloff = 0;
  smooth.strength_m_per_s = 100;  // as far as the average in one dab
  auto sum = [&] {
    double total = 0;
    for (int z = -3; z <= 3; ++z)
      for (int x = -3; x <= 3; ++x) total += s.groundHeight_m(x, z) - 10.0;
    return total;
  };
  const double total = sum();
  s.dab(smooth, 0, 0, 1);
  EXPECT_NEAR(s.groundHeight_m(0, 0), 10.0 + 8.0 * 4 / 16, 2e-3);  // the centre weight of [1 2 1]^2 / 16
  EXPECT_NEAR(s.groundHeight_m(1, 0), 10.0 + 8.0 * 2 / 16, 2e-3);
  EXPECT_NEAR(sum(), total, 0.01);
  // Noise: up and down, the same for the same seed, other for another.
  DesignDocument n1 = flatDoc(65, 1.0, 10.0), n2 = flatDoc(65, 1.0, 10.0), n3 = flatDoc(65, 1.0, 10.0);
  Brush noise;
  noise.kind = BrushKind::Noise;
  noise.radius_m = 12;
  noise.strength_m_per_s = 2;
  noise.seed = 5;
  n1.dab(noise, 0, 0, 1);
  n2.dab(noise, 0, 0, 1);
  noise.seed = 6;
  n3.dab(noise, 0, 0, 1);
  EXPECT_EQ(n1.contentHash(), n2.contentHash());
  EXPECT_NE(n1.contentHash(), n3.contentHash());
  const terrain::Aabb box = n1.terrain().bounds();
  EXPECT_LT(box.min.y(), 9.9);
  EXPECT_GT(box.max.y(), 10.1);
  expectTreeMatchesRebuild(n1.terrain());
}

TEST(DesignBrush, RidgeAndDitchAlongALine) {
  DesignDocument d = flatDoc(129, 1.0, 20.0);
  const terrain::HeightMap before = d.terrain().heights();
  const SampleRect r = d.line(true, Vec2(-30, 0), Vec2(30, 0), 8, 5);
  EXPECT_EQ(r, diffRect(before, d.terrain().heights()));
  EXPECT_NEAR(d.groundHeight_m(0, 0), 25.0, 2e-3);
  EXPECT_NEAR(d.groundHeight_m(-30, 0), 25.0, 2e-3) << "the crest runs to the end";
  EXPECT_NEAR(d.groundHeight_m(0, 2), 20 + 5 * 0.75 * 0.75, 2e-3);  // on a sample, u = 0.5: (1 - 0.25)^2
  EXPECT_NEAR(d.groundHeight_m(0, 4), 20.0, 2e-3) << "the foot";
  expectTreeMatchesRebuild(d.terrain());
  d.line(false, Vec2(0, -30), Vec2(0, 30), 6, 3);
  EXPECT_NEAR(d.groundHeight_m(0, 20), 17.0, 2e-3) << "ditch";
  EXPECT_NEAR(d.groundHeight_m(0, 0), 22.0, 2e-3) << "the ditch cuts through the ridge";
}

// ---- painting ----------------------------------------------------------------------------

TEST(DesignPaint, PhysicsReadsThePaintedFrictionAndSoftnessAtOnce) {
  DesignDocument d = flatDoc(65, 1.0, 0.0);
  TerrainHeightField field(d.terrain());
  EXPECT_NEAR(field.frictionAt(3.2, 4.1), 0.6, 1e-6) << "a new flat map is grass";
  EXPECT_NEAR(field.softnessAt(3.2, 4.1), 0.4, 1e-6);
  const Surface* mud = findSurface("mud");
  ASSERT_NE(mud, nullptr);
  const SampleRect r = d.paint(*mud, 3, 4, 2.5);
  ASSERT_FALSE(r.empty());
  EXPECT_NEAR(field.frictionAt(3.2, 4.1), 0.3, 1e-6);
  EXPECT_NEAR(field.softnessAt(3.2, 4.1), 0.7, 1e-6);
  EXPECT_NEAR(field.frictionAt(3 + 4, 4), 0.6, 1e-6) << "outside the radius";
  const terrain::MaterialMaps& m = *d.terrain().materials();
  int bi, bj;
  d.terrain().blockAt(3.2, 4.1, bi, bj);
  EXPECT_EQ(m.get(terrain::MaterialLayer::Texture, bi, bj), mud->material.texture);
  EXPECT_EQ(m.get(terrain::MaterialLayer::Sound, bi, bj), std::uint8_t(terrain::SurfaceSound::Mud));
  // Every block painted lies inside the rectangle returned (its corner samples).
  for (int j = 0; j < m.blocksZ(); ++j)
    for (int i = 0; i < m.blocksX(); ++i)
      if (m.get(terrain::MaterialLayer::Friction, i, j) == 30) {
        EXPECT_TRUE(i >= r.i0 && i + 1 <= r.i1 && j >= r.j0 && j + 1 <= r.j1) << i << "," << j;
      }
  for (const char* name : {"grass", "rock", "sand", "mud", "snow", "asphalt", "gravel"})
    EXPECT_NE(findSurface(name), nullptr) << name;
}

// ---- objects -----------------------------------------------------------------------------

TEST(DesignObjects, PlacedOnTheGroundMovedDuplicatedRemoved) {
  DesignDocument d = flatDoc(129, 1.0, 10.0);
  Brush b;
  b.radius_m = 10;
  b.falloff = 0;
  b.strength_m_per_s = 5;
  d.dab(b, 20, 20, 1);  // a 5 m plateau
  PlacedObject tree;
  tree.kind = PlacedKind::Model;
  tree.asset = "base:assets/models/tree.obj";
  tree.position_m = Vec3(20, 999, 20);  // y is the document's to decide
  const std::uint32_t a = d.addObject(tree);
  ASSERT_NE(a, 0u);
  EXPECT_NEAR(d.objects().at(a).position_m.y(), 15.0, 2e-3);
  PlacedObject moved = d.objects().at(a);
  moved.position_m = Vec3(-20, 0, 0);
  EXPECT_TRUE(d.moveObject(a, moved));
  EXPECT_NEAR(d.objects().at(a).position_m.y(), 10.0, 2e-3);
  const std::uint32_t c = d.duplicateObject(a);
  ASSERT_NE(c, 0u);
  EXPECT_NE(c, a);
  EXPECT_EQ(d.objects().at(c), d.objects().at(a));
  EXPECT_TRUE(d.removeObject(a));
  EXPECT_EQ(d.objects().count(a), 0u);
  EXPECT_FALSE(d.removeObject(a));
  EXPECT_EQ(d.duplicateObject(12345), 0u);
  PlacedObject bad = tree;
  bad.scale = Vec3(1, 0, 1);
  EXPECT_EQ(d.addObject(bad), 0u);
  bad = tree;
  bad.position_m.x() = std::nanf("");
  EXPECT_EQ(d.addObject(bad), 0u);
  d.setStart(Vec3(20, -3, 20), 1.0);
  EXPECT_NEAR(d.start().position_m.y(), 15.0, 2e-3);
  EXPECT_DOUBLE_EQ(d.start().heading_rad, 1.0);
}

// Objects and the start stay on the ground when it is brushed or cut under
// them later, and undo and redo put them back with the ground.
TEST(DesignObjects, ObjectsAndTheStartFollowTheGroundBrushedUnderThem) {
  DesignDocument d = flatDoc(129, 1.0, 10.0);
  PlacedObject tree;
  tree.kind = PlacedKind::Model;
  tree.asset = "base:assets/models/tree.obj";
  tree.position_m = Vec3(20, 0, 20);
  const std::uint32_t id = d.addObject(tree);
  ASSERT_NE(id, 0u);
  d.setStart(Vec3(-30, 0, 0), 0.0);
  Brush b;
  b.radius_m = 10;
  b.falloff = 0;
  b.strength_m_per_s = 5;
  d.dab(b, 20, 20, 1);  // a 5 m plateau under the tree
  EXPECT_NEAR(d.objects().at(id).position_m.y(), d.groundHeight_m(20, 20), 1e-4);
  EXPECT_NEAR(d.objects().at(id).position_m.y(), 15.0, 2e-3);
  d.line(false, Vec2(-40, 0), Vec2(-20, 0), 6, 2);  // a 2 m ditch along the start
  EXPECT_NEAR(d.start().position_m.y(), d.groundHeight_m(-30, 0), 1e-4);
  EXPECT_LT(d.start().position_m.y(), 9.0);
  ASSERT_TRUE(d.undo());
  EXPECT_NEAR(d.start().position_m.y(), 10.0, 2e-3) << "the ditch undone";
  ASSERT_TRUE(d.undo());
  EXPECT_NEAR(d.objects().at(id).position_m.y(), 10.0, 2e-3) << "the plateau undone";
  ASSERT_TRUE(d.redo());
  EXPECT_NEAR(d.objects().at(id).position_m.y(), 15.0, 2e-3) << "the plateau again";
}

// ---- undo ------------------------------------------------------------------------------------

TEST(DesignUndo, EveryEditUndoesAndRedoesBitIdentically) {
  DesignDocument d = flatDoc(257, 1.0, 30.0);
  std::vector<std::uint64_t> hashes{d.contentHash()};
  std::uint64_t rng = 7;
  auto u = [&] { return double(splitmix64(rng) >> 11) * 0x1.0p-53; };
  Brush b;
  for (int step = 0; step < 35; ++step) {
    const double x = -120 + 240 * u(), z = -120 + 240 * u();
    switch (step % 7) {
      case 0:  // a stroke of dabs of every kind
        d.beginStroke();
        for (int k = 0; k < 8; ++k) {
          b.kind = BrushKind(k % 5);
          b.radius_m = 3 + 15 * u();
          b.strength_m_per_s = 1 + 5 * u();
          b.flattenHeight_m = 25;
          b.falloff = u();
          d.dab(b, x + 3 * k, z, 1.0 / 60);
        }
        d.endStroke();
        break;
      case 1: d.line(step % 4 == 1, Vec2(x, z), Vec2(z, x), 4 + 6 * u(), 2 + 3 * u()); break;
      case 2: d.paint(surfacePalette()[1 + std::size_t(step / 6) % (surfacePalette().size() - 1)], x, z, 2 + 10 * u()); break;
      case 3: {
        PlacedObject o;
        o.kind = PlacedKind::Box;
        o.position_m = Vec3(Real(x), 0, Real(z));
        d.addObject(o);
        break;
      }
      case 4:
        if (!d.objects().empty()) {
          PlacedObject o = d.objects().begin()->second;
          o.position_m.x() += 3;
          d.moveObject(d.objects().begin()->first, o);
        } else {
          d.setStart(Vec3(Real(x), 0, Real(z)), 0.5);
        }
        break;
      case 5: d.setVehicle("base:car" + std::to_string(step)); break;
      case 6: ASSERT_TRUE(d.setSky({24 * u(), step % 2 ? "storm" : "cloudy", u()})); break;
    }
    hashes.push_back(d.contentHash());
    ASSERT_NE(hashes.back(), hashes[hashes.size() - 2]) << "step " << step << " changed nothing";
  }
  for (std::size_t k = hashes.size() - 1; k > 0; --k) {
    ASSERT_TRUE(d.undo());
    ASSERT_EQ(d.contentHash(), hashes[k - 1]) << "undo back to state " << k - 1;
  }
  EXPECT_FALSE(d.undo());
  expectTreeMatchesRebuild(d.terrain());
  for (std::size_t k = 1; k < hashes.size(); ++k) {
    ASSERT_TRUE(d.redo());
    ASSERT_EQ(d.contentHash(), hashes[k]) << "redo to state " << k;
  }
  EXPECT_FALSE(d.redo());
  expectTreeMatchesRebuild(d.terrain());
  // A new edit after an undo drops the redo steps.
  d.undo();
  d.addObject(PlacedObject{});
  EXPECT_FALSE(d.canRedo());
}

TEST(DesignSky, OutOfRangeValuesAreRefusedNamingTheFieldAndChangeNothing) {
  DesignDocument d = flatDoc(33, 1.0, 5.0);
  const std::uint64_t before = d.contentHash();
  for (const auto& [sky, field] : std::vector<std::pair<DesignSky, std::string>>{
           {{24.5, "clear", 0.5}, "sky.time_of_day_h"},
           {{std::nan(""), "clear", 0.5}, "sky.time_of_day_h"},
           {{12, "fog", 0.5}, "sky.weather"},
           {{12, "clear", 1.5}, "sky.clouds"},
           {{12, "clear", std::numeric_limits<double>::infinity()}, "sky.clouds"}}) {
    EXPECT_NE(checkSky(sky).find(field), std::string::npos) << checkSky(sky);
    EXPECT_FALSE(d.setSky(sky)) << field;
  }
  EXPECT_EQ(d.contentHash(), before);
  EXPECT_FALSE(d.canUndo());
  EXPECT_EQ(d.sky(), DesignSky{});
  EXPECT_TRUE(checkSky({0, "storm", 0}).empty());
  EXPECT_TRUE(checkSky({24, "cloudy", 1}).empty());
}

TEST(DesignUndo, AStrokeKeepsOnlyWhatItTouchedAndTheBudgetDropsTheOldest) {
  DesignDocument d = flatDoc(1025, 1.0, 30.0);
  Brush b;
  b.radius_m = 5;
  b.falloff = 0;
  b.strength_m_per_s = 1;
  d.beginStroke();
  for (int k = 0; k < 10; ++k) d.dab(b, -300 + k * 0.5, 200, 0.1);
  d.endStroke();
  // The stroke changed samples in a box about 16 x 11 samples: before and
  // after, 2 bytes each, plus bookkeeping; far from the 2 MiB of the map.
  // (Every stroke here lies inside one 32 x 32 undo tile, so all keep the
  // same number of bytes.)
  const std::size_t oneStroke = d.undoBytes();
  EXPECT_GT(oneStroke, 16u * 11u * 4u / 2u);
  EXPECT_LT(oneStroke, 4096u) << "a small stroke on a 1025^2 map";
  // A budget of five such strokes: after twenty, only the newest five remain.
  d.setUndoBudget(5 * oneStroke + oneStroke / 2);
  std::vector<std::uint64_t> hashes{d.contentHash()};
  for (int s = 0; s < 20; ++s) {
    d.beginStroke();
    for (int k = 0; k < 10; ++k) d.dab(b, 32 * s - 467 + k * 0.5, -80, 0.1);
    d.endStroke();
    hashes.push_back(d.contentHash());
    EXPECT_LE(d.undoBytes(), d.undoBudget());
  }
  int undone = 0;
  while (d.undo()) ++undone;
  EXPECT_EQ(undone, 5);
  EXPECT_EQ(d.contentHash(), hashes[15]) << "the state after stroke 15: older steps were dropped, not mixed";
  // One step bigger than the budget is still kept (the last edit can be undone).
  d.setUndoBudget(16);
  d.beginStroke();
  d.dab(b, 0, 0, 1);
  d.endStroke();
  EXPECT_TRUE(d.canUndo());
  const std::uint64_t after = d.contentHash();
  d.undo();
  EXPECT_NE(d.contentHash(), after);
}

}  // namespace tumble::app
