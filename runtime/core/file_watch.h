#pragma once
// FileWatch: which files under a few folders changed since the last look.
//
// Polling, not inotify: every poll stats the watched files (a mod is tens of
// files, a few microseconds each), so it behaves the same on every platform
// and file system (network folders, editors that save by rename) and is
// deterministic: changes come back sorted by path, and nothing happens
// between polls. pollIfDue() limits the scans to a period (0.25 s: a saved
// file is seen within a quarter of a second, well inside the one second a
// modder expects).
//
// A file counts as changed when its modification time or size differs from
// the last poll, when it appears, or when it disappears.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace tumble {

struct FileChange {
  enum class Kind { Modified, Added, Removed };
  std::string path;  ///< absolute, lexically normal
  Kind kind = Kind::Modified;
};

class FileWatch {
 public:
  static constexpr double kDefaultPeriod_s = 0.25;

  /// Watches every file under each root (recursively) whose name ends with
  /// one of `extensions` (".lua"; empty: every file). Roots that do not exist
  /// are watched too: files appearing there are reported as added. The
  /// current state is the baseline (no change reported for it).
  FileWatch(std::vector<std::string> roots, std::vector<std::string> extensions, double period_s = kDefaultPeriod_s);

  /// Scans now; changes since the last scan, sorted by path.
  std::vector<FileChange> poll();
  /// Scans only if `period_s` passed since the last scan (now_s: any
  /// monotonic clock, s); otherwise returns nothing.
  std::vector<FileChange> pollIfDue(double now_s);

  std::size_t fileCount() const { return m_stamps.size(); }
  const std::vector<std::string>& roots() const { return m_roots; }

 private:
  struct Stamp {
    std::filesystem::file_time_type mtime{};
    std::uintmax_t size = 0;
    bool operator==(const Stamp&) const = default;
  };
  std::map<std::string, Stamp> scan() const;
  bool wanted(const std::filesystem::path& p) const;

  std::vector<std::string> m_roots;
  std::vector<std::string> m_extensions;
  double m_period_s;
  double m_lastPoll_s = -1e300;
  std::map<std::string, Stamp> m_stamps;  ///< ordered: changes come out sorted
};

}  // namespace tumble
