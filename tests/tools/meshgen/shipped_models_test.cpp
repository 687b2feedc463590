// The project's own models (the runtime's assets/models and the base mod's
// mods/base/assets/models, made by tools/meshgen): regenerating them with the
// generator gives the committed bytes, every part is a closed surface, and
// mass properties computed from the meshes match the analytic solids.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <tuple>

#include "tools/meshgen/meshgen.h"
#include "core/file_util.h"
#include "physics/mass_properties.h"
#include "render/model.h"

namespace tumble::tools {
namespace {

namespace fs = std::filesystem;

fs::path sourceDir() {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  return fs::path(source ? source : ".");
}

// The committed file `name`, in the folder the generator puts it in.
fs::path modelPath(const std::string& name) {
  for (const GeneratedFolder& folder : generateModelFolders())
    for (const GeneratedFile& file : folder.files)
      if (file.name == name) return sourceDir() / folder.path / name;
  ADD_FAILURE() << name << " is not a generated file";
  return sourceDir() / name;
}

std::shared_ptr<const render::Model> load(const std::string& name) {
  auto model = render::loadModel(modelPath(name).string());
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
  const std::vector<GeneratedFolder> folders = generateModelFolders();
  ASSERT_EQ(folders.size(), 2u);
  // The runtime's wheel and its two textures; the base mod's 12 models
  // (the hatchback and the truck twice: each one's inertia solid and its
  // body with wheel arches) and 6 textures.
  EXPECT_EQ(folders[0].path, "assets/models");
  EXPECT_EQ(folders[0].files.size(), 4u);
  EXPECT_EQ(folders[1].path, "mods/base/assets/models");
  EXPECT_EQ(folders[1].files.size(), 30u);
  for (const GeneratedFolder& folder : folders) {
    const fs::path dir = sourceDir() / folder.path;
    for (const GeneratedFile& file : folder.files) {
      auto committed = readBinaryFile((dir / file.name).string());
      ASSERT_TRUE(committed.ok()) << folder.path << "/" << file.name
                                  << " is generated but not committed: run `tumble meshgen`";
      const std::string bytes(committed->begin(), committed->end());
      EXPECT_TRUE(bytes == file.bytes) << folder.path << "/" << file.name
                                       << " differs from what `tumble meshgen` writes now";
    }
    // Nothing stale: every committed file is one the generator makes.
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      bool known = false;
      for (const GeneratedFile& file : folder.files) known |= file.name == name;
      EXPECT_TRUE(known) << folder.path << "/" << name << " is in a generated folder but not generated";
    }
  }
}

TEST(ShippedModels, EveryPartIsAClosedSurface) {
  for (const char* name : {"hatchback.obj", "hatchback_shaped.obj", "truck.obj", "truck_shaped.obj", "buggy.obj", "wheel.obj", "cockpit.obj",
                           "rock.obj", "tree.obj", "building.obj", "barrier.obj", "checkpoint_arch.obj"}) {
    auto model = load(name);
    ASSERT_TRUE(model);
    // The wheel's tread and sides, and the three car bodies, are
    // materials of one closed surface; every other object (node) is closed
    // on its own.
    const std::string n = name;
    if (n == "wheel.obj" || n == "hatchback.obj" || n == "hatchback_shaped.obj" || n == "truck.obj" ||
        n == "truck_shaped.obj" || n == "buggy.obj") {
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

/// Edges, faces and vertices of a model with coincident vertices welded;
/// checks it is one connected, closed, consistently wound 2-manifold
/// (every edge used once in each direction; around every vertex the faces
/// form one fan) and returns its Euler characteristic V - E + F.
int checkOneManifoldSurface(const render::FlatMesh& flat, const std::string& name) {
  std::map<std::tuple<float, float, float>, std::uint32_t> ids;
  std::vector<std::uint32_t> weld;
  for (const Eigen::Vector3f& p : flat.positions)
    weld.push_back(ids.emplace(std::make_tuple(p.x(), p.y(), p.z()), std::uint32_t(ids.size())).first->second);
  std::vector<Vec3> v;
  for (const auto& p : flat.positions) v.push_back(p.cast<Real>());
  EXPECT_TRUE(physics::isClosedMesh(v, flat.triangles)) << name << " is not closed";
  // Vertex links: for triangle (a, b, c) the vertex a sees the edge b -> c.
  std::vector<std::map<std::uint32_t, std::uint32_t>> link(ids.size());
  int repeated = 0;  // a vertex that sees the same link edge twice: more than one sheet through it
  std::vector<std::uint32_t> parent(flat.triangles.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edgeFace;
  for (std::uint32_t f = 0; f < flat.triangles.size(); ++f) {
    parent[f] = f;
    const auto& t = flat.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = weld[t[k]], b = weld[t[(k + 1) % 3]], c = weld[t[(k + 2) % 3]];
      repeated += !link[a].emplace(b, c).second;
      edgeFace[{a, b}] = f;
    }
  }
  EXPECT_EQ(repeated, 0) << name << ": edges or vertices shared by more than two faces";
  int pinched = 0;
  for (const auto& l : link) {
    if (l.empty()) continue;
    std::size_t steps = 0;
    std::uint32_t at = l.begin()->first;
    do {
      auto it = l.find(at);
      if (it == l.end()) break;
      at = it->second, ++steps;
    } while (at != l.begin()->first && steps <= l.size());
    pinched += steps != l.size();
  }
  EXPECT_EQ(pinched, 0) << name << ": vertices where two sheets of the surface touch";
  // One connected piece: union the faces across each edge.
  std::function<std::uint32_t(std::uint32_t)> root = [&](std::uint32_t f) {
    return parent[f] == f ? f : parent[f] = root(parent[f]);
  };
  for (const auto& [edge, f] : edgeFace)
    if (auto it = edgeFace.find({edge.second, edge.first}); it != edgeFace.end()) parent[root(f)] = root(it->second);
  std::size_t pieces = 0;
  for (std::uint32_t f = 0; f < parent.size(); ++f) pieces += root(f) == f;
  EXPECT_EQ(pieces, 1u) << name << " is not one connected surface";
  const int V = int(ids.size()), E = int(edgeFace.size() / 2), F = int(flat.triangles.size());
  return V - E + F;
}

// chassis.inertia = "mesh" needs the chassis to be one closed solid: the
// hatchback, truck and buggy bodies are one connected, closed, outward-wound
// manifold each (no overlapping parts counted twice), of the topology they
// are built with: the hatchback a sphere (Euler characteristic 2), the truck
// a sphere with a pocket (2), the buggy a pan with a roll cage of four
// independent loops (each side frame, and the two cross tubes joining
// them), genus 4: 2 - 2 * 4 = -6.
TEST(ShippedModels, CarBodiesAreEachOneClosedManifoldSolid) {
  for (const auto& [name, euler] :
       {std::pair{"hatchback.obj", 2}, std::pair{"hatchback_shaped.obj", 2}, std::pair{"truck.obj", 2},
        std::pair{"truck_shaped.obj", 2}, std::pair{"buggy.obj", -6}}) {
    auto model = load(name);
    ASSERT_TRUE(model);
    const render::FlatMesh flat = render::flattenModel(*model);
    EXPECT_EQ(checkOneManifoldSurface(flat, name), euler) << name;
    const physics::MassProperties p = massOf(*model, 1);
    EXPECT_TRUE(p.valid && p.volume_m3 > 0) << name << " must be wound outward";
  }
}

// Every car has lamps that glow (an emissive colour, .mtl Ke) at both ends:
// headlights facing forward (+Z) in the front half, tail lights facing back
// in the rear half, red; nothing else on the car gives off light. Each lamp
// is a pair, one either side of the middle.
TEST(ShippedModels, EveryCarHasGlowingHeadlightsInFrontAndTailLightsBehind) {
  for (const char* name : {"hatchback.obj", "hatchback_shaped.obj", "truck.obj", "truck_shaped.obj", "buggy.obj"}) {
    auto model = load(name);
    ASSERT_TRUE(model);
    double front = 0, back = 0;                     // lamp area, m^2
    double frontLeft = 0, backLeft = 0;             // of it at x < 0
    for (const render::ModelMesh& mesh : model->meshes) {
      const render::ModelMaterial& material = model->materials[std::size_t(mesh.material)];
      const bool head = material.name == "headlight", tail = material.name == "taillight";
      if (!head && !tail) {
        EXPECT_TRUE(material.emissive.isZero()) << name << ": " << material.name << " glows";
        continue;
      }
      EXPECT_GT(material.emissive.x(), 0.5f) << name << ": " << material.name;
      if (tail) EXPECT_GT(material.emissive.x(), 10 * material.emissive.y()) << name << ": tail lights are red";
      for (const auto& t : mesh.triangles) {
        const Eigen::Vector3f a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
        const Eigen::Vector3f cross = (b - a).cross(c - a);
        const double area = 0.5 * cross.norm();
        const Eigen::Vector3f centre = (a + b + c) / 3, n = cross.normalized();
        if (head) {
          EXPECT_GT(n.z(), 0.3f) << name << ": a headlight face not facing forward";
          EXPECT_GT(centre.z(), 0.0f) << name << ": a headlight in the rear half";
          front += area;
          if (centre.x() < 0) frontLeft += area;
        } else {
          EXPECT_LT(n.z(), -0.9f) << name << ": a tail light face not facing back";
          EXPECT_LT(centre.z(), 0.0f) << name << ": a tail light in the front half";
          back += area;
          if (centre.x() < 0) backLeft += area;
        }
      }
    }
    // At least a 10 x 7 cm lamp each side.
    EXPECT_GT(front, 2 * 0.007) << name;
    EXPECT_GT(back, 2 * 0.007) << name;
    EXPECT_NEAR(frontLeft, front / 2, 1e-6) << name << ": headlights in a left and right pair";
    EXPECT_NEAR(backLeft, back / 2, 1e-6) << name << ": tail lights in a left and right pair";
  }
}

// The hatchback is its side profile extruded across the 1.56 m body plus
// the two bumpers, every cell solid across the whole width: its volume is
// the profile's area times the width. Parts that overlap (glass or bumpers
// laid over the body) would count their shared volume twice.
TEST(ShippedModels, HatchbackVolumeIsItsProfileTimesItsWidth) {
  auto model = load("hatchback.obj");
  ASSERT_TRUE(model);
  const physics::MassProperties p = massOf(*model, 1);
  ASSERT_TRUE(p.valid);
  // Outline (z, y) in m, shoelace area.
  const double outline[][2] = {{-2.0, 0.28}, {2.0, 0.28}, {2.0, 0.78}, {1.25, 0.92}, {0.45, 1.42}, {-1.55, 1.45}, {-2.0, 0.95}};
  double area = 0;
  for (std::size_t i = 0; i < std::size(outline); ++i) {
    const auto& a = outline[i];
    const auto& b = outline[(i + 1) % std::size(outline)];
    area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
  }
  const double width = 1.56, bumpers = 2 * 0.07 * 0.17;  // m, m^2
  EXPECT_NEAR(p.volume_m3, std::abs(area) * width + bumpers * width, 1e-3);
  EXPECT_LT(std::abs(p.centreOfMass_m.x()), 1e-4) << "symmetric across the width";
}

// The jump ramp: a right-angled wedge 6 m long, 0.9 m high, 4 m wide.
TEST(ShippedModels, RampIsAWedgeRisingAlongZ) {
  auto ramp = load("ramp.obj");
  ASSERT_TRUE(ramp);
  const physics::MassProperties p = massOf(*ramp, 1);
  ASSERT_TRUE(p.valid);
  const double length = 6, lip = 0.9, width = 4;
  EXPECT_NEAR(p.volume_m3, 0.5 * length * lip * width, 1e-4);
  // A triangle's centroid: a third of the way up, two thirds of the way along.
  EXPECT_LT((p.centreOfMass_m - Vec3(0, Real(lip / 3), Real(length / 2 - length / 3))).norm(), 1e-4);
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
}  // namespace tumble::tools
