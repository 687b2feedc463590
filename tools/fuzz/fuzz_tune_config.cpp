// The designer's saved tunable values (tune/<mod>.json): Tunables::loadOverrides,
// then a declaration that meets the values read.
#include "fuzz_util.h"
#include "script/tunables.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tumble::script::Tunables t;
  auto st = t.loadOverrides(tumble::fuzz::writeScratch("tune.json", data, size));
  (void)st;
  tumble::script::Tunable g;
  g.name = "gravity";
  g.min = 0;
  g.max = 100;
  g.defaultValue = 9.81;
  auto d = t.declare(g);
  (void)d;
  (void)t.takeProblems();
  return 0;
}
