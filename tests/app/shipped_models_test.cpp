// The project's own models (mods/base/assets/models): regenerating them with
// the generator gives the committed bytes, every part is a closed surface,
// and mass properties computed from the meshes match the analytic solids.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "app/meshgen.h"
#include "core/file_util.h"
#include "physics/mass_properties.h"
#include "render/model.h"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;

fs::path modelsDir() {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  return fs::path(source ? source : ".") / "mods/base/assets/models";
}

std::shared_ptr<const render::Model> load(const std::string& name) {
  auto model = render::loadModel((modelsDir() / name).string());
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error());
  return model.ok() ? *model : nullptr;
}

physics::MassProperties massOf(const render::Model& model, Real density) {
  const render::FlatMesh flat = render::flattenModel(model);
  std::vector<Vec3> v;
  for (const Eigen::Vector3f& p : flat.positions) v.push_back(p.cast<Real>());
  return physics::massPropertiesOfMesh(v, flat.triangles, density);
}

TEST(ShippedModels, RegeneratingGivesTheCommittedBytes) {
  const std::vector<GeneratedFile> files = generateModelFiles();
  ASSERT_GE(files.size(), 28u);
  for (const GeneratedFile& file : files) {
    auto committed = readBinaryFile((modelsDir() / file.name).string());
    ASSERT_TRUE(committed.ok()) << file.name << " is generated but not committed: run `tumble meshgen`";
    const std::string bytes(committed->begin(), committed->end());
    EXPECT_TRUE(bytes == file.bytes) << file.name << " differs from what `tumble meshgen` writes now";
  }
  // Nothing stale: every committed file is one the generator makes.
  for (const auto& entry : fs::directory_iterator(modelsDir())) {
    const std::string name = entry.path().filename().string();
    bool known = false;
    for (const GeneratedFile& file : files) known |= file.name == name;
    EXPECT_TRUE(known) << name << " is in the models folder but not generated";
  }
}

TEST(ShippedModels, EveryPartIsAClosedSurface) {
  for (const char* name : {"hatchback.obj", "truck.obj", "buggy.obj", "wheel.obj", "cockpit.obj", "rock.obj",
                           "tree.obj", "building.obj", "barrier.obj", "checkpoint_arch.obj"}) {
    auto model = load(name);
    ASSERT_TRUE(model);
    // The wheel's tread and sides are two materials of one closed surface;
    // every other object (node) is closed on its own.
    if (std::string(name) == "wheel.obj") {
      const render::FlatMesh flat = render::flattenModel(*model);
      std::vector<Vec3> v;
      for (const auto& p : flat.positions) v.push_back(p.cast<Real>());
      EXPECT_TRUE(physics::isClosedMesh(v, flat.triangles)) << name;
      continue;
    }
    for (const render::ModelNode& node : model->nodes) {
      for (int m : node.meshes) {
        const render::ModelMesh& mesh = model->meshes[m];
        std::vector<Vec3> v;
        for (const auto& p : mesh.positions) v.push_back(p.cast<Real>());
        EXPECT_TRUE(physics::isClosedMesh(v, mesh.triangles)) << name << " part " << node.name;
      }
    }
  }
}

TEST(ShippedModels, WheelMassPropertiesMatchTheCylinder) {
  auto wheel = load("wheel.obj");
  ASSERT_TRUE(wheel);
  const Real density = 1100;  // kg/m^3, rubber
  const physics::MassProperties p = massOf(*wheel, density);
  ASSERT_TRUE(p.valid);
  // A 32-gon prism of circumradius 0.35 m, 0.25 m long along X: exact volume
  // n/2 r^2 sin(2 pi / n) w; the inertia is within 1 % of the solid cylinder.
  const double r = 0.35, w = 0.25, n = 32;
  const double volume = 0.5 * n * r * r * std::sin(2 * M_PI / n) * w;
  EXPECT_NEAR(p.volume_m3, volume, 1e-4);
  EXPECT_NEAR(p.mass_kg, density * volume, 0.1);
  EXPECT_LT(p.centreOfMass_m.norm(), 1e-4);
  const double m = p.mass_kg;
  EXPECT_NEAR(p.inertia_kgm2(0, 0) / (m * r * r / 2), 1.0, 0.01);
  EXPECT_NEAR(p.inertia_kgm2(1, 1) / (m * (3 * r * r + w * w) / 12), 1.0, 0.01);
  EXPECT_NEAR(p.inertia_kgm2(2, 2) / (m * (3 * r * r + w * w) / 12), 1.0, 0.01);
}

TEST(ShippedModels, BarrierMassPropertiesMatchTheBox) {
  auto barrier = load("barrier.obj");
  ASSERT_TRUE(barrier);
  const Real density = 2400;  // kg/m^3, concrete
  const physics::MassProperties p = massOf(*barrier, density);
  ASSERT_TRUE(p.valid);
  const double a = 2.0, b = 0.8, c = 0.4;  // m: x, y, z
  const double m = density * a * b * c;
  EXPECT_NEAR(p.mass_kg, m, 0.5);
  EXPECT_LT((p.centreOfMass_m - Vec3(0, 0.4, 0)).norm(), 1e-4);
  EXPECT_NEAR(p.inertia_kgm2(0, 0), m * (b * b + c * c) / 12, 0.5);
  EXPECT_NEAR(p.inertia_kgm2(1, 1), m * (a * a + c * c) / 12, 0.5);
  EXPECT_NEAR(p.inertia_kgm2(2, 2), m * (a * a + b * b) / 12, 0.5);
}

}  // namespace
}  // namespace tumble::app
