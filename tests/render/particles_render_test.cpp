// Particle billboards on the offscreen driver: they show where the camera
// looks, alpha-blended ones are sorted back to front whatever order they come
// in, additive ones brighten what is behind them, and shapes in front hide
// them (depth test) while they never hide each other (no depth writes).
#include <gtest/gtest.h>

#include "render/internal/camera_math.h"
#include "render/internal/particles_pass.h"
#include "render/renderer.h"
#include "render_test_util.h"

namespace tumble::render {
namespace {

using test::countPixels;
using test::Image;
using test::isGreenish;
using test::isReddish;
using test::loadPng;

constexpr int kWidth = 320, kHeight = 240;

DrawParticle particle(const Eigen::Vector3f& p, const Eigen::Vector3f& rgb, float size, float alpha = 1) {
  DrawParticle q;
  q.position = p;
  q.size_m = size;
  q.color = Eigen::Vector4f(rgb.x(), rgb.y(), rgb.z(), alpha);
  return q;
}

class ParticlesRender : public ::testing::Test {
 protected:
  void SetUp() override {
    m_renderer = test::makeOffscreenRenderer(kWidth, kHeight, /*hud=*/false);
    ASSERT_NE(m_renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
    m_view = makeFrameView(m_renderer->camera(), float(kWidth) / kHeight);
  }
  Image render(const FrameSnapshot& frame, const std::string& name) {
    Controls controls;
    const std::string path = m_scratch.file(name);
    const Status status = m_renderer->drawFrame(frame, HudStats{}, controls, path.c_str());
    EXPECT_TRUE(status.ok()) << (status.ok() ? "" : status.error());
    return loadPng(path);
  }
  const std::uint8_t* centre(const Image& image) { return image.at(kWidth / 2, kHeight / 2); }

  test::ScratchDir m_scratch;
  std::unique_ptr<Renderer> m_renderer;
  FrameView m_view;
};

TEST_F(ParticlesRender, ACloudOfParticlesShowsWhereTheCameraLooks) {
  const Image sky = render(FrameSnapshot{}, "sky.png");
  EXPECT_EQ(countPixels(sky, isReddish), 0);
  FrameSnapshot frame;
  const Eigen::Vector3f t = m_renderer->camera().target;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      frame.particles.push_back(particle(t + 0.4f * (float(i) * m_view.right + float(j) * m_view.up), {0.9f, 0.05f, 0.05f}, 0.6f));
  const Image image = render(frame, "cloud.png");
  // 2.2 m across at 14 m with a 1 rad field of view: ~40 px wide, soft edges.
  EXPECT_GT(countPixels(image, isReddish), 400);
  EXPECT_EQ(countPixels(image, isReddish, 0, 0, kWidth, kHeight / 3), 0) << "all of it near the centre";
  const std::uint8_t* p = centre(image);
  EXPECT_TRUE(isReddish(p[0], p[1], p[2])) << int(p[0]) << " " << int(p[1]) << " " << int(p[2]);
}

TEST_F(ParticlesRender, AlphaBlendedParticlesAreSortedBackToFront) {
  const Eigen::Vector3f t = m_renderer->camera().target;
  const DrawParticle nearGreen = particle(t - 2.0f * m_view.forward, {0.05f, 0.9f, 0.05f}, 1.0f, 0.9f);
  const DrawParticle farRed = particle(t + 2.0f * m_view.forward, {0.9f, 0.05f, 0.05f}, 4.0f, 0.9f);
  // Given near first: drawn unsorted, the far red one would cover it.
  FrameSnapshot frame;
  frame.particles = {nearGreen, farRed};
  const Image a = render(frame, "near_first.png");
  frame.particles = {farRed, nearGreen};
  const Image b = render(frame, "far_first.png");
  for (const Image* image : {&a, &b}) {
    const std::uint8_t* p = centre(*image);
    EXPECT_TRUE(isGreenish(p[0], p[1], p[2])) << "the near particle is in front: " << int(p[0]) << " " << int(p[1])
                                              << " " << int(p[2]);
  }
  EXPECT_TRUE(a.rgb == b.rgb) << "the input order does not matter";
  // No depth writes: the far particle still shows around the smaller near one.
  EXPECT_GT(countPixels(a, isReddish), 50);
}

TEST_F(ParticlesRender, AdditiveParticlesBrightenAndShapesInFrontHideParticles) {
  const Eigen::Vector3f t = m_renderer->camera().target;
  const Image sky = render(FrameSnapshot{}, "sky.png");
  FrameSnapshot glow;
  glow.additiveParticles.push_back(particle(t, {0.8f, 0.5f, 0.1f}, 1.0f));
  const Image lit = render(glow, "glow.png");
  const std::uint8_t* s = centre(sky);
  const std::uint8_t* l = centre(lit);
  EXPECT_GT(int(l[0]), int(s[0]) + 20) << "additive light adds to the red channel";
  EXPECT_GE(int(l[2]), int(s[2]) - 2) << "and takes nothing away";
  // A box between the camera and a red particle hides it.
  FrameSnapshot hidden;
  DrawShape box;
  box.kind = ShapeKind::Box;
  box.position = t - 3.0f * m_view.forward;
  box.halfExtents = Eigen::Vector3f::Constant(1.0f);
  box.color = {0.2f, 0.2f, 0.9f};
  hidden.shapes.push_back(box);
  hidden.particles.push_back(particle(t + 1.0f * m_view.forward, {0.9f, 0.05f, 0.05f}, 1.0f));
  const Image behind = render(hidden, "behind_box.png");
  EXPECT_EQ(countPixels(behind, isReddish), 0) << "the depth test hides particles behind shapes";
}

TEST(ParticlesSort, FarthestAlongTheViewComesFirstAndTiesKeepTheirOrder) {
  std::vector<DrawParticle> ps(4);
  ps[0].position = {0, 0, -5};
  ps[1].position = {0, 0, -20};
  ps[2].position = {3, 1, -5};  // same depth as 0: after it
  ps[3].position = {0, 0, 2};   // behind the eye: nearest
  std::vector<std::uint32_t> order;
  std::vector<float> depth;
  ParticlesPass::sortBackToFront(ps, Eigen::Vector3f::Zero(), Eigen::Vector3f(0, 0, -1), order, depth);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{1, 0, 2, 3}));
}

}  // namespace
}  // namespace tumble::render
