// The player's bindings file (bindings.json): input::loadOverrides on any bytes.
#include "fuzz_util.h"
#include "input/overrides_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto o = tumble::input::loadOverrides(tumble::fuzz::writeScratch("bindings.json", data, size));
  (void)o;
  return 0;
}
