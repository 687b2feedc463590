#pragma once
// Helpers shared by the terrain tests.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "terrain/height_map.h"

namespace tumble::terrain::test {

/// A fresh directory per test binary run, under the system temp dir.
/// Removed again when the test binary exits.
inline std::filesystem::path tempDir() {
  struct Dir {
    std::filesystem::path path;
    Dir() : path(std::filesystem::temp_directory_path() / ("tumble_terrain_test_" + std::to_string(::getpid()))) {
      std::filesystem::create_directories(path);
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

inline std::string tempFile(const std::string& name) { return (tempDir() / name).string(); }

inline std::uint64_t fnv1a(const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t k = 0; k < size; ++k) h = (h ^ p[k]) * 0x100000001b3ull;
  return h;
}

inline std::uint64_t hashMap(const HeightMap& m) {
  return fnv1a(m.samples().data(), m.samples().size() * sizeof(std::uint16_t));
}

inline std::string sharedDir() {
  const char* d = std::getenv("TUMBLE_SHARED_DIR");
  return d ? d : "/work/shared";
}

}  // namespace tumble::terrain::test
