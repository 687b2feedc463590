// Models on the GPU (offscreen, Mesa llvmpipe): the textured 3DS jeep and the
// RC car show their textures in a screenshot, draws are sorted by material,
// culled nodes are not drawn, and dropped models leave the GPU.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "render/internal/camera_math.h"
#include "render/internal/gl_util.h"
#include "render/internal/mesh_draw_list.h"
#include "render/model.h"
#include "shared_assets.h"
#include "render/renderer.h"
#include "render_test_util.h"

namespace tumble::render {
namespace {

using tumble::test::sharedAsset;
using test::countPixels;
using test::Image;
using test::loadPng;

constexpr int kWidth = 320, kHeight = 240;

std::shared_ptr<const Model> mustLoad(const std::string& path) {
  auto model = loadModel(path);
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error());
  return model.ok() ? *model : nullptr;
}

// The jeep's skin: olive green paint. The sky is blue-dominant and the
// untextured material grey, so neither passes.
bool isOlive(int r, int g, int b) { return g > 60 && g > r + 12 && g > b + 12; }
// The RC chassis' vertex colour, a mid blue, seen against a grey floor.
bool isChassisBlue(int r, int g, int b) { return b > 120 && b > r + 60 && b > g + 25; }
bool isDark(int r, int g, int b) { return r < 45 && g < 45 && b < 45; }

class ModelRender : public ::testing::Test {
 protected:
  void SetUp() override {
    m_renderer = test::makeOffscreenRenderer(kWidth, kHeight, /*hud=*/false);
    ASSERT_NE(m_renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
  }
  Image render(const FrameSnapshot& frame, const std::string& name) {
    Controls controls;
    const std::string path = m_scratch.file(name);
    const Status status = m_renderer->drawFrame(frame, HudStats{}, controls, path.c_str());
    EXPECT_TRUE(status.ok()) << (status.ok() ? "" : status.error());
    if (const char* keep = std::getenv("TUMBLE_MODEL_DEMO_DIR"); keep && *keep) {
      std::filesystem::copy_file(path, std::filesystem::path(keep) / name,
                                 std::filesystem::copy_options::overwrite_existing);
    }
    return loadPng(path);
  }
  test::ScratchDir m_scratch;
  std::unique_ptr<Renderer> m_renderer;
};

TEST_F(ModelRender, JeepScreenshotShowsItsTexture) {
  auto jeep = mustLoad(sharedAsset("models/jeep1.3ds"));
  ASSERT_TRUE(jeep);
  // The file is in decimetre-ish units, about 16.6 long: a quarter makes a 4 m jeep.
  Camera& camera = m_renderer->camera();
  camera.target = {0, 0.9f, 0};
  camera.yaw_rad = 0.9f;
  camera.pitch_rad = 0.3f;
  camera.distance_m = 5.0f;
  FrameSnapshot frame;
  ModelInstance instance;
  instance.model = jeep;
  instance.scale = Eigen::Vector3f::Constant(0.25f);
  instance.position = {0, 0, 1.0f};  // the model's centre is at z = -1 m (scaled)
  frame.models.push_back(instance);
  const Image textured = render(frame, "jeep.png");

  // The same geometry without its texture: grey.
  auto plain = std::make_shared<Model>(*jeep);
  plain->images.clear();
  for (ModelMaterial& m : plain->materials) m.image = -1;
  frame.models[0].model = plain;
  const Image untextured = render(frame, "jeep_untextured.png");

  const int olive = countPixels(textured, isOlive);
  const int dark = countPixels(textured, isDark);
  EXPECT_GT(olive, 2000) << "the jeep's green paint should cover much of the frame";
  EXPECT_GT(dark, 300) << "tyres, grille and chassis are near black in the texture";
  EXPECT_LT(countPixels(untextured, isOlive), 20);
  EXPECT_LT(countPixels(untextured, isDark), dark / 4);
  // All seven meshes share one material: one bind for the whole jeep.
  EXPECT_EQ(m_renderer->meshStats().materialSwitches, 1);
  EXPECT_EQ(m_renderer->meshStats().drawCalls, 7);
  EXPECT_EQ(m_renderer->meshStats().triangles, 2032);
}

TEST_F(ModelRender, RcCarChassisAndTexturedWheels) {
  auto chassis = mustLoad(sharedAsset("racecar/meshes/chassis.dae"));
  auto wheel = mustLoad(sharedAsset("racecar/meshes/left_front_wheel.obj"));
  ASSERT_TRUE(chassis && wheel);
  // Wheel images are decoded (wheel.jpg), the chassis is vertex-coloured.
  ASSERT_EQ(wheel->images.size(), 1u);
  Camera& camera = m_renderer->camera();
  camera.target = {0.16f, 0.0f, 0.0f};
  camera.yaw_rad = 0.5f;
  camera.pitch_rad = 0.9f;
  camera.distance_m = 0.7f;
  FrameSnapshot frame;
  DrawShape floor;
  floor.kind = ShapeKind::Plane;
  floor.position = {0, -0.05f, 0};
  floor.color = {0.5f, 0.5f, 0.5f};
  frame.shapes.push_back(floor);
  // The car's files are Z-up (ROS): turn them to Y-up.
  const Eigen::Quaternionf zUpToYUp(Eigen::AngleAxisf(-float(kPi) / 2, Eigen::Vector3f::UnitX()));
  ModelInstance body;
  body.model = chassis;
  body.orientation = zUpToYUp;
  frame.models.push_back(body);
  // Wheel centres from racecar.urdf (x forward 0 / 0.325 m, y +-0.1 m).
  for (float x : {0.0f, 0.325f}) {
    for (float side : {1.0f, -1.0f}) {
      ModelInstance w;
      w.model = wheel;
      w.orientation = zUpToYUp * Eigen::Quaternionf(Eigen::AngleAxisf(side * float(kPi) / 2, Eigen::Vector3f::UnitX()));
      w.position = zUpToYUp * Eigen::Vector3f(x, side * 0.1f, 0);
      frame.models.push_back(w);
    }
  }
  const Image car = render(frame, "rc_car.png");
  EXPECT_GT(countPixels(car, isChassisBlue), 1000);
  EXPECT_GT(countPixels(car, isDark), 200) << "the tyres of wheel.jpg are near black";
  EXPECT_GT(countPixels(car, test::isReddish), 100) << "the rims of wheel.jpg are red";
  const MeshStats& stats = m_renderer->meshStats();
  EXPECT_EQ(stats.instances, 5);
  EXPECT_EQ(stats.modelsResident, 2);
}

// A lamp: a material's emissive colour (.mtl Ke) is added to its lit
// colour, so at night, with no sun on it, the lamp face still shows its
// own colour while a plain face of the same paint next to it is dark.
TEST_F(ModelRender, EmissiveMaterialGlowsAtNightAndAPlainOneDoesNot) {
  auto model = std::make_shared<Model>();
  ModelMesh quad;
  for (const Eigen::Vector3f p : {Eigen::Vector3f(-0.5f, -0.5f, 0), Eigen::Vector3f(0.5f, -0.5f, 0),
                                  Eigen::Vector3f(0.5f, 0.5f, 0), Eigen::Vector3f(-0.5f, 0.5f, 0)}) {
    quad.positions.push_back(p);
    quad.normals.push_back(Eigen::Vector3f::UnitZ());
  }
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  ModelMaterial paint{"paint", {0.3f, 0.02f, 0.02f}};
  ModelMaterial lamp = paint;
  lamp.name = "lamp";
  lamp.emissive = {0.9f, 0.03f, 0.01f};
  model->materials = {paint, lamp};
  quad.material = 0;
  model->meshes.push_back(quad);
  quad.material = 1;
  model->meshes.push_back(quad);
  model->nodes.push_back(ModelNode{});  // the root, holding the two quads
  for (int i = 0; i < 2; ++i) {
    ModelNode node;
    node.parent = 0;
    node.local = Eigen::Affine3f(Eigen::Translation3f(i == 0 ? -0.7f : 0.7f, 0, 0)).matrix();
    node.meshes = {i};
    model->nodes.push_back(node);
    model->nodes[0].children.push_back(i + 1);
  }
  computeBounds(*model);
  FrameSnapshot frame;
  frame.sky.timeOfDay_h = 1.0f;  // night: the sun is below the horizon
  ModelInstance instance;
  instance.model = model;
  frame.models.push_back(instance);
  Camera& camera = m_renderer->camera();
  camera.target = {0, 0, 0};
  camera.yaw_rad = 0;
  camera.pitch_rad = 0;
  camera.distance_m = 3;
  const Image night = render(frame, "lamp_night.png");
  // The quads' centres on screen: the model straddles the middle, the plain
  // quad on one side, the lamp on the other.
  const auto left = m_renderer->viewPoint({-0.7f, 0, 0}), right = m_renderer->viewPoint({0.7f, 0, 0});
  ASSERT_TRUE(left && right);
  // View point (-1..1, y up) to pixel.
  auto at = [&](const Eigen::Vector2f& v) { return night.at(int((v.x() + 1) / 2 * kWidth), int((1 - v.y()) / 2 * kHeight)); };
  ASSERT_GT(right->x() - left->x(), 0.2f) << "both quads are in view";
  const std::uint8_t* plain = at(*left);
  const std::uint8_t* glowing = at(*right);
  // Linear 0.9 emitted is 0.95 on screen (gamma 2.2): the lamp reads near
  // full red whatever the night's ambient adds; the plain paint gets only
  // the night's ambient.
  EXPECT_GT(glowing[0], 235) << "lamp " << int(glowing[0]) << " " << int(glowing[1]) << " " << int(glowing[2]);
  EXPECT_LT(plain[0], 120) << "plain paint at night " << int(plain[0]);
  EXPECT_GT(glowing[0], glowing[1] + 150) << "the lamp glows red, not white";
}

// Two models, each with two materials, placed in alternation: unsorted the
// material would change at every draw; sorted, once per material.
TEST(MeshDrawList, DrawsAreSortedByMaterial) {
  auto makeModel = [](int materials) {
    auto model = std::make_shared<Model>();
    for (int m = 0; m < materials; ++m) {
      ModelMesh mesh;
      mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
      mesh.normals.assign(3, Eigen::Vector3f::UnitZ());
      mesh.triangles = {{0, 1, 2}};
      mesh.material = m;
      model->meshes.push_back(mesh);
      ModelMaterial material;
      material.name = std::string(1, char('a' + m));
      model->materials.push_back(material);
    }
    ModelNode root;
    for (int m = 0; m < materials; ++m) root.meshes.push_back(m);
    model->nodes.push_back(root);
    computeBounds(*model);
    return std::shared_ptr<const Model>(model);
  };
  auto a = makeModel(2), b = makeModel(2);
  std::vector<ModelInstance> instances;
  for (int i = 0; i < 10; ++i) {
    ModelInstance inst;
    inst.model = i % 2 ? a : b;
    inst.position = {float(i) - 5.0f, 0, 0};
    instances.push_back(inst);
  }
  Camera camera;
  camera.target = {0, 0, 0};
  camera.distance_m = 20;
  const Eigen::Matrix4f vp = makeFrameView(camera, 4.0f / 3.0f).viewProjection;
  std::vector<MeshDraw> draws;
  MeshStats stats;
  buildMeshDrawList(instances, vp, draws, stats);
  EXPECT_EQ(stats.drawCalls, 20);
  EXPECT_EQ(stats.materialSwitches, 4);  // (a, 0), (a, 1), (b, 0), (b, 1)

  // In instance order it would have been 20.
  std::vector<MeshDraw> unsorted;
  for (const ModelInstance& inst : instances) {
    for (int m = 0; m < 2; ++m) {
      MeshDraw d;
      d.model = inst.model.get();
      d.material = m;
      unsorted.push_back(d);
    }
  }
  EXPECT_EQ(countMaterialSwitches(unsorted), 20);

  // A tint is part of the material: two tints of one model, two binds each.
  for (int i = 0; i < 10; ++i) {
    instances[i].model = a;
    instances[i].tint = i % 2 ? Eigen::Vector3f(1, 0, 0) : Eigen::Vector3f(0, 1, 0);
  }
  buildMeshDrawList(instances, vp, draws, stats);
  EXPECT_EQ(stats.materialSwitches, 4);

  // Behind the camera: culled, nothing drawn.
  for (ModelInstance& inst : instances) inst.position = makeFrameView(camera, 4.0f / 3.0f).eye + Eigen::Vector3f(0, 0, 30);
  buildMeshDrawList(instances, vp, draws, stats);
  EXPECT_EQ(stats.drawCalls, 0);
  EXPECT_EQ(stats.nodesCulled, 10);
}

TEST_F(ModelRender, DroppedModelsLeaveTheGpu) {
  auto box = mustLoad(sharedAsset("models/BoxTextured.glb"));
  ASSERT_TRUE(box);
  FrameSnapshot frame;
  ModelInstance inst;
  inst.model = box;
  inst.position = m_renderer->camera().target;
  inst.scale = Eigen::Vector3f::Constant(3.0f);
  frame.models.push_back(inst);
  const Image shown = render(frame, "box.png");
  EXPECT_EQ(m_renderer->meshStats().modelsResident, 1);
  EXPECT_EQ(m_renderer->meshStats().drawCalls, 1);
  const Image sky = render(FrameSnapshot{}, "sky.png");
  EXPECT_NE(shown.rgb, sky.rgb);
  // The test still holds `box`: it stays resident until released.
  EXPECT_EQ(m_renderer->meshStats().modelsResident, 1);
  box.reset();
  inst.model.reset();
  frame.models.clear();
  render(frame, "sky2.png");
  EXPECT_EQ(m_renderer->meshStats().modelsResident, 0);
}

// The designer's palette pictures: the model alone fills the square (a 4 m
// jeep and a 10 cm wheel alike), nothing of it is cut off at the edges, and
// the window's frame is left as it was.
TEST_F(ModelRender, ThumbnailShowsTheWholeModelAndLeavesTheFrameAlone) {
  auto jeep = mustLoad(sharedAsset("models/jeep1.3ds"));
  auto wheel = mustLoad(sharedAsset("racecar/meshes/left_front_wheel.obj"));
  ASSERT_TRUE(jeep && wheel);
  const Image before = render(FrameSnapshot{}, "before_thumbnail.png");

  constexpr int kSide = 96;
  auto picture = [&](const std::shared_ptr<const Model>& model) {
    Image image;
    auto made = m_renderer->renderModelThumbnail(model, kSide);
    EXPECT_TRUE(made.ok()) << (made.ok() ? "" : made.error());
    if (!made.ok()) return image;
    EXPECT_EQ(made->width, kSide);
    std::vector<std::uint8_t> rgba(std::size_t(kSide) * kSide * 4);
    glBindTexture(GL_TEXTURE_2D, GLuint(made->texture));
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    m_renderer->freeUiImage(*made);
    image.width = image.height = kSide;
    for (std::size_t p = 0; p < rgba.size() / 4; ++p)
      for (int c = 0; c < 3; ++c) image.rgb.push_back(rgba[4 * p + std::size_t(c)]);
    return image;
  };
  const Image jeepPicture = picture(jeep), wheelPicture = picture(wheel);
  ASSERT_EQ(jeepPicture.width, kSide);
  ASSERT_EQ(wheelPicture.width, kSide);

  // The background is the corner's colour; the model covers a good part of
  // the square and none of its border.
  auto background = [](const Image& image) {
    const std::uint8_t* c = image.at(0, 0);
    return [r = int(c[0]), g = int(c[1]), b = int(c[2])](int pr, int pg, int pb) {
      return std::abs(pr - r) <= 3 && std::abs(pg - g) <= 3 && std::abs(pb - b) <= 3;
    };
  };
  for (const Image* image : {&jeepPicture, &wheelPicture}) {
    const auto isBackground = background(*image);
    const int border = 4 * (kSide - 1);
    const int borderBackground = countPixels(*image, isBackground, 0, 0, kSide, 1) +
                                 countPixels(*image, isBackground, 0, kSide - 1, kSide, kSide) +
                                 countPixels(*image, isBackground, 0, 1, 1, kSide - 1) +
                                 countPixels(*image, isBackground, kSide - 1, 1, kSide, kSide - 1);
    EXPECT_EQ(borderBackground, border) << "the model is cut off at the picture's edge";
    const int covered = kSide * kSide - countPixels(*image, isBackground);
    EXPECT_GT(covered, kSide * kSide / 6) << "the model should fill the picture, whatever its size";
  }
  // The jeep in its textured paint: the same geometry untextured shows none.
  auto plain = std::make_shared<Model>(*jeep);
  plain->images.clear();
  for (ModelMaterial& m : plain->materials) m.image = -1;
  const int olive = countPixels(jeepPicture, isOlive);
  EXPECT_GT(olive, 100);
  EXPECT_LT(countPixels(picture(plain), isOlive), olive / 10);

  // The window's frame is the one drawn before the pictures.
  const std::string after = m_scratch.file("after_thumbnail.png");
  ASSERT_TRUE(m_renderer->saveScreenshot(after).ok());
  EXPECT_EQ(loadPng(after).rgb, before.rgb);
  EXPECT_FALSE(m_renderer->renderModelThumbnail(jeep, 4).ok()) << "a size outside 16..512 is refused";
}

}  // namespace
}  // namespace tumble::render

namespace tumble::render {
namespace {

// Every model the project ships (the runtime's wheel in assets/models, the
// base mod's in mods/base/assets/models, made by `tumble meshgen`) loads
// without a warning, and all of them drawn side by side fill the frame with
// more than sky.
TEST_F(ModelRender, ShippedModelsLoadAndDraw) {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  ASSERT_NE(source, nullptr);
  const std::filesystem::path modDir = std::filesystem::path(source) / "mods/base/assets/models";
  const std::filesystem::path runtimeDir = std::filesystem::path(source) / "assets/models";
  const char* names[] = {"hatchback", "truck", "buggy", "wheel", "cockpit", "rock", "tree", "building", "barrier",
                         "checkpoint_arch"};
  FrameSnapshot frame;
  DrawShape ground;
  ground.kind = ShapeKind::Plane;
  ground.color = {0.45f, 0.5f, 0.42f};
  frame.shapes.push_back(ground);
  float x = -14;
  for (const char* name : names) {
    const std::filesystem::path& dir = std::string(name) == "wheel" ? runtimeDir : modDir;
    auto model = loadModel((dir / (std::string(name) + ".obj")).string());
    ASSERT_TRUE(model.ok()) << model.error();
    EXPECT_TRUE((*model)->warnings.empty()) << name << ": " << (*model)->warnings[0];
    const BoundingBox& box = (*model)->nodes[0].coverBox;
    const float width = box.max.x() - box.min.x();
    ModelInstance instance;
    instance.model = *model;
    instance.position = {x + width / 2 - box.center().x(), std::string(name) == "wheel" ? 0.35f : 0.0f, 0};
    if (std::string(name) == "building") instance.position.z() = -9;
    x += width + 0.6f;
    frame.models.push_back(instance);
  }
  Camera& camera = m_renderer->camera();
  camera.target = {0, 1.5f, 0};
  camera.yaw_rad = 0.35f;
  camera.pitch_rad = 0.35f;
  camera.distance_m = 26;
  const Image shot = render(frame, "shipped_models.png");
  EXPECT_EQ(m_renderer->meshStats().instances, 10);
  EXPECT_GE(m_renderer->meshStats().drawCalls, 10);
  // Red hatchback paint, yellow buggy tubes, green leaves are all in view.
  EXPECT_GT(countPixels(shot, test::isReddish), 100);
  EXPECT_GT(countPixels(shot, test::isYellowish), 20);
  EXPECT_GT(countPixels(shot, test::isGreenish), 100);
}

}  // namespace
}  // namespace tumble::render
