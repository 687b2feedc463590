// Save files (<save folder>/MOD/NAME.json): save.read on any bytes, in a
// running scene, and save.write of whatever table it gave back.
#include <cstdlib>

#include "fuzz_scene.h"

namespace {

// on_update reads the save "f" (the fuzz input) and writes back what it read
// as "g"; both inside pcall so a refusal is a Lua error, not a paused callback.
const char* kScenario = R"(
return {
  on_update = function(ctx)
    local ok, t = pcall(save.read, "f")
    if ok and type(t) == "table" then pcall(save.write, "g", t) end
  end,
}
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::unique_ptr<tumble::app::Scene> scene = [] {
    auto s = tumble::fuzz::sceneFor("save_reader", kScenario);
    if (!s) std::abort();
    s->start();
    return s;
  }();
  static long long step = 0;
  tumble::fuzz::writeScratch("saves/fuzzmod/f.json", data, size);
  scene->host().update(double(step) / 60.0, 1.0 / 60.0, step);
  ++step;
  if (!scene->host().errors().empty()) std::abort();  // the reader threw past pcall
  return 0;
}
