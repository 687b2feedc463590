// A mod's input bindings (bindings.lua): script::loadModBindings on any text.
#include "fuzz_util.h"
#include "script/mod_bindings.h"
#include "script/mods.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const tumble::script::ModInfo mod = [] {
    auto m = tumble::script::loadManifest(tumble::fuzz::fuzzMod());
    if (!m) std::abort();
    return m.value();
  }();
  tumble::fuzz::writeScratch("fuzzmod/bindings.lua", data, size);
  auto b = tumble::script::loadModBindings(mod);
  (void)b;
  return 0;
}
