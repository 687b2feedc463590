// The app's side of models, in process: static models on a terrain are
// registered in its tree of static objects with boxes that hold the model,
// and the frame snapshot draws bodies with models as models, not shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "app/scene.h"
#include "app/scene_models.h"
#include "app/terrain_scene.h"
#include "render/internal/terrain_textures.h"
#include "render/model.h"

namespace tumble::app {
namespace {

std::unique_ptr<Scene> makeScene(const std::string& ref, std::map<std::string, std::string> sets = {}) {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  SceneOptions options;
  options.scenarioRef = ref;
  options.sets = std::move(sets);
  options.modDirs = {std::string(source ? source : ".") + "/tests/app/mods"};
  auto scene = Scene::create(options);
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error());
  return scene.ok() ? std::move(*scene) : nullptr;
}

TEST(SceneModels, StaticModelsGoIntoTheTerrainTree) {
  auto scene = makeScene("models:terrain_scenery");
  ASSERT_TRUE(scene);
  scene->host().start();
  scene->registerStaticObjects();
  ASSERT_NE(scene->terrainScene(), nullptr);
  const terrain::StaticObjects& registry = scene->terrainScene()->terrain().staticObjects();
  const auto& statics = scene->host().presentation().statics;
  ASSERT_EQ(statics.size(), 3u);
  int registered = 0;
  for (const script::StaticModel& s : statics) {
    if (s.body.isNull()) continue;  // collision = "none"
    ASSERT_TRUE(registry.contains(s.body.index));
    ++registered;
    // The registered box holds the placed model's bounds (checked at the
    // model's own bounding-box corners, rotated and moved into place).
    auto model = scene->models().get(s.file);
    ASSERT_TRUE(model.ok());
    const render::BoundingBox& local = (*model)->nodes[0].coverBox;
    const terrain::Aabb& box = registry.boxOf(s.body.index);
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 c((corner & 1 ? local.max : local.min).x(), (corner & 2 ? local.max : local.min).y(),
                   (corner & 4 ? local.max : local.min).z());
      const Vec3 world = s.position_m + s.rotation * c.cwiseProduct(s.scale);
      EXPECT_TRUE((world.array() >= box.min.array() - 1e-3f).all() && (world.array() <= box.max.array() + 1e-3f).all())
          << s.file << " corner " << corner;
    }
  }
  EXPECT_EQ(registered, 2);
  EXPECT_EQ(registry.size(), 2u);
}

TEST(SceneModels, BodiesWithModelsAreDrawnAsModels) {
  auto scene = makeScene("base:showroom", {{"autopilot", "1"}});  // the sliding box
  ASSERT_TRUE(scene);
  scene->host().start();
  scene->savePreviousState();
  render::FrameSnapshot frame;
  scene->snapshot(frame, 1.0);
  // The car and 1 + 2 + 5 + 6 + 1 + 1 static models; trees and the arch
  // have no body, the plane is the only plain shape left.
  EXPECT_EQ(frame.models.size(), 1u + 2u + 5u + 6u + 1u + 1u);
  ASSERT_EQ(frame.shapes.size(), 1u);
  EXPECT_EQ(frame.shapes[0].kind, render::ShapeKind::Plane);
  // The same model file is loaded once and shared.
  EXPECT_EQ(frame.models[1].model.get(), frame.models[2].model.get());
}

// Placements of one model file at one scale share one immutable mesh shape
// (node tree, triangles, edge flags); another scale gets its own, as its
// triangles are elsewhere in the body frame.
TEST(SceneModels, PlacementsOfOneFileAndScaleShareOneMeshShape) {
  // Trees at scales 1, 1.25, 1, 1.25, 1; rocks at 1, 1.25.
  auto scene = makeScene("models:forest", {{"trees", "5"}, {"rocks", "2"}, {"sizes", "2"}});
  ASSERT_TRUE(scene);
  scene->host().start();
  const auto& statics = scene->host().presentation().statics;
  ASSERT_EQ(statics.size(), 7u);
  std::vector<const physics::MeshShape*> mesh;
  for (const script::StaticModel& s : statics) {
    const physics::Shape& shape = scene->world().body(s.body).shape;
    ASSERT_EQ(shape.type, physics::ShapeType::Mesh);
    mesh.push_back(shape.mesh.get());
  }
  EXPECT_EQ(mesh[0], mesh[2]);
  EXPECT_EQ(mesh[0], mesh[4]);
  EXPECT_EQ(mesh[1], mesh[3]);
  EXPECT_NE(mesh[0], mesh[1]) << "another scale, another shape";
  EXPECT_NE(mesh[5], mesh[6]);
  EXPECT_NE(mesh[0], mesh[5]) << "another file, another shape";
  // The larger tree's triangles are the smaller one's scaled by 1.25.
  ASSERT_EQ(mesh[0]->triangles.size(), mesh[1]->triangles.size());
  for (std::size_t t = 0; t < mesh[0]->triangles.size(); ++t)
    EXPECT_TRUE(mesh[1]->triangles[t].v[0].isApprox(mesh[0]->triangles[t].v[0] * Real(1.25)));
  EXPECT_EQ(scene->models().meshShapesBuilt(), 4u);
  EXPECT_EQ(scene->models().meshShapesPlaced(), 7u);
}

// Sharing changes nothing a body meets: a ball dropped on the first rock (a
// shared shape) lands on it, not on the ground under it.
TEST(SceneModels, ASharedMeshShapeStillCollides) {
  auto scene = makeScene("models:forest", {{"trees", "3"}, {"rocks", "3"}, {"sizes", "1"}});
  ASSERT_TRUE(scene);
  scene->host().start();
  EXPECT_EQ(scene->models().meshShapesBuilt(), 2u);
  for (int i = 0; i < 60; ++i) scene->world().step(Real(1.0 / 60));
  scene->host().finish(1.0, 60);
  ASSERT_EQ(scene->host().expectations().size(), 1u);
  EXPECT_TRUE(scene->host().expectations()[0].ok) << scene->host().expectations()[0].value;
}

// world.plane{texture = NAME} draws the terrain's ground texture of that
// name on the plane: the frame's plane shapes carry the texture index whose
// render-side name is the one the script gave ("checker" and no texture:
// -1, the checkerboard), and bad values are refused with the list of names.
TEST(SceneModels, PlanesDrawTheGroundTextureTheScriptNames) {
  auto scene = makeScene("models:ground_planes");
  ASSERT_TRUE(scene);
  scene->host().start();
  scene->host().finish(0.0, 0);
  for (const script::Expectation& e : scene->host().expectations()) EXPECT_TRUE(e.ok) << e.name;
  EXPECT_EQ(scene->host().expectations().size(), 8u);
  render::FrameSnapshot frame;
  scene->snapshot(frame, 1.0);
  const char* names[] = {"checker", "grass", "rock", "sand", "mud", "snow", "gravel", "dirt", "moss"};
  int planes = 0;
  for (const render::DrawShape& s : frame.shapes) {
    if (s.kind != render::ShapeKind::Plane) continue;
    ++planes;
    const int y = int(std::lround(s.position.y()));
    if (y == 20 || y == 1) {
      EXPECT_EQ(s.groundTexture, -1) << "the plane at y = " << y << " is the checkerboard";
      continue;
    }
    ASSERT_GE(y, 2);
    ASSERT_LE(y, 9);
    ASSERT_GE(s.groundTexture, 0) << names[y - 1];
    EXPECT_STREQ(render::terrainTextureName(s.groundTexture), names[y - 1]);
  }
  EXPECT_EQ(planes, 10);
}

}  // namespace
}  // namespace tumble::app
