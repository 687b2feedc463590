#include "app/thumbnails.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "core/log.h"

extern char** environ;

namespace tumble::app {

namespace fs = std::filesystem;

namespace {

constexpr const char* kWidth = "384";
constexpr const char* kHeight = "216";
constexpr const char* kSeconds = "1.5";  // bodies have fallen, cars have settled

std::string cacheRoot() {
  if (const char* d = std::getenv("TUMBLE_CACHE_DIR"); d && *d) return (fs::path(d) / "thumbnails").string();
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "tumble" / "thumbnails").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "tumble" / "thumbnails").string();
  return (fs::temp_directory_path() / "tumble-thumbnails").string();
}

// Runs this binary with args, output discarded; returns its exit status or -1.
int runSelf(const std::vector<std::string>& args) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return -1;
  std::vector<char*> argv;
  std::string exeText = exe.string();
  argv.push_back(exeText.data());
  std::vector<std::string> copy = args;
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::string ThumbnailCache::pathFor(const std::string& scenarioRef) {
  const auto colon = scenarioRef.find(':');
  const std::string mod = colon == std::string::npos ? "base" : scenarioRef.substr(0, colon);
  const std::string name = colon == std::string::npos ? scenarioRef : scenarioRef.substr(colon + 1);
  return (fs::path(cacheRoot()) / mod / (name + ".png")).string();
}

ThumbnailCache::ThumbnailCache(render::Renderer& renderer, std::vector<std::string> modDirs)
    : m_renderer(renderer), m_modDirs(std::move(modDirs)), m_worker([this] { work(); }) {}

ThumbnailCache::~ThumbnailCache() {
  {
    std::lock_guard lock(m_mutex);
    m_stop = true;
    m_queue.clear();
  }
  m_wake.notify_all();
  m_worker.join();
  for (auto& [ref, e] : m_entries) m_renderer.freeUiImage(e.image);
}

bool ThumbnailCache::upToDate(const Entry& e) const {
  std::error_code ec1, ec2;
  const auto png = fs::last_write_time(e.png, ec1);
  const auto lua = fs::last_write_time(e.file, ec2);
  return !ec1 && !ec2 && png >= lua;
}

const Thumbnail* ThumbnailCache::get(const ScenarioEntry& s) {
  std::unique_lock lock(m_mutex);
  auto it = m_entries.find(s.ref);
  if (it == m_entries.end()) {
    Entry e;
    e.file = s.file;
    e.png = pathFor(s.ref);
    if (upToDate(e)) {
      e.state = State::Done;
      e.fromCache = true;
    } else {
      m_queue.push_back(s.ref);
      m_wake.notify_all();
    }
    it = m_entries.emplace(s.ref, std::move(e)).first;
  }
  Entry& e = it->second;
  if (e.state != State::Done) return nullptr;
  if (!e.uploadTried) {  // GL work stays on this (the render) thread
    e.uploadTried = true;
    auto img = m_renderer.loadUiImage(e.png);
    if (!img) {
      e.state = State::Failed;
      e.message = img.error();
      return nullptr;
    }
    e.image = *img;
  }
  return &e.image;
}

std::string ThumbnailCache::status(const ScenarioEntry& s) const {
  std::lock_guard lock(m_mutex);
  auto it = m_entries.find(s.ref);
  if (it == m_entries.end()) return "";
  switch (it->second.state) {
    case State::Queued: return "preview queued ...";
    case State::Rendering: return "rendering a preview ...";
    case State::Done: return it->second.fromCache ? "cached" : "rendered";
    case State::Failed: return "no preview: " + it->second.message;
  }
  return "";
}

void ThumbnailCache::work() {
  for (;;) {
    std::string ref, png;
    {
      std::unique_lock lock(m_mutex);
      m_wake.wait(lock, [this] { return m_stop || !m_queue.empty(); });
      if (m_stop) return;
      ref = m_queue.front();
      m_queue.pop_front();
      Entry& e = m_entries[ref];
      e.state = State::Rendering;
      png = e.png;
    }
    std::error_code ec;
    fs::create_directories(fs::path(png).parent_path(), ec);
    const bool folderMade = !ec;
    fs::remove(png, ec);  // a stale picture must not pass for a new one
    std::vector<std::string> args;
    for (const std::string& d : m_modDirs) args.insert(args.end(), {"--mods", d});
    args.insert(args.end(), {"run", ref, "--seconds", kSeconds, "--screenshot", png, "--width", kWidth, "--height", kHeight});
    const int status = folderMade ? runSelf(args) : -1;
    std::lock_guard lock(m_mutex);
    Entry& e = m_entries[ref];
    // Exit 2 (an expectation failed after 1.5 s) still made the picture.
    if (fs::exists(png, ec) && (status == 0 || status == 2 || status == 3)) {
      e.state = State::Done;
    } else {
      e.state = State::Failed;
      e.message = !folderMade ? "cannot create " + fs::path(png).parent_path().string() : "the preview run failed (exit " + std::to_string(status) + ")";
      log::warn("thumbnail " + ref + ": " + e.message);
    }
  }
}

}  // namespace tumble::app
