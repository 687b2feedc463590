#include "core/file_util.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tumble {

Result<std::string> readTextFile(const std::string& path, std::size_t maxBytes) {
  // Regular files only, checked before opening: opening a FIFO blocks until
  // a writer comes, and /dev/zero or /dev/urandom never end.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return makeError(path + ": cannot open for reading (" + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode))
    return makeError(path + ": not a regular file (a folder, device or pipe); expected a file");
  if (std::uint64_t(st.st_size) > maxBytes)
    return makeError(path + ": " + std::to_string(st.st_size) + " bytes is larger than the " +
                     std::to_string(maxBytes) + " bytes allowed for this file");
  int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return makeError(path + ": cannot open for reading (" + std::strerror(errno) + ")");
  std::string text;
  char buffer[65536];
  for (;;) {
    ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      std::string why = std::strerror(errno);
      ::close(fd);
      return makeError(path + ": read failed (" + why + ")");
    }
    if (n == 0) break;
    if (text.size() + std::size_t(n) > maxBytes) {  // the file grew while being read
      ::close(fd);
      return makeError(path + ": larger than the " + std::to_string(maxBytes) + " bytes allowed for this file");
    }
    text.append(buffer, std::size_t(n));
  }
  ::close(fd);
  return text;
}

Result<std::vector<std::uint8_t>> readBinaryFile(const std::string& path, std::size_t maxBytes) {
  auto text = readTextFile(path, maxBytes);
  if (!text) return makeError(text.error());
  return std::vector<std::uint8_t>(text->begin(), text->end());
}

Status writeFileAtomic(const std::string& path, const void* data, std::size_t size) {
  std::string tmp = path + ".tmp" + std::to_string(::getpid());
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return makeError(path + ": cannot write (" + std::strerror(errno) + ")");
  const char* p = static_cast<const char*>(data);
  std::size_t left = size;
  while (left > 0) {
    ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      std::string why = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      return makeError(path + ": write failed (" + why + ")");
    }
    p += n;
    left -= std::size_t(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    return makeError(path + ": flushing failed (" + why + ")");
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    return makeError(path + ": rename failed (" + why + ")");
  }
  // The rename is an entry in the folder: fsync the folder too, or a crash
  // right after could bring back the old file (or none) on some file systems.
  const std::string dir = std::filesystem::path(path).parent_path().string();
  int dirFd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirFd >= 0) {
    const int error = ::fsync(dirFd) == 0 ? 0 : errno;
    ::close(dirFd);
    // EINVAL: a file system that cannot sync folders (the rename stands).
    if (error != 0 && error != EINVAL)
      return makeError(path + ": flushing its folder failed (" + std::strerror(error) + ")");
  }
  return Ok{};
}

namespace {

// "best.json.tmp12345" -> 12345 (the writer's process id), or 0.
long temporaryOwner(const std::string& name) {
  const std::size_t at = name.rfind(".tmp");
  if (at == std::string::npos || at == 0 || at + 4 >= name.size()) return 0;
  long pid = 0;
  for (std::size_t i = at + 4; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9' || pid > 100000000) return 0;
    pid = pid * 10 + (name[i] - '0');
  }
  return pid;
}

}  // namespace

std::size_t removeOrphanedTemporaries(const std::string& dir, int depth) {
  namespace fs = std::filesystem;
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_directory(ec) && !entry.is_symlink(ec)) {
      if (depth > 0) removed += removeOrphanedTemporaries(entry.path().string(), depth - 1);
      continue;
    }
    if (!entry.is_regular_file(ec)) continue;
    const long pid = temporaryOwner(entry.path().filename().string());
    // A writer still running (this process, or another tumble) keeps its file.
    if (pid <= 0 || pid == long(::getpid()) || ::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;
    if (fs::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

}  // namespace tumble
