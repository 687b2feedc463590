// The player's settings.json: app::loadPlayerSettings on any bytes.
#include "app/player_settings.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tumble::fuzz::writeScratch("config/settings.json", data, size);
  auto s = tumble::app::loadPlayerSettings(path);
  (void)s;
  return 0;
}
