// Materials painted on generated terrain follow the land's shape, and the
// friction physics reads through the drag map follows the materials.
#include <gtest/gtest.h>

#include "app/terrain_scene.h"
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
