#pragma once
// Reading user files and writing them atomically (write a temporary file
// beside the target, flush, fsync, rename), so a crash never leaves a
// half-written save, screenshot or report.
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble {

Result<std::string> readTextFile(const std::string& path);
Result<std::vector<std::uint8_t>> readBinaryFile(const std::string& path);
Status writeFileAtomic(const std::string& path, const void* data, std::size_t size);
inline Status writeFileAtomic(const std::string& path, const std::string& text) {
  return writeFileAtomic(path, text.data(), text.size());
}

}  // namespace tumble
