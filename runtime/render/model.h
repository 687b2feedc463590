#pragma once
// Models as plain data: a node tree with transforms, triangle meshes,
// materials and decoded texture images. Loaded with assimp (model_loader.cpp:
// .obj + .mtl, .gltf / .glb, .fbx, .dae and .3ds: only those importers), but
// nothing in this header is assimp or OpenGL, so the app can compute mass
// properties or collision boxes from a Model without a GL context, and tests
// can check bounds and culling without one.
//
// Index
//   ModelImage, ModelMaterial, ModelMesh    textures, materials, triangles
//   BoundingSphere, BoundingBox             bounds (model space)
//   ModelNode, Model                        the object tree (as in the driving paper)
//   loadModel                               assimp -> Model, with clear errors
//   computeBounds, cullModel                tree bounds; view culling with them
//   overlapModel                            nodes near a world box (early-out for collision tests)
//   flattenModel                            every triangle in model space (mass properties)
//
// "Model space" is the frame of the root node's parent: a node's toModel
// matrix maps its local coordinates there. An instance of a model is drawn
// with one more transform, model space -> world.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"

namespace tumble::render {

/// Decoded texture: RGBA8, rows top-down (uv (0, 0) is the top-left texel;
/// the loader flips assimp's v so that this holds).
struct ModelImage {
  std::string source;  // file path, or "<file>:*N" for an embedded texture
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4
};

struct ModelMaterial {
  std::string name;
  Eigen::Vector3f diffuse{0.8f, 0.8f, 0.8f};  // linear RGB 0..1 (multiplies the texture)
  int image = -1;  // index into Model::images; -1: untextured (colour only)
  // Light the surface gives off itself (a lamp), linear RGB 0..1, added to
  // the lit colour whatever the sun and sky: .mtl `Ke`, glTF
  // `emissiveFactor`, 3DS self-illumination colour. Zero for most materials.
  Eigen::Vector3f emissive = Eigen::Vector3f::Zero();
};

struct BoundingBox {
  Eigen::Vector3f min{0, 0, 0}, max{0, 0, 0};  // m
  bool empty = true;  // no point added yet
  void add(const Eigen::Vector3f& p);
  void add(const BoundingBox& other);
  bool contains(const BoundingBox& other, float tolerance_m = 1e-4f) const;
  Eigen::Vector3f center() const { return 0.5f * (min + max); }
};

struct BoundingSphere {
  Eigen::Vector3f center{0, 0, 0};  // m
  float radius_m = -1;              // negative: empty
  bool empty() const { return radius_m < 0; }
  /// Grows to the smallest sphere containing this one and `other`.
  void add(const BoundingSphere& other);
  bool contains(const BoundingSphere& other, float tolerance_m = 1e-4f) const;
};

/// Triangles with one material. Attributes are per vertex, in the owning
/// node's local frame; normals are unit length.
struct ModelMesh {
  std::vector<Eigen::Vector3f> positions;  // m
  std::vector<Eigen::Vector3f> normals;
  std::vector<Eigen::Vector2f> uvs;        // empty when the mesh has none
  std::vector<Eigen::Vector3f> colors;     // linear RGB 0..1 per vertex; empty when none
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  int material = 0;  // index into Model::materials
};

/// A node of the object tree: meshes, a transform, children. The bounds are
/// in model space: `tight*` cover the node's own meshes only, `cover*` also
/// every descendant, so a query can drop a whole subtree with one test.
struct ModelNode {
  std::string name;
  int parent = -1;                 // -1 for the root (node 0)
  std::vector<int> children;       // indices into Model::nodes, each > this node's
  std::vector<int> meshes;         // indices into Model::meshes
  Eigen::Matrix4f local = Eigen::Matrix4f::Identity();    // to the parent's frame
  Eigen::Matrix4f toModel = Eigen::Matrix4f::Identity();  // to model space (product up the tree)
  BoundingBox tightBox, coverBox;
  BoundingSphere tightSphere, coverSphere;
};

struct Model {
  std::string source;  // the file it came from
  std::vector<ModelNode> nodes;  // nodes[0] is the root; parents come before children
  std::vector<ModelMesh> meshes;
  std::vector<ModelMaterial> materials;
  std::vector<ModelImage> images;
  std::vector<std::string> warnings;  // e.g. a texture that was not found
  std::size_t triangleCount() const;
};

struct ModelLoadOptions {
  float scale = 1.0f;  // uniform factor applied to the root (file units -> m)
  /// The importer process is stopped after this long, s (a file assimp
  /// loops on); the largest models the loader takes import in a few seconds.
  double importTimeout_s = 60.0;
};

/// Loads a model with assimp, in a process of its own (tumble_model_import,
/// render/internal/model_import.h): a file that crashes or hangs assimp is
/// an error naming it, never a crash or a hang of the game. Textures are decoded with stb_image: files next
/// to the model (names matched case-insensitively, as old 3DS files store
/// them upper-case) and textures embedded in .glb / .gltf / .3ds. A missing or
/// unreadable texture is not an error: the material keeps its colour and a
/// warning naming the texture goes to Model::warnings and the log. A file
/// that is missing, truncated, not a model, or has no triangles is an error
/// whose message starts with the path and says what is wrong. Every file the
/// model refers to (an .obj's .mtl, textures, glTF buffers) must be a regular
/// file inside the model's folder: paths such as "../../etc/passwd" in a
/// material are not read (the texture counts as missing).
Result<std::shared_ptr<const Model>> loadModel(const std::string& path, const ModelLoadOptions& options = {});
/// True if the file's name ends in the extension of a format loadModel
/// reads (.obj, .gltf, .glb, .fbx, .dae, .3ds; any case): what palettes list.
bool hasModelExtension(const std::string& path);

/// Recomputes toModel and every node's tight and covering bounds (the loader
/// calls it; call it again after editing a Model by hand).
void computeBounds(Model& model);

/// Nodes whose meshes are (possibly) visible through `viewProjection` when
/// the model is placed by `modelToWorld`, in tree order. A subtree whose
/// covering sphere or box is entirely outside one frustum plane is skipped
/// without visiting it. `nodesTested` (optional) counts nodes looked at.
void cullModel(const Model& model, const Eigen::Matrix4f& modelToWorld, const Eigen::Matrix4f& viewProjection,
               std::vector<int>& visibleNodes, int* nodesTested = nullptr);

/// Nodes with meshes whose tight bounds may overlap `worldBox` when the
/// model is placed by `modelToWorld` (rigid or uniformly scaled), in tree
/// order: the broad test before any triangle test. A subtree whose covering
/// sphere misses the box is skipped without visiting it. `nodesTested`
/// (optional) counts nodes looked at.
void overlapModel(const Model& model, const Eigen::Matrix4f& modelToWorld, const BoundingBox& worldBox,
                  std::vector<int>& nodes, int* nodesTested = nullptr);

/// Every triangle of the model in model space, vertices shared within each
/// mesh: what massPropertiesOfMesh and collision boxes need.
struct FlatMesh {
  std::vector<Eigen::Vector3f> positions;  // m
  std::vector<std::array<std::uint32_t, 3>> triangles;
};
FlatMesh flattenModel(const Model& model);

}  // namespace tumble::render
