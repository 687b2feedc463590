// The collision view (F3 when playing; Scene::setCollisionView): the
// snapshot draws what collides instead of what models show. Static models'
// triangle meshes become wireframe lines, each edge once, where the placed
// shape is; a picture of it shows the lines where the normal view shows
// none.
#include <gtest/gtest.h>

#include <cstdlib>

#include "../render/render_test_util.h"
#include "app/scene.h"
#include "app/scene_models.h"
#include "physics/mesh_shape.h"

namespace tumble::app {
namespace {

std::unique_ptr<Scene> forest(std::map<std::string, std::string> sets) {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  SceneOptions options;
  options.scenarioRef = "models:forest";
  options.modDirs = {std::string(source ? source : ".") + "/tests/app/mods"};
  options.sets = std::move(sets);
  auto scene = Scene::create(options);
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error());
  if (!scene.ok()) return nullptr;
  (*scene)->host().start();
  (*scene)->savePreviousState();
  return std::move(*scene);
}

// The bright orange of creases and borders (Scene: kCrease).
bool isCreaseOrange(int r, int g, int b) { return r > 200 && g > 90 && g < 190 && b < 80; }

TEST(CollisionView, MeshesBecomeWireframesOfTheirEdges) {
  auto scene = forest({{"trees", "2"}, {"rocks", "1"}, {"sizes", "1"}});
  ASSERT_TRUE(scene);
  render::FrameSnapshot normal, collision;
  scene->snapshot(normal, 1.0);
  EXPECT_EQ(normal.models.size(), 3u);
  EXPECT_TRUE(normal.lines.empty()) << "the normal view draws the models, not their triangles";

  scene->setCollisionView(true);
  scene->snapshot(collision, 1.0);
  EXPECT_TRUE(collision.models.empty()) << "the collision view leaves the models out";
  // The shipped models are closed surfaces: every edge is shared by two
  // triangles, so a mesh of T triangles has 3 T / 2 distinct edges.
  const auto& statics = scene->host().presentation().statics;
  ASSERT_EQ(statics.size(), 3u);
  std::size_t edges = 0;
  for (const script::StaticModel& s : statics)
    edges += scene->world().body(s.body).shape.mesh->triangles.size() * 3 / 2;
  EXPECT_EQ(collision.lines.size(), edges);
  // Every line lies on a placed mesh: within its body's box, and at least
  // one end on a vertex of one of its triangles (placed by the body pose).
  int creases = 0;
  for (const render::DebugLine& line : collision.lines) {
    bool inside = false;
    for (const script::StaticModel& s : statics) {
      const physics::Body& b = scene->world().body(s.body);
      Vec3 lo, hi;
      b.shape.bounds(b.position_m, b.orientation, &lo, &hi);
      const Vec3 a = line.a.cast<Real>(), c = line.b.cast<Real>();
      const Vec3 eps = Vec3::Constant(Real(1e-4));
      inside = inside || ((a.array() >= (lo - eps).array()).all() && (a.array() <= (hi + eps).array()).all() &&
                          (c.array() >= (lo - eps).array()).all() && (c.array() <= (hi + eps).array()).all());
    }
    EXPECT_TRUE(inside) << "a line outside every mesh: " << line.a.transpose() << " - " << line.b.transpose();
    creases += isCreaseOrange(int(line.color.x() * 255), int(line.color.y() * 255), int(line.color.z() * 255));
  }
  // The rock and tree are faceted: some edges are creases, and the flat
  // parts of the tree (its trunk's side quads split in two) have seams.
  EXPECT_GT(creases, 0);
  EXPECT_LT(creases, int(collision.lines.size()));
  // Plane, ball and the three mesh bodies' wireframes; nothing else is a shape.
  EXPECT_EQ(collision.shapes.size(), 2u);
}

TEST(CollisionView, APictureShowsTheWireframe) {
  auto scene = forest({{"trees", "1"}, {"rocks", "0"}});
  ASSERT_TRUE(scene);
  auto renderer = render::test::makeOffscreenRenderer(320, 240, /*hud=*/false);
  ASSERT_NE(renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
  // The one tree stands at (4, 0, 0), 3 m tall; look at its middle.
  const Vec3 tree = scene->world().body(scene->host().presentation().statics[0].body).position_m;
  renderer->camera().target = (tree + Vec3(0, 1.5, 0)).cast<float>();
  renderer->camera().distance_m = 6;
  render::test::ScratchDir scratch;
  auto shot = [&](bool collisionView, const std::string& name) {
    scene->setCollisionView(collisionView);
    render::FrameSnapshot frame;
    scene->snapshot(frame, 1.0);
    render::Controls controls;
    const std::string path = scratch.file(name);
    const Status st = renderer->drawFrame(frame, render::HudStats{}, controls, path.c_str());
    EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.error());
    return render::test::loadPng(path);
  };
  const render::test::Image normal = shot(false, "normal.png"), collision = shot(true, "collision.png");
  const int before = render::test::countPixels(normal, isCreaseOrange);
  const int after = render::test::countPixels(collision, isCreaseOrange);
  EXPECT_LT(before, 20) << "the tree model has no such orange";
  EXPECT_GT(after, 200) << "the wireframe's creases (about 380 px)";
  if (const char* keep = std::getenv("TUMBLE_KEEP_SHOTS")) {
    std::filesystem::copy_file(scratch.file("collision.png"), std::string(keep) + "/collision_view.png",
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(scratch.file("normal.png"), std::string(keep) + "/normal_view.png",
                               std::filesystem::copy_options::overwrite_existing);
  }
}

}  // namespace
}  // namespace tumble::app
