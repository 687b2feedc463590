// Models as plain data: loading real third-party files with assimp (the 3DS
// jeep of the driving paper, the RC car in Collada + OBJ, a binary glTF with
// an embedded texture), bad files, the object tree's bounds and view culling.
// No GL context needed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <stb_image_write.h>

#include "render/internal/camera_math.h"
#include "render/internal/model_import.h"
#include "render/model.h"
#include "shared_assets.h"

namespace tumble::render {
namespace {

using tumble::test::sharedAsset;
namespace fs = std::filesystem;

fs::path scratchDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("tumble_model_" + name + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::shared_ptr<const Model> mustLoad(const std::string& path) {
  auto model = loadModel(path);
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error());
  return model.ok() ? *model : nullptr;
}

// Mean colour of an image, 0..255 per channel.
Eigen::Vector3f meanColor(const ModelImage& image) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
    sum += Eigen::Vector3d(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]);
  }
  return (sum / double(image.rgba.size() / 4)).cast<float>();
}

void expectTreeBoundsHold(const Model& model) {
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const ModelNode& node = model.nodes[i];
    EXPECT_TRUE(node.coverBox.contains(node.tightBox)) << "node " << i;
    EXPECT_TRUE(node.coverSphere.contains(node.tightSphere)) << "node " << i;
    for (int child : node.children) {
      EXPECT_GT(child, int(i)) << "children come after their parent";
      EXPECT_TRUE(node.coverBox.contains(model.nodes[child].coverBox)) << "node " << i << " child " << child;
      EXPECT_TRUE(node.coverSphere.contains(model.nodes[child].coverSphere)) << "node " << i << " child " << child;
    }
    // The tight volumes hold every vertex of the node's meshes.
    for (int m : node.meshes) {
      for (const Eigen::Vector3f& p : model.meshes[m].positions) {
        const Eigen::Vector3f q = (node.toModel * p.homogeneous()).head<3>();
        BoundingBox point;
        point.add(q);
        EXPECT_TRUE(node.tightBox.contains(point));
        EXPECT_LE((q - node.tightSphere.center).norm(), node.tightSphere.radius_m * (1 + 1e-5f) + 1e-6f);
      }
    }
  }
}

TEST(ModelLoad, JeepThreeDsLoadsWithItsTexture) {
  auto jeep = mustLoad(sharedAsset("models/jeep1.3ds"));
  ASSERT_TRUE(jeep);
  // The author's readme: 2032 polygons with a 512x512 jpg.
  EXPECT_NEAR(double(jeep->triangleCount()), 2032.0, 40.0);
  ASSERT_EQ(jeep->images.size(), 1u);
  EXPECT_EQ(jeep->images[0].width, 512);
  EXPECT_EQ(jeep->images[0].height, 512);
  EXPECT_NE(jeep->images[0].source.find("jeep1.jpg"), std::string::npos) << jeep->images[0].source;
  EXPECT_TRUE(jeep->warnings.empty());
  int textured = 0;
  for (const ModelMesh& mesh : jeep->meshes) {
    EXPECT_EQ(mesh.uvs.size(), mesh.positions.size());
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    textured += jeep->materials[mesh.material].image == 0;
  }
  EXPECT_GT(textured, 0);
  // The jeep's skin is mostly olive-green camouflage: green channel leads blue.
  const Eigen::Vector3f mean = meanColor(jeep->images[0]);
  EXPECT_GT(mean.y(), mean.z()) << mean.transpose();
  expectTreeBoundsHold(*jeep);
}

TEST(ModelLoad, RcCarChassisAndWheelsLoad) {
  auto chassis = mustLoad(sharedAsset("racecar/meshes/chassis.dae"));
  ASSERT_TRUE(chassis);
  EXPECT_GT(chassis->triangleCount(), 50u);
  // The Collada chassis is coloured per vertex, a mid blue.
  bool blue = false;
  for (const ModelMesh& mesh : chassis->meshes) {
    if (!mesh.colors.empty()) blue = mesh.colors[0].z() > mesh.colors[0].x() + 0.2f;
  }
  EXPECT_TRUE(blue);
  expectTreeBoundsHold(*chassis);

  for (const char* wheel : {"left_front_wheel", "right_rear_wheel"}) {
    auto model = mustLoad(sharedAsset(std::string("racecar/meshes/") + wheel + ".obj"));
    ASSERT_TRUE(model);
    ASSERT_EQ(model->images.size(), 1u) << wheel;
    EXPECT_NE(model->images[0].source.find("wheel.jpg"), std::string::npos);
    EXPECT_TRUE(model->warnings.empty());
    // A wheel of the 1:10 car: about 11 cm across (URDF radius 0.05 m, file in metres).
    const BoundingBox& box = model->nodes[0].coverBox;
    const float diameter = (box.max - box.min).maxCoeff();
    EXPECT_GT(diameter, 0.05f);
    EXPECT_LT(diameter, 0.2f);
  }
}

TEST(ModelLoad, EmbeddedGlbTextureIsDecoded) {
  auto box = mustLoad(sharedAsset("models/BoxTextured.glb"));
  ASSERT_TRUE(box);
  ASSERT_EQ(box->images.size(), 1u);
  EXPECT_GT(box->images[0].width, 0);
  EXPECT_EQ(box->images[0].rgba.size(), std::size_t(box->images[0].width) * box->images[0].height * 4);
  EXPECT_EQ(box->triangleCount(), 12u);
  expectTreeBoundsHold(*box);
}

std::string base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= std::uint8_t(bytes[i + 2]);
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

// A text glTF 2.0 file written at `path`: one textured triangle whose
// material is `material` (JSON), buffer and a 2 x 2 red/green PNG as data URIs.
void writeTriangleGltf(const fs::path& path, const std::string& material) {
  const float data[] = {0, 0, 0, 1, 0, 0, 0, 1, 0,  // positions
                        0, 0, 1, 0, 0, 1};           // uvs
  const std::uint16_t indices[] = {0, 1, 2, 0};     // padded to 4 bytes
  std::string buffer(reinterpret_cast<const char*>(data), sizeof data);
  buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
  const unsigned char pixels[] = {255, 0, 0, 0, 255, 0, 0, 255, 0, 255, 0, 0};
  std::string png;
  stbi_write_png_to_func([](void* ctx, void* d, int n) { static_cast<std::string*>(ctx)->append(static_cast<char*>(d), n); },
                         &png, 2, 2, 3, pixels, 6);
  std::ofstream(path)
      << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],)"
      << R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],)"
      << R"("materials": [)" << material << "],"
      << R"("textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,)" << base64(png) << R"("}],)"
      << R"("buffers": [{"byteLength": )" << buffer.size() << R"(, "uri": "data:application/octet-stream;base64,)"
      << base64(buffer) << R"("}],)"
      << R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},)"
      << R"({"buffer": 0, "byteOffset": 60, "byteLength": 6}],)"
      << R"("accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},)"
      << R"({"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},)"
      << R"({"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
}

TEST(ModelLoad, TextGltfWithDataUriTextureLoads) {
  const fs::path dir = scratchDir("gltf");
  writeTriangleGltf(dir / "tri.gltf", R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})");
  auto model = mustLoad((dir / "tri.gltf").string());
  ASSERT_TRUE(model);
  EXPECT_EQ(model->triangleCount(), 1u);
  ASSERT_EQ(model->images.size(), 1u);
  EXPECT_EQ(model->images[0].width, 2);
  EXPECT_EQ(model->images[0].rgba[0], 255);  // top-left texel red
  EXPECT_EQ(model->images[0].rgba[5], 255);  // top-right texel green
  EXPECT_EQ(model->meshes[0].uvs.size(), 3u);
  EXPECT_TRUE(model->materials[0].emissive.isZero());
  fs::remove_all(dir);
}

// A lamp's glow: .mtl Ke and glTF emissiveFactor are read as linear colour
// (like Kd), a material without one gives off nothing, and an emissive
// texture (not drawn) does not make its surface glow in its factor's white.
TEST(ModelLoad, EmissiveColoursAreReadAndAnEmissiveTextureIsNotTakenForWhite) {
  const fs::path dir = scratchDir("emissive");
  std::ofstream(dir / "lamp.mtl") << "newmtl paint\nKd 0.8 0.1 0.1\n"
                                     "newmtl lamp\nKd 0.9 0.9 0.9\nKe 1.0 0.5 0.0\n";
  std::ofstream(dir / "lamp.obj") << "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "usemtl paint\nf 1 2 3\nusemtl lamp\nf 1 3 4\n";
  auto obj = mustLoad((dir / "lamp.obj").string());
  ASSERT_TRUE(obj);
  int lamps = 0;
  for (const ModelMaterial& m : obj->materials) {
    if (m.name == "lamp") {
      ++lamps;
      EXPECT_NEAR(m.emissive.x(), 1.0f, 1e-4f);
      EXPECT_NEAR(m.emissive.y(), 0.214f, 1e-3f);  // 0.5 sRGB is 0.214 linear
      EXPECT_NEAR(m.emissive.z(), 0.0f, 1e-6f);
    } else {
      EXPECT_TRUE(m.emissive.isZero()) << m.name;
    }
  }
  EXPECT_EQ(lamps, 1);

  writeTriangleGltf(dir / "glow.gltf", R"({"emissiveFactor": [0.0, 1.0, 0.5]})");
  auto glow = mustLoad((dir / "glow.gltf").string());
  ASSERT_TRUE(glow);
  EXPECT_NEAR(glow->materials[0].emissive.y(), 1.0f, 1e-4f);
  EXPECT_TRUE(glow->warnings.empty());

  writeTriangleGltf(dir / "textured.gltf", R"({"emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}})");
  auto textured = mustLoad((dir / "textured.gltf").string());
  ASSERT_TRUE(textured);
  EXPECT_TRUE(textured->materials[0].emissive.isZero());
  ASSERT_EQ(textured->warnings.size(), 1u);
  EXPECT_NE(textured->warnings[0].find("emissive texture is not drawn"), std::string::npos) << textured->warnings[0];
  fs::remove_all(dir);
}

TEST(ModelLoad, TruncatedJeepIsAClearErrorNotACrash) {
  const fs::path dir = scratchDir("truncated");
  std::ifstream in(sharedAsset("models/jeep1.3ds"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 10000u);
  for (std::size_t keep : {std::size_t(5), std::size_t(200), bytes.size() / 3, bytes.size() - 7}) {
    const fs::path file = dir / ("jeep_" + std::to_string(keep) + ".3ds");
    std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(keep));
    auto model = loadModel(file.string());
    // Either assimp refuses it, or what it salvaged is still consistent.
    if (!model.ok()) {
      EXPECT_NE(model.error().find(file.string()), std::string::npos) << model.error();
    } else {
      expectTreeBoundsHold(**model);
      EXPECT_LT((*model)->triangleCount(), 2100u);
    }
  }
  // Cut inside the header: there is nothing to salvage.
  auto tiny = loadModel((dir / "jeep_5.3ds").string());
  ASSERT_FALSE(tiny.ok());
  EXPECT_NE(tiny.error().find("jeep_5.3ds"), std::string::npos) << tiny.error();
  fs::remove_all(dir);
}

TEST(ModelLoad, NonModelAndMissingFilesAreClearErrors) {
  const fs::path dir = scratchDir("bad");
  const fs::path text = dir / "notes.obj";
  std::ofstream(text) << "this is a shopping list, not a model\nmilk\neggs\n";
  auto model = loadModel(text.string());
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().find("notes.obj"), std::string::npos) << model.error();

  const fs::path png = dir / "picture.3ds";
  std::ofstream(png, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n garbage", 17);
  auto notModel = loadModel(png.string());
  ASSERT_FALSE(notModel.ok());
  EXPECT_NE(notModel.error().find("picture.3ds"), std::string::npos) << notModel.error();

  auto missing = loadModel((dir / "nothing_here.glb").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().find("no such model file"), std::string::npos) << missing.error();
  fs::remove_all(dir);
}

// The model fuzzer's input that made Debian's assimp 5.2.5 loop for ever in
// its PLY importer (a list property with an unknown count type). Only the
// importers of the formats models come in are kept, so it is refused
// whatever it is called: as .ply (not a model format here), and as .obj or
// .gltf, which also hung: when the importer the name picks cannot read a
// file, assimp tries every importer on its content.
TEST(ModelLoad, APlyHeaderThatHangsAssimpIsRefusedUnderAnyName) {
  const fs::path dir = scratchDir("ply");
  const std::string hang =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int10\n4 0 1 2 3\n";
  for (const char* name : {"mesh.ply", "rock.obj", "tree.gltf", "no_extension"}) {
    const fs::path file = dir / name;
    std::ofstream(file, std::ios::binary) << hang;
    auto model = loadModel(file.string());
    ASSERT_FALSE(model.ok()) << name;
    EXPECT_NE(model.error().find(name), std::string::npos) << model.error();
    EXPECT_NE(model.error().find(".obj (+ .mtl), .gltf / .glb, .fbx, .dae or .3ds"), std::string::npos)
        << model.error();
  }
  fs::remove_all(dir);
}

// Debian's assimp 5.2.5 dereferences a null material when an .mtl has a
// texture line before its first newmtl (found by the model fuzzer). The
// import runs in its own process, so the game gets an error naming the
// file instead of dying with it.
TEST(ModelLoad, AnMtlThatCrashesAssimpIsAnErrorAndTheGameGoesOn) {
  const fs::path dir = scratchDir("crash");
  std::ofstream(dir / "crate.obj") << "mtllib crate.mtl\no crate\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "crate.mtl") << "map_Kd wood.png\nnewmtl wood\nKd 1 1 1\n";
  auto model = loadModel((dir / "crate.obj").string());
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().find("crate.obj: the model importer crashed on this file"), std::string::npos)
      << model.error();
  // The same files with the texture inside the material load.
  std::ofstream(dir / "crate.mtl") << "newmtl wood\nKd 1 1 1\nmap_Kd wood.png\n";
  auto fixed = loadModel((dir / "crate.obj").string());
  ASSERT_TRUE(fixed.ok()) << fixed.error();
  EXPECT_EQ((*fixed)->triangleCount(), 1u);
  fs::remove_all(dir);
}

// An importer that never answers is stopped at the model's time limit, and
// one that answers nonsense is refused, with messages naming the file.
TEST(ModelLoad, AnImporterThatHangsIsStoppedAndADamagedAnswerIsRefused) {
  const fs::path dir = scratchDir("hang");
  std::ofstream(dir / "box.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const fs::path hang = dir / "hang.sh", garbage = dir / "garbage.sh";
  std::ofstream(hang) << "#!/bin/sh\nexec sleep 30\n";
  std::ofstream(garbage) << "#!/bin/sh\nprintf 'TIM1 this is not a model'\n";
  fs::permissions(hang, fs::perms::owner_all);
  fs::permissions(garbage, fs::perms::owner_all);
  ModelLoadOptions quick;
  quick.importTimeout_s = 1;
  ::setenv("TUMBLE_MODEL_IMPORTER", hang.c_str(), 1);
  auto hung = loadModel((dir / "box.obj").string(), quick);
  ::setenv("TUMBLE_MODEL_IMPORTER", garbage.c_str(), 1);
  auto damaged = loadModel((dir / "box.obj").string(), quick);
  ::setenv("TUMBLE_MODEL_IMPORTER", (dir / "missing").c_str(), 1);
  auto missing = loadModel((dir / "box.obj").string(), quick);
  ::unsetenv("TUMBLE_MODEL_IMPORTER");
  ASSERT_FALSE(hung.ok());
  EXPECT_NE(hung.error().find("box.obj: the model importer did not finish within 1 s"), std::string::npos)
      << hung.error();
  ASSERT_FALSE(damaged.ok());
  EXPECT_NE(damaged.error().find("box.obj: the model importer's answer is damaged"), std::string::npos)
      << damaged.error();
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().find("cannot start the model importer"), std::string::npos) << missing.error();
  auto real = loadModel((dir / "box.obj").string(), quick);
  ASSERT_TRUE(real.ok()) << real.error();
  fs::remove_all(dir);
}

// The importer's answer carries the whole model: what the game gets through
// it is what the loader made, field for field; every cut of the answer and
// every changed byte is refused or gives a model whose indices all hold.
TEST(ModelImport, TheAnswerCarriesTheModelAndDamagedAnswersAreRefused) {
  const std::string path = sharedAsset("models/cube_with_diffuse_texture.3DS");
  if (path.empty()) GTEST_SKIP() << "../shared/assets/third_party not found";
  auto here = loadModelInThisProcess(path, {});
  ASSERT_TRUE(here.ok()) << here.error();
  auto there = loadModel(path);
  ASSERT_TRUE(there.ok()) << there.error();
  const Model &a = **here, &b = **there;
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  ASSERT_EQ(a.materials.size(), b.materials.size());
  ASSERT_EQ(a.images.size(), b.images.size());
  EXPECT_EQ(a.warnings, b.warnings);
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
    EXPECT_EQ(a.meshes[i].normals, b.meshes[i].normals);
    EXPECT_EQ(a.meshes[i].uvs, b.meshes[i].uvs);
    EXPECT_EQ(a.meshes[i].triangles, b.meshes[i].triangles);
    EXPECT_EQ(a.meshes[i].material, b.meshes[i].material);
  }
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].toModel, b.nodes[i].toModel);
    EXPECT_EQ(a.nodes[i].children, b.nodes[i].children);
    EXPECT_EQ(a.nodes[i].coverBox.min, b.nodes[i].coverBox.min);
    EXPECT_EQ(a.nodes[i].coverBox.max, b.nodes[i].coverBox.max);
  }
  for (std::size_t i = 0; i < a.images.size(); ++i) EXPECT_EQ(a.images[i].rgba, b.images[i].rgba);
  for (std::size_t i = 0; i < a.materials.size(); ++i) EXPECT_EQ(a.materials[i].image, b.materials[i].image);

  // Damaged answers: cuts and changed bytes (the image's pixels are most of
  // the bytes; steps keep this quick while every field is hit).
  const std::string bytes = encodeImportResult(here);
  int taken = 0, refused = 0;
  auto check = [&](const std::string& changed) {
    auto m = decodeImportResult(changed, "x");
    if (!m.ok()) {
      ++refused;
      EXPECT_NE(m.error().find("x: "), std::string::npos) << m.error();
      return;
    }
    ++taken;
    const Model& model = **m;
    for (const ModelNode& node : model.nodes)
      for (int c : node.children) ASSERT_LT(std::size_t(c), model.nodes.size());
    for (const ModelMesh& mesh : model.meshes) {
      ASSERT_LT(std::size_t(mesh.material), model.materials.size());
      for (const auto& t : mesh.triangles)
        for (std::uint32_t v : t) ASSERT_LT(v, mesh.positions.size());
    }
  };
  for (std::size_t cut = 0; cut < bytes.size(); cut += 1 + cut / 64) check(bytes.substr(0, cut));
  for (std::size_t at = 0; at < bytes.size(); at += 1 + at / 256)
    for (unsigned char v : {0x00, 0x01, 0x7f, 0x80, 0xff}) {
      std::string changed = bytes;
      changed[at] = char(v);
      check(changed);
    }
  EXPECT_GT(refused, 0);
  EXPECT_GT(taken, 0);  // pixel and coordinate bytes may take any value
}

TEST(ModelLoad, MissingTextureFallsBackToTheMaterialColourWithAWarning) {
  const fs::path dir = scratchDir("missing_texture");
  std::ofstream(dir / "crate.mtl") << "newmtl crate\nKd 0.9 0.2 0.1\nmap_Kd crate_wood.png\n";
  std::ofstream(dir / "crate.obj") << "mtllib crate.mtl\nusemtl crate\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                      "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  auto model = mustLoad((dir / "crate.obj").string());
  ASSERT_TRUE(model);
  EXPECT_TRUE(model->images.empty());
  ASSERT_EQ(model->warnings.size(), 1u);
  EXPECT_NE(model->warnings[0].find("crate_wood.png"), std::string::npos) << model->warnings[0];
  const ModelMaterial& material = model->materials[model->meshes[0].material];
  EXPECT_EQ(material.image, -1);
  EXPECT_GT(material.diffuse.x(), 0.7f);  // 0.9 sRGB -> 0.79 linear
  EXPECT_LT(material.diffuse.y(), 0.1f);
  fs::remove_all(dir);
}

// A hand-made tree: root (no mesh) -> two children, one with a grandchild
// far away, to check covering volumes and culling.
Model makeTree() {
  Model model;
  ModelMesh cube;
  for (int i = 0; i < 8; ++i) {
    cube.positions.emplace_back(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f);
    cube.normals.push_back(cube.positions.back().normalized());
  }
  cube.triangles = {{0, 1, 2}};
  model.meshes.push_back(cube);
  model.materials.push_back(ModelMaterial{});
  auto node = [&](int parent, const Eigen::Vector3f& offset) {
    ModelNode n;
    n.parent = parent;
    n.local = Eigen::Affine3f(Eigen::Translation3f(offset)).matrix();
    n.meshes = {0};
    model.nodes.push_back(n);
    if (parent >= 0) model.nodes[parent].children.push_back(int(model.nodes.size()) - 1);
  };
  node(-1, {0, 0, 0});
  model.nodes[0].meshes.clear();
  node(0, {2, 0, 0});
  node(0, {-2, 0, 0});
  node(2, {0, 0, -30});  // grandchild, 30 m further along -Z of its parent
  computeBounds(model);
  return model;
}

TEST(ModelTree, CoveringVolumesContainTheirChildren) {
  const Model model = makeTree();
  expectTreeBoundsHold(model);
  EXPECT_TRUE(model.nodes[0].tightBox.empty);
  // The root covers the grandchild at z = -30 +- 0.5.
  EXPECT_NEAR(model.nodes[0].coverBox.min.z(), -30.5f, 1e-5f);
  EXPECT_NEAR(model.nodes[0].coverBox.max.x(), 2.5f, 1e-5f);
  // The grandchild's tight sphere: the cube's half diagonal.
  EXPECT_NEAR(model.nodes[3].tightSphere.radius_m, std::sqrt(0.75f), 1e-5f);
}

TEST(ModelTree, NodesBehindTheCameraAreCulled) {
  const Model model = makeTree();
  Camera camera;
  camera.target = {0, 0, -10};  // looking down -Z from z = +4
  camera.yaw_rad = 0;
  camera.pitch_rad = 0;
  camera.distance_m = 14;
  const Eigen::Matrix4f vp = makeFrameView(camera, 1.5f).viewProjection;
  std::vector<int> visible;
  cullModel(model, Eigen::Matrix4f::Identity(), vp, visible);
  EXPECT_EQ(visible, (std::vector<int>{1, 2, 3}));

  // Model turned 180 degrees about Y: the children at x = -+2 stay in view,
  // the grandchild moves to z = +30, behind the camera at z = +4.
  Eigen::Matrix4f turn = Eigen::Affine3f(Eigen::AngleAxisf(float(kPi), Eigen::Vector3f::UnitY())).matrix();
  cullModel(model, turn, vp, visible);
  EXPECT_EQ(visible, (std::vector<int>{1, 2}));

  // The whole model behind the camera: the root's covering volume fails, so
  // no child is even looked at.
  int tested = 0;
  const Eigen::Matrix4f behind = Eigen::Affine3f(Eigen::Translation3f(0, 0, 80)).matrix() * turn;
  cullModel(model, behind, vp, visible, &tested);
  EXPECT_TRUE(visible.empty());
  EXPECT_EQ(tested, 1);
}

TEST(ModelTree, OverlapQuerySkipsSubtreesEarly) {
  const Model model = makeTree();
  std::vector<int> nodes;
  int tested = 0;
  BoundingBox box;
  // A box around the grandchild (model z = -30), model placed 100 m up X.
  const Eigen::Matrix4f place = Eigen::Affine3f(Eigen::Translation3f(100, 0, 0)).matrix();
  box.add(Eigen::Vector3f(97.5f, -0.2f, -30.2f));
  box.add(Eigen::Vector3f(98.5f, 0.2f, -29.8f));
  overlapModel(model, place, box, nodes, &tested);
  EXPECT_EQ(nodes, (std::vector<int>{3}));
  // Node 1 (x = +2) is looked at and dropped; nothing below it exists.
  EXPECT_EQ(tested, 4);

  // Far from everything: only the root's covering sphere is tested.
  BoundingBox far;
  far.add(Eigen::Vector3f(0, 50, 0));
  far.add(Eigen::Vector3f(1, 51, 1));
  overlapModel(model, place, far, nodes, &tested);
  EXPECT_TRUE(nodes.empty());
  EXPECT_EQ(tested, 1);

  // Scaled by 2: the grandchild moves to z = -60 and grows to 2 m.
  const Eigen::Matrix4f scaled = Eigen::Affine3f(Eigen::Scaling(2.0f)).matrix();
  BoundingBox nearScaled;
  nearScaled.add(Eigen::Vector3f(-4.9f, 0, -60));
  nearScaled.add(Eigen::Vector3f(-4.8f, 0.1f, -59.9f));
  overlapModel(model, scaled, nearScaled, nodes, &tested);
  EXPECT_EQ(nodes, (std::vector<int>{3}));
}

}  // namespace
}  // namespace tumble::render
