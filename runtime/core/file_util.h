#pragma once
// Reading user files and writing them atomically (write a temporary file
// beside the target, flush, fsync, rename), so a crash never leaves a
// half-written save, screenshot or report.
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble {

/// Largest file read unless a caller says otherwise (a 8193 x 8193 16-bit
/// height map is 134 MB uncompressed).
constexpr std::size_t kMaxReadBytes = std::size_t(256) << 20;

/// The whole of a regular file, at most maxBytes: a folder, FIFO or device
/// (/dev/zero) and a larger file are refused with a message naming the file.
Result<std::string> readTextFile(const std::string& path, std::size_t maxBytes = kMaxReadBytes);
Result<std::vector<std::uint8_t>> readBinaryFile(const std::string& path, std::size_t maxBytes = kMaxReadBytes);
Status writeFileAtomic(const std::string& path, const void* data, std::size_t size);
inline Status writeFileAtomic(const std::string& path, const std::string& text) {
  return writeFileAtomic(path, text.data(), text.size());
}

/// Removes the temporary files ("<name>.tmp<pid>") that writeFileAtomic left
/// in `dir` (and `depth` levels of folders below) when its process was
/// killed mid-write: those whose process is gone. Returns how many.
std::size_t removeOrphanedTemporaries(const std::string& dir, int depth = 0);

}  // namespace tumble
