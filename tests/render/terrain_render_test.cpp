// Terrain rendering on the offscreen driver (Mesa llvmpipe): ground where the
// ground is and sky above it, per-block textures where the map puts them,
// coarser levels far away, culling behind the camera, no cracks between
// levels, re-upload on a revision bump, and frame times of large maps.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>

#include "render/internal/camera_math.h"
#include "render/renderer.h"
#include "render_test_util.h"
#include "terrain_test_util.h"

namespace tumble::render {
namespace {

using test::countPixels;
using test::Image;
using test::loadPng;
using test::TestTerrain;

constexpr int kWidth = 320, kHeight = 240;

bool isSky(int r, int g, int b) { return b > r + 15 && b >= g; }
bool isGrassy(int r, int g, int b) { return g > r + 8 && g > b + 15; }
bool isSandy(int r, int g, int b) { return r > g && g > b + 15 && r > 90; }
// The sky below the horizon, seen when looking steeply down: Environment's
// groundColor (0.30, 0.30, 0.32) after the 1/2.2 encoding.
bool isGroundSky(int r, int g, int b) {
  return std::abs(r - 148) <= 4 && std::abs(g - 148) <= 4 && std::abs(b - 152) <= 4;
}

std::unique_ptr<Renderer> makeRenderer(int width, int height, int msaaSamples = 4) {
  ::setenv("SDL_VIDEODRIVER", "offscreen", 1);
  WindowConfig config;
  config.width = width;
  config.height = height;
  config.hud = false;
  config.forceOffscreen = true;
  config.msaaSamples = msaaSamples;
  auto renderer = Renderer::create(config);
  EXPECT_TRUE(renderer.ok()) << (renderer.ok() ? "" : renderer.error());
  return renderer.ok() ? std::move(*renderer) : nullptr;
}

class TerrainRender : public ::testing::Test {
 protected:
  void SetUp() override {
    m_renderer = makeRenderer(kWidth, kHeight);
    ASSERT_NE(m_renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
  }
  Image render(const TerrainSurface* terrain, const std::string& name) {
    FrameSnapshot frame;
    frame.terrain = terrain;
    Controls controls;
    const std::string path = m_scratch.file(name);
    const Status status = m_renderer->drawFrame(frame, HudStats{}, controls, path.c_str());
    EXPECT_TRUE(status.ok()) << (status.ok() ? "" : status.error());
    return loadPng(path);
  }
  test::ScratchDir m_scratch;
  std::unique_ptr<Renderer> m_renderer;
};

TEST_F(TerrainRender, AHillShowsGroundBelowAndSkyAboveTheHorizon) {
  // A 30 m Gaussian hill in the middle of a 256 m square of grass.
  TestTerrain t(257, 257);
  for (int j = 0; j < t.nz; ++j)
    for (int i = 0; i < t.nx; ++i)
      t.setHeight_m(i, j, 30.0 * std::exp(-((i - 128) * (i - 128) + (j - 128) * (j - 128)) / (2.0 * 30 * 30)));
  Camera& camera = m_renderer->camera();
  camera.target = t.centre() + Eigen::Vector3f(0, 10, 0);
  camera.yaw_rad = 0;
  camera.pitch_rad = 0.1f;
  camera.distance_m = 90;

  const Image image = render(&t.surface, "hill.png");
  ASSERT_EQ(image.width, kWidth);
  const TerrainStats& stats = m_renderer->terrainStats();
  EXPECT_GT(stats.chunksDrawn, 0);
  EXPECT_GT(stats.trianglesDrawn, 0);
  // The top rows look over the hill into the sky; the bottom rows are grass.
  EXPECT_EQ(countPixels(image, isSky, 0, 0, kWidth, 20), kWidth * 20);
  EXPECT_EQ(countPixels(image, isGrassy, 0, kHeight - 40, kWidth, kHeight), kWidth * 40);
  // The hill's summit (30 m up, 90 m ahead) is ground, not sky, on screen.
  const FrameView view = makeFrameView(camera, float(kWidth) / kHeight);
  const Eigen::Vector4f c = view.viewProjection * Eigen::Vector3f(t.centre().x(), 28.0f, t.centre().z()).homogeneous();
  const int px = int((c.x() / c.w() * 0.5f + 0.5f) * kWidth), py = int((0.5f - 0.5f * c.y() / c.w()) * kHeight);
  ASSERT_TRUE(px >= 0 && px < kWidth && py >= 0 && py < kHeight);
  const std::uint8_t* p = image.at(px, py);
  EXPECT_TRUE(isGrassy(p[0], p[1], p[2])) << int(p[0]) << " " << int(p[1]) << " " << int(p[2]);
  // Without a terrain the same view is sky only, and nothing is counted.
  const Image empty = render(nullptr, "no_terrain.png");
  EXPECT_EQ(countPixels(empty, isGrassy), 0);
  EXPECT_EQ(m_renderer->terrainStats().chunksTotal, 0);
}

TEST_F(TerrainRender, GroundLitPerVertexLooksLikeGroundLitPerPixel) {
  // The low preset's simple shading (terrainDetail off: light per vertex, no
  // bump detail) against the detailed one, on the 30 m hill seen from the
  // side: the same pixels are ground, their colour is close, and the slopes
  // keep their light and shade.
  TestTerrain t(257, 257);
  for (int j = 0; j < t.nz; ++j)
    for (int i = 0; i < t.nx; ++i)
      t.setHeight_m(i, j, 30.0 * std::exp(-((i - 128) * (i - 128) + (j - 128) * (j - 128)) / (2.0 * 30 * 30)));
  Camera& camera = m_renderer->camera();
  camera.target = t.centre() + Eigen::Vector3f(0, 10, 0);
  camera.yaw_rad = 0.8f;
  camera.pitch_rad = 0.25f;
  camera.distance_m = 90;
  RenderQuality quality;
  quality.shadows = false;
  quality.msaaSamples = 1;
  m_renderer->setQuality(quality);
  const Image detailed = render(&t.surface, "detailed.png");
  quality.terrainDetail = false;
  m_renderer->setQuality(quality);
  const Image simple = render(&t.surface, "simple.png");

  long groundBoth = 0, groundEither = 0;
  double sum[2][3] = {};
  // Mean brightness of each half of the picture: the hill's two flanks.
  double half[2][2] = {};
  long halfCount[2] = {};
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t* d = detailed.at(x, y);
      const std::uint8_t* s = simple.at(x, y);
      const bool gd = isGrassy(d[0], d[1], d[2]), gs = isGrassy(s[0], s[1], s[2]);
      groundEither += gd || gs;
      if (!(gd && gs)) continue;
      ++groundBoth;
      for (int c = 0; c < 3; ++c) sum[0][c] += d[c], sum[1][c] += s[c];
      const int h = x < kWidth / 2 ? 0 : 1;
      half[0][h] += d[0] + d[1] + d[2];
      half[1][h] += s[0] + s[1] + s[2];
      ++halfCount[h];
    }
  ASSERT_GT(groundBoth, kWidth * kHeight / 4) << "the hill and the plain fill much of the view";
  EXPECT_GT(groundBoth, groundEither * 99 / 100) << "ground in one is ground in the other";
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(sum[1][c] / double(groundBoth), sum[0][c] / double(groundBoth), 8.0) << "channel " << c;
  ASSERT_GT(halfCount[0], 0);
  ASSERT_GT(halfCount[1], 0);
  const double flankDetailed = half[0][0] / double(halfCount[0]) - half[0][1] / double(halfCount[1]);
  const double flankSimple = half[1][0] / double(halfCount[0]) - half[1][1] / double(halfCount[1]);
  EXPECT_GT(std::abs(flankDetailed), 6.0) << "the sun lights one flank more than the other";
  EXPECT_GT(flankSimple * flankDetailed, 0.0) << "the same flank is lit";
  EXPECT_NEAR(flankSimple, flankDetailed, 0.5 * std::abs(flankDetailed));
}

TEST_F(TerrainRender, TextureIndexPaintsItsOwnBlocks) {
  // Flat 128 m square seen from straight above; world x < 0 is the left of
  // the image (yaw 0 puts +X to the right).
  TestTerrain t(129, 129);
  t.surface.originX_m = -64;
  t.surface.originZ_m = -64;
  Camera& camera = m_renderer->camera();
  camera.target = {0, 0, 0};
  camera.yaw_rad = 0;
  camera.pitch_rad = 1.45f;
  camera.distance_m = 40;
  const Image grass = render(&t.surface, "grass.png");
  const int third = kWidth / 3;
  EXPECT_GT(countPixels(grass, isGrassy, 0, 0, third, kHeight), third * kHeight * 95 / 100);
  EXPECT_EQ(countPixels(grass, isSandy), 0);

  for (int bj = 0; bj < 128; ++bj)
    for (int bi = 0; bi < 64; ++bi) t.textureAt(bi, bj) = 2;  // sand
  ++t.surface.revision;
  const Image sand = render(&t.surface, "sand.png");
  EXPECT_TRUE(m_renderer->terrainStats().materialsUploaded);
  EXPECT_GT(countPixels(sand, isSandy, 0, 0, third, kHeight), third * kHeight * 95 / 100);
  EXPECT_EQ(countPixels(sand, isGrassy, 0, 0, third, kHeight), 0);
  // The right third, 13 m and more from the change, is untouched.
  int changed = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 2 * third; x < kWidth; ++x)
      changed += std::memcmp(grass.at(x, y), sand.at(x, y), 3) != 0;
  EXPECT_EQ(changed, 0);
}

// Blending (the high preset's texture splatting): where sand meets grass
// the colour changes over about a block instead of at one pixel's step,
// and ground away from any edge is drawn exactly as without blending.
TEST_F(TerrainRender, BlendedSurfacesMeetSoftlyAndUniformGroundIsUnchanged) {
  TestTerrain t(129, 129);
  t.surface.originX_m = -64;
  t.surface.originZ_m = -64;
  for (int bj = 0; bj < 128; ++bj)
    for (int bi = 0; bi < 64; ++bi) t.textureAt(bi, bj) = 2;  // sand for x < 0
  Camera& camera = m_renderer->camera();
  camera.target = {0, 0, 0};
  camera.yaw_rad = 0;
  camera.pitch_rad = 1.45f;
  camera.distance_m = 20;  // about 11 pixels a metre across the middle
  RenderQuality quality;
  quality.shadows = false;
  quality.msaaSamples = 1;
  m_renderer->setQuality(quality);
  const Image hard = render(&t.surface, "hard.png");
  quality.terrainBlend = true;
  m_renderer->setQuality(quality);
  const Image soft = render(&t.surface, "soft.png");

  // Along each row of the middle band: the largest step between
  // neighbouring pixels of (R - G), which is positive for sand and well
  // below zero for grass.
  auto largestStep = [](const Image& image) {
    double sum = 0;
    int rows = 0;
    for (int y = kHeight / 3; y < 2 * kHeight / 3; ++y, ++rows) {
      int largest = 0;
      for (int x = kWidth / 3; x < 2 * kWidth / 3; ++x) {
        const std::uint8_t* a = image.at(x - 1, y);
        const std::uint8_t* b = image.at(x, y);
        largest = std::max(largest, std::abs((int(a[0]) - a[1]) - (int(b[0]) - b[1])));
      }
      sum += largest;
    }
    return sum / rows;
  };
  const double hardStep = largestStep(hard), softStep = largestStep(soft);
  EXPECT_GT(hardStep, 30.0) << "sand meets grass at one step without blending";
  EXPECT_LT(softStep, 0.4 * hardStep) << "blended, the change is spread over the blocks beside the edge";
  // Both sides keep their surface: sand on the left, grass on the right.
  const int third = kWidth / 3;
  EXPECT_GT(countPixels(soft, isSandy, 0, 0, third, kHeight), third * kHeight * 95 / 100);
  EXPECT_GT(countPixels(soft, isGrassy, 2 * third, 0, kWidth, kHeight), (kWidth - 2 * third) * kHeight * 95 / 100);
  // Away from the edge (the outer sixths) the pixels are the same.
  int changed = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (x < kWidth / 6 || x >= 5 * kWidth / 6) changed += std::memcmp(hard.at(x, y), soft.at(x, y), 3) != 0;
  EXPECT_EQ(changed, 0);
}

TEST_F(TerrainRender, FarChunksUseFewerTrianglesAndChunksBehindAreCulled) {
  // A strip one chunk wide and 16 long (1 m spacing), the camera low at
  // chunk 4 looking down the strip towards +Z... and 4 chunks behind it.
  TestTerrain t(65, 1025);
  for (int j = 0; j < t.nz; ++j)
    for (int i = 0; i < t.nx; ++i) t.setHeight_m(i, j, 2.0 + std::sin(i * 0.3) + std::cos(j * 0.2));
  Camera& camera = m_renderer->camera();
  camera.target = {32, 3, 4 * 64 + 100};
  camera.yaw_rad = float(kPi);  // eye on the -Z side of the target, looking towards +Z
  camera.pitch_rad = 0.15f;
  camera.distance_m = 100;
  const FrameView view = makeFrameView(camera, float(kWidth) / kHeight);
  ASSERT_NEAR(view.eye.z(), 4 * 64, 2.0f);
  render(&t.surface, "strip.png");
  const TerrainStats& stats = m_renderer->terrainStats();
  EXPECT_EQ(stats.chunksTotal, 16);
  EXPECT_EQ(stats.chunksDrawn + stats.chunksCulled, 16);
  std::map<int, TerrainChunkDraw> byRow;
  for (const TerrainChunkDraw& d : stats.drawn) byRow[d.chunkZ] = d;
  // Chunks 0..2 lie wholly behind the eye (z < 192 m): culled.
  for (int cz = 0; cz < 3; ++cz) EXPECT_EQ(byRow.count(cz), 0u) << "chunk " << cz << " behind the camera drawn";
  ASSERT_TRUE(byRow.count(4) && byRow.count(12));
  EXPECT_EQ(byRow[4].lod, 0);  // the eye is above chunk 4
  EXPECT_GT(byRow[12].lod, byRow[4].lod);
  EXPECT_LT(byRow[12].triangles * 4, byRow[4].triangles);
  // Levels never get finer with distance along the strip.
  int previous = 0;
  for (const auto& [row, d] : byRow) {
    if (row < 4) continue;
    EXPECT_GE(d.lod, previous) << "chunk row " << row;
    previous = d.lod;
  }
  std::int64_t sum = 0;
  for (const TerrainChunkDraw& d : stats.drawn) sum += d.triangles;
  EXPECT_EQ(sum, stats.trianglesDrawn);
}

TEST_F(TerrainRender, NoCracksBetweenChunksOfDifferentLevels) {
  // Steep rough ground (0..12 m over 0.25 m samples, 16 x 16 chunks) seen
  // from 40 m at a slant, so borders between chunks of different levels fill
  // the view. Looking this steeply down, every background pixel would be the
  // sky's flat ground colour; the view lies wholly inside the terrain, so
  // there must be none. (With the skirts removed this test fails.)
  TestTerrain t(1025, 1025, 0.25f);
  t.surface.originX_m = -128;
  t.surface.originZ_m = -128;
  const std::vector<float> h = test::plasma(1025, 7, 0.8f);
  for (int j = 0; j < t.nz; ++j)
    for (int i = 0; i < t.nx; ++i) t.setHeight_m(i, j, 12.0 * h[std::size_t(j) * t.nx + i]);
  for (std::size_t b = 0; b < t.texture.size(); ++b) t.texture[b] = (b / 37) % 2 == 0 ? 0 : 2;
  Camera& camera = m_renderer->camera();
  camera.target = {0, 6, 0};
  camera.yaw_rad = 0.4f;
  camera.pitch_rad = 0.9f;
  camera.distance_m = 40;

  const Image image = render(&t.surface, "cracks.png");
  const TerrainStats& stats = m_renderer->terrainStats();
  std::set<int> levels;
  for (const TerrainChunkDraw& d : stats.drawn) levels.insert(d.lod);
  EXPECT_GE(levels.size(), 2u) << "the view must mix levels for this test to mean anything";
  EXPECT_EQ(countPixels(image, isGroundSky), 0) << "background shows through the terrain";
}

TEST_F(TerrainRender, RevisionBumpRebuildsChunks) {
  TestTerrain t(129, 129);
  Camera& camera = m_renderer->camera();
  camera.target = t.centre();
  camera.yaw_rad = 0;
  camera.pitch_rad = 0.6f;
  camera.distance_m = 60;
  const Image before = render(&t.surface, "before.png");
  const int uploaded = m_renderer->terrainStats().chunksUploaded;
  EXPECT_EQ(uploaded, m_renderer->terrainStats().chunksDrawn);
  EXPECT_TRUE(m_renderer->terrainStats().materialsUploaded);

  render(&t.surface, "same.png");
  EXPECT_EQ(m_renderer->terrainStats().chunksUploaded, 0) << "nothing changed, nothing to upload";
  EXPECT_FALSE(m_renderer->terrainStats().materialsUploaded);

  // Raise a 10 m block in the middle without telling: the cached mesh stays.
  for (int j = 54; j < 74; ++j)
    for (int i = 54; i < 74; ++i) t.setHeight_m(i, j, 10.0);
  const Image stale = render(&t.surface, "stale.png");
  EXPECT_TRUE(stale.rgb == before.rgb);
  ++t.surface.revision;
  const Image after = render(&t.surface, "after.png");
  EXPECT_EQ(m_renderer->terrainStats().chunksUploaded, m_renderer->terrainStats().chunksDrawn);
  EXPECT_FALSE(after.rgb == before.rgb);
}

TEST_F(TerrainRender, DirtyRectangleRebuildsOnlyTheChunksItTouches) {
  // 257 x 257 samples: 4 x 4 chunks, all in view.
  TestTerrain t(257, 257);
  Camera& camera = m_renderer->camera();
  camera.target = t.centre();
  camera.yaw_rad = 0;
  camera.pitch_rad = 1.2f;
  camera.distance_m = 300;
  render(&t.surface, "dirty_before.png");
  ASSERT_EQ(m_renderer->terrainStats().chunksDrawn, 16);
  // A 10 m hill and a rock patch inside chunk (1, 1) (samples 64..128).
  for (int j = 90; j <= 100; ++j)
    for (int i = 90; i <= 100; ++i) t.setHeight_m(i, j, 10.0);
  for (int bj = 92; bj < 98; ++bj)
    for (int bi = 92; bi < 98; ++bi) t.textureAt(bi, bj) = 1;
  t.surface.dirtySinceRevision = t.surface.revision;
  ++t.surface.revision;
  t.surface.dirtyI0 = 90;
  t.surface.dirtyJ0 = 90;
  t.surface.dirtyI1 = 100;
  t.surface.dirtyJ1 = 100;
  const Image partial = render(&t.surface, "dirty_partial.png");
  EXPECT_EQ(m_renderer->terrainStats().chunksInvalidated, 1);
  EXPECT_EQ(m_renderer->terrainStats().chunksUploaded, 1) << "only the chunk holding the edit is rebuilt";
  EXPECT_TRUE(m_renderer->terrainStats().materialsUploaded);

  // The same surface rebuilt from scratch (an unrelated revision) draws the same picture.
  t.surface.dirtySinceRevision = 0;
  t.surface.revision += 100;
  const Image full = render(&t.surface, "dirty_full.png");
  EXPECT_EQ(m_renderer->terrainStats().chunksUploaded, 16);
  EXPECT_TRUE(partial.rgb == full.rgb) << "the partial rebuild must match a full one";

  // An edit on a chunk corner (sample 128, 128: shared by four chunks, and
  // their neighbours' normals) rebuilds the four.
  t.setHeight_m(128, 128, 5.0);
  t.surface.dirtySinceRevision = t.surface.revision;
  ++t.surface.revision;
  t.surface.dirtyI0 = t.surface.dirtyI1 = 128;
  t.surface.dirtyJ0 = t.surface.dirtyJ1 = 128;
  const Image corner = render(&t.surface, "dirty_corner.png");
  EXPECT_EQ(m_renderer->terrainStats().chunksInvalidated, 4);
  t.surface.revision += 100;
  EXPECT_TRUE(render(&t.surface, "dirty_corner_full.png").rgb == corner.rgb);
}

// --- large maps: frame times (logged, not asserted) and LOD memory ---------

double msPerFrame(Renderer& renderer, const FrameSnapshot& frame, int frames) {
  Controls controls;
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < frames; ++k) {
    (void)renderer.drawFrame(frame, HudStats{}, controls);
    glFinish();
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
}

void addMarkers(FrameSnapshot& frame, const TestTerrain& t) {
  // A few boxes and balls resting on the ground, for scale in the demo.
  const Eigen::Vector3f colours[] = {{0.8f, 0.1f, 0.05f}, {0.9f, 0.7f, 0.1f}, {0.1f, 0.3f, 0.8f}};
  for (int k = 0; k < 6; ++k) {
    const int i = 300 - 30 + 11 * k, j = 700 + 20 - 7 * k;
    DrawShape s;
    s.kind = k % 2 == 0 ? ShapeKind::Box : ShapeKind::Sphere;
    s.radius_m = 2.0f;
    s.halfExtents = {2, 2, 2};
    s.position = {float(i) * t.surface.spacing_m, float(t.height_m(i, j)) + 2.0f, float(j) * t.surface.spacing_m};
    s.color = colours[k % 3];
    frame.shapes.push_back(s);
  }
}

// 1025^2: an overview from 220 m and a view low over the ground (the most
// full-detail chunks), with 4x MSAA (the renderer's default) and without;
// "sky" is the same frame with no terrain, so the difference is the
// terrain's own cost. Times are logged, not asserted: CI machines differ.
void time1025(int msaa, bool saveDemo) {
  auto renderer = makeRenderer(1280, 720, msaa);
  ASSERT_NE(renderer, nullptr);
  TestTerrain t(1025, 1025);
  test::paintPlasmaLandscape(t, 42, 80.0f);
  FrameSnapshot frame;
  addMarkers(frame, t);
  Camera& camera = renderer->camera();
  camera.target = {300, float(t.height_m(300, 700)) + 10.0f, 700};  // looking north-east over the map
  camera.yaw_rad = -2.3f;
  camera.pitch_rad = 0.28f;
  camera.distance_m = 160;
  const double sky = msPerFrame(*renderer, frame, 3);
  frame.terrain = &t.surface;
  const double first = msPerFrame(*renderer, frame, 1);  // textures, uploads
  const double overview = msPerFrame(*renderer, frame, 3);
  const TerrainStats overviewStats = renderer->terrainStats();
  if (saveDemo) {
    Controls controls;
    ASSERT_TRUE(renderer->drawFrame(frame, HudStats{}, controls, "/tmp/terrain_demo.png").ok());
    std::printf("[terrain] demo image: /tmp/terrain_demo.png\n");
  }
  camera.pitch_rad = 0.12f;
  camera.distance_m = 25;
  const double low = msPerFrame(*renderer, frame, 3);
  const TerrainStats& lowStats = renderer->terrainStats();
  const auto histogram = [](const TerrainStats& st) {
    std::string text;
    for (int lod = 0; lod <= 6; ++lod) {
      int n = 0;
      for (const TerrainChunkDraw& d : st.drawn) n += d.lod == lod;
      text += ' ';
      text += std::to_string(n);
    }
    return text;
  };
  std::printf("[terrain] chunks per level 0..6: overview%s; low view%s\n", histogram(overviewStats).c_str(),
              histogram(lowStats).c_str());
  std::printf("[terrain] 1025^2 at 1280x720, MSAA %d: sky only %.1f ms; first frame %.1f ms; overview %.1f "
              "ms/frame (%d chunks drawn, %d culled, %lld triangles); low view %.1f ms/frame (%d drawn, "
              "%lld triangles); %.1f MiB chunk vertices resident\n",
              msaa, sky, first, overview, overviewStats.chunksDrawn, overviewStats.chunksCulled,
              static_cast<long long>(overviewStats.trianglesDrawn), low, lowStats.chunksDrawn,
              static_cast<long long>(lowStats.trianglesDrawn), lowStats.residentBytes / 1048576.0);
  EXPECT_EQ(overviewStats.chunksTotal, 16 * 16);
}

TEST(TerrainLargeMaps, Frame1025At720p) {
  time1025(4, true);
  time1025(1, false);
}

TEST(TerrainLargeMaps, Map4097DrawsOnlyNearChunksInDetail) {
  auto renderer = makeRenderer(1280, 720);
  ASSERT_NE(renderer, nullptr);
  TestTerrain t(4097, 4097);
  test::paintPlasmaLandscape(t, 43, 300.0f);
  FrameSnapshot frame;
  frame.terrain = &t.surface;
  Camera& camera = renderer->camera();
  camera.target = t.centre() + Eigen::Vector3f(0, float(t.height_m(2048, 2048)), 0);
  camera.yaw_rad = 2.0f;
  camera.pitch_rad = 0.3f;
  camera.distance_m = 300;
  const double first = msPerFrame(*renderer, frame, 1);
  const double steady = msPerFrame(*renderer, frame, 3);
  const TerrainStats& stats = renderer->terrainStats();
  int fullDetail = 0;
  for (const TerrainChunkDraw& d : stats.drawn) fullDetail += d.lod == 0;
  const double fullBytes = 4097.0 * 4097.0 * sizeof(float) * 4;
  std::printf("[terrain] 4097^2 at 1280x720, MSAA 4: first frame %.1f ms, then %.1f ms/frame; %d of %d chunks "
              "drawn (%d at full detail), %lld triangles; %.1f MiB chunk vertices resident "
              "(full detail would be %.0f MiB)\n",
              first, steady, stats.chunksDrawn, stats.chunksTotal, fullDetail,
              static_cast<long long>(stats.trianglesDrawn), stats.residentBytes / 1048576.0,
              fullBytes / 1048576.0);
  EXPECT_EQ(stats.chunksTotal, 64 * 64);
  EXPECT_LT(fullDetail, stats.chunksTotal / 50);
  EXPECT_LT(double(stats.residentBytes), fullBytes / 20);
}

}  // namespace
}  // namespace tumble::render
