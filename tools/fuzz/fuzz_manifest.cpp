// Mod manifests (mod.lua): script::loadManifest on any text.
#include "fuzz_util.h"
#include "script/mods.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tumble::fuzz::writeScratch("m/mod.lua", data, size);
  auto m = tumble::script::loadManifest((tumble::fuzz::scratchDir() / "m").string());
  (void)m;
  return 0;
}
