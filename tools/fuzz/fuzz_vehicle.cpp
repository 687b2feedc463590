// Vehicle definitions (vehicles/NAME.lua): script::loadVehicleFile on any text.
#include "fuzz_util.h"
#include "script/mods.h"
#include "script/vehicle_defs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const tumble::script::ModInfo mod = [] {
    auto m = tumble::script::loadManifest(tumble::fuzz::fuzzMod());
    if (!m) std::abort();
    return m.value();
  }();
  tumble::fuzz::writeScratch("fuzzmod/vehicles/v.lua", data, size);
  auto v = tumble::script::loadVehicleFile(mod, "v");
  (void)v;
  return 0;
}
