// Height maps: a PNG and its JSON sidecar (terrain::loadHeightMapPng,
// terrain::loadSidecar). The input is the sidecar's text, then the PNG from
// its signature (\x89PNG) on; an input without text before the signature
// (any PNG file as a seed) has no sidecar.
#include <algorithm>
#include <cstring>

#include "fuzz_util.h"
#include "terrain/height_map.h"
#include "terrain/terrain_desc.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::uint8_t kSignature[] = {0x89, 'P', 'N', 'G'};
  const std::uint8_t* png = std::search(data, data + size, kSignature, kSignature + 4);
  std::error_code ec;
  std::filesystem::remove(tumble::fuzz::scratchDir() / "h.png.json", ec);
  if (png != data) tumble::fuzz::writeScratch("h.png.json", data, std::size_t(png - data));
  const std::string path = tumble::fuzz::writeScratch("h.png", png, size - std::size_t(png - data));
  auto map = tumble::terrain::loadHeightMapPng(path);
  (void)map;
  auto desc = tumble::terrain::loadSidecar(path);
  (void)desc;
  return 0;
}
