#pragma once
// Scenario thumbnails for the main menu. The engine renders each one
// offscreen by running itself (`tumble run MOD:SCENARIO --seconds 1.5
// --screenshot FILE --width 384 --height 216`, a headless run: the player's
// saves are not touched) on a worker thread, one at a time, and caches the
// picture in the user's cache folder:
//
//   $TUMBLE_CACHE_DIR/thumbnails/MOD/NAME.png, else
//   $XDG_CACHE_HOME/tumble/thumbnails/..., else ~/.cache/tumble/thumbnails/...
//
// A cached picture older than its scenario file is rendered again. Only the
// thumbnails the menu asks for (the highlighted scenario) are made. The
// main thread uploads finished pictures as textures (Renderer::loadUiImage).
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/game_catalog.h"
#include "render/renderer.h"

namespace tumble::app {

using Thumbnail = render::UiImage;

class ThumbnailCache {
 public:
  ThumbnailCache(render::Renderer& renderer, std::vector<std::string> modDirs);
  /// Lets the thumbnail being rendered finish (a few seconds at most), drops
  /// the queued ones, frees the textures.
  ~ThumbnailCache();
  ThumbnailCache(const ThumbnailCache&) = delete;
  ThumbnailCache& operator=(const ThumbnailCache&) = delete;

  /// The picture, or null while it is made (then it is queued) or if it failed.
  const Thumbnail* get(const ScenarioEntry& scenario);
  /// "rendering ...", "cached", "rendered", or why it failed.
  std::string status(const ScenarioEntry& scenario) const;
  /// Where the thumbnail of MOD:NAME is cached.
  static std::string pathFor(const std::string& scenarioRef);

 private:
  enum class State { Queued, Rendering, Done, Failed };
  struct Entry {
    State state = State::Queued;
    std::string file, png, message;
    bool fromCache = false;
    Thumbnail image;
    bool uploadTried = false;
  };
  void work();
  bool upToDate(const Entry& e) const;

  render::Renderer& m_renderer;
  std::vector<std::string> m_modDirs;
  mutable std::mutex m_mutex;
  std::condition_variable m_wake;
  std::map<std::string, Entry> m_entries;  ///< by MOD:NAME
  std::deque<std::string> m_queue;
  bool m_stop = false;
  std::thread m_worker;
};

}  // namespace tumble::app
