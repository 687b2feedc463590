#include "core/file_watch.h"

#include <system_error>

namespace fs = std::filesystem;

namespace tumble {

FileWatch::FileWatch(std::vector<std::string> roots, std::vector<std::string> extensions, double period_s)
    : m_extensions(std::move(extensions)), m_period_s(period_s) {
  for (auto& r : roots) m_roots.push_back(fs::absolute(r).lexically_normal().string());
  m_stamps = scan();
}

bool FileWatch::wanted(const fs::path& p) const {
  if (m_extensions.empty()) return true;
  const std::string name = p.filename().string();
  for (const auto& ext : m_extensions)
    if (name.size() >= ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0) return true;
  return false;
}

std::map<std::string, FileWatch::Stamp> FileWatch::scan() const {
  // Every call uses error codes: a file deleted mid-scan, or a folder we may
  // not read, is simply not there this time.
  std::map<std::string, Stamp> out;
  std::error_code ec;
  for (const auto& root : m_roots) {
    if (fs::is_regular_file(root, ec)) {
      Stamp s{fs::last_write_time(root, ec), fs::file_size(root, ec)};
      if (!ec) out[root] = s;
      continue;
    }
    fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
      std::error_code fe;
      if (!it->is_regular_file(fe) || !wanted(it->path())) continue;
      Stamp s{it->last_write_time(fe), 0};
      if (fe) continue;
      s.size = it->file_size(fe);
      if (fe) continue;
      out[it->path().lexically_normal().string()] = s;
    }
  }
  return out;
}

std::vector<FileChange> FileWatch::poll() {
  std::map<std::string, Stamp> now = scan();
  std::vector<FileChange> changes;
  // Both maps are sorted: one merge pass.
  auto a = m_stamps.begin(), b = now.begin();
  while (a != m_stamps.end() || b != now.end()) {
    if (b == now.end() || (a != m_stamps.end() && a->first < b->first)) {
      changes.push_back({a->first, FileChange::Kind::Removed});
      ++a;
    } else if (a == m_stamps.end() || b->first < a->first) {
      changes.push_back({b->first, FileChange::Kind::Added});
      ++b;
    } else {
      if (!(a->second == b->second)) changes.push_back({a->first, FileChange::Kind::Modified});
      ++a, ++b;
    }
  }
  m_stamps = std::move(now);
  return changes;
}

std::vector<FileChange> FileWatch::pollIfDue(double now_s) {
  if (now_s - m_lastPoll_s < m_period_s) return {};
  m_lastPoll_s = now_s;
  return poll();
}

}  // namespace tumble
