// Emitter definitions (emitters/NAME.lua): script::loadEmitterFile on any text.
#include "fuzz_util.h"
#include "script/emitter_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tumble::fuzz::writeScratch("fuzzmod/emitters/e.lua", data, size);
  auto e = tumble::script::loadEmitterFile(path, "fuzzmod");
  (void)e;
  return 0;
}
