// The look of ropes, cloth and rag-dolls, from the scene's snapshot to the
// picture: a rope is a chain of lit capsules of its own thickness (wider
// than a pixel, brighter on the side towards the sun), a cloth is a filled
// surface lit on both sides, a rag-doll's parts carry skin, shirt and
// trouser colours.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "../render/render_test_util.h"
#include "app/scene.h"

namespace tumble::app {
namespace {

std::unique_ptr<Scene> lookScene() {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  SceneOptions options;
  options.scenarioRef = "good:look_materials";
  options.modDirs = {std::string(source ? source : ".") + "/tests/app/mods"};
  auto scene = Scene::create(options);
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error());
  if (!scene.ok()) return nullptr;
  (*scene)->host().start();
  (*scene)->savePreviousState();
  return std::move(*scene);
}

const Eigen::Vector3f kRopeColor(0.9f, 0.6f, 0.2f), kClothColor(0.8f, 0.15f, 0.1f);

TEST(LookSnapshot, ARopeIsOneCapsuleOfItsRadiusPerSegmentAndClothIsASurface) {
  auto scene = lookScene();
  ASSERT_TRUE(scene);
  render::FrameSnapshot frame;
  scene->snapshot(frame, 1.0);
  int segments = 0;
  for (const render::DrawShape& s : frame.shapes) {
    if (s.color != kRopeColor) continue;
    ++segments;
    EXPECT_EQ(s.kind, render::ShapeKind::Capsule);
    EXPECT_FLOAT_EQ(s.radius_m, 0.02f) << "the rope's collision radius (default)";
    EXPECT_NEAR(2 * s.halfHeight_m, 0.2f, 1e-4f) << "2 m in 10 segments, not yet sagging";
    // Local Y along the rope (X).
    EXPECT_NEAR(std::abs((s.orientation * Eigen::Vector3f::UnitY()).x()), 1.0f, 1e-5f);
  }
  EXPECT_EQ(segments, 10);
  ASSERT_EQ(frame.surfaces.size(), 1u);
  EXPECT_EQ(frame.surfaces[0].positions.size(), 8u * 6u);
  EXPECT_EQ(frame.surfaces[0].indices.size(), 7u * 5u * 6u) << "two triangles per grid cell";
  EXPECT_EQ(frame.surfaces[0].color, kClothColor);
  for (const render::DebugLine& l : frame.lines) EXPECT_NE(l.color, kRopeColor) << "no rope lines any more";
}

TEST(LookSnapshot, RagdollPartsWearSkinShirtAndTrousers) {
  auto scene = lookScene();
  ASSERT_TRUE(scene);
  render::FrameSnapshot frame;
  scene->snapshot(frame, 1.0);
  // The doll lies around x = 6: its 11 parts.
  const Eigen::Vector3f skin(0.80f, 0.52f, 0.38f), shirt(0.1f, 0.6f, 0.2f), trousers(0.16f, 0.17f, 0.22f);
  int skins = 0, shirts = 0, trouserParts = 0, other = 0;
  for (const render::DrawShape& s : frame.shapes) {
    if (s.position.x() < 4) continue;
    if (s.color.isApprox(skin, 1e-5f)) ++skins;
    else if (s.color.isApprox(shirt, 1e-5f)) ++shirts;
    else if (s.color.isApprox(trousers, 1e-5f)) ++trouserParts;
    else ++other;
  }
  EXPECT_EQ(skins, 3) << "head and two forearms";
  EXPECT_EQ(shirts, 3) << "torso and two upper arms, in the shirt colour the scenario gave";
  EXPECT_EQ(trouserParts, 5) << "pelvis and four leg parts";
  EXPECT_EQ(other, 0);
}

class LookPicture : public ::testing::Test {
 protected:
  static constexpr int kWidth = 640, kHeight = 480;
  void SetUp() override {
    m_scene = lookScene();
    ASSERT_TRUE(m_scene);
    m_renderer = render::test::makeOffscreenRenderer(kWidth, kHeight, /*hud=*/false);
    ASSERT_NE(m_renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
  }
  render::test::Image shot(const Eigen::Vector3f& target, float yaw_rad, float distance_m, const std::string& name) {
    render::Camera& camera = m_renderer->camera();
    camera.target = target;
    camera.yaw_rad = yaw_rad;
    camera.pitch_rad = 0;
    camera.distance_m = distance_m;
    render::FrameSnapshot frame;
    m_scene->snapshot(frame, 1.0);
    render::Controls controls;
    const std::string path = m_scratch.file(name);
    const Status st = m_renderer->drawFrame(frame, render::HudStats{}, controls, path.c_str());
    EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.error());
    return render::test::loadPng(path);
  }
  render::test::ScratchDir m_scratch;
  std::unique_ptr<Scene> m_scene;
  std::unique_ptr<render::Renderer> m_renderer;
};

// Orange: red well above blue (the rope), whatever the shading.
bool isRopeOrange(const std::uint8_t* p) { return p[0] > 60 && p[0] > p[2] + 40 && p[1] > p[2] + 10; }

TEST_F(LookPicture, ARopeIsATubeWiderThanAPixelAndBrighterTowardsTheSun) {
  // The rope's middle straight ahead, 5 m away: 2 cm of radius is
  // 4 cm / (2 tan(0.5) 5 m / 480 px) = 3.5 px across.
  const render::test::Image image = shot({0, 1.5f, 3}, 0, 5, "rope.png");
  ASSERT_EQ(image.width, kWidth);
  const int x = kWidth / 2;
  std::vector<int> rows;
  for (int y = 0; y < kHeight; ++y)
    if (isRopeOrange(image.at(x, y))) rows.push_back(y);
  ASSERT_GE(rows.size(), 3u) << "wider than a 1-pixel line";
  EXPECT_LE(rows.size(), 6u) << "and no wider than its thickness";
  EXPECT_EQ(rows.back() - rows.front() + 1, int(rows.size())) << "one run of pixels";
  // The sun is up and ahead: the tube's top is lit, its underside only by the sky.
  auto brightness = [&](int y) { return int(image.at(x, y)[0]) + image.at(x, y)[1] + image.at(x, y)[2]; };
  EXPECT_GT(brightness(rows.front()), brightness(rows.back()) + 30) << "shaded like a tube, not a flat line";
}

TEST_F(LookPicture, ClothIsAFilledSurfaceLitOnBothSides) {
  // The cloth hangs 2 m wide, 1.5 m tall around (-6, 2.25, -2); seen from
  // +Z (its sunny side) and from -Z (its shaded side), 4 m away.
  const Eigen::Vector3f centre(-6, 2.25f, -2);
  const render::test::Image front = shot(centre, 0, 4, "front.png");
  const render::test::Image back = shot(centre, 3.14159265f, 4, "back.png");
  // 2 m x 1.5 m at 4 m (4.37 m of view over 480 px): about 220 x 165 px;
  // the middle 180 x 120 px is all cloth.
  auto isCloth = [](int r, int g, int b) { return r > 25 && r > g + 15 && r > b + 15; };
  const int x0 = kWidth / 2 - 90, x1 = kWidth / 2 + 90, y0 = kHeight / 2 - 60, y1 = kHeight / 2 + 60;
  const int area = (x1 - x0) * (y1 - y0);
  EXPECT_GT(render::test::countPixels(front, isCloth, x0, y0, x1, y1), area * 98 / 100) << "filled from the front";
  EXPECT_GT(render::test::countPixels(back, isCloth, x0, y0, x1, y1), area * 98 / 100) << "filled from behind";
  // Each side by its own normal: the side the sun faces is brighter.
  auto meanRed = [&](const render::test::Image& image) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) sum += image.at(x, y)[0];
    return sum / area;
  };
  EXPECT_GT(meanRed(front), meanRed(back) + 20) << "the sunny side is lit, the other side by the sky only";
  EXPECT_GT(meanRed(back), 25) << "the shaded side is still lit by the sky, not black";
}

}  // namespace
}  // namespace tumble::app
