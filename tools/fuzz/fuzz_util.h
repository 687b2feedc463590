#pragma once
// Shared by the fuzz targets (tools/fuzz/README.md): each writes the input
// into a scratch folder of its own process, as the file a loader reads, and
// calls the loader. A loader may refuse the input (that is the point) but
// must not crash, hang, leak or read outside its file.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace tumble::fuzz {

/// A folder for this process's scratch files (removed at exit).
inline const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / ("tumble-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(std::filesystem::temp_directory_path() / ("tumble-fuzz-" + std::to_string(getpid())), ec);
    });
    return d;
  }();
  return dir;
}

/// Writes `data` to `relative` under the scratch folder; returns the path.
inline std::string writeScratch(const std::string& relative, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path p = scratchDir() / relative;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return p.string();
}

/// A mod folder "fuzzmod" with a valid manifest; returns its folder.
inline std::string fuzzMod() {
  const std::string manifest = "return {name = \"fuzzmod\", version = \"1.0.0\", title = \"fuzz\", api = 1, depends = {}}\n";
  writeScratch("fuzzmod/mod.lua", reinterpret_cast<const std::uint8_t*>(manifest.data()), manifest.size());
  return (scratchDir() / "fuzzmod").string();
}

}  // namespace tumble::fuzz
