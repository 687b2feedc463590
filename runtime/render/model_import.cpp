// render::loadModel in a process of its own: see internal/model_import.h.
#include "render/internal/model_import.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/byte_stream.h"
#include "core/log.h"

extern char** environ;

namespace tumble::render {

namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kMagic = 0x314d4954;  // "TIM1"
// What a model may bring back: the loader's own caps (4 million triangles,
// 8192 x 8192 textures) allow about this much; more is a damaged answer.
constexpr std::size_t kMaxAnswerBytes = std::size_t(2) << 30;
constexpr std::size_t kMaxItems = 16'000'000;  // nodes, meshes, materials, images, warnings, vertices
constexpr std::size_t kMaxText = 1 << 20;
constexpr int kMaxTextureSide = 8192;

bool indexIn(int i, std::size_t n) { return i >= 0 && std::size_t(i) < n; }

}  // namespace

std::string encodeImportResult(const Result<std::shared_ptr<const Model>>& result) {
  ByteWriter w;
  w.pod(kMagic);
  w.pod(std::uint8_t(result.ok()));
  if (!result.ok()) {
    w.text(result.error());
    return w.take();
  }
  const Model& m = *result.value();
  w.text(m.source);
  w.pod(std::uint64_t(m.images.size()));
  for (const ModelImage& im : m.images) {
    w.text(im.source);
    w.pod(std::int32_t(im.width));
    w.pod(std::int32_t(im.height));
    w.vec(im.rgba);
  }
  w.pod(std::uint64_t(m.materials.size()));
  for (const ModelMaterial& mat : m.materials) {
    w.text(mat.name);
    w.pod(mat.diffuse);
    w.pod(std::int32_t(mat.image));
    w.pod(mat.emissive);
  }
  w.pod(std::uint64_t(m.meshes.size()));
  for (const ModelMesh& mesh : m.meshes) {
    w.vec(mesh.positions);
    w.vec(mesh.normals);
    w.vec(mesh.uvs);
    w.vec(mesh.colors);
    w.vec(mesh.triangles);
    w.pod(std::int32_t(mesh.material));
  }
  w.pod(std::uint64_t(m.nodes.size()));
  for (const ModelNode& node : m.nodes) {
    w.text(node.name);
    w.pod(std::int32_t(node.parent));
    w.vec(node.children);
    w.vec(node.meshes);
    w.pod(node.local);
    w.pod(node.toModel);
  }
  w.pod(std::uint64_t(m.warnings.size()));
  for (const std::string& s : m.warnings) w.text(s);
  return w.take();
}

Result<std::shared_ptr<const Model>> decodeImportResult(const std::string& bytes, const std::string& path) {
  ByteReader r(bytes);
  auto damaged = [&](const std::string& what) {
    return makeError(path + ": the model importer's answer is damaged (" + what + ")");
  };
  if (r.pod<std::uint32_t>() != kMagic) return damaged("not an import result");
  const std::uint8_t ok = r.pod<std::uint8_t>();
  if (!r.ok() || ok > 1) return damaged("header");
  if (!ok) {
    std::string error = r.text(kMaxText);
    if (!r.ok() || !r.atEnd()) return damaged("error message");
    return makeError(std::move(error));
  }
  auto model = std::make_shared<Model>();
  model->source = r.text(kMaxText);
  // Each count is checked against the bytes left (every item takes at
  // least 8) before anything is allocated for it.
  auto count = [&]() -> std::size_t {
    const auto n = r.pod<std::uint64_t>();
    if (!r.ok() || n > kMaxItems || n > r.remaining() / 8) return kMaxItems + 1;
    return std::size_t(n);
  };
  std::size_t n = count();
  if (n > kMaxItems) return damaged("images");
  model->images.resize(n);
  for (ModelImage& im : model->images) {
    im.source = r.text(kMaxText);
    im.width = r.pod<std::int32_t>();
    im.height = r.pod<std::int32_t>();
    im.rgba = r.vec<std::uint8_t>(std::size_t(kMaxTextureSide) * kMaxTextureSide * 4);
    if (!r.ok() || im.width <= 0 || im.height <= 0 || im.width > kMaxTextureSide || im.height > kMaxTextureSide ||
        im.rgba.size() != std::size_t(im.width) * std::size_t(im.height) * 4)
      return damaged("image");
  }
  if ((n = count()) > kMaxItems) return damaged("materials");
  model->materials.resize(n);
  for (ModelMaterial& mat : model->materials) {
    mat.name = r.text(kMaxText);
    mat.diffuse = r.pod<Eigen::Vector3f>();
    mat.image = r.pod<std::int32_t>();
    mat.emissive = r.pod<Eigen::Vector3f>();
    if (!r.ok() || (mat.image != -1 && !indexIn(mat.image, model->images.size()))) return damaged("material");
  }
  if ((n = count()) > kMaxItems) return damaged("meshes");
  model->meshes.resize(n);
  for (ModelMesh& mesh : model->meshes) {
    mesh.positions = r.vec<Eigen::Vector3f>(kMaxItems);
    mesh.normals = r.vec<Eigen::Vector3f>(kMaxItems);
    mesh.uvs = r.vec<Eigen::Vector2f>(kMaxItems);
    mesh.colors = r.vec<Eigen::Vector3f>(kMaxItems);
    mesh.triangles = r.vec<std::array<std::uint32_t, 3>>(kMaxItems);
    mesh.material = r.pod<std::int32_t>();
    const std::size_t v = mesh.positions.size();
    if (!r.ok() || mesh.normals.size() != v || (!mesh.uvs.empty() && mesh.uvs.size() != v) ||
        (!mesh.colors.empty() && mesh.colors.size() != v) || !indexIn(mesh.material, model->materials.size()))
      return damaged("mesh");
    for (const auto& t : mesh.triangles)
      if (t[0] >= v || t[1] >= v || t[2] >= v) return damaged("triangle");
  }
  if ((n = count()) > kMaxItems || n == 0) return damaged("nodes");
  model->nodes.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    ModelNode& node = model->nodes[i];
    node.name = r.text(kMaxText);
    node.parent = r.pod<std::int32_t>();
    node.children = r.vec<int>(kMaxItems);
    node.meshes = r.vec<int>(kMaxItems);
    node.local = r.pod<Eigen::Matrix4f>();
    node.toModel = r.pod<Eigen::Matrix4f>();
    if (!r.ok() || (i == 0 ? node.parent != -1 : !indexIn(node.parent, i))) return damaged("node");
    // Parents come before children (model.h), so walks of the tree end.
    for (int c : node.children)
      if (!indexIn(c, n) || std::size_t(c) <= i) return damaged("node children");
    for (int mi : node.meshes)
      if (!indexIn(mi, model->meshes.size())) return damaged("node meshes");
  }
  if ((n = count()) > kMaxItems) return damaged("warnings");
  model->warnings.resize(n);
  for (std::string& s : model->warnings) s = r.text(kMaxText);
  if (!r.ok() || !r.atEnd()) return damaged("length");
  computeBounds(*model);
  return std::shared_ptr<const Model>(std::move(model));
}

std::string modelImporterPath() {
  if (const char* env = std::getenv("TUMBLE_MODEL_IMPORTER"); env && *env) return env;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = self.parent_path() / "tumble_model_import";
    if (fs::is_regular_file(beside, ec)) return beside.string();
  }
  return std::string(TUMBLE_BIN_DIR) + "/tumble_model_import";
}

Result<std::shared_ptr<const Model>> loadModel(const std::string& path, const ModelLoadOptions& options) {
  if (Status st = checkModelRequest(path, options); !st) return makeError(st.error());
  const std::string importer = modelImporterPath();
  int out[2];
  if (::pipe2(out, O_CLOEXEC) != 0) return makeError(path + ": cannot start the model importer (pipe: " +
                                                      std::strerror(errno) + ")");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);  // dup2 clears close-on-exec on the copy
  char scale[64];
  std::snprintf(scale, sizeof scale, "%a", double(options.scale));  // exact: hexadecimal
  std::string file = path;
  char* argv[] = {const_cast<char*>(importer.c_str()), file.data(), scale, nullptr};
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, importer.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out[1]);
  if (spawned != 0) {
    ::close(out[0]);
    return makeError(path + ": cannot start the model importer " + importer + " (" + std::strerror(spawned) +
                     "); it is built with tumble (tumble_model_import)");
  }
  // Read its answer until it closes its end, or the time is up.
  std::string bytes;
  bool timedOut = false, tooLarge = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(options.importTimeout_s);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timedOut = true;
      break;
    }
    pollfd p{out[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    char buf[1 << 16];
    const ssize_t got = ::read(out[0], buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    if (bytes.size() + std::size_t(got) > kMaxAnswerBytes) {
      tooLarge = true;
      break;
    }
    bytes.append(buf, std::size_t(got));
  }
  ::close(out[0]);
  if (timedOut || tooLarge) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timedOut)
    return makeError(path + ": the model importer did not finish within " +
                     std::to_string(int(options.importTimeout_s)) + " s and was stopped (assimp loops on this file)");
  if (tooLarge) return makeError(path + ": the model is larger than the loader takes (over 2 GiB of data)");
  // A signal, or a sanitizer's report and exit in an instrumented build.
  if (WIFSIGNALED(status) || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return makeError(path + ": the model importer crashed on this file (" +
                     (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                          : "exit code " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1)) +
                     "): assimp cannot read it; expected an undamaged .obj (+ .mtl), .gltf / .glb, .fbx, .dae or .3ds");
  auto model = decodeImportResult(bytes, path);
  if (model)
    for (const std::string& w : (*model)->warnings) log::warn(w);
  return model;
}

}  // namespace tumble::render
