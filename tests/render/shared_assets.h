#pragma once
// Path of a third-party test file in ../shared/assets/third_party/. The test
// harness sets TUMBLE_SHARED_DIR; when it does not reach the test (ctest
// takes only the first entry of an ENVIRONMENT list that is not escaped),
// TUMBLE_SOURCE_DIR/../shared is the same folder.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace tumble::test {

inline std::string sharedAsset(const std::string& relative) {
  std::filesystem::path shared = "../shared";
  if (const char* dir = std::getenv("TUMBLE_SHARED_DIR"); dir && *dir) {
    shared = dir;
  } else if (const char* source = std::getenv("TUMBLE_SOURCE_DIR"); source && *source) {
    shared = std::filesystem::path(source) / ".." / "shared";
  }
  return (shared / "assets/third_party" / relative).string();
}

}  // namespace tumble::test
