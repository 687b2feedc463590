// Convex meshes (physics hulls) on the offscreen driver: they show up,
// flat shaded (each face one shade), a shared mesh draws at every instance,
// and broken mesh data draws nothing instead of failing.
#include <gtest/gtest.h>

#include <set>

#include "render/renderer.h"
#include "render_test_util.h"

namespace tumble::render {
namespace {

using test::countPixels;
using test::Image;
using test::isReddish;
using test::loadPng;

constexpr int kWidth = 320, kHeight = 240;

std::shared_ptr<ConvexMeshData> octahedron(float r, std::uint64_t id) {
  auto m = std::make_shared<ConvexMeshData>();
  m->id = id;
  m->vertices = {{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
  // Counter-clockwise seen from outside.
  m->indices = {0, 2, 4, 4, 2, 1, 1, 2, 5, 5, 2, 0, 4, 3, 0, 1, 3, 4, 5, 3, 1, 0, 3, 5};
  return m;
}

DrawShape meshShape(std::shared_ptr<const ConvexMeshData> mesh, Eigen::Vector3f position) {
  DrawShape s;
  s.kind = ShapeKind::ConvexMesh;
  s.convexMesh = std::move(mesh);
  s.position = position;
  s.color = {0.9f, 0.1f, 0.1f};
  return s;
}

class ConvexMeshRender : public ::testing::Test {
 protected:
  void SetUp() override {
    m_renderer = test::makeOffscreenRenderer(kWidth, kHeight, /*hud=*/false);
    ASSERT_NE(m_renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
    m_renderer->camera().target = {0, 0, 0};
    m_renderer->camera().distance_m = 8;
  }
  Image render(const FrameSnapshot& frame, const std::string& name) {
    Controls controls;
    const std::string path = m_scratch.file(name);
    const Status status = m_renderer->drawFrame(frame, HudStats{}, controls, path.c_str());
    EXPECT_TRUE(status.ok()) << (status.ok() ? "" : status.error());
    return loadPng(path);
  }
  test::ScratchDir m_scratch;
  std::unique_ptr<Renderer> m_renderer;
};

TEST_F(ConvexMeshRender, AppearsFlatShadedAndInstanced) {
  FrameSnapshot one;
  auto mesh = octahedron(1, 7);
  one.shapes.push_back(meshShape(mesh, {0, 0, 0}));
  const Image a = render(one, "one.png");
  const int single = countPixels(a, isReddish);
  EXPECT_GT(single, 500) << "the octahedron must be visible";
  // Flat shading: the visible faces each have one shade, so the red pixels
  // take only a few distinct colours (smooth shading would give hundreds).
  std::set<int> shades;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const std::uint8_t* p = a.at(x, y);
      if (isReddish(p[0], p[1], p[2])) shades.insert(p[0]);
    }
  EXPECT_GE(shades.size(), 3u) << "several faces, several shades";
  // Edges are anti-aliased (MSAA), so allow some blended shades, far fewer than a gradient.
  EXPECT_LT(shades.size(), 60u);

  // The same mesh at a second place: twice the red, one upload.
  FrameSnapshot two = one;
  two.shapes.push_back(meshShape(mesh, {0, 0, 2.5f}));
  const Image b = render(two, "two.png");
  EXPECT_GT(countPixels(b, isReddish), single * 3 / 2);
}

TEST_F(ConvexMeshRender, BrokenMeshDataDrawsNothing) {
  auto bad = std::make_shared<ConvexMeshData>();
  bad->id = 9;
  bad->vertices = {{0, 0, 0}, {1, 0, 0}};
  bad->indices = {0, 1, 5, 0, 1};  // an index past the vertices, a dangling pair
  FrameSnapshot frame;
  frame.shapes.push_back(meshShape(bad, {0, 0, 0}));
  frame.shapes.push_back(meshShape(nullptr, {0, 0, 0}));
  const Image image = render(frame, "bad.png");
  EXPECT_EQ(countPixels(image, isReddish), 0);
}

}  // namespace
}  // namespace tumble::render
