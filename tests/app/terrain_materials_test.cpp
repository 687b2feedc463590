// Materials painted on generated terrain follow the land's shape, and the
// friction physics reads through the drag map follows the materials.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "app/terrain_scene.h"
#include "physics/world.h"
#include "terrain/height_map.h"
#include "terrain/terrain.h"

namespace tumble::app {

TEST(TerrainMaterials, SteepIsRockHighIsSnowFlatIsGrassAndFrictionFollows) {
  // 65 x 65 samples, 1 m apart: flat at 0 m for x < 32, then a 45 degree
  // ramp up to 32 m (the top 15% of the height range is snow).
  terrain::HeightMap map(65, 65);
  terrain::TerrainDesc desc;
  desc.spacing_m = 1;
  desc.heightScale_m = 0.001;  // 1 mm per unit
  for (int j = 0; j < 65; ++j)
    for (int i = 0; i < 65; ++i) map.set(i, j, std::uint16_t(i < 32 ? 0 : (i - 32) * 1000));
  auto created = terrain::Terrain::create(std::move(map), desc);
  ASSERT_TRUE(created.ok()) << created.error();
  terrain::Terrain t = std::move(created.value());
  paintMaterials(t, false);
  ASSERT_NE(t.materials(), nullptr);
  const auto& texture = t.materials()->layer(terrain::MaterialLayer::Texture);
  auto at = [&](int bx, int bz) { return texture[std::size_t(bz) * 64 + bx]; };
  EXPECT_EQ(at(40, 10), 1) << "45 degree ramp: rock";
  EXPECT_EQ(at(63, 10), 1) << "the top of the ramp is steep too: rock wins over snow";
  int grassOrMud = 0;
  for (int bx = 0; bx < 31; ++bx) grassOrMud += at(bx, 40) == 0 || at(bx, 40) == 3;
  EXPECT_EQ(grassOrMud, 31) << "flat low ground: grass or mud";
  // Friction at a contact comes from the painted drag map.
  EXPECT_NEAR(t.frictionAt(Real(40.5), Real(10.5)), 0.8, 1e-6) << "rock";
  Real flat = t.frictionAt(Real(10.5), Real(40.5));
  EXPECT_TRUE(std::abs(flat - Real(0.6)) < 1e-6 || std::abs(flat - Real(0.3)) < 1e-6) << flat;
}

TEST(TerrainMaterials, HighFlatGroundIsSnow) {
  terrain::HeightMap map(33, 33);
  terrain::TerrainDesc desc;
  desc.heightScale_m = 0.001;
  // A low plain and a high plateau (flat, so not rock).
  for (int j = 0; j < 33; ++j)
    for (int i = 0; i < 33; ++i) map.set(i, j, std::uint16_t(i < 16 ? 0 : 10000));
  auto created = terrain::Terrain::create(std::move(map), desc);
  ASSERT_TRUE(created.ok());
  terrain::Terrain t = std::move(created.value());
  paintMaterials(t, false);
  const auto& texture = t.materials()->layer(terrain::MaterialLayer::Texture);
  EXPECT_EQ(texture[std::size_t(5) * 32 + 25], 4) << "high plateau: snow";
  EXPECT_NEAR(t.frictionAt(Real(25.5), Real(5.5)), 0.2, 1e-6) << "snow is slippery";
}

}  // namespace tumble::app

// Material layers painted by a designer beside a height-map image replace the
// painted ones: friction from "NAME.friction.png" reaches physics.
namespace tumble::app {

namespace {
std::filesystem::path freshDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("tumble_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}
}  // namespace

TEST(TerrainMaterials, LayerFilesBesideAHeightMapReplaceThePaintedLayers) {
  const auto dir = freshDir("layers");
  const std::string mapPath = (dir / "flat.png").string();
  terrain::HeightMap map(17, 9);  // flat: painted grass, mu 0.6 (or mud)
  ASSERT_TRUE(terrain::saveHeightMapPng(map, mapPath).ok());
  EXPECT_EQ(materialLayerPath(mapPath, terrain::MaterialLayer::Friction), (dir / "flat.friction.png").string());

  // The designer's drag map: mu 0.15 on the left half, 1.2 on the right.
  terrain::MaterialMaps painted(16, 8);
  for (int bz = 0; bz < 8; ++bz)
    for (int bx = 0; bx < 16; ++bx)
      painted.set(terrain::MaterialLayer::Friction, bx, bz, std::uint8_t(bx < 8 ? 15 : 120));
  ASSERT_TRUE(painted.saveLayerPng(terrain::MaterialLayer::Friction, (dir / "flat.friction.png").string()).ok());

  auto scene = TerrainScene::create({{"terrain.heightmap", mapPath}, {"terrain.spacing", "1"}});
  ASSERT_TRUE(scene.ok()) << scene.error();
  const physics::HeightField& field = scene.value()->heightField();
  // Centred on the origin: x from -8 to 8, z from -4 to 4.
  EXPECT_NEAR(field.frictionAt(Real(-6.5), Real(0.5)), 0.15, 1e-6);
  EXPECT_NEAR(field.frictionAt(Real(6.5), Real(-2.5)), 1.2, 1e-6);
  // Layers without a file keep their painted values (texture: grass or mud).
  const auto& texture = scene.value()->terrain().materials()->layer(terrain::MaterialLayer::Texture);
  EXPECT_TRUE(texture[0] == 0 || texture[0] == 3) << int(texture[0]);
  std::filesystem::remove_all(dir);
}

TEST(TerrainMaterials, ALayerFileOfTheWrongSizeIsAnErrorNamingItAndTheSizeExpected) {
  const auto dir = freshDir("badlayer");
  const std::string mapPath = (dir / "map.png").string();
  ASSERT_TRUE(terrain::saveHeightMapPng(terrain::HeightMap(17, 9), mapPath).ok());
  // One pixel per sample instead of per block: a common mistake.
  ASSERT_TRUE(terrain::MaterialMaps(17, 9).saveLayerPng(terrain::MaterialLayer::Bump, (dir / "map.bump.png").string()).ok());
  auto scene = TerrainScene::create({{"terrain.heightmap", mapPath}});
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.error().find("map.bump.png"), std::string::npos) << scene.error();
  EXPECT_NE(scene.error().find("16 x 8"), std::string::npos) << scene.error();
  std::filesystem::remove_all(dir);
}

// The drag map decides how far a sliding block goes: the
// same block at the same speed on grass (mu 0.64) and on mud (mu 0.16) of
// one terrain stops where Coulomb friction says, v0^2 / (2 mu g), with the
// pair coefficient sqrt(mu_block * mu_ground) (world.h) and mu_block = 1.
TEST(TerrainMaterials, DragMapSetsASlidingBlocksStoppingDistance) {
  terrain::HeightMap map(129, 65);  // flat, 0.5 m spacing: 64 x 32 m
  terrain::TerrainDesc desc;
  desc.spacing_m = 0.5;
  desc.originX_m = -32;
  desc.originZ_m = -16;
  auto created = terrain::Terrain::create(std::move(map), desc);
  ASSERT_TRUE(created.ok()) << created.error();
  terrain::Terrain t = std::move(created.value());
  terrain::MaterialMaps& m = t.createMaterials();
  for (int bz = 0; bz < m.blocksZ(); ++bz)
    for (int bx = 0; bx < m.blocksX(); ++bx)
      m.set(terrain::MaterialLayer::Friction, bx, bz, std::uint8_t(bz < 32 ? 64 : 16));  // z < 0: grass, z > 0: mud
  TerrainHeightField field(t);
  physics::World w;
  w.setHeightField(&field);
  const Real v0 = 6;
  auto slide = [&](Real z) {
    physics::BodyDef d;
    d.shape = physics::Shape::box(Vec3(Real(0.3), Real(0.2), Real(0.3)));
    d.position_m = Vec3(-25, Real(0.2), z);
    d.linearVelocity_mps = Vec3(v0, 0, 0);
    d.friction = 1;
    return w.createBody(d).value();
  };
  const physics::BodyId grass = slide(-8), mud = slide(8);
  for (int i = 0; i < 360; ++i) w.step(Real(1.0 / 60));
  for (auto [id, mu] : {std::pair{grass, 0.8}, std::pair{mud, 0.4}}) {
    const double dist = w.body(id).position_m.x() + 25;
    const double expected = v0 * v0 / (2 * mu * 9.80665);
    std::printf("mu %.2f: slid %.3f m, expected %.3f m (%+.2f%%)\n", mu, dist, expected, 100 * (dist / expected - 1));
    EXPECT_NEAR(dist, expected, 0.02 * expected);
    EXPECT_LT(w.body(id).linearVelocity_mps.norm(), 1e-3);
  }
}

}  // namespace tumble::app
