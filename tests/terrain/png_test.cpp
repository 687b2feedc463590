// Height-map PNG I/O: exact 16-bit round trips, 8-bit and RGB input, and
// clear errors (never a crash) for broken files.
#include <gtest/gtest.h>

#include <fstream>

#include "core/file_util.h"
#include "terrain/generators.h"
#include "terrain/height_map.h"
#include "terrain/png_io.h"
#include "terrain/terrain.h"
#include "test_util.h"

using namespace tumble;
using namespace tumble::terrain;
using namespace tumble::terrain::test;

namespace {

HeightMap noiseMap(int w, int h, std::uint64_t seed) {
  HeightMap m(w, h);
  Rng rng(seed);
  for (auto& v : m.samples()) v = std::uint16_t(rng.next() & 0xffff);
  m.set(0, 0, 0);
  m.set(w - 1, h - 1, 65535);
  return m;
}

std::vector<std::uint8_t> validPng() {
  auto png = encodeHeightMapPng(generatePlasma(64, 48, {5, 0.5}));
  EXPECT_TRUE(png.ok());
  return *png;
}

}  // namespace

TEST(HeightMapPng, SixteenBitRoundTripIsExactForNonSquareMaps) {
  for (auto [w, h] : {std::pair{37, 23}, std::pair{2, 2}, std::pair{257, 129}, std::pair{5, 300}}) {
    const HeightMap original = noiseMap(w, h, std::uint64_t(w * 1000 + h));
    const std::string path = tempFile("rt_" + std::to_string(w) + "x" + std::to_string(h) + ".png");
    ASSERT_TRUE(saveHeightMapPng(original, path).ok());
    auto loaded = loadHeightMapPng(path);
    ASSERT_TRUE(loaded.ok()) << loaded.error();
    EXPECT_EQ(loaded->width(), w);
    EXPECT_EQ(loaded->height(), h);
    EXPECT_TRUE(*loaded == original) << w << "x" << h;
  }
}

TEST(HeightMapPng, EightBitGreyIsWidenedBy257) {
  std::vector<std::uint8_t> grey(6 * 4);
  for (std::size_t k = 0; k < grey.size(); ++k) grey[k] = std::uint8_t(k * 11);
  grey.back() = 255;
  auto png = encodePngGrey8(grey.data(), 6, 4);
  ASSERT_TRUE(png.ok());
  auto map = decodeHeightMapPng(*png, "grey8.png");
  ASSERT_TRUE(map.ok()) << map.error();
  ASSERT_EQ(map->width(), 6);
  ASSERT_EQ(map->height(), 4);
  for (std::size_t k = 0; k < grey.size(); ++k) EXPECT_EQ(map->samples()[k], grey[k] * 257);
  EXPECT_EQ(map->at(5, 3), 65535);
}

TEST(HeightMapPng, RgbIsReducedToLuminance) {
  // white, red, green, blue, mid grey, black
  const std::vector<std::uint8_t> rgb = {255, 255, 255, 255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128, 0, 0, 0};
  auto png = encodePngRgb8(rgb.data(), 3, 2);
  ASSERT_TRUE(png.ok());
  auto map = decodeHeightMapPng(*png, "rgb.png");
  ASSERT_TRUE(map.ok()) << map.error();
  EXPECT_EQ(map->at(0, 0), 65535);                     // white stays white
  EXPECT_NEAR(map->at(1, 0) / 65535.0, 0.2126, 0.003);  // Rec.709 weights
  EXPECT_NEAR(map->at(2, 0) / 65535.0, 0.7152, 0.003);
  EXPECT_NEAR(map->at(0, 1) / 65535.0, 0.0722, 0.003);
  EXPECT_EQ(map->at(1, 1), 128 * 257);                  // grey stays grey
  EXPECT_EQ(map->at(2, 1), 0);
  // importImage8 gives the same answer from raw pixels.
  EXPECT_TRUE(importImage8(rgb.data(), 3, 2, 3) == *map);
}

TEST(HeightMapPng, TruncatedFileNamesTheFileAndTheProblem) {
  std::vector<std::uint8_t> png = validPng();
  for (std::size_t keep : {std::size_t(8), std::size_t(20), std::size_t(40), png.size() / 2, png.size() - 13}) {
    std::vector<std::uint8_t> cut(png.begin(), png.begin() + std::ptrdiff_t(keep));
    const std::string path = tempFile("truncated.png");
    ASSERT_TRUE(writeFileAtomic(path, cut.data(), cut.size()).ok());
    auto map = loadHeightMapPng(path);
    ASSERT_FALSE(map.ok()) << "kept " << keep << " bytes";
    EXPECT_NE(map.error().find(path), std::string::npos) << map.error();
    EXPECT_NE(map.error().find("truncated"), std::string::npos) << map.error();
  }
}

TEST(HeightMapPng, NonPngAndEmptyFilesGiveClearErrors) {
  const std::string text = tempFile("notes.png");
  ASSERT_TRUE(writeFileAtomic(text, std::string("this is not an image\n")).ok());
  auto a = loadHeightMapPng(text);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.error().find("not a PNG file"), std::string::npos) << a.error();
  EXPECT_NE(a.error().find(text), std::string::npos);

  const std::string empty = tempFile("empty.png");
  ASSERT_TRUE(writeFileAtomic(empty, std::string()).ok());
  auto b = loadHeightMapPng(empty);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.error().find("empty"), std::string::npos) << b.error();

  auto c = loadHeightMapPng(tempFile("does_not_exist.png"));
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().find("does_not_exist.png"), std::string::npos);
}

TEST(HeightMapPng, WrongSizesAreRefusedWithTheValidRange) {
  std::vector<std::uint8_t> wide(4098 * 2, 7);
  auto tooWide = decodeHeightMapPng(*encodePngGrey8(wide.data(), 4098, 2), "wide.png");
  ASSERT_FALSE(tooWide.ok());
  EXPECT_NE(tooWide.error().find("4097"), std::string::npos) << tooWide.error();

  std::vector<std::uint8_t> thin(1 * 5, 7);
  auto tooThin = decodeHeightMapPng(*encodePngGrey8(thin.data(), 1, 5), "thin.png");
  ASSERT_FALSE(tooThin.ok());
  EXPECT_NE(tooThin.error().find("thin.png"), std::string::npos);
  EXPECT_NE(tooThin.error().find("between 2 and 4097"), std::string::npos) << tooThin.error();
}

TEST(HeightMapPng, CorruptedBytesNeverCrash) {
  // Flip bytes all over a valid file: every result must be a value or an
  // error, never a crash (CRC errors, bad chunk lengths, bad zlib data).
  const std::vector<std::uint8_t> png = validPng();
  Rng rng(99);
  int errors = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<std::uint8_t> bad = png;
    const int flips = 1 + int(rng.next() % 4);
    for (int f = 0; f < flips; ++f) bad[8 + rng.next() % (bad.size() - 8)] ^= std::uint8_t(1 + rng.next() % 255);
    auto map = decodeHeightMapPng(bad, "fuzz.png");
    if (!map.ok()) {
      ++errors;
      EXPECT_EQ(map.error().rfind("fuzz.png", 0), 0u) << map.error();
    }
  }
  EXPECT_GT(errors, 300);  // CRCs catch nearly every flip
}

TEST(HeightMapPng, SidecarSetsSpacingAndScale) {
  const std::string path = tempFile("with_sidecar.png");
  ASSERT_TRUE(saveHeightMapPng(HeightMap(9, 5, 1000), path).ok());
  ASSERT_TRUE(writeFileAtomic(path + ".json",
                              std::string(R"({"spacing_m": 2.5, "height_scale_m": 0.05, "base_height_m": -10,
                                              "origin_x_m": 100, "origin_z_m": -40})"))
                  .ok());
  auto t = Terrain::loadPng(path);
  ASSERT_TRUE(t.ok()) << t.error();
  EXPECT_DOUBLE_EQ(t->desc().spacing_m, 2.5);
  EXPECT_FLOAT_EQ(t->heightAt(100 + 2.5f * 3, -40 + 2.5f * 2), -10 + 1000 * 0.05f);
  const Vec3 corner = t->samplePosition(8, 4);
  EXPECT_FLOAT_EQ(corner.x(), 120.0f);
  EXPECT_FLOAT_EQ(corner.z(), -30.0f);

  auto typo = parseTerrainDesc(R"({"spacing": 2})", "x.png.json");
  ASSERT_FALSE(typo.ok());
  EXPECT_NE(typo.error().find("unknown field \"spacing\""), std::string::npos) << typo.error();
  EXPECT_NE(typo.error().find("spacing_m"), std::string::npos);
  EXPECT_FALSE(parseTerrainDesc(R"({"spacing_m": -1})", "x.png.json").ok());
  EXPECT_FALSE(parseTerrainDesc(R"({"height_scale_m": "big"})", "x.png.json").ok());
  EXPECT_FALSE(parseTerrainDesc("{not json", "x.png.json").ok());
  auto roundTrip = parseTerrainDesc(terrainDescToJson({3, 0.02, 5, 6, 7}), "rt.json");
  ASSERT_TRUE(roundTrip.ok());
  EXPECT_DOUBLE_EQ(roundTrip->heightScale_m, 0.02);
  EXPECT_DOUBLE_EQ(roundTrip->originZ_m, 7);
}

TEST(HeightMapPng, RealThirdPartyMapLoads) {
  // wm_height_out.png from the BeamNG heightmap-roads tutorial (see readme.txt).
  const std::string path = sharedDir() + "/assets/third_party/heightmaps/wm_height_out.png";
  auto t = Terrain::loadPng(path);
  ASSERT_TRUE(t.ok()) << t.error();
  EXPECT_EQ(t->heights().width(), 512);
  EXPECT_EQ(t->heights().height(), 512);
  const auto [lo, hi] = std::minmax_element(t->heights().samples().begin(), t->heights().samples().end());
  EXPECT_LT(*lo, *hi);                 // real relief, not a flat image
  EXPECT_EQ(*hi % 257, 0);             // it is 8-bit, widened by 257
  // The tree bounds it and a vertical ray finds the surface at heightAt.
  const auto hit = t->rayCast(Vec3(200.5f, 1000, 300.25f), Vec3(0, -1, 0), 2000);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->point.y(), t->heightAt(200.5f, 300.25f), 1e-3);
}
