// Replays (`run --replay FILE`): app::loadReplay on any bytes. A replay
// carries a checksum over its content, which random bytes never match; so
// that the field checks behind it are fuzzed too, a JSON object whose
// "checksum" is the string "fix" gets the right checksum before loading
// (only when it nests at most 64 deep: serialising it here must not be what
// overflows the stack; a deeper one goes to the loader as it is).
#include "app/replay.h"
#include "core/hash.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json doc = nlohmann::json::parse(
      text, [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) { return depth <= 64; }, false);
  if (!doc.is_discarded() && doc.is_object()) {
    if (auto c = doc.find("checksum"); c != doc.end() && *c == "fix") {
      nlohmann::json content = doc;
      content.erase("checksum");
      const std::string dumped = content.dump();
      tumble::Hasher h;
      h.bytes(dumped.data(), dumped.size());
      doc["checksum"] = h.hex();
      text = doc.dump();
    }
  }
  const std::string path = tumble::fuzz::writeScratch("r.replay.json", reinterpret_cast<const std::uint8_t*>(text.data()),
                                                      text.size());
  auto r = tumble::app::loadReplay(path);
  (void)r;
  return 0;
}
