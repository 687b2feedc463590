// Material maps: one byte per block per layer, each an editable 8-bit PNG.
#include <gtest/gtest.h>

#include "core/file_util.h"
#include "terrain/material_map.h"
#include "terrain/png_io.h"
#include "test_util.h"

using namespace tumble;
using namespace tumble::terrain;
using namespace tumble::terrain::test;

TEST(MaterialMaps, DefaultsAndCompactStorage) {
  MaterialMaps m(64, 32);
  EXPECT_EQ(m.get(MaterialLayer::Friction, 10, 10), 60);
  EXPECT_DOUBLE_EQ(m.frictionCoefficient(10, 10), 0.6);
  EXPECT_EQ(m.get(MaterialLayer::Sound, 0, 0), std::uint8_t(SurfaceSound::Grass));
  EXPECT_EQ(m.bytes(), 64u * 32u * std::size_t(kMaterialLayerCount));  // one byte per block per layer
}

TEST(MaterialMaps, EachLayerRoundTripsThroughAn8BitPng) {
  MaterialMaps m(37, 21);
  for (int j = 0; j < 21; ++j)
    for (int i = 0; i < 37; ++i) {
      m.set(MaterialLayer::Texture, i, j, std::uint8_t(i * 7 + j));
      m.set(MaterialLayer::Bump, i, j, std::uint8_t(255 - i));
      m.set(MaterialLayer::Friction, i, j, std::uint8_t(j * 10));
      m.set(MaterialLayer::Sound, i, j, std::uint8_t((i + j) % 10));
    }
  MaterialMaps loaded(37, 21);
  for (int l = 0; l < kMaterialLayerCount; ++l) {
    const auto layer = MaterialLayer(l);
    const std::string path = tempFile(std::string("mat_") + materialLayerName(layer) + ".png");
    ASSERT_TRUE(m.saveLayerPng(layer, path).ok());
    ASSERT_TRUE(loaded.loadLayerPng(layer, path).ok());
    EXPECT_EQ(loaded.layer(layer), m.layer(layer)) << materialLayerName(layer);
  }
  EXPECT_DOUBLE_EQ(loaded.frictionCoefficient(3, 20), 2.0);
}

TEST(MaterialMaps, WrongSizeOrBrokenFileSaysWhatIsExpected) {
  MaterialMaps m(16, 8);
  std::vector<std::uint8_t> px(17 * 8, 1);
  const std::string path = tempFile("wrong_size_friction.png");
  auto png = encodePngGrey8(px.data(), 17, 8);
  ASSERT_TRUE(writeFileAtomic(path, png->data(), png->size()).ok());
  const Status s = m.loadLayerPng(MaterialLayer::Friction, path);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find(path), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("16 x 8"), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("friction"), std::string::npos) << s.error();
  EXPECT_EQ(m.get(MaterialLayer::Friction, 0, 0), 60);  // unchanged on error

  const Status broken = m.decodeLayerPng(MaterialLayer::Bump, {1, 2, 3}, "bump.png");
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.error().find("bump.png"), std::string::npos);
  EXPECT_FALSE(parseMaterialLayer("drag").ok());
  EXPECT_EQ(*parseMaterialLayer("sound"), MaterialLayer::Sound);
}
