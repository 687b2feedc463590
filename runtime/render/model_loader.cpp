// loadModel: assimp -> plain Model (model.h). assimp parses the formats and
// triangulates; stb_image decodes textures. Everything assimp-specific stays
// in this file.
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <stb_image.h>  // libstb provides the implementation

#include <algorithm>
#include <assimp/BaseImporter.h>
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include "render/internal/model_import.h"
#include "render/model.h"

namespace tumble::render {

namespace {

namespace fs = std::filesystem;

// Caps that keep a hostile or corrupt file from exhausting memory.
constexpr std::size_t kMaxTriangles = 4'000'000;
constexpr int kMaxTextureSide = 8192;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

Eigen::Matrix4f toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4f out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out(r, c) = m[r][c];
  return out;
}

// sRGB 0..1 (what modelling tools store) -> linear, like the shape colours.
// Out of range is clamped; NaN reads as 0.
float srgbToLinear(float c) {
  if (!(c > 0.0f)) return 0.0f;
  c = std::min(c, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// The formats a model may be in: what modelling tools export for games.
// Only these importers of assimp's ~40 are kept. Debian's assimp 5.2.5 PLY
// importer loops for ever on a header whose list property has an unknown
// count type ("property list uchar int10 ..."; found by the model fuzzer),
// and assimp picks an importer by content when none claims the name, so a
// mod's "tree.obj" holding that text reached it. Fewer importers, less of
// third-party parsing a mod's file can reach.
constexpr const char* kModelFormats[] = {"obj", "gltf", "glb", "fbx", "dae", "3ds"};
constexpr const char* kModelFormatList = ".obj (+ .mtl), .gltf / .glb, .fbx, .dae or .3ds";

bool isModelFormat(const std::string& extension) {
  for (const char* f : kModelFormats)
    if (lower(extension) == f) return true;
  return false;
}

// Removes (and frees: UnregisterLoader does not) every importer that reads
// none of kModelFormats.
void keepModelImporters(Assimp::Importer& importer) {
  std::vector<Assimp::BaseImporter*> others;
  for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
    const aiImporterDesc* desc = importer.GetImporterInfo(i);
    bool keep = false;
    std::string extension;
    for (const char* c = desc && desc->mFileExtensions ? desc->mFileExtensions : "";; ++c) {
      if (*c == ' ' || *c == '\0') {
        keep = keep || isModelFormat(extension);
        extension.clear();
        if (*c == '\0') break;
      } else {
        extension += *c;
      }
    }
    if (!keep) others.push_back(importer.GetImporter(i));
  }
  for (Assimp::BaseImporter* other : others) {
    importer.UnregisterLoader(other);
    delete other;
  }
}

}  // namespace

Status checkModelRequest(const std::string& path, const ModelLoadOptions& options) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return makeError(path + ": no such model file");
  if (!(options.scale > 0) || !std::isfinite(options.scale))
    return makeError(path + ": scale must be a positive number, got " + std::to_string(options.scale));
  return Ok{};
}

bool hasModelExtension(const std::string& path) {
  const std::string extension = fs::path(path).extension().string();
  return extension.size() > 1 && isModelFormat(extension.substr(1));
}

namespace {

// True if `path` (resolved, symlinks followed) lies inside `root` (resolved).
bool isInside(const fs::path& root, const fs::path& path) {
  std::error_code ec;
  const fs::path r = fs::weakly_canonical(root, ec);
  if (ec) return false;
  const fs::path p = fs::weakly_canonical(path, ec);
  if (ec) return false;
  const fs::path rel = p.lexically_relative(r);
  return !rel.empty() && *rel.begin() != "..";
}

// The files assimp opens for a model (an .obj's .mtl, a .gltf's buffers)
// must be regular files inside the model's root folder: a model from a mod
// never reads "../../../../etc/passwd", a FIFO or /dev/zero.
class ConfinedIOSystem : public Assimp::DefaultIOSystem {
 public:
  ConfinedIOSystem(fs::path root, std::vector<std::string>* warnings)
      : m_root(std::move(root)), m_warnings(warnings) {}
  bool Exists(const char* file) const override { return allowed(file) && DefaultIOSystem::Exists(file); }
  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override {
    if (!allowed(file)) {
      m_warnings->push_back(std::string("model file refers to \"") + (file ? file : "") + "\", outside " +
                            m_root.string() + " or not a regular file; not read");
      return nullptr;
    }
    return DefaultIOSystem::Open(file, mode);
  }

 private:
  bool allowed(const char* file) const {
    std::error_code ec;
    return file && isInside(m_root, file) && fs::is_regular_file(file, ec);
  }
  fs::path m_root;
  std::vector<std::string>* m_warnings;
};

// A texture path as stored in the file ("C:\\MAPS\\JEEP1.JPG", "tex/a.png")
// found next to the model: exact relative path first, then the bare file
// name matched case-insensitively in the model's folder.
std::optional<fs::path> findTextureFile(const fs::path& modelDir, std::string stored) {
  std::replace(stored.begin(), stored.end(), '\\', '/');
  if (stored.empty()) return std::nullopt;
  std::error_code ec;
  const fs::path direct = modelDir / stored;
  // Only files inside the model's folder: "../../../../etc/passwd" is not
  // looked for (its bare name is, next to the model, below).
  if (isInside(modelDir, direct) && fs::is_regular_file(direct, ec)) return direct;
  const std::string name = lower(fs::path(stored).filename().string());
  for (const auto& entry : fs::directory_iterator(modelDir, ec)) {
    if (entry.is_regular_file(ec) && lower(entry.path().filename().string()) == name && isInside(modelDir, entry.path()))
      return entry.path();
  }
  return std::nullopt;
}

Result<ModelImage> decodeImage(const std::string& label, const unsigned char* bytes, std::size_t size) {
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes, static_cast<int>(size), &w, &h, &channels)) {
    return makeError(label + ": not a readable image (" + stbi_failure_reason() + ")");
  }
  if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide) {
    return makeError(label + ": image is " + std::to_string(w) + "x" + std::to_string(h) + ", expected 1.." +
                     std::to_string(kMaxTextureSide) + " pixels a side");
  }
  stbi_uc* data = stbi_load_from_memory(bytes, static_cast<int>(size), &w, &h, &channels, 4);
  if (data == nullptr) return makeError(label + ": image data is broken (" + stbi_failure_reason() + ")");
  ModelImage image;
  image.source = label;
  image.width = w;
  image.height = h;
  image.rgba.assign(data, data + static_cast<std::size_t>(w) * h * 4);
  stbi_image_free(data);
  return image;
}

Result<ModelImage> loadImageFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return makeError(file.string() + ": cannot read");
  return decodeImage(file.string(), bytes.data(), bytes.size());
}

Result<ModelImage> embeddedImage(const std::string& label, const aiTexture& tex) {
  if (tex.mHeight == 0) {  // compressed (png, jpg ...): mWidth is the byte count
    return decodeImage(label, reinterpret_cast<const unsigned char*>(tex.pcData), tex.mWidth);
  }
  if (tex.mWidth > unsigned(kMaxTextureSide) || tex.mHeight > unsigned(kMaxTextureSide)) {
    return makeError(label + ": embedded texture too large");
  }
  ModelImage image;
  image.source = label;
  image.width = static_cast<int>(tex.mWidth);
  image.height = static_cast<int>(tex.mHeight);
  image.rgba.reserve(std::size_t(tex.mWidth) * tex.mHeight * 4);
  for (std::size_t i = 0; i < std::size_t(tex.mWidth) * tex.mHeight; ++i) {
    const aiTexel& t = tex.pcData[i];
    image.rgba.insert(image.rgba.end(), {t.r, t.g, t.b, t.a});
  }
  return image;
}

class Converter {
 public:
  Converter(const std::string& path, const aiScene& scene, Model& model)
      : m_path(path), m_dir(fs::path(path).parent_path()), m_scene(scene), m_model(model) {
    if (m_dir.empty()) m_dir = ".";
  }

  void materials() {
    for (unsigned i = 0; i < m_scene.mNumMaterials; ++i) {
      const aiMaterial& source = *m_scene.mMaterials[i];
      ModelMaterial material;
      aiString name;
      if (source.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) material.name = name.C_Str();
      aiColor3D diffuse(0.8f, 0.8f, 0.8f);
      if (source.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS) {
        material.diffuse = {srgbToLinear(diffuse.r), srgbToLinear(diffuse.g), srgbToLinear(diffuse.b)};
      }
      aiString texture;
      const bool hasTexture =
          source.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS ||
          source.GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == AI_SUCCESS;
      if (hasTexture && texture.length > 0) {
        material.image = image(texture.C_Str(), material.name);
        // A texture replaces the colour; glTF's base colour factor and OBJ's
        // Kd under a map_Kd are usually white, 3DS often stores grey.
        if (material.image >= 0) material.diffuse = Eigen::Vector3f::Ones();
      }
      // A lamp's glow. With an emissive texture the colour is only its
      // factor (glTF writes white there), and the texture is not drawn, so
      // such a surface does not glow rather than glowing white all over.
      aiColor3D emissive(0, 0, 0);
      if (source.GetTextureCount(aiTextureType_EMISSIVE) > 0) {
        std::string warning = m_path + ": material \"" + material.name +
                              "\": its emissive texture is not drawn; the surface does not glow";
        m_model.warnings.push_back(std::move(warning));
      } else if (source.Get(AI_MATKEY_COLOR_EMISSIVE, emissive) == AI_SUCCESS) {
        material.emissive = {srgbToLinear(emissive.r), srgbToLinear(emissive.g), srgbToLinear(emissive.b)};
      }
      m_model.materials.push_back(std::move(material));
    }
    if (m_model.materials.empty()) m_model.materials.push_back(ModelMaterial{"default"});
  }

  Status meshes() {
    std::size_t total = 0;
    for (unsigned i = 0; i < m_scene.mNumMeshes; ++i) {
      const aiMesh& source = *m_scene.mMeshes[i];
      ModelMesh mesh;
      mesh.material = source.mMaterialIndex < m_model.materials.size() ? int(source.mMaterialIndex) : 0;
      mesh.positions.reserve(source.mNumVertices);
      for (unsigned v = 0; v < source.mNumVertices; ++v) {
        const aiVector3D& p = source.mVertices[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
          return makeError(m_path + ": mesh " + std::to_string(i) + " has a non-finite vertex position");
        }
        mesh.positions.emplace_back(p.x, p.y, p.z);
        Eigen::Vector3f n = source.mNormals ? Eigen::Vector3f(source.mNormals[v].x, source.mNormals[v].y,
                                                              source.mNormals[v].z)
                                            : Eigen::Vector3f::UnitY();
        const float len = n.norm();
        mesh.normals.push_back(std::isfinite(len) && len > 1e-12f ? Eigen::Vector3f(n / len) : Eigen::Vector3f::UnitY());
        if (source.mColors[0]) {
          const aiColor4D& c = source.mColors[0][v];
          mesh.colors.emplace_back(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b));
        }
        if (source.mTextureCoords[0]) {
          mesh.uvs.emplace_back(source.mTextureCoords[0][v].x, source.mTextureCoords[0][v].y);
        }
      }
      for (unsigned f = 0; f < source.mNumFaces; ++f) {
        const aiFace& face = source.mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines (SortByPType keeps them apart)
        std::array<std::uint32_t, 3> t{face.mIndices[0], face.mIndices[1], face.mIndices[2]};
        if (t[0] >= source.mNumVertices || t[1] >= source.mNumVertices || t[2] >= source.mNumVertices) {
          return makeError(m_path + ": mesh " + std::to_string(i) + " face " + std::to_string(f) +
                           " indexes a vertex that does not exist");
        }
        mesh.triangles.push_back(t);
      }
      total += mesh.triangles.size();
      if (total > kMaxTriangles) {
        return makeError(m_path + ": more than " + std::to_string(kMaxTriangles) + " triangles");
      }
      m_model.meshes.push_back(std::move(mesh));
    }
    if (total == 0) return makeError(m_path + ": the file holds no triangles");
    return Ok{};
  }

  void nodes(const aiNode& root, float scale) {
    addNode(root, -1);
    m_model.nodes[0].local = Eigen::Matrix4f(Eigen::Affine3f(Eigen::Scaling(scale)).matrix() * m_model.nodes[0].local);
  }

 private:
  void addNode(const aiNode& source, int parent) {
    const int index = static_cast<int>(m_model.nodes.size());
    ModelNode node;
    node.name = source.mName.C_Str();
    node.parent = parent;
    node.local = toEigen(source.mTransformation);
    if (!node.local.allFinite()) node.local = Eigen::Matrix4f::Identity();
    for (unsigned i = 0; i < source.mNumMeshes; ++i) {
      const unsigned mesh = source.mMeshes[i];
      if (mesh < m_model.meshes.size() && !m_model.meshes[mesh].triangles.empty()) node.meshes.push_back(int(mesh));
    }
    m_model.nodes.push_back(std::move(node));
    if (parent >= 0) m_model.nodes[parent].children.push_back(index);
    for (unsigned i = 0; i < source.mNumChildren; ++i) {
      if (source.mChildren[i] != nullptr) addNode(*source.mChildren[i], index);
    }
  }

  // Index into m_model.images of the texture `stored`, decoding it on first
  // use; -1 (and a warning) when it cannot be had.
  int image(const std::string& stored, const std::string& materialName) {
    if (auto it = m_imageIndex.find(stored); it != m_imageIndex.end()) return it->second;
    Result<ModelImage> decoded = makeError("");
    if (const aiTexture* tex = m_scene.GetEmbeddedTexture(stored.c_str())) {
      decoded = embeddedImage(m_path + ":" + stored, *tex);
    } else if (auto file = findTextureFile(m_dir, stored)) {
      decoded = loadImageFile(*file);
    } else {
      decoded = makeError("texture \"" + stored + "\" not found next to the model (looked in " + m_dir.string() + ")");
    }
    int index = -1;
    if (decoded) {
      index = static_cast<int>(m_model.images.size());
      m_model.images.push_back(std::move(*decoded));
    } else {
      std::string warning = m_path + ": material \"" + materialName + "\": " + decoded.error() +
                            "; drawing it in its material colour";
      m_model.warnings.push_back(std::move(warning));
    }
    m_imageIndex[stored] = index;
    return index;
  }

  std::string m_path;
  fs::path m_dir;
  const aiScene& m_scene;
  Model& m_model;
  std::map<std::string, int> m_imageIndex;
};

}  // namespace

Result<std::shared_ptr<const Model>> loadModelInThisProcess(const std::string& path, const ModelLoadOptions& options) {
  if (Status st = checkModelRequest(path, options); !st) return makeError(st.error());
  Assimp::Importer importer;
  keepModelImporters(importer);
  std::vector<std::string> fileWarnings;
  importer.SetIOHandler(new ConfinedIOSystem(fs::absolute(path).parent_path(), &fileWarnings));  // the importer owns it
  // Lines and points are dropped: models here are surfaces.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_LINE | aiPrimitiveType_POINT);
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                         aiProcess_SortByPType | aiProcess_ValidateDataStructure | aiProcess_FlipUVs;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (scene == nullptr) {
    std::string why = importer.GetErrorString();
    if (why.empty()) why = "assimp could not read it";
    return makeError(path + ": not a readable model (" + why +
                     "); expected " + kModelFormatList);
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || scene->mRootNode == nullptr) {
    return makeError(path + ": the model is incomplete (no scene graph or no meshes); is the file truncated?");
  }
  auto model = std::make_shared<Model>();
  model->source = path;
  model->warnings = std::move(fileWarnings);
  Converter converter(path, *scene, *model);
  converter.materials();
  if (Status s = converter.meshes(); !s) return makeError(s.error());
  converter.nodes(*scene->mRootNode, options.scale);
  computeBounds(*model);
  if (model->nodes[0].coverBox.empty) return makeError(path + ": no node of the scene graph uses a mesh");
  return std::shared_ptr<const Model>(std::move(model));
}

}  // namespace tumble::render
