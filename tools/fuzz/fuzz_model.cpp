// Models (a mod's .obj, .3ds, .gltf, .glb, .dae, ... files): render::loadModel
// (the assimp wrapper) on any bytes. The file is named without a known
// extension, so assimp picks its importer from the content (every importer
// whose signature matches), as it does for a mod file it cannot tell by its
// name. Text after a line "#side" is written beside it as "m.mtl" (what an
// .obj's "mtllib m.mtl" reads); a 1x1 PNG "t.png" lies beside it too, so
// materials can name a texture that decodes.
#include <cstring>
#include <string_view>

#include "core/log.h"
#include "fuzz_util.h"
#include "render/model.h"

namespace {

// A valid 1x1 RGBA PNG.
const unsigned char kPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
    0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x00, 0x05, 0x00, 0x01, 0xff,
    0x89, 0x99, 0x3d, 0x1d, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

}  // namespace

// Debian's libassimp 5.2.5 leaks the mesh it was building when an ASCII STL
// breaks off mid-facet (found here: tools/fuzz/corpus/model/leak_assimp_stl;
// 1 to 2 kB per such file, allocated and lost inside libassimp.so, never
// handed to loadModel). It is not ours to free, so LeakSanitizer is told to
// ignore leaks from inside libassimp only; leaks in our code, overflows and
// every other check still stop the run.
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool once = [] {
    tumble::log::setLevel(tumble::log::Level::Error);  // missing textures warn on most inputs
    tumble::fuzz::writeScratch("model/t.png", kPng, sizeof kPng);
    return true;
  }();
  (void)once;
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  const std::size_t side = all.find("\n#side\n");
  const std::string_view model = side == std::string_view::npos ? all : all.substr(0, side);
  const std::string_view mtl = side == std::string_view::npos ? std::string_view() : all.substr(side + 7);
  tumble::fuzz::writeScratch("model/m.mtl", reinterpret_cast<const std::uint8_t*>(mtl.data()), mtl.size());
  const std::string path =
      tumble::fuzz::writeScratch("model/m.model", reinterpret_cast<const std::uint8_t*>(model.data()), model.size());
  auto m = tumble::render::loadModel(path);
  (void)m;
  return 0;
}
